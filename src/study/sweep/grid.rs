//! The motions a sweep reports at its grid values: every branch crossing a
//! value, solved there by Newton from the branch's neighbouring points.

use crate::bifurcation::branch::Branch;
use crate::dynamics::simulate::Simulator;
use crate::model::Model;
use crate::orbit::motion::{solve_with, Motion};
use crate::orbit::periodic::SwitchingPoint;
use crate::study::search::same_motion;

/// Two motions closer than this (switching points: phases in radians,
/// displacements relative to the motion's size) are one.
pub(super) const SAME: f64 = 1e-6;

/// Every motion of `branch` at the simulator's parameter `value`: one per
/// stretch of the branch (between two of its points) that crosses `value`,
/// solved by Newton from the linear interpolation of its ends. A branch that
/// turns back at folds crosses a value several times.
pub(super) fn at_value<M: Model>(sim: &Simulator<M>, branch: &Branch, value: f64) -> Vec<Motion> {
    let mut out: Vec<Motion> = Vec::new();
    for pair in branch.points.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        let (lo, hi) = (a.value.min(b.value), a.value.max(b.value));
        if !(value >= lo && value <= hi) || a.points.len() != b.points.len() {
            continue;
        }
        let t = if hi > lo {
            (value - a.value) / (b.value - a.value)
        } else {
            0.0
        };
        let guess: Vec<SwitchingPoint> = a
            .points
            .iter()
            .zip(&b.points)
            .map(|(p, q)| SwitchingPoint {
                phase: p.phase + t * (q.phase - p.phase),
                x: p.x + t * (q.x - p.x),
            })
            .collect();
        let m = solve_with(
            sim,
            branch.structure.clone(),
            guess,
            Default::default(),
            false,
        );
        if m.termination.converged() && !out.iter().any(|o| same_motion(o, &m, SAME)) {
            out.push(m);
        }
    }
    out
}
