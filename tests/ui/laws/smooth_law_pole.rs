// A smooth law with a pole at v = 2.0001, inside its range V ± 8:
// rejected at the law (the pole of an affine argument is found exactly).
stickslip::model! {
    model bad {
        param V = 1.0, > 0;
        param W = 1.5, > 0;
        oscillator { mass: 1.0, damping: 0.1, stiffness: 4.0, forcing: 6.0, frequency: W }
        law {
            belt: V,
            stick: 12.0,
            range: 8.0,
            kinetic: sign(v - V) * 3.0 + 0.01 / (v - 2.0001),
        }
        scene pl4 { free: W; pieces: 4; }
    }
}

fn main() {}
