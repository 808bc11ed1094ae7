//! The codimension-two points of a curve set: the curves' codim-2 ends and
//! their special points, merged where they lie at one place (within
//! [`SAME_PLACE`] of the box's spans), with every curve that ends or passes
//! there.

use crate::bifurcation::curve::{Curve, CurveEndReason, Plane};
use crate::bifurcation::TransitionKind;

use super::Codim2Point;

/// Two points within this fraction of the box's spans are one place.
pub(super) const SAME_PLACE: f64 = 1e-7;

/// A curve passing within this fraction of the spans of a codim-2 point
/// (its polyline, between computed points) passes through it.
const PASSES: f64 = 1e-6;

/// A codim-2 point being merged: the conditions that meet there.
struct Meeting {
    x: f64,
    y: f64,
    /// The conditions' transitions and boundaries.
    conditions: Vec<(TransitionKind, Option<usize>)>,
    curves: Vec<usize>,
}

fn spans(plane: &Plane) -> (f64, f64) {
    (
        plane.x_range[1] - plane.x_range[0],
        plane.y_range[1] - plane.y_range[0],
    )
}

/// Whether `(x, y)` and `(u, v)` are one place, `tol` a fraction of the spans.
pub(super) fn same_place(plane: &Plane, tol: f64, (x, y): (f64, f64), (u, v): (f64, f64)) -> bool {
    let (sx, sy) = spans(plane);
    (x - u).abs() <= tol * sx && (y - v).abs() <= tol * sy
}

/// Distance of `(x, y)` from the polyline of `curve`, in units of the spans.
fn distance(plane: &Plane, curve: &Curve, (x, y): (f64, f64)) -> f64 {
    let (sx, sy) = spans(plane);
    let scaled = |p: &crate::bifurcation::curve::CurvePoint| ((p.x - x) / sx, (p.y - y) / sy);
    let mut best = f64::INFINITY;
    for w in curve.points.windows(2) {
        let (a, b) = (scaled(&w[0]), scaled(&w[1]));
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (-(a.0 * dx + a.1 * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (px, py) = (a.0 + t * dx, a.1 + t * dy);
        best = best.min(px.hypot(py));
    }
    if let Some(p) = curve.points.first() {
        let (px, py) = scaled(p);
        best = best.min(px.hypot(py));
    }
    best
}

/// The codim-2 points of `curves` (in their final order), sorted by `(x, y)`.
pub(super) fn codim2_points(plane: &Plane, curves: &[Curve]) -> Vec<Codim2Point> {
    let mut found: Vec<Meeting> = Vec::new();
    let mut add = |x: f64, y: f64, own: (TransitionKind, Option<usize>), other, i: usize| {
        let conditions = vec![own, other];
        match found
            .iter_mut()
            .find(|m| same_place(plane, SAME_PLACE, (m.x, m.y), (x, y)))
        {
            Some(m) => {
                m.conditions.extend(conditions);
                m.curves.push(i);
            }
            None => found.push(Meeting {
                x,
                y,
                conditions,
                curves: vec![i],
            }),
        }
    };
    for (i, c) in curves.iter().enumerate() {
        let own = (c.kind, c.boundary);
        for end in &c.ends {
            if let CurveEndReason::Codim2 { kind, boundary } = end.reason {
                add(end.at.x, end.at.y, own, (kind, boundary), i);
            }
        }
        for s in &c.special {
            add(s.at.x, s.at.y, own, (s.kind, None), i);
        }
    }
    // Curves of a meeting condition that pass through without ending there.
    for m in &mut found {
        for (j, c) in curves.iter().enumerate() {
            if m.curves.contains(&j) {
                continue;
            }
            let meets = m
                .conditions
                .iter()
                .any(|&(k, b)| k == c.kind && (b.is_none() || b == c.boundary));
            if meets && distance(plane, c, (m.x, m.y)) <= PASSES {
                m.curves.push(j);
            }
        }
    }
    let mut out: Vec<Codim2Point> = found
        .into_iter()
        .map(|m| {
            let mut kinds: Vec<TransitionKind> = m.conditions.iter().map(|c| c.0).collect();
            kinds.sort_by_key(|k| k.name());
            kinds.dedup();
            let mut curves = m.curves;
            curves.sort_unstable();
            curves.dedup();
            Codim2Point {
                x: m.x,
                y: m.y,
                kinds,
                curves,
            }
        })
        .collect();
    out.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    out
}
