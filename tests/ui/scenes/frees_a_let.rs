// A scene frees parameters, not derived quantities.
stickslip::model! {
    model bad {
        param m = 1.0, > 0;
        param d = 0.05, >= 0;
        param c = 1.0, > 0;
        param W = 1.0, > 0;
        param mu = 0.3;
        param k = 0.1;
        let A = 0.5 * m;
        oscillator { mass: m, damping: d, stiffness: c, forcing: A, frequency: W }
        boundary Sigma1: v = 1.0, stick 0.4;
        boundary Sigma2: v = 2.0;
        domain 1: Sigma1 < v < Sigma2 => mu + k * (v - 1.0);
        domain 2: v > Sigma2 => mu + k;
        domain 3: v < Sigma1 => -mu;
        scene s {
            free: W, A;
        }
    }
}

fn main() {}
