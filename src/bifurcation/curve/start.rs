//! A curve from its start: the checks, the extended system, the corrected
//! start and its tangent, both directions traced and joined; and which
//! condition vanishes at a transition located on a branch.

use crate::bifurcation::bordered::Correction;
use crate::bifurcation::continuation::transition_kind;
use crate::bifurcation::TransitionKind;
use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::{Model, ParamSet};
use crate::orbit::admissible::{self, ViolationKind, SAME_EVENT};
use crate::orbit::periodic::{arrival, PeriodicSolver, SwitchingPoint};
use crate::orbit::structure::Structure;

use super::condition::{neighbours, rest_margin, Evaluator};
use super::extended::Extended;
use super::trace::{Run, Sample, Tracer};
use super::{Condition, Curve, CurveEnd, CurveError, CurveOptions, CurvePoint, Plane, Special};

/// A segment shorter than this (in `W t`) at a transition shrinks to nothing there.
const VANISHING: f64 = 1e-3;

/// Whether a segment of the motion with switching points `points` (of
/// `structure`) lasts less than [`VANISHING`] (in `W t`; the last one up to
/// the first a cycle on): a segment shrinking to nothing, on which the
/// structure's equations degenerate, so that no condition of this motion
/// has a regular curve there (the reduced motion, the segment removed,
/// carries it).
pub(super) fn vanishing_segment(structure: &Structure, points: &[SwitchingPoint]) -> bool {
    let shift = std::f64::consts::TAU * structure.periods() as f64;
    (0..points.len())
        .any(|k| (arrival(points, k, shift).phase - points[k].phase).abs() <= VANISHING)
}

/// How far (in the plane, each parameter over its span) the corrected start
/// of a curve may lie from the transition it is started at.
pub(super) const START_REACH: f64 = 1e-4;

/// The unknowns `(x_0, W t_0, …, λx, λy)` of a curve point.
pub fn unknowns(point: &CurvePoint) -> Vec<f64> {
    let mut x = Vec::with_capacity(2 * point.points.len() + 2);
    for q in &point.points {
        x.push(q.x);
        x.push(q.phase);
    }
    x.push(point.x);
    x.push(point.y);
    x
}

pub(super) fn to_point(x: &[f64]) -> CurvePoint {
    let n = x.len();
    let points = x[..n - 2]
        .chunks_exact(2)
        .map(|c| SwitchingPoint {
            x: c[0],
            phase: c[1],
        })
        .collect();
    CurvePoint {
        x: x[n - 2],
        y: x[n - 1],
        points,
    }
}

fn with<M: Model>(base: &M::Params, plane: &Plane, x: f64, y: f64) -> M::Params {
    let mut p = *base;
    p.set(plane.x, x);
    p.set(plane.y, y);
    p
}

fn check_plane<M: Model>(base: &M::Params, plane: &Plane) -> Result<(), CurveError> {
    let count = base.names().len();
    if plane.x >= count || plane.y >= count || plane.x == plane.y {
        return Err(CurveError::Options(format!(
            "the plane's parameters must be two different indices below {count} (got {} and {})",
            plane.x, plane.y
        )));
    }
    for r in [plane.x_range, plane.y_range] {
        if !(r[0].is_finite() && r[1].is_finite() && r[0] < r[1]) {
            return Err(CurveError::Options(format!(
                "a range [{}, {}] must be finite with lo < hi",
                r[0], r[1]
            )));
        }
    }
    Ok(())
}

/// The no-motion regime's domain of a `RestGrazing` curve through `(x, y)`:
/// the boundary's neighbour whose margin is the smaller in magnitude.
fn rest_domain<M: Model>(p: &M::Params, condition: Condition) -> Result<usize, CurveError> {
    let Condition::RestGrazing { boundary } = condition else {
        return Ok(0);
    };
    if boundary >= M::info(p).boundaries.len() {
        return Err(CurveError::Options(format!(
            "boundary {boundary} does not exist"
        )));
    }
    neighbours(M::info(p), boundary)
        .map(|j| (j, rest_margin::<M>(p, j, boundary).abs()))
        .filter(|(_, v)| v.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(j, _)| j)
        .ok_or_else(|| {
            CurveError::Condition(format!(
                "no damped domain next to boundary {boundary} has a steady response"
            ))
        })
}

