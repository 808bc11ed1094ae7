// A `powi` exponent beyond i32 is rejected at the exponent, not wrapped.
stickslip::model! {
    model bad {
        param m = 1.0, > 0;
        param d = 0.05, >= 0;
        param c = 1.0, > 0;
        param A = 0.5;
        param W = 1.0, > 0;
        param mu = 0.3;
        param k = 0.1;
        param V = 1.0;
        oscillator { mass: m, damping: d, stiffness: c, forcing: powi(A, 2147483648), frequency: W }
        boundary Sigma1: v = V, stick 0.5;
        domain 1: v > Sigma1 => mu + k * (v - V);
        domain 2: v < Sigma1 => -mu - k * (V - v);
    }
}

fn main() {}
