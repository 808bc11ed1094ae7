// `sqrt(v + 7)` is finite on [-7, 9], but its derivative is infinite at
// v = -7; the pieces are placed with f'', so the law is rejected.
stickslip::model! {
    model bad {
        param V = 1.0, > 0;
        param W = 1.5, > 0;
        oscillator { mass: 1.0, damping: 0.1, stiffness: 4.0, forcing: 6.0, frequency: W }
        law {
            belt: V,
            stick: 12.0,
            range: 8.0,
            kinetic: sign(v - V) * 3.0 + 0.01 * sqrt(v + 7.0),
        }
        scene pl4 { free: W; pieces: 4; }
    }
}

fn main() {}
