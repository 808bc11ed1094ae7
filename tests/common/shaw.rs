//! Shaw's oscillator (S. W. Shaw, J. Sound Vib. 108, 1986): `coulomb` on a
//! fixed surface without damping (`V = 0, d = 0`), static friction 1.5×
//! kinetic (`mus = 0.45, muk = 0.3`), symmetric under
//! `(x, v, W t) → (−x, −v, W t + π)`; and the box W ∈ [0.3, 1.2] ×
//! Q0 ∈ [0.5, 2] of `benches/curves-runs.sh shaw`.

use stickslip::bifurcation::curve::Plane;
use stickslip::models::coulomb::Params;
use stickslip::ParamSet;

/// The oscillator's parameters (the forcing's W and Q0 at their defaults).
pub fn params() -> Params {
    Params {
        V: 0.0,
        d: 0.0,
        mus: 0.45,
        muk: 0.3,
        ..Default::default()
    }
}

/// The box W ∈ [0.3, 1.2] × Q0 ∈ [0.5, 2].
pub fn plane() -> Plane {
    Plane {
        x: Params::index_of("W").unwrap(),
        y: Params::index_of("Q0").unwrap(),
        x_range: [0.3, 1.2],
        y_range: [0.5, 2.0],
    }
}

/// The parameters at `W = x, Q0 = y`.
pub fn at(x: f64, y: f64) -> Params {
    let (mut p, plane) = (params(), plane());
    p.set(plane.x, x);
    p.set(plane.y, y);
    p
}