/// The extended system of the curve of `condition` of `structure` through
/// `point` (not corrected), its scales taken there.
pub fn system<M: Model>(
    base: &M::Params,
    plane: &Plane,
    structure: Option<&Structure>,
    point: &CurvePoint,
    condition: Condition,
) -> Result<Extended<M>, CurveError> {
    check_plane::<M>(base, plane)?;
    match (condition, structure) {
        (Condition::RestGrazing { .. }, None) => {
            if !point.points.is_empty() {
                return Err(CurveError::Options(
                    "the no-motion regime has no switching points".into(),
                ));
            }
        }
        (Condition::RestGrazing { .. }, Some(_)) => {
            return Err(CurveError::Options(
                "a rest-grazing curve has no structure".into(),
            ))
        }
        (_, None) => {
            return Err(CurveError::Options(
                "a margin or eigenvalue curve needs the motion's structure".into(),
            ))
        }
        (_, Some(s)) => {
            if s.is_autonomous() {
                return Err(CurveError::Autonomous);
            }
            if s.len() != point.points.len() || s.is_empty() {
                return Err(CurveError::Options(format!(
                    "{} switching points for a structure of {} mappings",
                    point.points.len(),
                    s.len()
                )));
            }
            if let Condition::Margin { segment, .. } = condition {
                if segment >= s.len() {
                    return Err(CurveError::Options(format!(
                        "segment {segment} of a structure of {} mappings",
                        s.len()
                    )));
                }
            }
        }
    }
    if !(point.x.is_finite()
        && point.y.is_finite()
        && point
            .points
            .iter()
            .all(|q| q.x.is_finite() && q.phase.is_finite()))
    {
        return Err(CurveError::Start("a coordinate is not finite".into()));
    }
    let p = with::<M>(base, plane, point.x, point.y);
    p.check()
        .map_err(|e| CurveError::Start(format!("invalid parameters: {e}")))?;
    let domain = rest_domain::<M>(&p, condition)?;
    let eval = Evaluator::<M>::new(condition, structure, &p, domain).map_err(CurveError::Start)?;
    let length = PeriodicSolver::<M>::length_scale(&p, &point.points);
    let mut sys = Extended::new(*base, *plane, length, eval);
    sys.restrict_to_symmetric(&unknowns(point));
    Ok(sys)
}

fn check_options(opts: &CurveOptions) -> Result<(), CurveError> {
    if !(opts.min_step > 0.0
        && opts.min_step <= opts.initial_step
        && opts.initial_step <= opts.max_step
        && opts.max_step.is_finite())
    {
        return Err(CurveError::Options(format!(
            "need 0 < min_step <= initial_step <= max_step (got {}, {}, {})",
            opts.min_step, opts.initial_step, opts.max_step
        )));
    }
    if !(opts.tolerance > 0.0 && opts.location_tolerance > 0.0 && opts.max_points >= 2) {
        return Err(CurveError::Options(
            "the tolerances must be positive and max_points at least 2".into(),
        ));
    }
    Ok(())
}

/// The curve's kind: the condition's transition; an arrival or departure
/// on a stick boundary that vanishes with a force criterion is named by the
/// criterion (as [`admissible::worst_margin`] names it).
fn kind_of<M: Model>(
    condition: Condition,
    p: &M::Params,
    structure: Option<&Structure>,
    points: &[SwitchingPoint],
) -> TransitionKind {
    match condition {
        Condition::Eigen(k) => k,
        Condition::RestGrazing { .. } | Condition::NormalField { .. } => TransitionKind::Grazing,
        Condition::Margin { kind, boundary, .. } => {
            let named = structure.and_then(|s| {
                let sim = Simulator::<M>::new(*p, SimOptions::default()).ok()?;
                admissible::worst_margin(&sim, s, points)
            });
            match named {
                Some(w)
                    if w.boundary == boundary
                        && matches!(w.kind, ViolationKind::Pass | ViolationKind::StickOnset)
                        && matches!(
                            kind,
                            ViolationKind::Arrival
                                | ViolationKind::Interior
                                | ViolationKind::Departure
                        ) =>
                {
                    transition_kind(w.kind)
                }
                _ => transition_kind(kind),
            }
        }
    }
}

