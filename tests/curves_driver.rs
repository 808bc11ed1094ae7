//! The curves run on the paper model, box W ∈ [0.2, 8], Q0 ∈ [0, 180],
//! with `--at Q0=40,100,150`, checked against independent computations:
//!
//! * every reported curve point is re-solved by Newton at its parameters
//!   (from the curve's switching points) and satisfies its condition to
//!   1e-10, and the re-solved motion is the curve's to 1e-8;
//! * a sweep along W at each `--at` line locates transitions (every
//!   non-smooth branch end, every eigenvalue bifurcation, every grazing of
//!   the no-motion regime): each matches a curve crossing of the same kind,
//!   boundary and motion to 1e-10 in W (both locate the zero of one smooth
//!   margin: 5e-13 apart at most, as measured); each crossing matches a sweep
//!   transition, or the motion it belongs to is proved to exist there by
//!   Newton (the sweep did not find that branch: the test says which).
//!
//! Transitions of motions of more than 12 mappings (the period-adding
//! cascades near the border of `P_{3_33 4_33}`) are not traced by default
//! and are left out of the comparison. The run costs about a minute in
//! the test profile.
//!
//! The sweep comparison failed (and was ignored) until issue 12: at
//! Q0 = 100 the sweep located the grazing of Σ2 that ends
//! `P_{3_31 1_11 3_13 4_33}` at a W that depended on its grid (7.98672047,
//! 7.98671968, 7.986719686508 against the curve's 7.986719674157211).
//! Within the event search's graze tolerance the margin was 0 rather than
//! the closed form's, and regula falsi, stopping on that exact zero,
//! reported its last positive trial (`tests/sweep_grazing.rs`). Past that,
//! the branch of `P_{3_31 0_11 1_11 3_13 4_33}` ended at a grazing of Σ1
//! that no curve has (W = 3.3279422): near its end, where `1_11` shrinks
//! to nothing, the locating trials converged onto the solutions in which
//! `1_11` takes no time; they are now corrected from the chord of the
//! bracket (`bifurcation::continuation`).

mod common;

use std::sync::OnceLock;

use common::cycle::codim2_residuals;

use stickslip::bifurcation::curve::{
    condition_value, crossings, Condition, Curve, CurveOptions, CurvePoint, Line, Plane,
};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::admissible::ViolationKind;
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, Termination};
use stickslip::study::curves::{traced, CurveSet, CurvesOptions, CurvesSettings};
use stickslip::study::sweep::{sweep, Sweep, SweepOptions};
use stickslip::ParamSet;

const AT: [f64; 3] = [40.0, 100.0, 150.0];

fn options() -> CurvesOptions {
    CurvesOptions {
        x: ("W".into(), [0.2, 8.0]),
        y: ("Q0".into(), [0.0, 180.0]),
        seeds: Vec::new(),
        at: AT.iter().map(|&v| Line::Y(v)).collect(),
    }
}

struct Run {
    plane: Plane,
    set: CurveSet,
    curves: Vec<Curve>,
}

/// One curves run shared by the tests.
fn run() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| {
        let base = Params::default();
        let opts = options();
        let plane = opts.plane::<Paper>(&base).expect("a valid box");
        let (set, curves) =
            traced::<Paper>(&base, &opts, &CurvesSettings::default()).expect("the run runs");
        assert!(!set.curves.is_empty(), "no curve traced");
        Run { plane, set, curves }
    })
}

fn at(plane: &Plane, x: f64, y: f64) -> Params {
    let mut p = Params::default();
    p.set(plane.x, x);
    p.set(plane.y, y);
    p
}

/// Whether a flow of `structure` from a boundary back to it lasts less
/// than 1e-6 in phase at `points` (an excursion about to vanish).
fn vanishing_excursion(
    structure: &stickslip::orbit::structure::Structure,
    points: &[stickslip::orbit::periodic::SwitchingPoint],
) -> bool {
    let shift = 2.0 * std::f64::consts::PI * structure.periods() as f64;
    structure.steps().iter().enumerate().any(|(k, &step)| {
        let mi = Paper::INFO.mappings[step];
        let b = stickslip::orbit::periodic::arrival(points, k, shift);
        mi.domain.is_some() && mi.from == mi.to && b.phase - points[k].phase < 1e-6
    })
}

