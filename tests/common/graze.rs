//! Near-grazing starts for the paper model, built backwards from the state
//! at a velocity extremum with the closed-form flow (used by the tests of the
//! step rule, `tests/grazing.rs`, and of the extremes, `tests/extremes.rs`).

use stickslip::dynamics::simulate::Simulator;
use stickslip::models::paper::Paper;
use stickslip::Model;

/// Every side of every band of the paper model that a boundary closes:
/// `(domain index, towards its upper boundary?)`.
pub const BAND_SIDES: [(usize, bool); 6] = [
    (0, true),  // Ω4 up to Σ3
    (1, true),  // Ω3 up to Σ1 (stick boundary)
    (1, false), // Ω3 down to Σ3
    (2, true),  // Ω1 up to Σ2
    (2, false), // Ω1 down to Σ1 (stick boundary)
    (3, false), // Ω2 down to Σ2
];

/// The band of domain `j`.
pub fn band(sim: &Simulator<Paper>, j: usize) -> (f64, f64) {
    let d = Paper::INFO.domains[j];
    (
        d.lower.map_or(f64::NEG_INFINITY, |k| sim.velocity(k)),
        d.upper.map_or(f64::INFINITY, |k| sim.velocity(k)),
    )
}

/// A flow in domain `j` whose velocity has an extremum passing the upper
/// (`upper`) or lower boundary by `overshoot` (negative: staying short by
/// that much), and stays inside the band before it. Built backwards: at a
/// phase `phi_m` near `phi_base` the state `v_m = V_b ± overshoot`,
/// `x_m` with zero acceleration (`c_j x_m = A0 cos phi_m - b_j - 2 d_j v_m`)
/// and the rate of the acceleration of the right sign (a maximum or a
/// minimum of v); the closed form run backwards by `back` gives the start.
/// Returns `(x0, v0, phi0, phi_m)`.
pub fn near_graze(
    sim: &Simulator<Paper>,
    j: usize,
    upper: bool,
    phi_base: f64,
    overshoot: f64,
) -> Option<(f64, f64, f64, f64)> {
    let p = sim.params();
    let (lo, hi) = band(sim, j);
    let sign = if upper { 1.0 } else { -1.0 };
    let vm = if upper { hi } else { lo } + sign * overshoot;
    let co = Paper::coefficients(p, j);
    let a0 = sim.oscillator().amplitude;
    for k in 0..628 {
        let phi_m = phi_base + 0.01 * k as f64;
        let xm = (a0 * phi_m.cos() - co.b - co.two_d * vm) / co.c;
        let [acc, rate] = Paper::normal_field(p, j, xm, vm, phi_m);
        debug_assert!(acc.abs() < 1e-12);
        // A maximum needs a' < 0, a minimum a' > 0, clearly.
        if sign * rate > -1e-3 {
            continue;
        }
        for back in [2.0, 1.0, 0.5, 0.25] {
            let phi0 = phi_m - back;
            let [x0, v0] = Paper::flow(p, j, xm, vm, phi_m, phi0);
            // Strictly inside the band from the start until just before the extremum.
            let inside = |v: f64| v > lo && v < hi;
            let clear = (0..2000).all(|i| {
                let phi = phi0 + back * i as f64 / 2000.0;
                inside(Paper::flow(p, j, xm, vm, phi_m, phi)[1])
            });
            if clear && inside(v0) {
                return Some((x0, v0, phi0, phi_m));
            }
        }
    }
    None
}
