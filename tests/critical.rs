//! Flows across the damping-regime boundary `d_j^2 - c_j` in [-1e-6, 1e-6],
//! and exactly 0, against an independent reference: the Taylor series in the
//! elapsed time of the solution of `x'' + 2 d_j x' + c_j x = A0 cos(W t) - b_j`,
//! integrated in short, well-conditioned steps (`tests/common/taylor.rs`). Relative error <= 1e-12.
//! Both paths are covered: the run-time regime switch (`homogeneous::general`,
//! all parameters free) and the regime fixed at build time by a scene.

mod common;

use common::rng;
use common::taylor::Ode;
use rand::Rng;
use stickslip::models::paper::{Paper, Params};
use stickslip::{Model, Regime};

stickslip::model! {
    /// A model whose domains sit at, just above and just below critical damping
    /// (c = 4, d_j = 2, 2 + 1e-7, 2 - 1e-7) and one with d_j = 0.5.
    model regimes {
        param d = 2.0;
        param c = 4.0, > 0;
        param Q0 = 3.0;
        param W = 1.3, > 0;
        param V = 1.0;
        oscillator { mass: 1.0, damping: d, stiffness: c, forcing: Q0, frequency: W }
        boundary Sigma1: v = V, stick 2.0;
        boundary Sigma2: v = V + 1.0;
        boundary Sigma3: v = V - 1.0;
        domain 1: Sigma1 < v < Sigma2 => 1.0;
        domain 2: v > Sigma2 => 1.0 + 2.0e-7 * (v - V - 1.0);
        domain 3: Sigma3 < v < Sigma1 => -1.0 - 2.0e-7 * (v - V);
        domain 4: v < Sigma3 => -1.0 + 2.0e-7 - 3.0 * (v - V + 1.0);
        scene fixed { free: W, Q0; }
    }
}

fn check_flow<M: Model>(p: &M::Params, j: usize, r: &mut rand::rngs::StdRng, what: &str) -> f64 {
    let co = M::coefficients(p, j);
    let osc = M::oscillator(p);
    let mut worst = 0.0f64;
    for &tau in &[0.05, 0.3, 0.9, 1.6] {
        let (x0, v0, phi0) = (
            r.gen_range(-2.0..2.0),
            r.gen_range(-3.0..3.0),
            r.gen_range(0.0..6.0),
        );
        let phi1 = phi0 + osc.frequency * tau;
        let [x, v] = M::flow(p, j, x0, v0, phi0, phi1);
        // The reference uses the elapsed time the generated code sees.
        let t = (phi1 - phi0) / osc.frequency;
        // The Taylor reference in 64 sub-steps, so that every series is well
        // conditioned in `f64`.
        let (xr, vr) = Ode::of::<M>(p, j).taylor_in(64, x0, v0, phi0, t);
        let err = ((x - xr).powi(2) + (v - vr).powi(2)).sqrt() / (xr * xr + vr * vr).sqrt();
        worst = worst.max(err);
        assert!(
            err <= 1e-12,
            "{what}, domain {j}, tau {tau}: flow ({x}, {v}) vs reference ({xr}, {vr}): relative error {err:e}; inputs {:?}", (co, osc, x0, v0, phi0, phi1)
        );
    }
    worst
}

#[test]
fn runtime_regime_switch_is_exact_across_critical_damping() {
    let mut r = rng(3);
    let mut worst = 0.0f64;
    for j in 0..Paper::INFO.domains.len() {
        for &delta in &[
            -1e-6, -1e-8, -1e-10, -1e-12, -1e-14, 0.0, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6,
        ] {
            let mut p = Params {
                d: 0.0,
                ..Params::default()
            };
            let half_slope = Paper::coefficients(&p, j).two_d / 2.0;
            p.d = (p.c + delta).sqrt() - half_slope;
            let dj = Paper::coefficients(&p, j).two_d / 2.0;
            if delta == 0.0 {
                p.c = dj * dj;
                assert_eq!(Paper::coefficients(&p, j).regime(), Regime::Critical);
            }
            worst = worst.max(check_flow::<Paper>(
                &p,
                j,
                &mut r,
                &format!("d_j^2 - c = {delta:e}"),
            ));
        }
    }
    eprintln!("worst relative error: {worst:e}");
}

#[test]
fn build_time_regimes_are_exact_near_critical_damping() {
    use regimes::fixed::{Fixed, Params as FixedParams};
    use regimes::{Params as FullParams, Regimes};
    let info = Fixed::INFO;
    let regime_of = |label: u32| {
        info.domains
            .iter()
            .find(|d| d.label == label)
            .and_then(|d| d.fixed_regime)
    };
    assert_eq!(regime_of(1), Some(Regime::Critical));
    assert_eq!(regime_of(2), Some(Regime::Overdamped));
    assert_eq!(regime_of(3), Some(Regime::Underdamped));
    assert_eq!(regime_of(4), Some(Regime::Underdamped));
    assert!(
        Regimes::INFO
            .domains
            .iter()
            .all(|d| d.fixed_regime.is_none()),
        "all parameters free: regime chosen at run time"
    );
    let mut r = rng(9);
    for j in 0..4 {
        for w in [0.2, 1.3, 7.0] {
            let fixed = FixedParams { W: w, Q0: 3.0 };
            let full = FullParams {
                W: w,
                ..FullParams::default()
            };
            check_flow::<Fixed>(&fixed, j, &mut r, &format!("scene, W = {w}"));
            check_flow::<Regimes>(&full, j, &mut r, &format!("full model, W = {w}"));
        }
    }
}