/// Re-solve the motion of `curve` at `point` by Newton from the point's
/// switching points; its condition there (and the largest distance of the
/// re-solved switching points from the given ones).
fn resolved(plane: &Plane, curve: &Curve, point: &CurvePoint) -> Result<(f64, f64), String> {
    let base = Params::default();
    let Some(structure) = &curve.structure else {
        let v = condition_value::<Paper>(&base, plane, None, point, curve.condition)
            .map_err(|e| e.to_string())?;
        return Ok((v, 0.0));
    };
    let sim = Simulator::<Paper>::new(at(plane, point.x, point.y), SimOptions::default())
        .map_err(|e| e.to_string())?;
    let m = solve(
        &sim,
        structure.clone(),
        point.points.clone(),
        NewtonOptions {
            tolerance: 1e-13,
            max_iterations: 60,
        },
    );
    // On a grazing of an arrival (or a departure) the elimination is
    // singular at the curve itself: Newton there either says so or, with a
    // residual at rounding, moves the points by about the square root of
    // it (1e-8), and the condition with them. Check the point's own
    // residual and condition instead. The same holds near the end of a
    // local excursion that shrinks to nothing (a flow from a boundary back
    // to it lasting less than 1e-6 in phase: its arrival is all but
    // tangent; measured 1.7e-8 on the stick-onset curve of
    // `P_{3_31 1_12 2_22 1_21 3_13 4_33}` where `2_22` lasts 1.2e-7).
    let tangency = matches!(
        curve.condition,
        Condition::Margin {
            kind: ViolationKind::Arrival | ViolationKind::Departure,
            ..
        }
    ) || vanishing_excursion(structure, &point.points);
    if !m.termination.converged() || tangency {
        let p = at(plane, point.x, point.y);
        let solver = PeriodicSolver::<Paper>::new(structure.clone());
        let r = solver.residual(&p, &point.points);
        let l = PeriodicSolver::<Paper>::length_scale(&p, &point.points);
        let w = p.get(plane.x).abs().max(1.0);
        if !(tangency || matches!(m.termination, Termination::Singular { .. })) || r > 1e-10 * l * w
        {
            return Err(format!("Newton: {:?} (residual {r:e})", m.termination));
        }
        let v = condition_value::<Paper>(&base, plane, Some(structure), point, curve.condition)
            .map_err(|e| e.to_string())?;
        return Ok((v, 0.0));
    }
    // The same motion may come back with every phase shifted by 2πk.
    let tau = 2.0 * std::f64::consts::PI;
    let shift = ((m.points[0].phase - point.points[0].phase) / tau).round() * tau;
    let moved = m
        .points
        .iter()
        .zip(&point.points)
        .map(|(a, b)| (a.phase - shift - b.phase).abs().max((a.x - b.x).abs()))
        .fold(0.0, f64::max);
    let again = CurvePoint {
        x: point.x,
        y: point.y,
        points: m.points,
    };
    let v = condition_value::<Paper>(&base, plane, Some(structure), &again, curve.condition)
        .map_err(|e| e.to_string())?;
    Ok((v, moved))
}

#[test]
fn every_curve_point_satisfies_its_condition() {
    let r = run();
    let mut checked = 0;
    for (i, c) in r.curves.iter().enumerate() {
        assert_eq!(c.points.len(), r.set.curves[i].points.len());
        for (k, q) in c.points.iter().enumerate() {
            assert_eq!([q.x, q.y], r.set.curves[i].points[k], "curve {i} point {k}");
            let (v, moved) = resolved(&r.plane, c, q)
                .unwrap_or_else(|e| panic!("curve {i} point {k} at {:?}: {e}", [q.x, q.y]));
            assert!(
                v.abs() <= 1e-10,
                "curve {i} ({:?} of {:?}) point {k} at W = {}, Q0 = {}: condition {v:e}",
                c.kind,
                r.set.curves[i].structure,
                q.x,
                q.y
            );
            assert!(
                moved <= 1e-8,
                "curve {i} ({:?} of {:?}) point {k} at W = {}, Q0 = {}: Newton moved it by {moved:e}", c.kind, r.set.curves[i].structure, q.x, q.y
            );
            checked += 1;
        }
    }
    assert!(checked > 0);
}

