//! The mapping equations of a cycle of mappings at its switching points,
//! from the generated residuals alone: the check that a motion built by
//! hand in a test (a structure reduced, a half of a doubled one) is one.

use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::Model;

/// The largest `|f|` (Euclidean, per mapping) of the mapping equations of
/// `steps` (mapping indices) from each of `points` to the next, the last
/// to the first one cycle (`2π · periods`) later.
pub fn worst_residual<M: Model>(
    p: &M::Params,
    steps: &[usize],
    points: &[SwitchingPoint],
    periods: u32,
) -> f64 {
    let shift = std::f64::consts::TAU * f64::from(periods);
    let mut worst = 0.0f64;
    for (i, &step) in steps.iter().enumerate() {
        let a = points[i];
        let b = points.get(i + 1).copied().unwrap_or(SwitchingPoint {
            x: points[0].x,
            phase: points[0].phase + shift,
        });
        let r = M::residual(p, step, a.x, a.phase, b.x, b.phase).norm();
        worst = if r.is_nan() {
            f64::INFINITY
        } else {
            worst.max(r)
        };
    }
    worst
}

/// The codimension-two ends of the fold curves among `curves`, each with
/// its curve's motion.
pub fn fold_ends(
    curves: &[stickslip::bifurcation::curve::Curve],
) -> Vec<(
    &stickslip::orbit::structure::Structure,
    &stickslip::bifurcation::curve::CurveEnd,
)> {
    use stickslip::bifurcation::curve::{Condition, CurveEndReason};
    use stickslip::bifurcation::TransitionKind;
    curves
        .iter()
        .filter(|c| c.condition == Condition::Eigen(TransitionKind::Fold))
        .filter_map(|c| c.structure.as_ref().map(|s| (s, &c.ends)))
        .flat_map(|(s, ends)| ends.iter().map(move |e| (s, e)))
        .filter(|(_, e)| matches!(e.reason, CurveEndReason::Codim2 { .. }))
        .collect()
}

/// `|g| / scale` of `condition` of the motion `point` of `structure`
/// (`condition_value` over `condition_scale`, the curves' public
/// evaluators), every parameter but the plane's two from `base`.
pub fn held<M: Model>(
    base: &M::Params,
    plane: &stickslip::bifurcation::curve::Plane,
    structure: &stickslip::orbit::structure::Structure,
    point: &stickslip::bifurcation::curve::CurvePoint,
    condition: stickslip::bifurcation::curve::Condition,
) -> f64 {
    use stickslip::bifurcation::curve::{condition_scale, condition_value};
    use stickslip::ParamSet;
    let g =
        condition_value::<M>(base, plane, Some(structure), point, condition).expect("evaluable");
    let mut p = *base;
    p.set(plane.x, point.x);
    p.set(plane.y, point.y);
    (g / condition_scale::<M>(&p, condition, Some(structure), &point.points)).abs()
}

/// Every end of `curves` that is neither on the box's edge nor at a
/// codimension-two point, described (kind, motion, place, why).
pub fn other_ends(
    info: &stickslip::ModelInfo,
    curves: &[stickslip::bifurcation::curve::Curve],
) -> Vec<String> {
    use stickslip::bifurcation::curve::CurveEndReason;
    curves
        .iter()
        .flat_map(|c| c.ends.iter().map(move |e| (c, e)))
        .filter(|(_, e)| {
            !matches!(
                e.reason,
                CurveEndReason::BoxEdge | CurveEndReason::Codim2 { .. }
            )
        })
        .map(|(c, e)| {
            format!(
                "{:?} {:?} ends at W = {}, Q0 = {}: {:?}",
                c.kind,
                c.structure.as_ref().map(|s| s.notation(info)),
                e.at.x,
                e.at.y,
                e.reason
            )
        })
        .collect()
}

/// The curves of `M` over the box `W` × `Q0` (`w` × `q`) with the default
/// settings, every other parameter from `base`, and that plane.
pub fn traced_wq<M: Model>(
    base: &M::Params,
    w: [f64; 2],
    q: [f64; 2],
) -> (
    Vec<stickslip::bifurcation::curve::Curve>,
    stickslip::bifurcation::curve::Plane,
) {
    use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
    let opts = CurvesOptions {
        x: ("W".into(), w),
        y: ("Q0".into(), q),
        seeds: Vec::new(),
        at: Vec::new(),
    };
    let (_, curves) = traced::<M>(base, &opts, &CurvesSettings::default()).expect("run");
    // The box's plane as the run itself builds it.
    let plane = opts.plane::<M>(base).expect("a valid box");
    (curves, plane)
}

/// Every codimension-two end of `curves` that has a second condition, with
/// how well that holds there (`codim2_residual`, from the motion's
/// conditions as the admissibility walk computes them): `(curve index, end
/// index, residual)`. An end without one must be where an excursion shrank
/// to nothing (two equal switching points, solved on the reduced motion).
pub fn codim2_residuals<M: Model>(
    base: &M::Params,
    plane: &stickslip::bifurcation::curve::Plane,
    curves: &[stickslip::bifurcation::curve::Curve],
) -> Vec<(usize, usize, f64)> {
    use stickslip::bifurcation::curve::{codim2_residual, CurveEndReason};
    let mut out = Vec::new();
    for (i, c) in curves.iter().enumerate() {
        for (k, e) in c.ends.iter().enumerate() {
            if !matches!(e.reason, CurveEndReason::Codim2 { .. }) {
                continue;
            }
            match codim2_residual::<M>(base, plane, c, e) {
                Some(v) => out.push((i, k, v)),
                None => assert!(
                    c.shrunk_excursion(&e.at),
                    "curve {i} end {k}: no second condition at {e:?}"
                ),
            }
        }
    }
    out
}
