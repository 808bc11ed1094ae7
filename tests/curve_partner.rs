//! Branch switching at a codimension-two point: from the end of a traced
//! curve where a second condition of its motion vanishes, the second
//! condition's curve (`partner_start`, then `trace`).
//!
//! On the paper model (Fig. 11's plane) the motion
//! `S = P_{3_31 0_11 3_13 4_33 3_31 0_11 3_13 4_33 3_33 4_33}^3` of the
//! period-adding cascade lives in a thin band between its grazing curve
//! and its passable-onset curve, which meet at the band's tip near
//! W = 3.5838, Q0 = 72.017. Until stop 41 a `curves` run over Fig. 11's box
//! traced the grazing curve (a line crosses it) and not the passable-onset
//! curve from the tip up to Q0 = 88.3: no line located it.
//!
//! Checked independently:
//!
//! 1. a sweep along W at Q0 = 80 ends the branch of `S` at a grazing and a
//!    passable onset; the grazing curve traced from the first ends at the
//!    tip, a codimension-two point whose second kind is the passable onset;
//! 2. the partner's start lies on the passable-onset side of nothing: its
//!    condition is another margin than the curve's own, and the curve's
//!    own (grazing) margin is positive there (the motion exists);
//! 3. the curve traced from it crosses Q0 = 80 within 1e-8 in W of the
//!    sweep's own passable onset there (its location is the sweep's, not
//!    the curve's), and ends at the tip, within 1e-8 of the box of the
//!    grazing curve's end;
//! 4. at points along it, `PeriodicSolver` re-solves the motion to the same
//!    switching points and the passable-onset margin is zero to 1e-10 of
//!    its scale.

mod common;

use common::sweep_ends::branch_ends;
use stickslip::bifurcation::curve::{
    codim2_places, condition_at_transition, condition_scale, condition_value, crossings,
    partner_start, trace, trace_watching, CurveEndReason, CurveOptions, CurvePoint, Line, Plane,
    PARTNER_STEP,
};
use stickslip::bifurcation::TransitionKind;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::{sweep, SweepOptions};

const S: &str = "P_{3_31 0_11 3_13 4_33 3_31 0_11 3_13 4_33 3_33 4_33}";
const Q0: f64 = 80.0;

fn plane() -> Plane {
    Plane {
        x: Params::index_of("W").unwrap(),
        y: Params::index_of("Q0").unwrap(),
        x_range: [3.0, 3.7],
        y_range: [65.0, 100.0],
    }
}

fn at(w: f64, q: f64) -> Params {
    Params {
        W: w,
        Q0: q,
        ..Params::default()
    }
}

#[test]
fn the_passable_onset_curve_is_switched_to_at_the_band_tip() {
    let info = Paper::INFO;
    let base = Params::default();
    let plane = plane();
    let opts = CurveOptions::default();
    let s =
        sweep::<Paper>(at(3.43, Q0), "W", 3.41, 3.45, 40, SweepOptions::default()).expect("sweep");
    let grazing = branch_ends(&s, S, "grazing");
    let [(w_graze, points)] = grazing.as_slice() else {
        panic!("one grazing end of {S}: {grazing:?}");
    };
    let onset = branch_ends(&s, S, "passable_onset");
    let [(w_onset, _)] = onset.as_slice() else {
        panic!("one passable-onset end of {S}: {onset:?}");
    };
    let structure = Structure::parse(info, S, 3).unwrap();
    let condition = condition_at_transition::<Paper>(
        &at(*w_graze, Q0),
        &structure,
        points,
        TransitionKind::Grazing,
    )
    .expect("a condition at the grazing");
    let start = CurvePoint {
        x: *w_graze,
        y: Q0,
        points: points.clone(),
    };
    let curve = trace::<Paper>(&base, &plane, Some(&structure), &start, condition, &opts)
        .expect("the grazing curve");
    assert_eq!(curve.kind, TransitionKind::Grazing);
    // 1. Its end at the band's tip.
    let places = codim2_places(&curve);
    let place = places
        .iter()
        .find(|p| (p.at.y - 72.0168).abs() < 0.01)
        .copied()
        .unwrap_or_else(|| panic!("an end at the tip: {:?}", curve.ends));
    let (kind, boundary, tip) = (place.kind, place.boundary, place.at);
    assert_eq!(kind, TransitionKind::PassableOnset);
    assert!(curve
        .ends
        .iter()
        .any(|e| e.at == *tip && e.reason == CurveEndReason::Codim2 { kind, boundary }));
    // 2. The partner's start.
    let partner =
        partner_start::<Paper>(&base, &plane, &curve, &place, PARTNER_STEP, opts.tolerance)
            .expect("a start of the second curve");
    assert_ne!(partner.condition, curve.condition);
    assert_eq!(partner.structure, structure);
    let own = condition_value::<Paper>(
        &base,
        &plane,
        Some(&structure),
        &partner.point,
        curve.condition,
    )
    .unwrap();
    assert!(own > 0.0, "the grazing margin {own:e} at the start");
    let moved = ((partner.point.x - tip.x) / 0.7).hypot((partner.point.y - tip.y) / 35.0);
    assert!(moved > 0.0 && moved <= 10.0 * PARTNER_STEP, "{moved:e}");
    // 3. The second curve: the sweep's passable onset on it, its end at the tip.
    // The grazing margin, small at the start, watched: the curve ends where
    // it vanishes.
    let second = trace_watching::<Paper>(
        &base,
        &plane,
        Some(&structure),
        &partner.point,
        partner.condition,
        Some(curve.condition),
        &opts,
    )
    .expect("the passable-onset curve");
    assert_eq!(second.kind, TransitionKind::PassableOnset);
    let cross = crossings::<Paper>(&base, &plane, &second, Line::Y(Q0), &opts);
    assert!(
        cross.iter().any(|q| (q.x - w_onset).abs() <= 1e-8),
        "crossings {:?} against the sweep's passable onset at W = {w_onset}",
        cross.iter().map(|q| q.x).collect::<Vec<_>>()
    );
    let meets = second.ends.iter().any(|e| {
        matches!(e.reason, CurveEndReason::Codim2 { .. })
            && ((e.at.x - tip.x) / 0.7).hypot((e.at.y - tip.y) / 35.0) <= 1e-8
    });
    assert!(meets, "an end at the tip {tip:?}: {:?}", second.ends);
    // 4. Its points re-solved.
    let n = second.points.len();
    assert!(n >= 4, "{n} points");
    for q in [n / 4, n / 2, 3 * n / 4].map(|k| &second.points[k]) {
        let p = at(q.x, q.y);
        let mut solved = q.points.clone();
        let mut solver = PeriodicSolver::<Paper>::new(structure.clone());
        let done = solver.solve(&p, &mut solved, NewtonOptions::default());
        assert!(done.converged(), "{done:?}");
        for (a, b) in solved.iter().zip(&q.points) {
            assert!((a.x - b.x).abs() <= 1e-9 && (a.phase - b.phase).abs() <= 1e-9);
        }
        let here = CurvePoint {
            points: solved,
            ..q.clone()
        };
        let v = condition_value::<Paper>(&base, &plane, Some(&structure), &here, second.condition)
            .unwrap();
        let scale = condition_scale::<Paper>(&p, second.condition, Some(&structure), &here.points);
        assert!(v.abs() <= 1e-10 * scale, "margin {v:e} of {scale:e}");
    }
}
