//! A fold curve of period-2 motions `T T` whose two halves merge: on
//! `stribeck8` W = 2.3…2.6 × Q0 = 1…3 (`T` = `7_76 6_65 5_51 0_11 5_15
//! 6_56 7_67 8_77`) the fold of `T T` runs into `T`'s period-doubling curve
//! at a degenerate period doubling. Until stop 28 the curve ended there as
//! a corrector failure ("Newton step 3e-9"), 5.7e-5 short of the point, the
//! halves still 0.03 apart.
//!
//! Checked: the curve now ends at a codimension-two point with `T`'s
//! period doubling, where `T`'s mapping equations and `det(I + DP_T)` hold
//! to 1e-10 and the motion's own fold test function to 1e-10 of their
//! scales (public evaluators). And independently: the test's own quadratic
//! extrapolation of the traced fold points in the halves' squared
//! difference, to zero difference, lies on `T`'s period-doubling curve
//! (the motion re-solved there by `PeriodicSolver`, its `det(I + DP_T)`
//! below 1e-10) and within 1e-10 of the end (of the box).

mod common;

use common::cycle::{held, traced_wq, worst_residual};
use stickslip::bifurcation::curve::{Condition, CurveEndReason, CurvePoint};
use stickslip::bifurcation::TransitionKind;
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::periodic::{
    monodromy, NewtonOptions, PeriodicSolver, SwitchingPoint, Termination,
};
use stickslip::orbit::structure::Structure;
use stickslip::ParamSet;

/// The squared difference of the two halves of a motion of `periods`
/// forcing periods (the second half's phases less half the cycle).
fn apart(points: &[SwitchingPoint], periods: u32) -> f64 {
    let h = points.len() / 2;
    let half = std::f64::consts::PI * f64::from(periods);
    (0..h)
        .map(|i| {
            let (a, b) = (points[i], points[i + h]);
            (b.x - a.x).powi(2) + (b.phase - a.phase - half).powi(2)
        })
        .sum()
}

#[test]
fn a_fold_of_period_two_motions_whose_halves_merge_ends_on_the_period_doubling_of_the_half() {
    let base = stribeck8::Params::default();
    let (wr, qr) = ([2.3, 2.6], [1.0, 3.0]);
    let (curves, plane) = traced_wq::<Stribeck8>(&base, wr, qr);
    let info = Stribeck8::INFO;
    let mut found = 0;
    for c in &curves {
        if c.condition != Condition::Eigen(TransitionKind::Fold) {
            continue;
        }
        let s = c.structure.as_ref().expect("a motion");
        for (e, last) in c.ends.iter().zip([0, c.points.len() - 1]) {
            let CurveEndReason::Codim2 {
                kind: TransitionKind::PeriodDoubling,
                ..
            } = e.reason
            else {
                continue;
            };
            found += 1;
            let (steps, periods) = (s.steps(), s.periods());
            let h = steps.len() / 2;
            assert_eq!(steps[..h], steps[h..], "two equal halves");
            let t = Structure::from_indices(info, &steps[..h], periods / 2).unwrap();
            let mut p = base;
            p.set(plane.x, e.at.x);
            p.set(plane.y, e.at.y);
            let half = CurvePoint {
                x: e.at.x,
                y: e.at.y,
                points: e.at.points[..h].to_vec(),
            };
            assert!(worst_residual::<Stribeck8>(&p, t.steps(), &half.points, t.periods()) < 1e-10);
            let pd = Condition::Eigen(TransitionKind::PeriodDoubling);
            let g = held::<Stribeck8>(&base, &plane, &t, &half, pd);
            assert!(g <= 1e-10, "det(I + DP_T) at {g:e} of its scale");
            let g = held::<Stribeck8>(&base, &plane, s, &e.at, c.condition);
            assert!(g <= 1e-10, "the fold at {g:e} of its scale");
            assert!(apart(&e.at.points, periods) < 1e-20, "the halves coincide");

            // The test's own extrapolation: three traced points, walking
            // in from the end, with distinct squared differences.
            let inward: Vec<&CurvePoint> = if last == 0 {
                c.points[1..].iter().collect()
            } else {
                c.points[..last].iter().rev().collect()
            };
            let mut chosen: Vec<(f64, &CurvePoint)> = Vec::new();
            for q in inward {
                let a = apart(&q.points, periods);
                if chosen.last().is_none_or(|l| a >= 2.0 * l.0) {
                    chosen.push((a, q));
                }
                if chosen.len() == 3 {
                    break;
                }
            }
            assert_eq!(chosen.len(), 3);
            assert!(chosen[0].0 < 0.25 * chosen[2].0, "the halves merge");
            let lagrange = |v: &dyn Fn(&CurvePoint) -> f64| -> f64 {
                (0..3)
                    .map(|k| {
                        let w: f64 = (0..3)
                            .filter(|&j| j != k)
                            .map(|j| chosen[j].0 / (chosen[j].0 - chosen[k].0))
                            .product();
                        w * v(chosen[k].1)
                    })
                    .sum()
            };
            let (w0, q0) = (lagrange(&|q| q.x), lagrange(&|q| q.y));
            let off = ((w0 - e.at.x) / (wr[1] - wr[0])).hypot((q0 - e.at.y) / (qr[1] - qr[0]));
            // Measured 5.3e-13; a linear extrapolation is 4.2e-9 off.
            assert!(off < 1e-10, "the end is {off:e} from the extrapolation");
            // `T` re-solved at the extrapolated parameters: a period doubling.
            let mut p = base;
            p.set(plane.x, w0);
            p.set(plane.y, q0);
            let mut pts = half.points.clone();
            let done = PeriodicSolver::<Stribeck8>::new(t.clone()).solve(
                &p,
                &mut pts,
                NewtonOptions::default(),
            );
            assert!(matches!(done, Termination::Converged { .. }), "{done:?}");
            let shift = std::f64::consts::TAU * f64::from(t.periods());
            let dp = monodromy::<Stribeck8>(&p, t.steps(), shift, &pts).expect("DP");
            let v = 1.0 + dp.trace() + dp.determinant();
            assert!(
                v.abs() < 1e-10,
                "det(I + DP_T) = {v:e} at the extrapolation"
            );
        }
    }
    assert_eq!(found, 1, "one fold curve ends so");
}
