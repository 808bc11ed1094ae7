//! Branch switching at a codimension-two point: the start of the second
//! condition's curve through a point where a traced curve ends (or a
//! special point it passes), as AUTO and MatCont switch from a
//! codimension-two point onto the other curve through it.
//!
//! At such a point two conditions of one motion vanish at once: the
//! curve's own, `A`, and a second, `B`. The curve of `B` passes there too;
//! where `A` is an admissibility margin, only its half on the side where
//! `A > 0` is a transition (beyond it the motion does not exist), and a
//! trace started exactly at the point fails (`A` is another condition that
//! fails at the start). So the start is one step along `B`'s tangent,
//! corrected onto `B = 0` by pseudo-arclength, on the side where `A`'s
//! margin is positive (either side for an eigenvalue test function `A`:
//! the motion exists on both).

use crate::bifurcation::bordered::Correction;
use crate::bifurcation::TransitionKind;
use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::{Model, ParamSet};
use crate::orbit::admissible::{self, ViolationKind, SAME_EVENT};
use crate::orbit::structure::Structure;

use super::condition::{condition_scale, COMPANION_SLACK};
use super::start::{
    condition_value, second_margins, system, to_point, unknowns, vanishing_segment,
};
use super::{Condition, Curve, CurveEndReason, CurvePoint, Plane};

/// The step from the codimension-two point onto the second curve, in the
/// scaled metric (each parameter over its span).
pub const PARTNER_STEP: f64 = 1e-3;

/// A start found on a line held `step` from the point may lie this many
/// steps from it, no further.
const REACH: f64 = 10.0;

/// The start of a second curve through a codimension-two point.
#[derive(Clone, Debug, PartialEq)]
pub struct PartnerStart {
    /// The second condition, of the curve's own motion.
    pub condition: Condition,
    /// The transition it marks.
    pub kind: TransitionKind,
    /// Its boundary, if any.
    pub boundary: Option<usize>,
    /// The motion (the curve's).
    pub structure: Structure,
    /// The start: on `condition`'s curve, a step from the point, where the
    /// curve's own condition holds (its margin positive).
    pub point: CurvePoint,
    /// Whether the second curve runs more horizontally than vertically
    /// there (each parameter over its span): a vertical line crosses it
    /// transversally.
    pub horizontal: bool,
}

/// A codimension-two point of a curve: where a second condition of its
/// motion vanishes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Codim2Place<'a> {
    /// The second condition's transition.
    pub kind: TransitionKind,
    /// Its boundary, if any.
    pub boundary: Option<usize>,
    /// Where (one of the curve's points).
    pub at: &'a CurvePoint,
}

/// The codimension-two points of `curve` where a second condition of its
/// motion vanishes: its codim-2 ends, and the fold and period-doubling
/// points along a margin curve ([`super::Special`]). Not the ends where an
/// excursion shrank to nothing (their second curve is the reduced
/// motion's).
pub fn codim2_places(curve: &Curve) -> Vec<Codim2Place<'_>> {
    let mut out = Vec::new();
    if curve.structure.is_none() {
        return out;
    }
    for e in &curve.ends {
        if let CurveEndReason::Codim2 { kind, boundary } = e.reason {
            if !curve.shrunk_excursion(&e.at) {
                out.push(Codim2Place {
                    kind,
                    boundary,
                    at: &e.at,
                });
            }
        }
    }
    for s in &curve.special {
        out.push(Codim2Place {
            kind: s.kind,
            boundary: None,
            at: &s.at,
        });
    }
    out
}

/// The second condition vanishing at `at` with `curve`'s own: the
/// eigenvalue test function of an eigenvalue `kind`, else the motion's
/// margin of that kind (on `boundary`) other than the curve's own that is
/// smallest there relative to its scale.
fn second_condition<M: Model>(
    base: &M::Params,
    plane: &Plane,
    curve: &Curve,
    structure: &Structure,
    kind: TransitionKind,
    boundary: Option<usize>,
    at: &CurvePoint,
) -> Option<Condition> {
    if kind.is_eigenvalue() {
        let c = Condition::Eigen(kind);
        return (c != curve.condition).then_some(c);
    }
    second_margins::<M>(base, plane, structure, curve.condition, kind, boundary, at)?
        .scaled
        .into_iter()
        .filter(|(_, r)| r.is_finite())
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(c, _)| c)
}