fn end_of(e: Option<(super::CurveEndReason, Sample)>) -> Option<CurveEnd> {
    e.map(|(reason, at)| CurveEnd {
        reason,
        at: to_point(&at.x),
    })
}

/// Trace the curve through `start` on which `condition` of the motion of
/// `structure` vanishes, both ways, in `plane` (every other parameter from
/// `base`). `start` need only be close: it is corrected first (with its
/// `y` fixed, or else its `x`).
pub fn trace<M: Model>(
    base: &M::Params,
    plane: &Plane,
    structure: Option<&Structure>,
    start: &CurvePoint,
    condition: Condition,
    opts: &CurveOptions,
) -> Result<Curve, CurveError> {
    trace_watching::<M>(base, plane, structure, start, condition, None, opts)
}

/// [`trace`], with the margin `watched` watched along the curve even where
/// it nearly vanishes at the start (a condition that vanishes with the
/// curve's own there, to 1e-6, is otherwise taken for the same event and
/// left out): the curve's end where it vanishes is then a
/// codimension-two end. For a curve started by branch switching
/// ([`super::partner_start`]) a step from the codimension-two point, where
/// the first curve's condition is still small: left out, the curve ran
/// through the point into the region where the motion is not admissible
/// (the paper model's `P_{(3_31 0_11 3_13 4_33)^2 3_33 4_33 3_31 0_11
/// 3_13 4_33 3_33 4_33}^5` passable onset across its band's tip at
/// W = 3.5838, Q0 = 72.017, where its `3_33` flows cross Σ1 beyond).
pub fn trace_watching<M: Model>(
    base: &M::Params,
    plane: &Plane,
    structure: Option<&Structure>,
    start: &CurvePoint,
    condition: Condition,
    watched: Option<Condition>,
    opts: &CurveOptions,
) -> Result<Curve, CurveError> {
    check_options(opts)?;
    let sys = system::<M>(base, plane, structure, start, condition)?;
    let n = sys.len();
    let mut x = unknowns(start);
    // Phase origin: 0 <= W t_0 < 2π.
    if n > 2 {
        let turns = (x[1] / std::f64::consts::TAU).floor();
        for k in 0..(n - 2) / 2 {
            x[2 * k + 1] -= turns * std::f64::consts::TAU;
        }
    }
    let mut tracer = Tracer {
        sys,
        opts,
        plane: *plane,
    };
    let mut border = vec![0.0; n];
    let mut corrected = None;
    let mut why = String::new();
    // On a symmetric motion the mirror of the curve's own tangential
    // arrival is pinned (the regular form of its double root), and a
    // symmetric motion's pitchfork is solved on the symmetric motions alone
    // (`system`); should the start not solve so, it is tried without.
    let regular: &[bool] = if tracer.sys.pin_tangent_arrivals(&x) > 0 || tracer.sys.restricted() {
        &[true, false]
    } else {
        &[false]
    };
    for (&special, axis) in regular.iter().flat_map(|r| [(r, 1), (r, 0)]) {
        if !special {
            tracer.sys.unpin();
            tracer.sys.unrestrict();
        }
        tracer.sys.axis(axis, &mut border);
        let mut trial = x.clone();
        match tracer
            .sys
            .correct(&mut trial, &border, &x, opts.tolerance, 40)
        {
            Correction::Converged { .. } => {
                // The condition must vanish at the start, not elsewhere: a
                // corrector that runs off (the start's condition not the
                // one that vanishes there) would trace another curve.
                let moved = tracer.plane_distance(&trial, &x);
                if moved <= START_REACH {
                    corrected = Some(trial);
                    break;
                }
                why = format!(
                    "the condition vanishes {moved:.1e} of the box away from the start, not at it"
                );
            }
            Correction::Failed(w) => why = w,
        }
    }
    let x = corrected.ok_or(CurveError::Start(why))?;
    {
        let p = tracer.sys.params(&x);
        let pts = to_point(&x).points;
        tracer.sys.eval.exclude_companions(&p, &pts);
        if let Some(id) = watched.and_then(Condition::margin_id) {
            tracer.sys.eval.watch(id);
        }
        if tracer.sys.pinned() > 0 {
            tracer.sys.pin_tangent_arrivals(&x);
        }
    }
    let mut t = vec![0.0; n];
    let mut tangent = Err(String::new());
    for axis in [0, 1] {
        tracer.sys.axis(axis, &mut border);
        tangent = tracer.sys.tangent(&x, &border, &mut t);
        if tangent.is_ok() {
            break;
        }
    }
    tangent.map_err(CurveError::Start)?;
    let first = tracer
        .examine(x.clone(), t.clone())
        .map_err(CurveError::Start)?;
    if first.companion < 0.0 {
        return Err(CurveError::Start(format!(
            "a condition within {SAME_EVENT:e} of zero at the start, taken to vanish with the curve's own, is violated there beyond rounding ({:?})",
            first.companion_id
        )));
    }
    if first.other_event.is_nan() || first.other_event <= 0.0 {
        return Err(CurveError::Start(format!(
            "another condition fails at the start ({:?}, margin {:e})",
            first.worst_event, first.other_event
        )));
    }
    let p = tracer.sys.params(&x);
    let start_point = to_point(&x);
    let kind = kind_of::<M>(condition, &p, structure, &start_point.points);
    let boundary = match condition {
        Condition::Margin { boundary, .. } => boundary,
        Condition::RestGrazing { boundary } => Some(boundary),
        Condition::Eigen(_) | Condition::NormalField { .. } => None,
    };
    let forward = tracer.run(first.clone(), true);
    let make = |points: Vec<Sample>, ends: Vec<CurveEnd>, special: Vec<Special>| Curve {
        kind,
        condition,
        boundary,
        structure: structure.cloned(),
        points: points.iter().map(|s| to_point(&s.x)).collect(),
        ends,
        special,
    };
    let specials = |run: &Run, shift: usize, reverse: Option<usize>| -> Vec<Special> {
        run.special
            .iter()
            .map(|f| Special {
                index: match reverse {
                    Some(nb) => nb - f.index - 1,
                    None => f.index + shift,
                },
                kind: f.kind,
                at: to_point(&f.at.x),
            })
            .collect()
    };
    if forward.end.is_none() {
        let special = specials(&forward, 0, None);
        return Ok(make(forward.points, Vec::new(), special));
    }
    let mut back_start = first;
    back_start.t.iter_mut().for_each(|c| *c = -*c);
    let backward = tracer.run(back_start, false);
    let nb = backward.points.len() - 1;
    let mut special = specials(&backward, 0, Some(nb));
    special.reverse();
    special.extend(specials(&forward, nb, None));
    let mut points: Vec<Sample> = backward.points.into_iter().skip(1).rev().collect();
    points.extend(forward.points);
    let ends = [end_of(backward.end), end_of(forward.end)]
        .into_iter()
        .flatten()
        .collect();
    Ok(make(points, ends, special))
}

