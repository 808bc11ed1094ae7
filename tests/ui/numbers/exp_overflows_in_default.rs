// `exp(1000.0)` folds to inf: rejected at the call, with the reason.
stickslip::model! {
    model bad {
        param m = 1.0, > 0;
        param d = 0.05, >= 0;
        param c = 1.0, > 0;
        param A = exp(1000.0);
        param W = 1.0, > 0;
        param mu = 0.3;
        param k = 0.1;
        param V = 1.0;
        oscillator { mass: m, damping: d, stiffness: c, forcing: A, frequency: W }
        boundary Sigma1: v = V, stick 0.5;
        domain 1: v > Sigma1 => mu + k * (v - V);
        domain 2: v < Sigma1 => -mu - k * (V - v);
    }
}

fn main() {}
