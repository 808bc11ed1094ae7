// `ln(v + 3)` is -inf at v = -3 and NaN below, inside the range [-7, 9].
stickslip::model! {
    model bad {
        param V = 1.0, > 0;
        param W = 1.5, > 0;
        oscillator { mass: 1.0, damping: 0.1, stiffness: 4.0, forcing: 6.0, frequency: W }
        law {
            belt: V,
            stick: 12.0,
            range: 8.0,
            kinetic: sign(v - V) * 3.0 + 0.01 * ln(v + 3.0),
        }
        scene pl4 { free: W; pieces: 4; }
    }
}

fn main() {}