/// The start of the second curve through the codimension-two point
/// `place` of `curve` (one of [`codim2_places`]), where a condition of its
/// kind (on its boundary) vanishes with the curve's own: `step` (in the scaled
/// metric; [`PARTNER_STEP`] first) along the second condition's tangent
/// from `at`, corrected onto its curve by pseudo-arclength to `tolerance`,
/// on the side where the curve's own margin is positive (the first side
/// that converges, for an eigenvalue curve). Where the second curve's
/// system is singular at the point (a stick's end whose extremum of `Fnf`
/// sits at the stick's exit there, an interior grazing merging into an
/// end) or neither side holds, the start is solved instead on the four
/// lines `step` from the point, each parameter held in turn. `None` if no
/// second condition is found or no trial converges inside the box, within
/// ten steps of the point, with the own margin positive. A trial whose
/// motion has a segment shorter than `1e-3` rad is refused, as a line's
/// start is ([`super::condition_at_transition`]): a segment of no length
/// solves its mapping equation exactly, so the structure has solutions
/// where its motion is the reduced one (the segment removed), singular
/// ones, and the second curve traced on them is the reduced motion's
/// border under another name, or none (`tests/curve_partner_vanishing.rs`).
pub fn partner_start<M: Model>(
    base: &M::Params,
    plane: &Plane,
    curve: &Curve,
    place: &Codim2Place<'_>,
    step: f64,
    tolerance: f64,
) -> Option<PartnerStart> {
    let Codim2Place { kind, boundary, at } = *place;
    let structure = curve.structure.as_ref()?;
    let second = second_condition::<M>(base, plane, curve, structure, kind, boundary, at)?;
    let mut sys = system::<M>(base, plane, Some(structure), at, second).ok()?;
    let x0 = unknowns(at);
    let n = x0.len();
    let spans = sys.spans();
    let mut t = vec![0.0; n];
    let mut border = vec![0.0; n];
    let tangent = (0..2).any(|axis| {
        sys.axis(axis, &mut border);
        sys.tangent(&x0, &border, &mut t).is_ok()
    });
    // Trials: (the anchor's offset, the border row, whether the second
    // curve runs more horizontally there).
    let mut trials: Vec<(Vec<f64>, Vec<f64>, bool)> = Vec::new();
    if tangent {
        let horizontal = (t[n - 2] / spans[0]).abs() >= (t[n - 1] / spans[1]).abs();
        for sign in [1.0, -1.0] {
            trials.push((
                t.iter().map(|d| sign * step * d).collect(),
                t.clone(),
                horizontal,
            ));
        }
    }
    for axis in 0..2 {
        for sign in [1.0, -1.0] {
            let mut offset = vec![0.0; n];
            offset[n - 2 + axis] = sign * step * spans[axis];
            let mut held = vec![0.0; n];
            sys.axis(axis, &mut held);
            // Holding `x`, the line is vertical: the curve crosses it.
            trials.push((offset, held, axis == 0));
        }
    }
    let own_margin = matches!(curve.condition, Condition::Margin { .. });
    let inside = |y: &[f64]| {
        (plane.x_range[0]..=plane.x_range[1]).contains(&y[n - 2])
            && (plane.y_range[0]..=plane.y_range[1]).contains(&y[n - 1])
    };
    let near = |y: &[f64]| {
        ((y[n - 2] - x0[n - 2]) / spans[0]).hypot((y[n - 1] - x0[n - 1]) / spans[1]) <= REACH * step
    };
    for (offset, border, horizontal) in trials {
        let anchor: Vec<f64> = x0.iter().zip(&offset).map(|(x, d)| x + d).collect();
        let mut y = anchor.clone();
        if !matches!(
            sys.correct(&mut y, &border, &anchor, tolerance, 40),
            Correction::Converged { .. }
        ) || !inside(&y)
            || !near(&y)
        {
            continue;
        }
        let point = to_point(&y);
        // A segment that stays shrunk to nothing along the second curve:
        // that curve is the reduced motion's, as a line's start refuses it
        // (`condition_at_transition`).
        if vanishing_segment(structure, &point.points) {
            continue;
        }
        if own_margin {
            let own = condition_value::<M>(base, plane, Some(structure), &point, curve.condition);
            if !own.is_ok_and(|v| v > 0.0) {
                continue;
            }
        }
        let boundary = match second {
            Condition::Margin { boundary, .. } => boundary,
            _ => None,
        };
        return Some(PartnerStart {
            condition: second,
            kind,
            boundary,
            structure: structure.clone(),
            point,
            horizontal,
        });
    }
    None
}

