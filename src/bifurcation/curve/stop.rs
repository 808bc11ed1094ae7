//! How a curve that cannot go on ends: where its corrector fails at the
//! smallest step or it stalls (singular at the point, no headway in the
//! plane, or crawling), at a codimension-two point ahead if one is solved
//! directly: with the other margin that falls ([`Tracer::pair_point`]), at
//! a tangential end of the grazed segment ([`Tracer::tangency_point`]), or
//! on the reduced motion where an excursion shrinks to nothing
//! ([`Tracer::excursion_point`]), or, on a fold curve of a motion of two
//! equal halves that merge, at the degenerate period doubling of the half
//! ([`Tracer::halves_point`]); else as a corrector failure that says why.

use crate::bifurcation::bordered::Correction;
use crate::bifurcation::continuation::transition_kind;
use crate::bifurcation::TransitionKind;
use crate::model::{MappingKind, Model};
use crate::orbit::admissible::{ConditionId, ViolationKind, SAME_EVENT};
use crate::orbit::periodic::SwitchingPoint;

use super::condition::condition_scale;
use super::extended::Extended;
use super::trace::{Found, Sample, Tracer, HOLDS_TO};
use super::{Condition, CurveEndReason};

/// How many smallest steps beyond the last point a vanishing other margin
/// may reach zero for a corrector failure there to be a codimension-two
/// end ([`Tracer::vanishing_other`]).
const CODIM2_REACH: f64 = 16.0;

/// Over how many of the last steps the trend of a vanishing other margin
/// is measured ([`Tracer::vanishing_other`]).
const TREND_POINTS: usize = 12;

/// How far beyond the linear extrapolation of the vanishing other margin
/// a codimension-two point solved directly may lie
/// ([`Tracer::vanishing_other`]).
pub(super) const PAIR_REACH: f64 = 4.0;

/// Over how many accepted steps a curve that makes no headway has stalled
/// ([`Tracer::stalled`]).
const STALL_POINTS: usize = 48;

/// A curve whose last [`STALL_POINTS`] steps average less than this many
/// smallest steps crawls ([`Tracer::stalled`]): at that pace the point
/// limit comes long before the curve gets anywhere.
const CRAWL_STEPS: f64 = 100.0;

/// Over how many accepted steps a curve that moves the parameters by less
/// than [`CREEP_SPAN`] of the box creeps ([`Tracer::stalled`]).
const CREEP_POINTS: usize = 400;

/// A curve whose last [`CREEP_POINTS`] steps move the parameters by less
/// than this (in the plane, each parameter over its span) creeps: at that
/// pace it needs some 4e5 points to cross the box. Such a curve advances
/// by steps far above the smallest, so the crawl test misses it, and it
/// ran on to the point limit: on `stribeck8` W=0.5:3 × Q0=4.6:4.8 a
/// grazing curve of a 15-mapping motion took 1750 steps of 1e-7…1e-6 of
/// the box near W = 1.3028, Q0 = 4.686, 2.5e-5 in W together.
const CREEP_SPAN: f64 = 1e-3;

/// A margin that falls to less than this fraction of itself over the last
/// [`TREND_POINTS`] steps is vanishing ([`Tracer::falling_other`]). On the
/// Shaw case's grazing curves the pass margin falls from 4.2e-3 to 4.3e-6
/// over the last 12 points before the condition can no longer be held to
/// 1e-10 of its scale (1.0e-3 of itself).
const FALLEN: f64 = 1e-2;

/// Newton iterations at most for a codimension-two point solved directly
/// ([`Extended::correct_pair`](super::extended::Extended::correct_pair)
/// stops earlier once its residuals stall at rounding).
pub(super) const PAIR_ITERATIONS: usize = 64;

/// How many margins at most a codimension-two point is solved with in turn
/// ([`Tracer::pair_point`]).
const PAIR_RESOLVES: usize = 3;

