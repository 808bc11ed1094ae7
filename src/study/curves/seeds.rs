//! A seed line's sweep and the curve starts it gives: every non-smooth end
//! of every branch (with its switching points), every eigenvalue
//! bifurcation on the branches, and every grazing of the no-motion regime,
//! each with the condition that vanishes there.

use crate::bifurcation::curve::{
    condition_at_transition, condition_value, Condition, CurvePoint, Line, Plane,
};
use crate::bifurcation::{EndReason, TransitionKind};
use crate::model::param::ParamSet;
use crate::model::{Model, ModelInfo};
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::structure::Structure;
use crate::study::sweep::{sweep_branches, SweepError, SweepOptions};

/// Where a curve must pass: a transition located on a seed line.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Start {
    /// The transition.
    pub kind: TransitionKind,
    /// The boundary involved, if any.
    pub boundary: Option<usize>,
    /// The motion (`None`: the no-motion regime).
    pub structure: Option<Structure>,
    /// What vanishes there.
    pub condition: Condition,
    /// The point, on the line, with the motion's switching points.
    pub point: CurvePoint,
    /// The line it was found on.
    pub line: Line,
}

/// What a sweep along one line found.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct LineSweep {
    /// The line.
    pub line: Line,
    /// The transitions on it, in the order the sweep found them.
    pub starts: Vec<Start>,
    /// What lives at each grid value (its motions' names, sorted, joined by `;`).
    pub labels: Vec<String>,
}

/// `P_{...}`, with `^N` for N > 1 forcing periods; `NM` for none.
pub(super) fn structure_name(info: &ModelInfo, s: Option<&Structure>) -> String {
    match s {
        None => "NM".into(),
        Some(s) => s.label(info),
    }
}

/// The parameters at `(x, y)` of `plane`.
pub(super) fn params_at<M: Model>(base: &M::Params, plane: &Plane, x: f64, y: f64) -> M::Params {
    let mut p = *base;
    p.set(plane.x, x);
    p.set(plane.y, y);
    p
}

/// Sweep along `line` on `count` values over `range` of the swept
/// parameter (`None`: across the whole box) and collect its starts.
pub(super) fn sweep_line<M: Model>(
    base: &M::Params,
    plane: &Plane,
    line: Line,
    range: Option<[f64; 2]>,
    count: usize,
    opts: SweepOptions,
) -> Result<LineSweep, SweepError> {
    // The swept parameter, its range, the fixed one.
    let (swept, whole) = match line {
        Line::Y(_) => (plane.x, plane.x_range),
        Line::X(_) => (plane.y, plane.y_range),
    };
    let [lo, hi] = range.unwrap_or(whole);
    let mut fixed = *base;
    match line {
        Line::Y(v) => fixed.set(plane.y, v),
        Line::X(v) => fixed.set(plane.x, v),
    }
    let name = base.names()[swept];
    let (sw, branches) = sweep_branches::<M>(fixed, name, lo, hi, count, opts)?;
    let on_line = |value: f64, points: &[SwitchingPoint]| match line {
        Line::Y(y) => CurvePoint {
            x: value,
            y,
            points: points.to_vec(),
        },
        Line::X(x) => CurvePoint {
            x,
            y: value,
            points: points.to_vec(),
        },
    };
    let mut starts = Vec::new();
    for b in &branches {
        for end in &b.ends {
            let EndReason::Transition { kind, boundary } = end.reason else {
                continue;
            };
            let point = on_line(end.at.value, &end.at.points);
            let p = params_at::<M>(base, plane, point.x, point.y);
            if let Some(condition) =
                condition_at_transition::<M>(&p, &b.structure, &end.at.points, kind)
            {
                starts.push(Start {
                    kind,
                    boundary,
                    structure: Some(b.structure.clone()),
                    condition,
                    point,
                    line,
                });
            }
        }
        for bif in &b.bifurcations {
            let point = on_line(bif.at.value, &bif.at.points);
            let p = params_at::<M>(base, plane, point.x, point.y);
            if let Some(condition) =
                condition_at_transition::<M>(&p, &b.structure, &bif.at.points, bif.kind)
            {
                starts.push(Start {
                    kind: bif.kind,
                    boundary: None,
                    structure: Some(b.structure.clone()),
                    condition,
                    point,
                    line,
                });
            }
        }
    }
    // The no-motion regime's edges: the boundary grazed is the one whose
    // grazing condition vanishes there.
    for t in sw.transitions.iter().filter(|t| t.from == "NM") {
        let point = on_line(t.value, &[]);
        let grazed = (0..M::info(base).boundaries.len())
            .filter_map(|k| {
                let c = Condition::RestGrazing { boundary: k };
                let v = condition_value::<M>(base, plane, None, &point, c).ok()?;
                v.is_finite().then_some((v.abs(), k))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, k)) = grazed {
            starts.push(Start {
                kind: TransitionKind::Grazing,
                boundary: Some(k),
                structure: None,
                condition: Condition::RestGrazing { boundary: k },
                point,
                line,
            });
        }
    }
    // A start outside the box (a bifurcation located past a branch's
    // bound) is none of the box's.
    let [xl, xh] = plane.x_range;
    let [yl, yh] = plane.y_range;
    starts.retain(|s| (xl..=xh).contains(&s.point.x) && (yl..=yh).contains(&s.point.y));
    let labels = sw
        .points
        .iter()
        .map(|pt| {
            let mut names: Vec<&str> = pt.motions.iter().map(|m| m.structure.as_str()).collect();
            names.sort_unstable();
            names.dedup();
            names.join(";")
        })
        .collect();
    Ok(LineSweep {
        line,
        starts,
        labels,
    })
}