/// A curve switched to may not run where a condition of its motion other
/// than its own is violated by more than this fraction of that
/// condition's scale ([`condition_scale`]): the companions' slack
/// ([`COMPANION_SLACK`]). A condition that vanishes with the curve's own
/// all along holds to rounding.
pub const ADMISSIBLE_TO: f64 = COMPANION_SLACK;

/// The first point of `curve` (its ends aside) where a condition of its
/// motion other than its own is violated by more than [`ADMISSIBLE_TO`] of
/// its scale (by the admissibility walk, with its event search; a stick's
/// end by its smooth margin), with that margin over its scale: `None` if
/// the motion is admissible all along. The interior contact of a segment
/// whose arrival or departure on that boundary is tangential there (to
/// [`SAME_EVENT`]) is that tangency while its margin is within
/// `SAME_EVENT` of zero, not a contact: the velocity's extremum sits at
/// the segment's end, its margin zero or a rounding's square root off it
/// (the tracer watches it so).
///
/// Without a watch on a condition within `SAME_EVENT` of zero at a curve's
/// start, a curve can run on where its motion no longer exists: on the
/// paper model (W = 3…4 × Q0 = 65…75) a passable-onset curve of `P_{(3_31 0_11 3_13 4_33)^2 3_33 4_33 3_31 0_11
/// 3_13 4_33 3_33 4_33}^5` runs across its band's tip at W = 3.5838,
/// Q0 = 72.017 to Q0 = 71.97, where its `3_33` flow crosses Σ1 (margin
/// −5.1e-7 at Q0 = 72.014, −7.7e-6 at its end). Such a condition is
/// watched to [`COMPANION_SLACK`] of its scale; this check stays as the
/// branch switch's guard and the audit's measure
/// (`examples/curves_audit.rs`).
pub fn inadmissible_point<M: Model>(
    base: &M::Params,
    plane: &Plane,
    curve: &Curve,
) -> Option<(f64, CurvePoint)> {
    let structure = curve.structure.as_ref()?;
    let own = curve.condition.margin_id();
    let n = curve.points.len();
    let mut sim: Option<Simulator<M>> = None;
    for q in curve.points.iter().take(n.saturating_sub(1)).skip(1) {
        let mut p = *base;
        p.set(plane.x, q.x);
        p.set(plane.y, q.y);
        let sim = match &mut sim {
            Some(s) => {
                if s.set_params(p).is_err() {
                    continue;
                }
                s
            }
            None => match Simulator::<M>::new(p, SimOptions::default()) {
                Ok(s) => sim.insert(s),
                Err(_) => continue,
            },
        };
        let all = admissible::conditions(sim, structure, &q.points);
        let tangency = |c: &admissible::Violation| {
            c.kind == ViolationKind::Interior
                && all.iter().any(|e| {
                    matches!(e.kind, ViolationKind::Arrival | ViolationKind::Departure)
                        && (e.segment, e.boundary) == (c.segment, c.boundary)
                        && e.margin.abs() <= SAME_EVENT
                })
                && c.margin >= -SAME_EVENT
        };
        let worst = all
            .iter()
            .filter(|c| Some((c.kind, c.segment, c.boundary)) != own && !tangency(c))
            .filter_map(|c| {
                let id = (c.kind, c.segment, c.boundary);
                let m = if c.kind == ViolationKind::StickEnd {
                    admissible::margin_of(sim, structure, &q.points, id)?
                } else {
                    c.margin
                };
                let cond = Condition::Margin {
                    kind: c.kind,
                    segment: c.segment,
                    boundary: c.boundary,
                };
                let scaled = m / condition_scale::<M>(&p, cond, Some(structure), &q.points);
                scaled.is_finite().then_some(scaled)
            })
            .fold(f64::INFINITY, f64::min);
        if worst < -ADMISSIBLE_TO {
            return Some((worst, q.clone()));
        }
    }
    None
}