/// The condition's value at `point` (the motion's switching points given,
/// not corrected): zero on the curve. For tests and checks.
pub fn condition_value<M: Model>(
    base: &M::Params,
    plane: &Plane,
    structure: Option<&Structure>,
    point: &CurvePoint,
    condition: Condition,
) -> Result<f64, CurveError> {
    let mut sys = system::<M>(base, plane, structure, point, condition)?;
    let v = sys.condition(&unknowns(point));
    if v.is_nan() {
        return Err(CurveError::Condition(format!(
            "{condition:?} at ({}, {})",
            point.x, point.y
        )));
    }
    Ok(v)
}

/// How well the second condition holds at a codimension-two end of
/// `curve` (its own condition holds there as at every point of the curve):
/// over the motion's conditions that mark the end's kind (on its boundary,
/// if it names one), other than the curve's own, the smallest
/// `|margin| / scale` ([`condition_scale`](super::condition_scale)); for a
/// fold, period doubling or Neimark–Sacker end, the test function's over
/// its scale. `None` for another end, for the no-motion regime's curves,
/// for an end where an excursion shrank to nothing (two equal switching
/// points: solved on the reduced motion, `super::excursion`), or if no
/// such condition is evaluable there. Near 0 (rounding): both
/// conditions vanish at the reported point; larger: the end was located
/// only to where the curve could be followed (a cascade's accumulation,
/// where the curve's system turns singular), and this says how far.
pub fn codim2_residual<M: Model>(
    base: &M::Params,
    plane: &Plane,
    curve: &Curve,
    end: &CurveEnd,
) -> Option<f64> {
    let super::CurveEndReason::Codim2 { kind, boundary } = end.reason else {
        return None;
    };
    let structure = curve.structure.as_ref()?;
    // An excursion's end: solved on the reduced motion (`super::excursion`);
    // the full motion's conditions say nothing there.
    if curve.shrunk_excursion(&end.at) {
        return None;
    }
    let mut p = *base;
    p.set(plane.x, end.at.x);
    p.set(plane.y, end.at.y);
    let scaled = |c: Condition, v: f64| {
        (v / super::condition_scale::<M>(&p, c, Some(structure), &end.at.points)).abs()
    };
    if matches!(
        kind,
        TransitionKind::Fold
            | TransitionKind::BranchPoint
            | TransitionKind::PeriodDoubling
            | TransitionKind::NeimarkSacker
    ) {
        let c = Condition::Eigen(kind);
        let v = condition_value::<M>(base, plane, Some(structure), &end.at, c).ok()?;
        return Some(scaled(c, v).min(halves_residual::<M>(base, plane, curve, end, &p)));
    }
    let SecondMargins {
        sim,
        walked,
        scaled: margins,
    } = second_margins::<M>(
        base,
        plane,
        structure,
        curve.condition,
        kind,
        boundary,
        &end.at,
    )?;
    // A stick's vanishing where an extremum of `Fnf` at `±as` sits at an
    // end of the stick (on a passable-onset curve, which holds `|Fnf| = as`
    // at the stick's start: the interior extrema hold no such margin yet).
    // On `stribeck8` a passable-onset curve of a period-2 motion ends so
    // at W = 2.44708, Q0 = 2.11038, its interior extrema 4.6e-2 of the
    // scale off.
    let vanishing = kind == TransitionKind::StickVanishing;
    let touches = walked
        .iter()
        .filter(|c| {
            vanishing
                && c.kind == ViolationKind::StickEnd
                && (boundary.is_none() || c.boundary == boundary)
        })
        .filter_map(|c| {
            let touch = admissible::end_touch(&sim, structure, &end.at.points, c.segment)?;
            let cond = Condition::Margin {
                kind: c.kind,
                segment: c.segment,
                boundary: c.boundary,
            };
            Some(scaled(cond, touch))
        });
    margins
        .into_iter()
        .map(|(_, r)| r)
        .chain(touches)
        .min_by(f64::total_cmp)
}

