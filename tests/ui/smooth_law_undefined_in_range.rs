// `ln(v + 3)` is -inf at v = -3 and NaN below, inside the range [-7, 9].
stickslip::model! {
    model bad {
        param m = 1.0, > 0;
        param d = 0.1, >= 0;
        param c = 4.0, > 0;
        param V = 1.0, > 0;
        param mus = 0.6, >= 0;
        param muk = 0.3, >= 0;
        param vs = 0.4, > 0;
        param g = 9.8, > 0;
        param W = 1.5, > 0;
        oscillator { mass: m, damping: d, stiffness: c, forcing: 6.0 / m, frequency: W }
        law {
            belt: V,
            stick: mus * g * 2.0,
            range: 8.0,
            kinetic: sign(v - V) * (muk + (mus - muk) * exp(-abs(v - V) / vs)) * g + 0.01 * ln(v + 3.0),
        }
        scene pl4 { free: W; pieces: 4; }
    }
}

fn main() {}