/// A transition a sweep located: W, kind, boundary, motion.
#[derive(Debug)]
struct Located {
    w: f64,
    kind: &'static str,
    boundary: Option<String>,
    structure: String,
    /// What the sweep finds past it (branch ends only).
    to: Option<String>,
}

/// The number of mappings of `P_{...}`.
fn mappings(structure: &str) -> usize {
    structure.split_whitespace().count()
}

fn name(structure: &str, n: u32) -> String {
    if n > 1 {
        format!("{structure}^{n}")
    } else {
        structure.to_string()
    }
}

/// Every transition the sweep located: the non-smooth ends of every branch,
/// every eigenvalue bifurcation, every grazing of the no-motion regime.
fn located(s: &Sweep) -> Vec<Located> {
    let mut out = Vec::new();
    for b in s.branches.iter().filter(|b| mappings(&b.structure) <= 12) {
        for e in &b.ends {
            let kind = match e.reason.as_str() {
                "grazing" => "grazing",
                "stick_onset" => "stick_onset",
                "stick_vanishing" => "stick_vanishing",
                "passable_onset" => "passable_onset",
                _ => continue,
            };
            let structure = name(&b.structure, b.n);
            let to = s
                .transitions
                .iter()
                .find(|t| t.from == structure && t.value == e.value)
                .map(|t| t.to.clone());
            out.push(Located {
                w: e.value,
                kind,
                boundary: e.boundary.clone(),
                structure,
                to,
            });
        }
    }
    for f in s
        .bifurcations
        .iter()
        .filter(|f| mappings(&f.structure) <= 12)
    {
        out.push(Located {
            w: f.value,
            kind: f.kind.name(),
            boundary: None,
            structure: name(&f.structure, f.n),
            to: None,
        });
    }
    for t in s.transitions.iter().filter(|t| t.from == "NM") {
        out.push(Located {
            w: t.value,
            kind: t.kind.name(),
            boundary: t.boundary.clone(),
            structure: "NM".into(),
            to: Some(t.to.clone()),
        });
    }
    out
}

#[test]
fn sweeps_along_w_meet_the_curves_where_they_cross() {
    let r = run();
    let base = Params::default();
    let opts = CurveOptions::default();
    let mut unmatched_crossings = Vec::new();
    for &q0 in &AT {
        let mut p = base;
        p.set(r.plane.y, q0);
        let s = sweep::<Paper>(p, "W", 0.2, 8.0, 100, SweepOptions::default()).expect("sweep");
        let found = located(&s);
        // The crossings of this line, with their curves.
        let mut crossing = Vec::new();
        for (i, c) in r.set.curves.iter().enumerate() {
            for a in c.at.iter().filter(|a| a[1] == q0) {
                crossing.push((i, a[0]));
            }
        }
        let on_crossing = |t: &Located| {
            crossing.iter().any(|&(i, w)| {
                let c = &r.set.curves[i];
                c.kind.name() == t.kind
                    && c.boundary == t.boundary
                    && c.structure == t.structure
                    && (w - t.w).abs() <= 1e-10
            })
        };
        for t in &found {
            // A transition where a segment of `t`'s motion shrinks to
            // nothing degenerates its equations: its curve is traced from
            // the motion past it, which the sweep locates too (the same
            // transition from the other side, where it may bear the other
            // name: a stick onset is a passable onset seen from the motion
            // that passes) to 1e-10 on the curve.
            let other_side = || {
                found.iter().any(|u| {
                    Some(&u.structure) == t.to.as_ref()
                        && u.boundary == t.boundary
                        && (u.w - t.w).abs() <= 1e-7
                        && on_crossing(u)
                })
            };
            let hit = on_crossing(t) || other_side();
            if !on_crossing(t) && hit {
                eprintln!("Q0 = {q0}: {t:?} matched from the other side");
            }
            assert!(
                hit,
                "Q0 = {q0}: the sweep's {t:?} is on no curve crossing; crossings: {:?}",
                crossing
                    .iter()
                    .map(|&(i, w)| (w, r.set.curves[i].kind, &r.set.curves[i].structure))
                    .collect::<Vec<_>>()
            );
        }
        for &(i, w) in &crossing {
            let c = &r.set.curves[i];
            let hit = found.iter().any(|t| {
                c.kind.name() == t.kind
                    && c.boundary == t.boundary
                    && c.structure == t.structure
                    && (w - t.w).abs() <= 1e-10
            });
            if hit {
                continue;
            }
            // The sweep did not find this motion here: prove it exists.
            let exact = crossings::<Paper>(&base, &r.plane, &r.curves[i], Line::Y(q0), &opts);
            let q = exact
                .iter()
                .find(|q| (q.x - w).abs() <= 1e-12)
                .unwrap_or_else(|| panic!("curve {i}'s crossing W = {w} is not found again"));
            let (v, moved) = resolved(&r.plane, &r.curves[i], q)
                .unwrap_or_else(|e| panic!("curve {i} at W = {w}, Q0 = {q0}: no motion: {e}"));
            assert!(
                v.abs() <= 1e-10 && moved <= 1e-8,
                "curve {i} at W = {w}: {v:e}, {moved:e}"
            );
            unmatched_crossings.push(format!(
                "Q0 = {q0}, W = {w}: {} of {} (motion proved by Newton; the sweep did not follow its branch)",
                c.kind.name(),
                c.structure
            ));
        }
    }
    for line in &unmatched_crossings {
        eprintln!("{line}");
    }
}

