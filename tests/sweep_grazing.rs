//! A grazing located by a sweep is the zero of the smooth closed-form
//! margin, independent of the sweep's grid (issue 12).
//!
//! On the paper model at Q0 = 100, the flow `1_11` of `P_{3_31 1_11 3_13
//! 4_33}` grazes Σ2 at W = 7.986719674157211 (the two-parameter curve's
//! crossing, `tests/curves_driver.rs`). Within the event search's graze
//! tolerance (`|v − V_2| ≤ 1e-10` at the velocity's maximum, W within
//! about 6e-11 above the zero) the search reports a graze where the closed
//! form keeps the flow off Σ2 by a positive margin; the margin was then
//! taken as 0, and the sweep's regula falsi, stopping on that exact zero,
//! reported its last positive trial: 7.98671967558 on two grids,
//! 7.98671967431 on a third, up to 1.4e-9 off. Both sides of the
//! transition must now be located within 1e-10 of the curve on any grid,
//! and the margin must be the closed form's inside the tolerance band.

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::admissible::{worst_margin, ViolationKind};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::{sweep, Sweep, SweepOptions};
use stickslip::ParamSet;

/// The curve's crossing of Q0 = 100 (`tests/curves_driver.rs`).
const CURVE: f64 = 7.986719674157211;
const GRAZING: &str = "P_{3_31 1_11 3_13 4_33}";
/// The motion on the other side, whose own transition (its segment `2_22`
/// shrinking) was always located on the curve.
const OTHER: &str = "P_{3_31 1_12 2_22 1_21 3_13 4_33}";

fn base() -> Params {
    let mut p = Params::default();
    p.set(Params::index_of("Q0").unwrap(), 100.0);
    p
}

fn run(from: f64, to: f64, count: usize) -> Sweep {
    sweep::<Paper>(base(), "W", from, to, count, SweepOptions::default()).expect("sweep")
}

/// The grazing of Σ2 near W = 7.9867 that ends `from`, located by the
/// sweep (`P_{3_31 1_11 3_13 4_33}` grazes Σ2 near W = 3.73 too).
fn grazing(s: &Sweep, from: &str) -> f64 {
    let t: Vec<_> = s
        .transitions
        .iter()
        .filter(|t| {
            t.from == from
                && t.kind.name() == "grazing"
                && t.boundary.as_deref() == Some("Sigma2")
                && (t.value - CURVE).abs() < 1e-4
        })
        .collect();
    assert_eq!(t.len(), 1, "{from}: {:?}", s.transitions);
    t[0].value
}

/// Three grids (those that located it at 7.98671967558, 7.98671967558 and
/// 7.98671967431 before the fix): every one locates both sides within 1e-10
/// of the curve, and so of each other.
#[test]
fn the_sweep_locates_the_grazing_on_the_curve_on_every_grid() {
    let mut seen = Vec::new();
    for (from, to, count) in [(7.9, 8.0, 11), (7.9, 8.0, 7), (7.95, 8.0, 13)] {
        let s = run(from, to, count);
        let (w, other) = (grazing(&s, GRAZING), grazing(&s, OTHER));
        eprintln!(
            "W = {from}:{to}:{count}: {w:.15} ({:+e}), from the other side {other:.15} ({:+e})",
            w - CURVE,
            other - CURVE
        );
        assert!(
            (w - CURVE).abs() <= 1e-10,
            "grid {from}:{to}:{count}: {GRAZING} grazes Σ2 at {w}, the curve at {CURVE}"
        );
        assert!((other - CURVE).abs() <= 1e-10, "{OTHER}: {other}");
        seen.push(w);
    }
    let spread = seen.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
        - seen.iter().fold(f64::INFINITY, |a, &b| a.min(b));
    assert!(spread <= 1e-10, "{seen:?}");
}

