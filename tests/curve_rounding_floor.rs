//! Fold and period-doubling curves of long stick motions, whose test
//! function is steep: on `stribeck::pl4` (the Stribeck law's four-piece
//! model) the period-3 motions of 16 mappings near W = 0.938, Q0 = 4.931
//! have `DP` entries that move by 1e4 to 2e6 per unit of a switching point,
//! so an ulp of the unknowns moves `det(I ∓ DP)` by more than 1e-10 of its
//! scale. Until stop 28 a fold and a period-doubling curve ended there as
//! corrector failures ("the condition holds only to 1.2e-10 of its scale
//! there"); a point now also holds where its condition is within its
//! rounding floor.
//!
//! Checked: every curve of the box ends on its edge or at a
//! codimension-two point (the fold and the period doubling now end where
//! the event search's stick end flips, the motion's equations turning
//! singular there), and every
//! codimension-two end holds its second condition to 1e-8. And
//! independently: at every point of a
//! period-doubling curve whose condition is above 1e-10 of its scale, the
//! motion re-solved by `PeriodicSolver` at parameters 1e-9 either side of
//! the point (along `W` or along `Q0`) has its test function change sign:
//! the point lies within 1e-9 of the curve. (A fold's motion does not
//! exist on one side of its curve.)

mod common;

use common::cycle::{codim2_residuals, held, other_ends, traced_wq};
use stickslip::bifurcation::curve::Condition;
use stickslip::bifurcation::TransitionKind;
use stickslip::models::stribeck::pl4::{self, Pl4};
use stickslip::orbit::periodic::{monodromy, NewtonOptions, PeriodicSolver, Termination};
use stickslip::ParamSet;

/// How far either side of a point the test function is re-evaluated.
const SIDE: f64 = 1e-9;

#[test]
fn eigenvalue_curves_of_long_stick_motions_hold_to_their_rounding_floor_and_reach_the_box() {
    let base = pl4::Params::default();
    let (wr, qr) = ([0.92, 0.96], [4.8, 5.0]);
    let (curves, plane) = traced_wq::<Pl4>(&base, wr, qr);
    // One curve, the period doubling of the period-3 motion of 16 mappings
    // that the global search finds on a line since it no longer assigns
    // starts by distance, ends where it crawls into a grazing: a
    // codimension-two point it reports ahead and does not locate. Every
    // other end is on the box's edge or at a codimension-two point.
    let other = other_ends(Pl4::INFO, &curves);
    let (ahead, other): (Vec<_>, Vec<_>) = other
        .into_iter()
        .partition(|e| e.contains("a codimension-two point lies ahead, not located"));
    assert!(other.is_empty(), "{other:#?}");
    assert!(ahead.len() <= 1, "{ahead:#?}");
    // Every codimension-two end with a second condition holds it: the fold
    // and period-doubling ends where a stick vanishes held it to 1.8e-5 to
    // 4.1e-4 until stop 37, when `DP` still carried the pole of the
    // nearly tangential arrival before that stick.
    let ends = codim2_residuals::<Pl4>(&base, &plane, &curves);
    let worst = ends.iter().fold(0.0f64, |a, e| a.max(e.2));
    assert!(ends.len() >= 2 && worst <= 1e-8, "{ends:?}");
    let mut steep = 0;
    let mut checked = 0;
    let mut eigen = 0;
    let mut unsolved_far = 0.0f64;
    for c in &curves {
        // A period-doubling motion exists either side of its curve (a
        // fold's does not: its mapping equations turn singular there).
        let Condition::Eigen(kind @ TransitionKind::PeriodDoubling) = c.condition else {
            continue;
        };
        eigen += 1;
        let s = c.structure.as_ref().expect("a motion");
        let shift = std::f64::consts::TAU * f64::from(s.periods());
        let g = |p: &pl4::Params, pts: &[stickslip::orbit::periodic::SwitchingPoint]| {
            let dp = monodromy::<Pl4>(p, s.steps(), shift, pts).expect("DP");
            let sign = if kind == TransitionKind::Fold {
                -1.0
            } else {
                1.0
            };
            1.0 + sign * dp.trace() + dp.determinant()
        };
        for q in &c.points {
            if held::<Pl4>(&base, &plane, s, q, c.condition) <= 1e-10 {
                continue;
            }
            steep += 1;
            // The motion re-solved 1e-9 either side, along each axis.
            let side = |axis: usize, sign: f64| {
                let mut p = base;
                p.set(plane.x, q.x);
                p.set(plane.y, q.y);
                let (idx, v) = if axis == 0 {
                    (plane.x, q.x)
                } else {
                    (plane.y, q.y)
                };
                p.set(idx, v + sign * SIDE);
                let mut pts = q.points.clone();
                let done = PeriodicSolver::<Pl4>::new(s.clone()).solve(
                    &p,
                    &mut pts,
                    NewtonOptions::default(),
                );
                matches!(done, Termination::Converged { .. }).then(|| g(&p, &pts))
            };
            let mut solved = false;
            let mut crosses = false;
            for axis in 0..2 {
                if let (Some(a), Some(b)) = (side(axis, 1.0), side(axis, -1.0)) {
                    solved = true;
                    crosses |= a * b < 0.0;
                }
            }
            // The distance (of the box) to the curve's nearest end.
            let to_end = c
                .ends
                .iter()
                .map(|e| ((e.at.x - q.x) / 0.04).hypot((e.at.y - q.y) / 0.2))
                .fold(f64::INFINITY, f64::min);
            eprintln!(
                "W = {} Q0 = {}: solved {solved} crosses {crosses}, {to_end:e} from an end",
                q.x, q.y
            );
            if !solved {
                unsolved_far = unsolved_far.max(to_end);
            }
            if solved {
                checked += 1;
                assert!(
                    crosses,
                    "{kind:?} point W = {}, Q0 = {} is more than {SIDE:e} off its curve",
                    q.x, q.y
                );
            }
        }
    }
    assert!(eigen >= 6, "{eigen} period-doubling curves");
    // The steep points this test is about: 7 when written, 6 of them
    // re-solved either side (the seventh is the end where the period
    // doubling meets the stick's vanishing, the motion's equations
    // singular there); since stop 29 (finite differences at 1e-7) two of
    // 7 are curve ends and not re-solved; since stop 39, whose test
    // functions are cleared of the pole of a stick's exit turning
    // tangential (`exit_rates` in `bifurcation/curve/condition.rs`), 4 points
    // are steep, one of them an end. Only an end may fail.
    assert!(
        steep >= 3 && checked + 2 >= steep && unsolved_far == 0.0,
        "{checked} of {steep} steep points re-solved; one not re-solved lies {unsolved_far:e} from its curve's end"
    );
}
