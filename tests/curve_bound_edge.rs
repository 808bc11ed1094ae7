//! A box whose edge lies on a bound of the model's parameters: the damping
//! `d >= 0` of the paper model, on `d = 0`.
//!
//! A curve leaves the box where its corrected step lands beyond an edge,
//! and the end is then solved on that edge. Beyond `d = 0` nothing can be
//! evaluated (the parameters are invalid there), so until stop 43 the
//! corrector failed at every step that reached past the edge and the curve
//! ended as a `newton_failure` next to it ("the condition is not finite"):
//! on `--x d=0:1 --y Q0=60:80 --set W=3.5` 12 of 38 ends, and the curves'
//! starts on that edge, where the edge's sweep finds them, failed or were
//! traced a second time (19 curves, 5 failed starts). Now a step whose
//! corrector fails with its predictor outside the box is solved on the
//! edge it crosses (`Tracer::edge_past_predictor`).
//!
//! Checked: every end is on the box's edge or at a codimension-two point,
//! no start fails, no curve is traced twice, the ends on `d = 0` lie
//! exactly on it, and a sweep along Q0 at `d = 0` ends the same motions'
//! branches, with the same kind, within 1e-8 in Q0 of them.

mod common;

use common::sweep_ends::branch_ends;
use stickslip::bifurcation::curve::CurveEndReason;
use stickslip::bifurcation::TransitionKind;
use stickslip::models::paper::{Paper, Params};
use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
use stickslip::study::sweep::{sweep, SweepOptions};

fn kind_name(kind: TransitionKind) -> &'static str {
    match kind {
        TransitionKind::Grazing => "grazing",
        TransitionKind::PassableOnset => "passable_onset",
        TransitionKind::StickOnset => "stick_onset",
        TransitionKind::StickVanishing => "stick_vanishing",
        other => panic!("no margin kind: {other:?}"),
    }
}

#[test]
fn curves_leave_through_an_edge_on_a_parameter_bound() {
    let base = Params {
        W: 3.5,
        ..Params::default()
    };
    let opts = CurvesOptions {
        x: ("d".into(), [0.0, 1.0]),
        y: ("Q0".into(), [60.0, 80.0]),
        seeds: Vec::new(),
        at: Vec::new(),
    };
    let (set, curves) = traced::<Paper>(&base, &opts, &CurvesSettings::default()).unwrap();
    assert!(set.failed_starts.is_empty(), "{:?}", set.failed_starts);
    assert!(curves.len() >= 10, "{} curves", curves.len());
    let mut on_bound = Vec::new();
    for c in &curves {
        let name = c.structure.as_ref().unwrap().notation(Paper::INFO);
        for e in &c.ends {
            assert!(
                matches!(
                    e.reason,
                    CurveEndReason::BoxEdge | CurveEndReason::Codim2 { .. }
                ),
                "{:?} curve of {name} ends at ({}, {}): {:?}",
                c.kind,
                e.at.x,
                e.at.y,
                e.reason
            );
            if e.reason == CurveEndReason::BoxEdge && e.at.x <= 0.5 {
                assert_eq!(e.at.x, 0.0, "an end on d = 0 off it");
                on_bound.push((c.kind, name.clone(), e.at.y));
            }
        }
    }
    // No curve twice: two curves of one motion and kind end apart on d = 0.
    for (i, a) in on_bound.iter().enumerate() {
        for b in &on_bound[i + 1..] {
            assert!(
                (a.0, &a.1) != (b.0, &b.1) || (a.2 - b.2).abs() > 1e-6,
                "{:?} of {} twice, at Q0 = {} and {}",
                a.0,
                a.1,
                a.2,
                b.2
            );
        }
    }
    assert!(on_bound.len() >= 8, "{} ends on d = 0", on_bound.len());

    // The sweep along the edge.
    let mut p = base;
    p.d = 0.0;
    let s = sweep::<Paper>(p, "Q0", 75.5, 76.5, 40, SweepOptions::default()).expect("sweep");
    let mut matched = 0;
    for (kind, name, q0) in &on_bound {
        let ends = branch_ends(&s, name, kind_name(*kind));
        if ends.is_empty() {
            continue;
        }
        matched += 1;
        let nearest = ends
            .iter()
            .map(|(v, _)| (v - q0).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest <= 1e-8,
            "{kind:?} of {name} on d = 0 at Q0 = {q0}: the sweep's nearest end is {nearest:e} away"
        );
    }
    assert!(
        matched >= 10,
        "only {matched} of {} ends on d = 0 found by the sweep",
        on_bound.len()
    );
}