/// Where the trend of the other margin is measured from: the first point
/// with a finite margin among the last [`TREND_POINTS`] before the last of
/// `points` (at the smallest step the margin's rounding, a few 1e-8 on a
/// stick onset near a tangential arrival, is as large as its fall over one
/// step). Shared by [`Tracer::vanishing_other`] and
/// [`Tracer::falling_other`].
fn trend_start(points: &[Sample]) -> Option<&Sample> {
    let first = points.len().saturating_sub(TREND_POINTS + 1);
    points[first..points.len().checked_sub(1)?]
        .iter()
        .find(|q| q.other.is_finite())
}

impl<M: Model> Tracer<'_, M> {
    /// Where the corrector fails even at the smallest step, whether the
    /// curve has run into a codimension-two point it cannot step past: the
    /// smallest other margin falls towards zero along the last steps. There
    /// the curve's own system may turn singular as the other condition
    /// vanishes (an arrival before a stick turning tangential leaves the
    /// stick's start free along the stick to first order), or its own
    /// condition stop existing (a grazing extremum that leaves the segment
    /// through its arrival as that arrival turns tangential: no extremum,
    /// no grazing margin, beyond), so no candidate with the other margin
    /// `<= 0` is ever accepted for [`Self::codim2`] to locate.
    ///
    /// The point is solved where both conditions vanish
    /// ([`Self::pair_point`]), if that converges ahead of `prev`, in the
    /// plane within [`PAIR_REACH`] times the linear extrapolation of the
    /// margin along the last [`TREND_POINTS`] steps (plus [`CODIM2_REACH`]
    /// smallest steps); else, within [`PAIR_REACH`] times its extrapolation
    /// as the square of the distance, at a tangential end of the grazed
    /// segment ([`Self::tangency_point`]) or where an excursion of the
    /// motion vanishes ([`Self::excursion_point`]);
    /// otherwise `prev` is the end if that extrapolation (in the scaled
    /// metric) reaches zero within [`CODIM2_REACH`] smallest steps, or the
    /// margin already holds there ([`Self::holds_other`]). `None`: a plain
    /// failure.
    fn vanishing_other(
        &mut self,
        points: &[Sample],
        prev: &Sample,
    ) -> Option<(CurveEndReason, Sample)> {
        let before = trend_start(points)?;
        let (o0, o1) = (before.other, prev.other);
        if !(o0.is_finite() && o1.is_finite() && o1 >= 0.0 && o1 < o0) {
            return None;
        }
        let step = self.sys.distance(&prev.x, &before.x);
        // Linear extrapolation of the margin along the last steps.
        let reach = o1 * step / (o0 - o1);
        if reach.is_nan() {
            return None;
        }
        // The same in the plane alone.
        let reach_plane = o1 * self.plane_distance(&prev.x, &before.x) / (o0 - o1);
        let (kind, boundary) = prev
            .worst
            .map_or((TransitionKind::Grazing, None), |(k, _, b)| {
                (transition_kind(k), b)
            });
        let reason = CurveEndReason::Codim2 { kind, boundary };
        let bound = PAIR_REACH * reach_plane + CODIM2_REACH * self.opts.min_step;
        if let Some(at) = prev.worst.and_then(|id| self.pair_point(prev, id, bound)) {
            return Some((reason, at));
        }
        // Towards a tangential end of the grazed segment the margin that
        // falls is that end's field, which goes as the square of the
        // distance along the curve: extrapolated as such.
        let (r0, r1) = (o0.sqrt(), o1.sqrt());
        let reach_square = r1 * self.plane_distance(&prev.x, &before.x) / (r0 - r1);
        let bound = PAIR_REACH * reach_square + CODIM2_REACH * self.opts.min_step;
        if let Some(at) = self.tangency_point(prev, bound) {
            return Some((reason, at));
        }
        if let Some(at) = self.excursion_point(prev, bound) {
            return Some((reason, at));
        }
        if reach > CODIM2_REACH * self.opts.min_step && !self.holds_other(prev) {
            return None;
        }
        Some((reason, prev.clone()))
    }

    /// Whether the smallest other margin at `prev` holds as a curve
    /// point's own condition must (to [`HOLDS_TO`] of its scale,
    /// [`condition_scale`]): then `prev` satisfies both conditions and is
    /// the codimension-two point, however the margin falls. On the Shaw
    /// case (`coulomb` W=0.3:1.2 × Q0=0.5:2, `bash benches/curves-runs.sh
    /// shaw`) a grazing curve of a 24-mapping motion reached a passable
    /// onset's margin of 8.8e-11 (of a scale near 1) where the pair solve
    /// failed, the system singular there, and the extrapolated reach was
    /// still above [`CODIM2_REACH`] smallest steps.
    fn holds_other(&self, prev: &Sample) -> bool {
        let (Some((kind, segment, boundary)), Some(structure)) =
            (prev.worst, self.sys.eval.structure.as_ref())
        else {
            return false;
        };
        if prev.other.is_nan() || prev.other < 0.0 {
            return false;
        }
        let m = (prev.x.len() - 2) / 2;
        let mut pts = vec![SwitchingPoint { phase: 0.0, x: 0.0 }; m];
        Extended::<M>::points_into(&prev.x, &mut pts);
        let p = self.sys.params(&prev.x);
        let condition = Condition::Margin {
            kind,
            segment,
            boundary,
        };
        prev.other <= HOLDS_TO * condition_scale::<M>(&p, condition, Some(structure), &pts)
    }

    /// Whether the smallest other margin at `prev` (the last of `points`)
    /// has fallen over the last [`TREND_POINTS`] steps to zero within
    /// [`SAME_EVENT`], or to less than [`FALLEN`] of what it was: a
    /// codimension-two point the curve runs into without reaching it (where
    /// its own condition is defined on a sliver that narrows there: an
    /// interior extremum merging with its partner at a departure that turns
    /// tangential, whose margin falls as the square of the distance).
    fn falling_other(&self, points: &[Sample], prev: &Sample) -> bool {
        trend_start(points).is_some_and(|b| {
            (0.0..=SAME_EVENT.max(FALLEN * b.other)).contains(&prev.other) && prev.other < b.other
        })
    }

    /// The end of a curve that cannot go on from `prev` (the last of
    /// `points`) for the reason `why`: a codimension-two point ahead if
    /// [`Self::vanishing_other`] finds one (added to `points`, with the
    /// special points met on the way there), else `prev` with `why`.
    pub(super) fn stop(
        &mut self,
        points: &mut Vec<Sample>,
        special: &mut Vec<Found>,
        prev: Sample,
        why: String,
    ) -> (CurveEndReason, Sample) {
        let found = self.vanishing_other(points, &prev).or_else(|| {
            // A fold of `T T` whose halves merge: `T`'s degenerate period
            // doubling.
            let at = self.halves_point(points, &prev)?;
            let reason = CurveEndReason::Codim2 {
                kind: TransitionKind::PeriodDoubling,
                boundary: None,
            };
            Some((reason, at))
        });
        let Some((reason, at)) = found else {
            let why = match (prev.worst, self.falling_other(points, &prev)) {
                (Some((kind, segment, boundary)), true) => format!(
                    "{why}; the {} margin of segment {segment}{} is {:.1e} there and falling: a codimension-two point lies ahead, not located",
                    transition_kind(kind).name(),
                    boundary.map_or(String::new(), |b| format!(" on {}", self.sys.eval.sim.info().boundaries[b].label)),
                    prev.other
                ),
                _ => why,
            };
            let why = match self.motion_conditioning(&prev) {
                Some(c) => format!(
                    "{why}; the motion's mapping equations, with both parameters, have a smallest singular value {c:.1e} of their largest there"
                ),
                None => why,
            };
            return (CurveEndReason::NewtonFailure(why), prev);
        };
        let s_c = self.sys.dot_diff(&prev.t, &at.x, &prev.x);
        if s_c > 0.0 {
            for (sp, kind) in self.specials(&prev, &at, s_c) {
                special.push(Found {
                    index: points.len() - 1,
                    kind,
                    at: sp,
                });
            }
            points.push(at.clone());
        }
        (reason, at)
    }

    /// The smallest singular value of the motion's mapping equations'
    /// Jacobian in the switching points and both parameters at `prev` over
    /// its largest (`None` for the no-motion regime or where it cannot be
    /// assembled), appended to a failed end's reason: near zero where the
    /// motion is degenerate. Measured at the failed ends of
    /// `benches/curves-runs.sh`: Shaw's undamped pure slip
    /// `P_{1_11 2_11}` near W = 1/2, where the half cycle lasts one free
    /// period and the motion stops being isolated, 1.4e-6; s8full's two
    /// passable onsets whose excursion between two sticks shrinks to
    /// nothing, 2.4e-12 and 2.5e-12; pl4's twelve ends of 8- to
    /// 20-mapping stick motions 1.3e-6 to 1.4e-2, whose equations are
    /// ill-conditioned but not known to be degenerate.
    fn motion_conditioning(&mut self, prev: &Sample) -> Option<f64> {
        let k = self.sys.len();
        // The no-motion regime has no switching points.
        if k <= 2 {
            return None;
        }
        let jac = self.sys.jacobian(&prev.x).ok()?;
        let f = nalgebra::DMatrix::from_row_slice(k - 2, k, &jac[..(k - 2) * k]);
        let sv = f.singular_values();
        let (lo, hi) = (sv.min(), sv.max());
        (hi > 0.0 && lo.is_finite()).then(|| lo / hi)
    }

    /// Why the curve has stalled, if it has: the last [`STALL_POINTS`]
    /// steps were all accepted at the smallest step only (the corrector
    /// converges, slowly, on a system singular there), together moved
    /// the parameters by less than the location tolerance (the curve runs
    /// through the switching points alone, as where an interior extremum
    /// leaves its segment through an arrival that turns tangential), or
    /// together covered less than [`CRAWL_STEPS`] smallest steps each
    /// (every longer step fails, as where the curve's condition is defined
    /// on a narrowing sliver: [`Self::falling_other`]), or the last
    /// [`CREEP_POINTS`] steps moved the parameters by less than
    /// [`CREEP_SPAN`] of the box. Any way it would
    /// crawl on to the point limit; it ends there, at a
    /// codimension-two point if one is solved ([`Self::vanishing_other`]).
    pub(super) fn stalled(&self, points: &[Sample], at_min: usize) -> Option<String> {
        if at_min >= STALL_POINTS {
            return Some(format!(
                "the corrector converges only at the smallest step ({:.0e}) over {STALL_POINTS} steps: the system is singular there",
                self.opts.min_step
            ));
        }
        let n = points.len().checked_sub(STALL_POINTS + 1)?;
        let travelled: f64 = points[n..]
            .windows(2)
            .map(|w| self.sys.distance(&w[0].x, &w[1].x))
            .sum();
        let crawl = STALL_POINTS as f64 * CRAWL_STEPS * self.opts.min_step;
        if travelled < crawl {
            return Some(format!(
                "the curve crawls: its last {STALL_POINTS} steps cover {travelled:.1e} together, less than {CRAWL_STEPS} smallest steps each (every longer step fails)"
            ));
        }
        let (a, b) = (&points[n].x, &points[points.len() - 1].x);
        let k = a.len();
        let tol = self.opts.location_tolerance;
        let moved = (a[k - 2] - b[k - 2]).abs().max((a[k - 1] - b[k - 1]).abs());
        if moved < tol {
            return Some(format!(
                "the curve stalls: its last {STALL_POINTS} steps move the parameters by {moved:.1e}, less than the location tolerance {tol:.0e}"
            ));
        }
        let n = points.len().checked_sub(CREEP_POINTS + 1)?;
        let crept = self.plane_distance(&points[n].x, &points[points.len() - 1].x);
        (crept < CREEP_SPAN).then(|| {
            format!(
                "the curve creeps: its last {CREEP_POINTS} steps move the parameters by {crept:.1e} of the box together, less than {CREEP_SPAN:.0e}"
            )
        })
    }

    /// The point where the curve's condition (a margin, or an eigenvalue
    /// test function) and the margin of the motion `first` (the smallest
    /// other margin at `prev`, or the condition violated just beyond it)
    /// vanish together, solved from `prev` with both parameters free
    /// ([`Extended::correct_pair`](super::extended::Extended::correct_pair)), if it lies ahead of `prev`, within
    /// `bound` of it in the plane (each parameter over its span), in the
    /// box, and every other condition holds there (to [`SAME_EVENT`]: the
    /// second condition and those that vanish with it are zero there up to
    /// rounding; a solution on the far root of another arrival's equation
    /// is refused).
    ///
    /// Where a third margin is negative there, it vanished first: the
    /// point is solved again with that one, up to [`PAIR_RESOLVES`] times.
    /// Where two such solutions coincide in the plane to the location
    /// tolerance relative to each parameter's magnitude, the conditions
    /// vanish together to the tolerance the ends are located to, and the
    /// first along the curve is the end: two stick onsets of a
    /// period-adding cascade vanishing together near its accumulation,
    /// whose steep margins make each `-3e-6` at the other's point,
    /// `1.5e-10` away in `Q0 = 46.7`.
    pub(super) fn pair_point(
        &mut self,
        prev: &Sample,
        first: ConditionId,
        bound: f64,
    ) -> Option<Sample> {
        let mut id = first;
        let tol = self.opts.location_tolerance;
        let n = prev.x.len();
        let mut last: Option<Sample> = None;
        for _ in 0..PAIR_RESOLVES {
            let at = self.pair_point_with(prev, id, bound)?;
            if at.other >= -SAME_EVENT {
                return Some(at);
            }
            if let Some(l) = last {
                let same = |i: usize| (l.x[i] - at.x[i]).abs() <= tol * l.x[i].abs().max(1.0);
                if same(n - 2) && same(n - 1) {
                    let (sl, sa) = (
                        self.sys.dot_diff(&prev.t, &l.x, &prev.x),
                        self.sys.dot_diff(&prev.t, &at.x, &prev.x),
                    );
                    return Some(if sl <= sa { l } else { at });
                }
            }
            id = at.worst?;
            last = Some(at);
        }
        None
    }

    /// Where the curve's interior grazing of a flow segment merges into
    /// that segment's departure from (or arrival on) the grazed boundary as
    /// it turns tangential: the normal field and its rate vanish there
    /// together ([`Condition::NormalField`]), solved from `prev` with both
    /// parameters free, both rows replacing the curve's own (the grazing
    /// margin is not smooth at that point: near it the extremum's margin
    /// goes as the square of the distance to the end). Accepted as
    /// [`Self::pair_point`] accepts: converged, in the box, ahead of `prev`
    /// within `bound`, every other condition holding there to
    /// [`SAME_EVENT`]. The departure after a stick is left out: its field
    /// is the constant `as − ak` (zero to rounding with `as = ak`, the
    /// smooth laws' N-piece models, whose rate then is the departure's
    /// margin and the point a higher order one).
    pub(super) fn tangency_point(&mut self, prev: &Sample, bound: f64) -> Option<Sample> {
        let Condition::Margin {
            kind: ViolationKind::Interior,
            segment,
            boundary: Some(b),
        } = self.sys.eval.condition
        else {
            return None;
        };
        let steps = &self.sys.eval.steps;
        let m = steps.len();
        let info = self.sys.eval.sim.info();
        let mi = info.mappings[*steps.get(segment)?];
        let before = info.mappings[steps[(segment + m - 1) % m]];
        let ends = [
            (false, mi.from == b && before.kind != MappingKind::Stick),
            (true, mi.to == b),
        ];
        let mut best: Option<Sample> = None;
        for (arrival, applies) in ends {
            if !applies {
                continue;
            }
            let Some(at) = self.field_point(prev, segment, arrival, bound) else {
                continue;
            };
            let nearer = |a: &Sample| self.sys.dot_diff(&prev.t, &a.x, &prev.x);
            if best.as_ref().is_none_or(|q| nearer(&at) < nearer(q)) {
                best = Some(at);
            }
        }
        best
    }

    /// Where the normal field at one end of flow segment `segment` (its
    /// arrival, or its departure) and that field's rate vanish together
    /// ([`Condition::NormalField`]): the departure or arrival turns
    /// tangential to second order, and an interior extremum of the velocity
    /// leaves the segment through that end. Solved from `prev` with both
    /// parameters free, both rows replacing the curve's own; accepted as
    /// [`Self::tangency_point`] accepts.
    pub(super) fn field_point(
        &mut self,
        prev: &Sample,
        segment: usize,
        arrival: bool,
        bound: f64,
    ) -> Option<Sample> {
        let step = *self.sys.eval.steps.get(segment)?;
        // A flow segment only.
        self.sys.eval.sim.info().mappings[step].domain?;
        let field = |rate| Condition::NormalField {
            segment,
            arrival,
            rate,
        };
        let x = self.solve_pair(prev, Some(field(false)), field(true), bound)?;
        let at = self.examine(x, prev.t.clone()).ok()?;
        (at.other >= -SAME_EVENT).then_some(at)
    }

    /// The solution from `prev` of the mapping equations with `second` in
    /// place of the border row (and `own` in place of the curve's
    /// condition, if given; the curve's own is restored after), with both
    /// parameters free ([`Extended::correct_pair`](super::extended::Extended::correct_pair)),
    /// if it converges, lies in the box, and lies ahead of `prev` within
    /// `bound` of it in the plane (each parameter over its span).
    fn solve_pair(
        &mut self,
        prev: &Sample,
        own: Option<Condition>,
        second: Condition,
        bound: f64,
    ) -> Option<Vec<f64>> {
        let saved = own.map(|c| {
            let own = self.sys.eval.with(c);
            std::mem::replace(&mut self.sys.eval, own)
        });
        self.sys.pair = Some(self.sys.eval.with(second));
        let mut x = prev.x.clone();
        let done = self
            .sys
            .correct_pair(&mut x, self.opts.tolerance, PAIR_ITERATIONS);
        self.sys.pair = None;
        if let Some(e) = saved {
            self.sys.eval = e;
        }
        if !matches!(done, Correction::Converged { .. }) || self.out_of_box(&x) {
            return None;
        }
        let ahead = self.sys.dot_diff(&prev.t, &x, &prev.x);
        let far = self.plane_distance(&x, &prev.x);
        (ahead > 0.0 && far <= bound).then_some(x)
    }

    /// [`Self::pair_point`] with the second condition `id`, whatever the
    /// other margins there. On an eigenvalue curve too: its end at a margin
    /// was the bracket's last trial before, which holds that margin only as
    /// well as the bracket closed on it (Shaw's pitchfork meeting the
    /// passable onset: 3.1e-12 of its scale; solved, 2.0e-17). The test
    /// function is smooth in the unknowns where an arrival before a stick
    /// turns tangential (as a passable onset nears on `stribeck8` and
    /// `stribeck::pl4`, whose static and sliding friction agree at the
    /// belt's speed) only because `DP` takes such a flow together with its
    /// stick ([`monodromy_spectral`](crate::orbit::periodic::monodromy_spectral)):
    /// the two taken apart carry `(v − V) / a`, a pole off the motion, on
    /// which this solve does not converge.
    fn pair_point_with(&mut self, prev: &Sample, id: ConditionId, bound: f64) -> Option<Sample> {
        if !matches!(
            self.sys.eval.condition,
            Condition::Margin { .. } | Condition::Eigen(_)
        ) || self.sys.eval.structure.is_none()
            || id.0 == ViolationKind::Other
        {
            return None;
        }
        let second = Condition::Margin {
            kind: id.0,
            segment: id.1,
            boundary: id.2,
        };
        let x = self.solve_pair(prev, None, second, bound)?;
        // The pair's merit weighs each row by its gradient: where the
        // curve's own condition is steep (not smooth: an extremum merging
        // with a tangential departure) it may hold there only to more than
        // `HOLDS_TO` of its scale, and a Newton polish onto the curve does
        // not lower it (measured: 2.2e-9 on `stribeck8`). Such a point is no
        // point of the curve.
        if self.sys.held(&x) > HOLDS_TO {
            return None;
        }
        self.examine(x, prev.t.clone()).ok()
    }
}