/// The admissibility walk at a codimension-two point, and the margins it
/// names ([`second_margins`]).
pub(super) struct SecondMargins<M: Model> {
    /// The simulator at the point's parameters.
    pub sim: Simulator<M>,
    /// The walk's conditions there.
    pub walked: Vec<admissible::Violation>,
    /// Each candidate second condition with `|value| / scale` there.
    pub scaled: Vec<(Condition, f64)>,
}

/// The motion's margins that mark a codimension-two point `at` of kind
/// `kind` (on `boundary`, if it names one), other than the curve's own
/// `own`, each with `|value| / scale` ([`condition_scale`](super::condition_scale)),
/// measured as a curve measures it (a stick's end by its smooth margin,
/// not the event search's phase difference). The candidates come from
/// the admissibility walk, with an interior margin to each boundary (where
/// the event search finds an early contact the walk lists one interior
/// entry per segment, the contact's, while each boundary's has a smooth
/// margin). `None` if the walk cannot run there.
pub(super) fn second_margins<M: Model>(
    base: &M::Params,
    plane: &Plane,
    structure: &Structure,
    own: Condition,
    kind: TransitionKind,
    boundary: Option<usize>,
    at: &CurvePoint,
) -> Option<SecondMargins<M>> {
    let p = with::<M>(base, plane, at.x, at.y);
    let sim = Simulator::<M>::new(p, SimOptions::default()).ok()?;
    let walked = admissible::conditions(&sim, structure, &at.points);
    let mut candidates: Vec<Condition> = Vec::new();
    for c in &walked {
        let boundaries: Vec<Option<usize>> = if c.kind == ViolationKind::Interior {
            (0..M::info(&p).boundaries.len()).map(Some).collect()
        } else {
            vec![c.boundary]
        };
        for b in boundaries {
            let cond = Condition::Margin {
                kind: c.kind,
                segment: c.segment,
                boundary: b,
            };
            if transition_kind(c.kind) == kind
                && (boundary.is_none() || b == boundary)
                && cond != own
                && !candidates.contains(&cond)
            {
                candidates.push(cond);
            }
        }
    }
    let scaled = candidates
        .into_iter()
        .filter_map(|c| {
            let v = condition_value::<M>(base, plane, Some(structure), at, c).ok()?;
            let r = (v / super::condition_scale::<M>(&p, c, Some(structure), &at.points)).abs();
            Some((c, r))
        })
        .collect();
    Some(SecondMargins {
        sim,
        walked,
        scaled,
    })
}

