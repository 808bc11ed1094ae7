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
            // Each meeting on a curve names two conditions; one that
            // names the same transition twice (two grazings of one
            // boundary, by different segments) keeps both.
            let mut distinct = m.conditions.clone();
            distinct.sort_by_key(|c| (c.0.name(), c.1));
            distinct.dedup();
            let mut kinds: Vec<TransitionKind> = Vec::new();
            for c in &distinct {
                let twice = m
                    .conditions
                    .chunks_exact(2)
                    .any(|p| p[0] == *c && p[1] == *c);
                kinds.push(c.0);
                if twice {
                    kinds.push(c.0);
                }
            }
            kinds.sort_by_key(|k| k.name());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bifurcation::curve::{Condition, CurveEnd, CurvePoint, Special};

    const PLANE: Plane = Plane {
        x: 0,
        y: 1,
        x_range: [0.0, 10.0],
        y_range: [0.0, 100.0],
    };

    fn pt(x: f64, y: f64) -> CurvePoint {
        CurvePoint {
            x,
            y,
            points: Vec::new(),
        }
    }

    fn curve(
        kind: TransitionKind,
        boundary: Option<usize>,
        from: (f64, f64),
        to: (f64, f64),
    ) -> Curve {
        Curve {
            kind,
            condition: Condition::Eigen(TransitionKind::Fold),
            boundary,
            structure: None,
            points: vec![pt(from.0, from.1), pt(to.0, to.1)],
            ends: vec![
                CurveEnd {
                    reason: CurveEndReason::BoxEdge,
                    at: pt(from.0, from.1),
                },
                CurveEnd {
                    reason: CurveEndReason::BoxEdge,
                    at: pt(to.0, to.1),
                },
            ],
            special: Vec::new(),
        }
    }

    #[test]
    fn ends_at_one_place_merge_and_a_passing_curve_joins() {
        let g = TransitionKind::Grazing;
        let s = TransitionKind::StickOnset;
        // Curve 0 (grazing on 1) ends at (5, 50) meeting stick onset on 1;
        // curve 1 (stick onset on 1) ends there too, 1e-9 of the span away;
        // curve 2 (stick onset on 1) passes straight through (5, 50);
        // curve 3 (stick onset on 0) passes through too but on another boundary.
        let mut c0 = curve(g, Some(1), (0.0, 0.0), (5.0, 50.0));
        c0.ends[1].reason = CurveEndReason::Codim2 {
            kind: s,
            boundary: Some(1),
        };
        let mut c1 = curve(s, Some(1), (10.0, 100.0), (5.0 + 1e-8, 50.0));
        c1.ends[1].reason = CurveEndReason::Codim2 {
            kind: g,
            boundary: Some(1),
        };
        let c2 = curve(s, Some(1), (0.0, 100.0), (10.0, 0.0));
        let c3 = curve(s, Some(0), (0.0, 100.0), (10.0, 0.0));
        // A special point elsewhere on curve 3.
        let mut c3 = c3;
        c3.special.push(Special {
            index: 0,
            kind: TransitionKind::Fold,
            at: pt(2.0, 80.0),
        });
        let q = codim2_points(&PLANE, &[c0, c1, c2, c3]);
        assert_eq!(q.len(), 2, "{q:?}");
        // Sorted by x: the special point first.
        assert_eq!((q[0].x, q[0].y), (2.0, 80.0));
        assert_eq!(q[0].kinds, vec![TransitionKind::Fold, s]);
        assert_eq!(q[0].curves, vec![3]);
        assert_eq!(q[1].kinds, vec![g, s]);
        assert_eq!(q[1].curves, vec![0, 1, 2]);
    }

    #[test]
    fn distinct_places_stay_distinct() {
        let g = TransitionKind::Grazing;
        let mut a = curve(g, None, (0.0, 0.0), (5.0, 50.0));
        a.ends[1].reason = CurveEndReason::Codim2 {
            kind: TransitionKind::Fold,
            boundary: None,
        };
        let mut b = curve(g, None, (10.0, 0.0), (5.0 + 1e-3, 50.0));
        b.ends[1].reason = CurveEndReason::Codim2 {
            kind: TransitionKind::Fold,
            boundary: None,
        };
        let q = codim2_points(&PLANE, &[a, b]);
        assert_eq!(q.len(), 2, "{q:?}");
        assert_eq!(q[0].curves, vec![0]);
        assert_eq!(q[1].curves, vec![1]);
    }
}
