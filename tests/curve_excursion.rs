//! A curve whose motion loses an excursion between two sticks, where the
//! motion is one born at a period doubling: on `stribeck8` the period-2
//! motion `T'T` (`T` = `7_76 6_65 5_51 0_11 5_15 6_56 7_67 8_77`, `T'` the
//! same with the stick split by an excursion `0_11 1_11 0_11`) has a fold
//! curve along which the excursion shrinks to nothing. The reduced motion
//! `T T` has two equal halves there and its system is singular (a branch
//! point), so the end is solved on `T` with its period-doubling test
//! function and its stick touching `±as`: the point where `T`'s
//! period-doubling and stick-vanishing curves meet. Until this stop the
//! curve crawled 1.1e-2 of the box short of it ("the grazing margin of
//! segment 13 on Sigma1 is 7.4e-8 there and falling").
//!
//! The box is W = 1.85…2.0 × Q0 = 4.4…4.7 since stop 29: the sweeps of
//! the smaller W = 1.85…1.95 × Q0 = 4.45…4.7 no longer start that fold
//! once the walk stopped reading a stick starting at `as` by rounding as
//! one ending at once (`tests/stick_onset_start.rs`).
//!
//! Checked independently: `T`'s period-doubling curve, traced in the same
//! run on its own condition, ends at the same point; and there `T`'s
//! mapping equations, `det(I + DP)` and its stick's margin vanish, by the
//! public evaluators.

mod common;

use common::cycle::{fold_ends, held, traced_wq, worst_residual};
use stickslip::bifurcation::curve::{Condition, CurvePoint};
use stickslip::bifurcation::TransitionKind;
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::admissible::ViolationKind;
use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::orbit::structure::Structure;
use stickslip::MappingKind;

#[test]
fn a_curve_whose_excursion_between_sticks_vanishes_ends_at_the_period_doubling_it_was_born_at() {
    let base = stribeck8::Params::default();
    let (curves, plane) = traced_wq::<Stribeck8>(&base, [1.85, 2.0], [4.4, 4.7]);
    let info = Stribeck8::INFO;
    let mut solved = Vec::new();
    for (s, e) in fold_ends(&curves) {
        let pts = &e.at.points;
        let m = pts.len();
        let steps = s.steps();
        // The excursion: a zero-length segment between two sticks.
        let Some(k) = (1..m - 1).find(|&k| {
            (pts[k].x - pts[k + 1].x).abs() <= 1e-12
                && (pts[k].phase - pts[k + 1].phase).abs() <= 1e-12
                && info.mappings[steps[k - 1]].kind == MappingKind::Stick
                && info.mappings[steps[k + 1]].kind == MappingKind::Stick
        }) else {
            continue;
        };
        // The reduced motion by hand: the excursion and the stick
        // before it dropped (the stick after it goes on to the same
        // exit), starting at that stick.
        let mut reduced: Vec<usize> = steps[k + 1..].to_vec();
        reduced.extend_from_slice(&steps[..k - 1]);
        let mut q: Vec<SwitchingPoint> = pts[k - 1..k].to_vec();
        let shift = std::f64::consts::TAU * s.periods() as f64;
        q.extend(pts[k + 2..].iter().copied());
        q.extend(pts[..k - 1].iter().map(|p| SwitchingPoint {
            x: p.x,
            phase: p.phase + shift,
        }));
        let half = reduced.len() / 2;
        assert_eq!(
            reduced[..half],
            reduced[half..],
            "the reduced motion is T T"
        );
        let t = Structure::from_indices(info, &reduced[..half], s.periods() / 2).unwrap();
        let point = CurvePoint {
            x: e.at.x,
            y: e.at.y,
            points: q[..half].to_vec(),
        };
        let mut p = base;
        p.W = e.at.x;
        p.Q0 = e.at.y;
        // T's motion: its mapping equations, its period doubling, its
        // stick touching `±as`.
        let r = worst_residual::<Stribeck8>(&p, t.steps(), &point.points, t.periods());
        assert!(r <= 1e-10, "T's mapping equations: {r:e}");
        let t_shift = shift / 2.0;
        // The other half repeats the first (to the end's tolerance).
        for i in 0..half {
            assert!((q[half + i].x - q[i].x).abs() <= 1e-8, "{i}");
            assert!(
                (q[half + i].phase - q[i].phase - t_shift).abs() <= 1e-8,
                "{i}"
            );
        }
        let stick = info.mappings[t.steps()[0]].from;
        for condition in [
            Condition::Eigen(TransitionKind::PeriodDoubling),
            Condition::Margin {
                kind: ViolationKind::StickEnd,
                segment: 0,
                boundary: Some(stick),
            },
        ] {
            let r = held::<Stribeck8>(&base, &plane, &t, &point, condition);
            assert!(r <= 1e-10, "{condition:?}: {r:e} of its scale");
        }
        // Independently: T's period-doubling curve ends there.
        let canonical = t.canonical(info).0;
        let met = curves.iter().any(|d| {
            d.condition == Condition::Eigen(TransitionKind::PeriodDoubling)
                && d.structure
                    .as_ref()
                    .is_some_and(|u| u.canonical(info).0 == canonical)
                && d.ends
                    .iter()
                    .any(|f| (f.at.x - e.at.x).abs() <= 1e-8 && (f.at.y - e.at.y).abs() <= 1e-8)
        });
        assert!(
            met,
            "T's period doubling does not end at {:?}",
            (e.at.x, e.at.y)
        );
        solved.push((e.at.x, e.at.y));
    }
    assert!(
        !solved.is_empty(),
        "no fold curve loses an excursion between sticks"
    );
}
