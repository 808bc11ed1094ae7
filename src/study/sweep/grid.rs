//! The motions a sweep reports at its grid values: every branch crossing a
//! value, solved there by Newton from the branch's neighbouring points.

use crate::bifurcation::branch::Branch;
use crate::dynamics::simulate::Simulator;
use crate::model::Model;
use crate::orbit::motion::{solve_with, Motion};
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::structure::Structure;

const TAU: f64 = 2.0 * std::f64::consts::PI;

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
        if m.termination.converged() && !out.iter().any(|o| same_points(&o.points, &m.points)) {
            out.push(m);
        }
    }
    out
}

/// Whether two cycles are the same up to where they start: equal periods and
/// a rotation of one's mappings equal to the other's.
pub(super) fn same_cycle(a: &Structure, b: &Structure) -> bool {
    let (sa, sb) = (a.steps(), b.steps());
    if a.periods() != b.periods() || sa.len() != sb.len() {
        return false;
    }
    let m = sa.len();
    (0..m).any(|r| (0..m).all(|k| sa[(r + k) % m] == sb[k]))
}

/// Whether two motions pass the same switching points (phases mod 2π), in
/// whatever order, to 1e-6 relative.
pub(super) fn same_points(a: &[SwitchingPoint], b: &[SwitchingPoint]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let scale = a.iter().chain(b).fold(1.0f64, |s, p| s.max(p.x.abs()));
    let close = |p: &SwitchingPoint, q: &SwitchingPoint| {
        let d = (p.phase - q.phase).rem_euclid(TAU);
        d.min(TAU - d) < 1e-6 && (p.x - q.x).abs() < 1e-6 * scale
    };
    a.iter().all(|p| b.iter().any(|q| close(p, q)))
        && b.iter().all(|q| a.iter().any(|p| close(p, q)))
}
