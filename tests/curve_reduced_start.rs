//! A transition where an excursion between two sticks shrinks to nothing
//! starts the reduced motion's curve.
//!
//! On `stribeck8` (`as = ak`: a stick's exit leaves with no acceleration) a
//! sweep along Q0 at W = 2.375 ends the branch of
//! `P_{7_76 6_65 5_51 0_11 1_11 0_11 5_15 6_56 7_67 8_77}` at a grazing on
//! Sigma1, where its excursion `1_11` between the two sticks shrinks to
//! nothing and the motion becomes the reduced one, `P_{7_76 6_65 5_51 0_11
//! 5_15 6_56 7_67 8_77}`, whose stick touches `as` there (the same sweep
//! ends that branch there as a stick vanishing). The split motion's own
//! system is singular at that point and the sweep locates it only to the
//! square root of its tolerance (the excursion still lasts about 1e-3 rad),
//! so no corrector converges from it: until stop 40 every such start was
//! reported as a failed start (30 of `stribeck8` W = 0.5…3 × Q0 = 1…12,
//! 35 of `stribeck::pl4`'s).
//!
//! 1. `reduced_start` carries the transition to the reduced motion: the
//!    structure the sweep names beyond it, the merged stick's smooth margin,
//!    on the sweep's line (W held exactly), within 1e-8 in Q0 of where the
//!    sweep ends the reduced branch on its own (a regular location); there
//!    `PeriodicSolver` re-solves the reduced motion to the same points and
//!    the stick's margin is zero. A condition of the excursion that is not
//!    its vanishing (a contact with another boundary) is not carried.
//! 2. A run over a small box around it has no failed start (20 before
//!    stop 40: the split motion's starts fail, and the reduced motion's
//!    curve, traced from its own transition, passes there) and one
//!    stick-vanishing curve of the reduced motion.
//! 3. Where the reduced motion's curve is found by no line, it is traced
//!    from the carried start, after the lines: on W = 0.95…1.02 × Q0 =
//!    4.4…5.0 the passable onsets of the period-2 `T'T` (`T` = `7_76 6_65
//!    5_51 0_11 5_15 6_56 7_67 8_77`, `T'` with its stick split by `5_11`)
//!    carry to a period-2 `T T` whose halves differ, not `T` twice: its
//!    stick-vanishing curve, re-solved by `PeriodicSolver` at its points,
//!    has halves apart by more than 1e-6 (over the middle half of the
//!    curve: it ends where they meet, at `T`'s period doubling) and the
//!    margin zero to 1e-10 of its scale. The curves the run found before are all still found
//!    (traced as soon as the start failed, that curve cost four of them).

mod common;

use common::sweep_ends::branch_ends;
use stickslip::bifurcation::curve::{
    condition_at_transition, condition_scale, condition_value, reduced_start, Condition,
    CurveOptions, CurvePoint, Line, Plane,
};
use stickslip::bifurcation::TransitionKind;
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::admissible::ViolationKind;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver};
use stickslip::orbit::structure::Structure;
use stickslip::study::curves::{curves_with, CurvesOptions, CurvesSettings};
use stickslip::study::sweep::{sweep, SweepOptions};

const SPLIT: &str = "P_{7_76 6_65 5_51 0_11 1_11 0_11 5_15 6_56 7_67 8_77}";
const REDUCED: &str = "P_{7_76 6_65 5_51 0_11 5_15 6_56 7_67 8_77}";
const W: f64 = 2.375;

fn plane() -> Plane {
    Plane {
        x: stribeck8::Params::index_of("W").unwrap(),
        y: stribeck8::Params::index_of("Q0").unwrap(),
        x_range: [2.3, 2.45],
        y_range: [5.0, 5.4],
    }
}

fn at(w: f64, q: f64) -> stribeck8::Params {
    stribeck8::Params {
        W: w,
        Q0: q,
        ..stribeck8::Params::default()
    }
}