#[test]
fn codim2_points_name_their_curves_and_ends() {
    let r = run();
    for (k, q) in r.set.codim2.iter().enumerate() {
        assert!(
            q.kinds.len() >= 2 || q.curves.len() >= 2,
            "codim-2 point {k}: {q:?}"
        );
        for &i in &q.curves {
            assert!(i < r.set.curves.len());
        }
    }
    for (i, c) in r.set.curves.iter().enumerate() {
        for e in [&c.from, &c.to].into_iter().flatten() {
            if e.reason == "codim2" {
                let k = e
                    .codim2
                    .unwrap_or_else(|| panic!("curve {i}: codim2 end unindexed"));
                assert!(r.set.codim2[k].curves.contains(&i));
                let q = &r.set.codim2[k];
                assert!((q.x - e.point[0]).abs() <= 1e-6 && (q.y - e.point[1]).abs() <= 1e-4);
            }
        }
    }
}

/// Every codimension-two end of the run holds its second condition to
/// 1e-9 of its scale. Until stop 36 the ends near the period-adding
/// cascade's accumulation at W = 7.2438890, Q0 = 46.741843 were let
/// through at 1e-5: one grazing curve's end there was once located only
/// to where the corrector converged (1.4e-6). No end of this run needs it
/// any more (the largest is at rounding, with stop 35's code too).
const BOUND: f64 = 1e-9;

#[test]
fn codim2_ends_satisfy_both_conditions() {
    let r = run();
    let ends = codim2_residuals::<Paper>(&Params::default(), &r.plane, &r.curves);
    for &(i, k, v) in &ends {
        let (c, e) = (&r.curves[i], &r.curves[i].ends[k]);
        // From the motion's conditions as the admissibility walk
        // computes them (not the tracer's bookkeeping), and reported so.
        let summary = if k == 0 {
            &r.set.curves[i].from
        } else {
            &r.set.curves[i].to
        };
        assert_eq!(summary.as_ref().and_then(|s| s.residual), Some(v));
        assert!(
            v <= BOUND,
            "curve {i} ({:?} of {:?}) end {k} at W = {}, Q0 = {} ({:?}): the second condition holds only to {v:e} of its scale",
            c.condition,
            r.set.curves[i].structure,
            e.at.x,
            e.at.y,
            e.reason
        );
    }
    assert!(ends.len() >= 40, "only {} codimension-two ends", ends.len());
}
