//! A branch of a sweep as curves in one panel of the bifurcation diagram:
//! one curve per switching point (or per eigenvalue) through the branch's
//! points in arclength order, so that a branch turning back at a fold is
//! drawn as it turns. Stretches where the motion is stable are solid, where
//! unstable dashed; a segment between a stable and an unstable point
//! changes style halfway, where the bifurcation lies between them.

use crate::study::sweep::{BranchSample, BranchSummary};

/// How a stretch of a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stroke {
    /// The motion is stable there.
    Solid,
    /// The motion is unstable there.
    Dashed,
}

/// One stretch of one curve: a polyline in (parameter, quantity).
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// How it is drawn.
    pub stroke: Stroke,
    /// Its vertices.
    pub points: Vec<(f64, f64)>,
}

/// What a panel shows of a branch's point: one value per curve.
pub type Quantity = fn(&BranchSample) -> Vec<f64>;

/// The curves of `branch` for `quantity`. With `period`, the quantity is an
/// angle taken modulo it (a switching phase): a curve is broken where it
/// wraps round rather than drawn across the panel. With `unstable` false,
/// the dashed stretches are left out (the half segments next to a
/// bifurcation that belong to the stable side stay).
pub fn curves(
    branch: &BranchSummary,
    quantity: Quantity,
    period: Option<f64>,
    unstable: bool,
) -> Vec<Curve> {
    let values: Vec<Vec<f64>> = branch.points.iter().map(quantity).collect();
    let lanes = values.iter().map(Vec::len).max().unwrap_or(0);
    let mut out: Vec<Curve> = Vec::new();
    for lane in 0..lanes {
        let mut current: Option<Curve> = None;
        for (k, pair) in branch.points.windows(2).enumerate() {
            let (a, b) = (&pair[0], &pair[1]);
            let ya = values[k].get(lane).copied();
            let yb = values[k + 1].get(lane).copied();
            let (Some(ya), Some(yb)) = (ya, yb) else {
                flush(&mut current, &mut out);
                continue;
            };
            let wraps = period.is_some_and(|p| (yb - ya).abs() > 0.5 * p);
            if !(ya.is_finite() && yb.is_finite()) || wraps {
                flush(&mut current, &mut out);
                continue;
            }
            let (p, q) = ((a.value, ya), (b.value, yb));
            let style = |stable: bool| {
                if stable {
                    Stroke::Solid
                } else {
                    Stroke::Dashed
                }
            };
            let halves = if a.stable == b.stable {
                vec![(p, q, style(a.stable))]
            } else {
                let mid = (0.5 * (p.0 + q.0), 0.5 * (p.1 + q.1));
                vec![(p, mid, style(a.stable)), (mid, q, style(b.stable))]
            };
            for (from, to, stroke) in halves {
                if stroke == Stroke::Dashed && !unstable {
                    flush(&mut current, &mut out);
                    continue;
                }
                match &mut current {
                    Some(c) if c.stroke == stroke && c.points.last() == Some(&from) => {
                        c.points.push(to);
                    }
                    _ => {
                        flush(&mut current, &mut out);
                        current = Some(Curve {
                            stroke,
                            points: vec![from, to],
                        });
                    }
                }
            }
        }
        flush(&mut current, &mut out);
    }
    // A branch of one point is drawn as a point.
    if branch.points.len() == 1 {
        let p = &branch.points[0];
        if unstable || p.stable {
            for &y in values[0].iter().filter(|y| y.is_finite()) {
                out.push(Curve {
                    stroke: if p.stable {
                        Stroke::Solid
                    } else {
                        Stroke::Dashed
                    },
                    points: vec![(p.value, y)],
                });
            }
        }
    }
    out
}

fn flush(current: &mut Option<Curve>, out: &mut Vec<Curve>) {
    if let Some(c) = current.take() {
        out.push(c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(value: f64, y: f64, stable: bool) -> BranchSample {
        BranchSample {
            value,
            start_wt: y,
            start_x: y,
            eigenvalues: vec![],
            stable,
            max_abs_x: y.abs(),
            max_abs_v: y.abs(),
            period: None,
            points: vec![],
        }
    }

    fn branch(samples: Vec<BranchSample>) -> BranchSummary {
        BranchSummary {
            id: 0,
            structure: "P_{3_33 4_33}".into(),
            n: 1,
            points: samples,
            ends: vec![],
        }
    }

    #[test]
    fn a_fold_gives_a_solid_then_a_dashed_stretch_meeting_halfway() {
        // Stable up to 2, turning back unstable.
        let b = branch(vec![
            sample(1.0, 0.0, true),
            sample(2.0, 1.0, true),
            sample(1.5, 2.0, false),
            sample(1.0, 3.0, false),
        ]);
        let c = curves(&b, |s| vec![s.start_x], None, true);
        assert_eq!(c.len(), 2, "{c:?}");
        assert_eq!(c[0].stroke, Stroke::Solid);
        assert_eq!(c[0].points, vec![(1.0, 0.0), (2.0, 1.0), (1.75, 1.5)]);
        assert_eq!(c[1].stroke, Stroke::Dashed);
        assert_eq!(c[1].points, vec![(1.75, 1.5), (1.5, 2.0), (1.0, 3.0)]);
        // Without the unstable part: the solid stretch alone.
        let c = curves(&b, |s| vec![s.start_x], None, false);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].points, vec![(1.0, 0.0), (2.0, 1.0), (1.75, 1.5)]);
    }

    #[test]
    fn a_phase_wrapping_round_breaks_the_curve() {
        let b = branch(vec![
            sample(1.0, 6.0, true),
            sample(2.0, 6.2, true),
            sample(3.0, 0.1, true),
            sample(4.0, 0.3, true),
        ]);
        let c = curves(&b, |s| vec![s.start_wt], Some(std::f64::consts::TAU), true);
        assert_eq!(c.len(), 2);
        assert_eq!(c[0].points, vec![(1.0, 6.0), (2.0, 6.2)]);
        assert_eq!(c[1].points, vec![(3.0, 0.1), (4.0, 0.3)]);
    }
}