#[test]
fn a_vanishing_excursion_is_carried_to_the_reduced_motion() {
    let info = Stribeck8::INFO;
    let boundary = |label: &str| info.boundaries.iter().position(|b| b.label == label);
    let sigma1 = boundary("Sigma1").unwrap();
    let s = sweep::<Stribeck8>(at(W, 5.2), "Q0", 5.15, 5.25, 20, SweepOptions::default())
        .expect("sweep");
    let grazing = branch_ends(&s, SPLIT, "grazing");
    let [(q_split, points)] = grazing.as_slice() else {
        panic!("one grazing end of {SPLIT}: {grazing:?}");
    };
    let vanishing = branch_ends(&s, REDUCED, "stick_vanishing");
    let [(q_reduced, _)] = vanishing.as_slice() else {
        panic!("one stick-vanishing end of {REDUCED}: {vanishing:?}");
    };
    let split = Structure::parse(info, SPLIT, 1).unwrap();
    let p = at(W, *q_split);
    let condition =
        condition_at_transition::<Stribeck8>(&p, &split, points, TransitionKind::Grazing)
            .expect("a condition at the grazing");
    let start = CurvePoint {
        x: W,
        y: *q_split,
        points: points.clone(),
    };
    let tolerance = CurveOptions::default().tolerance;
    let base = stribeck8::Params::default();
    let r = reduced_start::<Stribeck8>(&base, &plane(), &split, &start, condition, 0, tolerance)
        .expect("the grazing is the excursion's vanishing");
    assert_eq!(r.structure.notation(info), REDUCED);
    assert_eq!(
        r.condition,
        Condition::Margin {
            kind: ViolationKind::StickEnd,
            // The stick `0_11`: fifth applied (the notation reads right to left).
            segment: 4,
            boundary: Some(sigma1),
        }
    );
    assert_eq!(r.point.x, W, "on the sweep's line");
    assert!(
        (r.point.y - q_reduced).abs() <= 1e-8,
        "Q0 {} against the reduced branch's end at {q_reduced}",
        r.point.y
    );
    // Independently: the reduced motion re-solved there has the same
    // switching points, and its stick's margin vanishes.
    let p = at(W, r.point.y);
    let mut solved = r.point.points.clone();
    let mut solver = PeriodicSolver::<Stribeck8>::new(r.structure.clone());
    let done = solver.solve(&p, &mut solved, NewtonOptions::default());
    assert!(done.converged(), "{done:?}");
    for (a, b) in solved.iter().zip(&r.point.points) {
        assert!((a.x - b.x).abs() <= 1e-9 && (a.phase - b.phase).abs() <= 1e-9);
    }
    let here = CurvePoint {
        points: solved,
        ..r.point.clone()
    };
    let v = condition_value::<Stribeck8>(&base, &plane(), Some(&r.structure), &here, r.condition)
        .expect("the margin");
    let scale = condition_scale::<Stribeck8>(&p, r.condition, Some(&r.structure), &here.points);
    assert!(v.abs() <= 1e-10 * scale, "margin {v:e} of {scale:e}");
    // The excursion's contact with another boundary is no vanishing.
    let other = Condition::Margin {
        kind: ViolationKind::Interior,
        segment: 5,
        boundary: boundary("Sigma2"),
    };
    assert!(
        reduced_start::<Stribeck8>(&base, &plane(), &split, &start, other, 0, tolerance).is_none()
    );
}

#[test]
fn a_run_across_the_vanishing_excursion_has_no_failed_start() {
    let opts = CurvesOptions {
        x: ("W".into(), plane().x_range),
        y: ("Q0".into(), plane().y_range),
        seeds: vec![Line::X(W)],
        at: Vec::new(),
    };
    let settings = CurvesSettings {
        spread: 0,
        edges: false,
        ..CurvesSettings::default()
    };
    let set = curves_with::<Stribeck8>(&stribeck8::Params::default(), &opts, &settings)
        .expect("the run runs");
    assert!(set.failed_starts.is_empty(), "{:#?}", set.failed_starts);
    let reduced = set
        .curves
        .iter()
        .filter(|c| c.kind == TransitionKind::StickVanishing && c.structure == REDUCED)
        .count();
    assert_eq!(reduced, 1, "one stick-vanishing curve of {REDUCED}");
}