/// At a period-doubling end of a fold curve of `T T` (two equal halves,
/// `super::halves`): `T`'s period-doubling test function on the first
/// half over its scale; `∞` for any other end.
fn halves_residual<M: Model>(
    base: &M::Params,
    plane: &Plane,
    curve: &Curve,
    end: &CurveEnd,
    p: &M::Params,
) -> f64 {
    let pd = Condition::Eigen(TransitionKind::PeriodDoubling);
    let half = || {
        let merging = curve.condition == Condition::Eigen(TransitionKind::Fold)
            && end.reason
                == (super::CurveEndReason::Codim2 {
                    kind: TransitionKind::PeriodDoubling,
                    boundary: None,
                });
        let t = curve.structure.as_ref()?.half().filter(|_| merging)?;
        let h = t.len();
        let at = CurvePoint {
            points: end.at.points[..h].to_vec(),
            ..end.at.clone()
        };
        let v = condition_value::<M>(base, plane, Some(&t), &at, pd).ok()?;
        Some((v / super::condition_scale::<M>(p, pd, Some(&t), &at.points)).abs())
    };
    half().unwrap_or(f64::INFINITY)
}

/// Which condition vanishes at a transition of kind `kind` located on a
/// branch of `structure` at parameters `p` with switching points `points`.
///
/// For a non-smooth kind: the admissibility condition with the smallest
/// margin there among those that name `kind` (as
/// [`crate::bifurcation::transition_kind`] names them; any kind if none
/// does), leaving out an interior margin to a boundary the segment both
/// starts and ends on (an excursion shrinking to nothing: its margin
/// vanishes quadratically, its arrival's linearly, and the arrival is
/// taken). A stick's end (`StickEnd`) is measured by its smooth margin
/// (the interior extrema of `Fnf` against `±as`, or the exit's rate
/// `d|Fnf|/dφ` if smaller, `orbit::admissible::margin_of`) rather than the
/// event search's phase
/// difference, which jumps; where the event search's margin is the
/// smallest (the sweep located a stick that ends early) the smooth one must
/// be the smallest too. `None` if nothing is evaluable, if the smallest
/// (by the event search) is a stick's end whose smooth margin is not the
/// smallest (a stick that never ends), or whose extremum of `Fnf` lies
/// within `1e-3` rad of the stick's start (the margin vanishes
/// quadratically; at its exit the exit's rate is the margin, a simple
/// zero), or if a segment's duration is below `1e-3` rad
/// there (a segment shrinking to nothing: the structure's equations
/// degenerate on the curve, which the motion on the other side of the
/// transition carries). For an
/// eigenvalue kind: `Eigen(kind)`; a branch point keeps its kind and is
/// traced on `det(I − DP)` like a fold.
pub fn condition_at_transition<M: Model>(
    p: &M::Params,
    structure: &Structure,
    points: &[SwitchingPoint],
    kind: TransitionKind,
) -> Option<Condition> {
    if kind.is_eigenvalue() {
        return Some(Condition::Eigen(kind));
    }
    if points.len() != structure.len() {
        return None;
    }
    let sim = Simulator::<M>::new(*p, SimOptions::default()).ok()?;
    let mut all = admissible::conditions(&sim, structure, points);
    let info = M::info(p);
    // The smallest as the sweep saw it (a stick's end by the event search).
    let seen = all
        .iter()
        .filter(|c| c.margin.is_finite())
        .min_by(|a, b| a.margin.total_cmp(&b.margin))
        .map(|c| (c.kind, c.segment, c.boundary))?;
    // A stick's end measured by its smooth margin (the interior extrema of
    // Fnf against ±as, or the exit's rate if smaller), NaN where it has none.
    for c in all.iter_mut().filter(|c| c.kind == ViolationKind::StickEnd) {
        c.margin = admissible::margin_of(&sim, structure, points, (c.kind, c.segment, c.boundary))
            .unwrap_or(f64::NAN);
    }
    // An interior margin to a boundary that the segment starts and ends
    // on, where the segment's arrival turns tangential with it, measures
    // an excursion that shrinks to nothing: it vanishes quadratically (no
    // simple zero), with the arrival's that vanishes linearly. Where the
    // arrival stays transversal, it is a second extremum of the excursion
    // touching the boundary (the segment splits in three): a simple zero.
    let transversal = |segment: usize| {
        all.iter().any(|a| {
            a.kind == ViolationKind::Arrival && a.segment == segment && a.margin > VANISHING
        })
    };
    let degenerate = |c: &admissible::Violation| {
        c.kind == ViolationKind::Interior && {
            let mi = info.mappings[structure.steps()[c.segment]];
            c.boundary == Some(mi.from) && c.boundary == Some(mi.to) && !transversal(c.segment)
        }
    };
    let usable = |c: &&admissible::Violation| {
        c.margin.is_finite() && c.kind != ViolationKind::Other && !degenerate(c)
    };
    let pick = |named: bool| {
        all.iter()
            .filter(usable)
            .filter(|c| !named || transition_kind(c.kind) == kind)
            .min_by(|a, b| a.margin.total_cmp(&b.margin))
    };
    let smallest = all
        .iter()
        .filter(|c| c.margin.is_finite())
        .min_by(|a, b| a.margin.total_cmp(&b.margin))?;
    // A stick that ends early: a curve only where its smooth margin is the
    // one that vanishes (an extremum of Fnf touching ±as), not for a stick
    // that never ends or ends at its exit tangentially.
    if seen.0 == ViolationKind::StickEnd
        && (smallest.kind, smallest.segment, smallest.boundary) != seen
    {
        return None;
    }
    // A segment shrinking to nothing: its mapping equation degenerates
    // (its arrival and departure turn tangential with it), so no condition
    // of this structure has a regular curve there; the motion on the other
    // side of the transition carries it.
    if vanishing_segment(structure, points) {
        return None;
    }
    let chosen = pick(true).or_else(|| pick(false))?;
    // A stick's end whose extremum of Fnf sits at the stick's start: the
    // margin vanishes quadratically there. (At its exit the margin is the
    // exit's rate, a simple zero.)
    if chosen.kind == ViolationKind::StickEnd {
        if let Some((_, gap)) =
            admissible::early_end_extremum(&sim, structure, points, chosen.segment)
        {
            if gap <= VANISHING {
                return None;
            }
        }
    }
    Some(Condition::Margin {
        kind: chosen.kind,
        segment: chosen.segment,
        boundary: chosen.boundary,
    })
}