/// Just above the zero, inside the event search's graze band, the margin
/// the sweep sees is the closed form's (positive and linear in W, as just
/// outside the band), not the 0 of an early contact.
#[test]
fn the_margin_is_smooth_through_the_graze_tolerance() {
    let s = run(7.9, 8.0, 11);
    let b = s
        .branches
        .iter()
        .find(|b| b.structure == GRAZING)
        .expect("the branch");
    // Its point nearest the grazing, phases made increasing again.
    let near = b
        .points
        .iter()
        .min_by(|p, q| (p.value - CURVE).abs().total_cmp(&(q.value - CURVE).abs()))
        .unwrap();
    let mut points: Vec<SwitchingPoint> = near.points.clone();
    for k in 1..points.len() {
        while points[k].phase <= points[k - 1].phase {
            points[k].phase += std::f64::consts::TAU;
        }
    }
    let structure = Structure::parse(Paper::INFO, GRAZING, 1).unwrap();
    let w = Params::index_of("W").unwrap();
    let margin = |dw: f64, points: &mut Vec<SwitchingPoint>| {
        let mut p = base();
        p.set(w, CURVE + dw);
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).unwrap();
        let m = solve(
            &sim,
            structure.clone(),
            points.clone(),
            NewtonOptions {
                tolerance: 1e-13,
                max_iterations: 60,
            },
        );
        assert!(
            m.termination.converged(),
            "W = {}: {:?}",
            CURVE + dw,
            m.termination
        );
        *points = m.points;
        let worst = worst_margin(&sim, &structure, points).unwrap();
        assert_eq!(
            (worst.kind, worst.boundary),
            (ViolationKind::Interior, Some(2)),
            "W = {}: {worst:?}",
            CURVE + dw
        );
        worst.margin
    };
    // Outside the band (margin about 3e-10): the slope of the margin in W.
    let (m0, m1) = (margin(2e-10, &mut points), margin(4e-10, &mut points));
    let slope = (m1 - m0) / 2e-10;
    assert!(slope > 0.1, "{m0:e} {m1:e}");
    for dw in [5e-11, 3e-11, 1e-11, 5e-12] {
        let m = margin(dw, &mut points);
        let linear = m0 + slope * (dw - 2e-10);
        eprintln!("W = CURVE + {dw:e}: margin {m:e} (linear {linear:e})");
        assert!(
            m > 0.0 && (m - linear).abs() <= 1e-13,
            "W = CURVE + {dw:e}: margin {m:e}, expected {linear:e}"
        );
    }
}

/// The grid of `tests/curves_driver.rs` (W = 0.2 : 8 in 100 values), which
/// located the grazing at 7.986719686508 before the fix, and ended the
/// branch of `P_{3_31 0_11 1_11 3_13 4_33}` at a grazing of Σ1 that no
/// curve has (W = 3.3279422): its end is where `1_11` shrinks to nothing,
/// and the locating trials there converged onto the solutions in which
/// `1_11` takes no time (every margin of which is violated). It ends at the
/// stick onset where the motion without `1_11` has its passable onset.
#[test]
fn the_curves_driver_grid_locates_both_ends_on_the_curves() {
    let s = run(0.2, 8.0, 100);
    let w = grazing(&s, GRAZING);
    assert!((w - CURVE).abs() <= 1e-10, "{GRAZING} grazes Σ2 at {w}");
    let loop_ = "P_{3_31 0_11 1_11 3_13 4_33}";
    let onset = s
        .transitions
        .iter()
        .find(|t| t.from == "P_{3_31 0_11 3_13 4_33}" && t.to == loop_ && t.value < 3.4)
        .expect("the passable onset near W = 3.328")
        .value;
    let ends: Vec<_> = s
        .transitions
        .iter()
        .filter(|t| t.from == loop_ && (t.value - onset).abs() < 1e-3)
        .collect();
    assert!(!ends.is_empty(), "{:?}", s.transitions);
    for t in ends {
        eprintln!("{t:?} (passable onset at {onset})");
        assert!(
            t.kind.name() == "stick_onset"
                && t.to == "P_{3_31 0_11 3_13 4_33}"
                && (t.value - onset).abs() <= 1e-7,
            "{t:?}, the passable onset at {onset}"
        );
    }
}