const T: &str = "P_{7_76 6_65 5_51 0_11 5_15 6_56 7_67 8_77}";

#[test]
fn a_reduced_motion_no_line_finds_is_traced_from_the_carried_start() {
    use stickslip::study::curves::traced;
    let base = stribeck8::Params::default();
    let info = Stribeck8::INFO;
    let opts = CurvesOptions {
        x: ("W".into(), [0.95, 1.02]),
        y: ("Q0".into(), [4.4, 5.0]),
        seeds: Vec::new(),
        at: Vec::new(),
    };
    // The lines and the carried starts alone (branch switching at the
    // codimension-two points, since stop 41, adds curves of its own:
    // `tests/curve_partner.rs`).
    let settings = CurvesSettings {
        max_partners: 0,
        ..CurvesSettings::default()
    };
    let (set, curves) = traced::<Stribeck8>(&base, &opts, &settings).unwrap();
    let plane = opts.plane::<Stribeck8>(&base).unwrap();
    assert!(set.failed_starts.is_empty(), "{:#?}", set.failed_starts);
    let name = |c: &stickslip::bifurcation::curve::Curve| {
        c.structure
            .as_ref()
            .map(|s| (s.notation(info), s.periods()))
    };
    // Found by the lines (stop 39's run found these ten, and nothing else).
    let kinds: Vec<(TransitionKind, Option<(String, u32)>)> =
        curves.iter().map(|c| (c.kind, name(c))).collect();
    let inner = &T[3..T.len() - 1];
    let tt = format!("(P_{{{inner}}})^{{×2}}");
    for (kind, structure, periods) in [
        (TransitionKind::StickVanishing, T, 1),
        (TransitionKind::Grazing, T, 1),
        (TransitionKind::PeriodDoubling, T, 1),
        (
            TransitionKind::Fold,
            "P_{7_76 6_65 5_51 0_11 5_11 0_11 5_15 6_56 7_67 8_77}",
            1,
        ),
        (TransitionKind::StickVanishing, tt.as_str(), 2),
    ] {
        assert!(
            kinds.contains(&(kind, Some((structure.to_string(), periods)))),
            "{kind:?} of {structure}^{periods} in {kinds:#?}"
        );
    }
    assert_eq!(curves.len(), 11, "{kinds:#?}");
    // The period-2 motion's curve: its halves differ, its stick touches.
    let c = curves
        .iter()
        .find(|c| c.kind == TransitionKind::StickVanishing && name(c).is_some_and(|n| n.1 == 2))
        .unwrap();
    let s = c.structure.as_ref().unwrap();
    let h = s.len() / 2;
    // (At its end at `T`'s period doubling the halves meet: the middle half
    // of the curve.)
    let n = c.points.len();
    for q in c.points[n / 4..3 * n / 4].iter().step_by(5) {
        let p = at(q.x, q.y);
        let mut pts = q.points.clone();
        let mut solver = PeriodicSolver::<Stribeck8>::new(s.clone());
        let done = solver.solve(&p, &mut pts, NewtonOptions::default());
        assert!(done.converged(), "{done:?}");
        let apart = (0..h).fold(0.0f64, |m, j| m.max((pts[j + h].x - pts[j].x).abs()));
        assert!(apart > 1e-6, "halves {apart:e} apart at ({}, {})", q.x, q.y);
        let here = CurvePoint {
            points: pts,
            ..q.clone()
        };
        let v = condition_value::<Stribeck8>(&base, &plane, Some(s), &here, c.condition).unwrap();
        let scale = condition_scale::<Stribeck8>(&p, c.condition, Some(s), &here.points);
        assert!(v.abs() <= 1e-10 * scale, "margin {v:e} of {scale:e}");
    }
}
