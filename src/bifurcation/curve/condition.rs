//! Each condition of a curve as a function of the switching points and the
//! parameters (zero on the curve), and what else is watched along it: the
//! margin of every other admissibility condition (a codimension-two end
//! where it vanishes) and the eigenvalue test functions.
//!
//! * `Margin`: the margin of exactly that condition of SPEC §6, as
//!   [`crate::orbit::admissible::conditions`] computes it (the smallest of
//!   the matching entries), in the quantity's unit (a velocity, an
//!   acceleration, a force or a phase); a stick that must not end early
//!   (`StickEnd`) by the smooth margin of `orbit::admissible::margin_of`
//!   (`as ∓ Fnf` at the stick's interior extrema of `Fnf`, or the exit's
//!   rate `d|Fnf|/dφ` if smaller, a force).
//! * `Eigen(Fold)` and `Eigen(BranchPoint)`: `det(I − DP)`;
//!   `Eigen(PeriodDoubling)`: `det(I + DP)`; `Eigen(NeimarkSacker)`:
//!   `det DP − 1` (dimensionless; the pair's being complex is watched along
//!   the curve, not imposed), each times the product of the sticks' exit
//!   rates over their scales ([`exit_rates`]: `DP` has a pole where an exit
//!   turns tangential, which the product clears).
//! * `RestGrazing`: the velocity margin of the no-motion regime's steady
//!   forced response ([`crate::orbit::steady::steady_response`]) to the
//!   boundary: `v_b − max v` when the boundary bounds the domain above,
//!   `min v − v_b` below. The domain is the neighbour of the boundary whose
//!   margin is the smaller in magnitude at the curve's start.
//! * `NormalField`: `±F_j` or `±DF_j` at one end of a flow segment
//!   ([`normal_field_at`], an acceleration or its rate).

use nalgebra::Matrix2;

use super::Condition;
use crate::bifurcation::TransitionKind;
use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::{MappingKind, Model, ModelInfo};
use crate::orbit::admissible::{self, ConditionId, ViolationKind, SAME_EVENT};
use crate::orbit::periodic::{arrival, monodromy, monodromy_spectral, SwitchingPoint};
use crate::orbit::steady::steady_response;
use crate::orbit::structure::Structure;

/// The value of an eigenvalue test function at `dp`.
pub(super) fn eigen_value(kind: TransitionKind, dp: &Matrix2<f64>) -> f64 {
    let (tr, det) = (dp.trace(), dp.determinant());
    match kind {
        TransitionKind::PeriodDoubling => 1.0 + tr + det,
        TransitionKind::NeimarkSacker => det - 1.0,
        _ => 1.0 - tr + det,
    }
}

/// The product over the sticks of `steps` at `points` of each exit's rate
/// `d|Fnf|/dφ` (`orbit::admissible::stick_exit_rate`) over its scale
/// `|A0| + as + |c v_s / W|`: what an eigenvalue test function of the whole
/// cycle is multiplied by. A stick's exit phase moves with its start as
/// `1 / (dFnf/dφ)`, so `DP` has a simple pole where an exit turns
/// tangential, and `det(I ± DP)` with it; the product clears it, leaving a
/// function smooth through that point with the same zeros elsewhere. The
/// test function is then smooth where a motion's period-doubling curve runs
/// into a stick's tangential exit: on the paper model near W = 2.6977,
/// Q0 = 204.18 (`P_{3_31 0_11 1_11 0_11 1_11 3_13 4_33 3_31 0_11 1_11 3_13
/// 4_33}`, the box of `tests/curve_stick_end.rs`) the raw `det(I + DP)` could
/// be held only to 1e-7 of its scale there and the curve crawled to a
/// corrector failure 6.4e-6 (of a force near 200) short of the exit's
/// tangency. Sticks that take no time count 1.
pub(super) fn exit_rates<M: Model>(
    p: &M::Params,
    steps: &[usize],
    shift: f64,
    points: &[SwitchingPoint],
) -> f64 {
    let info = M::info(p);
    let Some(bound) = M::static_bound(p) else {
        return 1.0;
    };
    if points.len() != steps.len() {
        return 1.0;
    }
    let osc = M::oscillator(p);
    let mut product = 1.0;
    for (k, &step) in steps.iter().enumerate() {
        let mi = info.mappings[step];
        if mi.kind != MappingKind::Stick {
            continue;
        }
        let b = arrival(points, k, shift);
        let Some(rate) =
            admissible::stick_exit_rate::<M>(p, mi.from, points[k].x, points[k].phase, b.phase)
        else {
            continue;
        };
        let vs = M::boundary_velocity(p, mi.from);
        let scale = osc.amplitude.abs() + bound.abs() + (osc.stiffness * vs / osc.frequency).abs();
        product *= rate / scale.max(f64::MIN_POSITIVE);
    }
    product
}

/// The mirrored half-cycle map `R DG` of a symmetric motion at `points`
/// (the whole cycle's): `DG` the product of the first `half` mappings'
/// local Jacobians, ordered `(W t, x)`, and `R = diag(1, −1)` the mirror
/// `x → −x` (the phase's shift by `N π` is a translation). The cycle's
/// `DP = (R DG)²`, so the eigenvalue `−1` of `R DG` is the `+1` of `DP`
/// where the symmetric motion's asymmetric pair branches off (a
/// pitchfork). `Err` with the mapping whose arrival is tangential.
pub(super) fn mirrored_half_map<M: Model>(
    p: &M::Params,
    steps: &[usize],
    half: usize,
    shift: f64,
    points: &[SwitchingPoint],
) -> Result<Matrix2<f64>, usize> {
    // The first half's points and the one it arrives at: `monodromy`
    // takes each arrival from the next point.
    if half > steps.len() || half >= points.len() {
        return Err(0);
    }
    let dg = monodromy::<M>(p, &steps[..half], shift, &points[..=half])?;
    Ok(Matrix2::new(1.0, 0.0, 0.0, -1.0) * dg)
}

/// The margin of the no-motion regime of domain `j` to boundary `k`
/// (positive: the steady response stays off it); NaN if there is none.
pub(super) fn rest_margin<M: Model>(p: &M::Params, j: usize, k: usize) -> f64 {
    let Some(r) = steady_response::<M>(p, j) else {
        return f64::NAN;
    };
    let vb = M::boundary_velocity(p, k);
    let dom = M::info(p).domains[j];
    if dom.upper == Some(k) {
        vb - r.max_v
    } else {
        -r.max_v - vb
    }
}

/// The normal field `F_j` (or its rate `DF_j` with `rate`) at the departure
/// of flow segment `segment` of `steps` (or its arrival), signed into the
/// domain at the departure and out of it at the arrival: positive where
/// that end is transversal. NaN for a stick or out of range.
pub(super) fn normal_field_at<M: Model>(
    p: &M::Params,
    steps: &[usize],
    points: &[SwitchingPoint],
    segment: usize,
    arrival: bool,
    rate: bool,
) -> f64 {
    let m = steps.len();
    if segment >= m || points.len() != m {
        return f64::NAN;
    }
    // The phase of the last arrival is shifted by whole forcing periods:
    // the field does not see it.
    let at = if arrival {
        points[(segment + 1) % m]
    } else {
        points[segment]
    };
    field_at_end::<M>(p, steps[segment], at, arrival, rate)
}

/// The normal field `F_j` (or its rate `DF_j` with `rate`) of flow mapping
/// `step` at `at`, its arrival point (else its departure point), signed
/// as [`normal_field_at`]. NaN for a stick.
pub(super) fn field_at_end<M: Model>(
    p: &M::Params,
    step: usize,
    at: SwitchingPoint,
    arrival: bool,
    rate: bool,
) -> f64 {
    let info = M::info(p);
    let mi = info.mappings[step];
    let Some(j) = mi.domain else {
        return f64::NAN;
    };
    let dom = info.domains[j];
    let k = if arrival { mi.to } else { mi.from };
    let [f, df] = M::normal_field(p, j, at.x, M::boundary_velocity(p, k), at.phase);
    let above = dom.lower == Some(k);
    let sign = if above != arrival { 1.0 } else { -1.0 };
    sign * if rate { df } else { f }
}

/// The domains next to boundary `k`.
pub(super) fn neighbours(info: &ModelInfo, k: usize) -> impl Iterator<Item = usize> + '_ {
    info.domains
        .iter()
        .enumerate()
        .filter(move |(_, d)| d.lower == Some(k) || d.upper == Some(k))
        .map(|(j, _)| j)
}

/// Evaluates one condition (and the watched quantities) at many points,
/// with one simulator reused: no allocation per evaluation.
#[derive(Clone, Debug)]
pub(super) struct Evaluator<M: Model> {
    pub condition: Condition,
    pub structure: Option<Structure>,
    pub steps: Vec<usize>,
    pub shift: f64,
    /// The no-motion regime's domain of a `RestGrazing` condition.
    pub rest_domain: usize,
    pub sim: Simulator<M>,
    /// Half the structure's length when the curve is a symmetric motion's
    /// pitchfork, solved on the symmetric motions alone: the eigenvalue
    /// test function is then that of the mirrored half-cycle map
    /// ([`mirrored_half_map`]), `det(I + R DG)`; 0 otherwise.
    pub half: usize,
    /// The conditions left out of [`Self::other`] (the curve's own and
    /// those that vanish with it), the first `excluded_len`.
    excluded: [ConditionId; 8],
    excluded_len: usize,
    /// The stick ends of the structure (`StickEnd`, segment, boundary), and
    /// after them the excluded conditions: what the walk of
    /// [`Self::other`] leaves out (built once, no allocation per point).
    /// A stick's end is watched by its smooth margin instead
    /// ([`Self::stick_ends`]).
    walk_excluded: Vec<ConditionId>,
    stick_ends: usize,
}

/// At most this many conditions vanish with a curve's own.
const MAX_EXCLUDED: usize = 8;

/// A condition that vanishes with a curve's own at its start (within
/// [`SAME_EVENT`], absolute: `Evaluator::exclude_companions`) is still
/// watched along the curve (`Evaluator::companion`): the curve ends where
/// its margin over its scale ([`condition_scale`]) falls below minus this,
/// at the point where it vanishes, and a start where it is already below
/// fails (a motion that does not exist there). One that truly
/// vanishes with the curve's own holds to rounding all along (to its
/// square root where the two meet tangentially: 2e-9 to 8e-9 of its scale
/// at such starts on the stick-end and `stribeck8` boxes); one that only
/// passes near zero there (a second border of a band near the band's tip:
/// within 1e-7 of its scale over much of the box on Fig. 11's) turns
/// negative where the curve leaves the region where its motion exists.
pub const COMPANION_SLACK: f64 = 1e-8;

impl<M: Model> Evaluator<M> {
    /// The evaluator at parameters `p` (which must be valid).
    pub fn new(
        condition: Condition,
        structure: Option<&Structure>,
        p: &M::Params,
        rest_domain: usize,
    ) -> Result<Self, String> {
        let sim = Simulator::<M>::new(*p, SimOptions::default()).map_err(|e| e.to_string())?;
        let info = M::info(p);
        let mut walk_excluded = Vec::new();
        if let Some(s) = structure {
            for (k, &step) in s.steps().iter().enumerate() {
                let mi = info.mappings[step];
                if mi.kind == MappingKind::Stick {
                    walk_excluded.push((ViolationKind::StickEnd, k, Some(mi.from)));
                }
            }
        }
        let stick_ends = walk_excluded.len();
        walk_excluded.reserve_exact(MAX_EXCLUDED);
        Ok(Self {
            condition,
            steps: structure.map_or(Vec::new(), |s| s.steps().to_vec()),
            shift: std::f64::consts::TAU * structure.map_or(1, |s| s.periods()) as f64,
            structure: structure.cloned(),
            rest_domain,
            sim,
            half: 0,
            excluded: [(ViolationKind::Other, usize::MAX, None); MAX_EXCLUDED],
            excluded_len: match condition {
                Condition::Margin { .. } => 1,
                _ => 0,
            },
            walk_excluded,
            stick_ends,
        })
        .map(|mut e: Self| {
            if let Condition::Margin {
                kind,
                segment,
                boundary,
            } = condition
            {
                e.excluded[0] = (kind, segment, boundary);
            }
            e.sync_excluded();
            e
        })
    }

    /// The walk's exclusions: the stick ends, then the excluded conditions.
    fn sync_excluded(&mut self) {
        self.walk_excluded.truncate(self.stick_ends);
        self.walk_excluded
            .extend_from_slice(&self.excluded[..self.excluded_len]);
    }

    /// Watch `id` again where [`Self::exclude_companions`] left it out (it
    /// vanished with the curve's own condition at the start, to
    /// [`SAME_EVENT`]): the condition of the curve a branch switch started
    /// from, small but positive at the start, a step from the
    /// codimension-two point where it vanishes. Never the curve's own.
    /// Watched exactly, not as a companion: its margin must be positive at
    /// the start. A companion's slack would let a switched start pass where
    /// that condition vanishes identically with the curve's own (a motion
    /// `T T` whose halves are the same, on `stribeck8`: its curves double
    /// those of `T`).
    pub fn watch(&mut self, id: ConditionId) {
        if self.condition.margin_id() == Some(id) {
            return;
        }
        let mut k = 0;
        for i in 0..self.excluded_len {
            if self.excluded[i] != id {
                self.excluded[k] = self.excluded[i];
                k += 1;
            }
        }
        self.excluded_len = k;
        self.sync_excluded();
    }

    /// The companions watched ([`Self::companion`]): the excluded
    /// conditions after the curve's own (`excluded[0]`), once
    /// [`Self::exclude_companions`] has run; none before, or for a curve
    /// whose condition is not a margin.
    fn companions(&self) -> &[ConditionId] {
        self.excluded.get(1..self.excluded_len).unwrap_or(&[])
    }

    /// Whether `id` is the interior contact of a segment whose arrival or
    /// departure on that boundary is excluded (tangential with the curve's
    /// own condition): the same event as that tangency
    /// ([`Self::exclude_companions`]). Its margin is zero where the
    /// velocity's extremum sits at that end, or a rounding's square root
    /// off zero where rounding puts the extremum just inside: on the paper
    /// model's passable onset of `P_{3_31 0_11 3_13 4_33}` near its turning
    /// point W = 2.66696, Q0 = 192.1287 it is −1.2e-7 of its scale, and
    /// `orbit` finds the motion admissible there. Watched to [`SAME_EVENT`]
    /// (absolute) for that: deeper, the extremum has left the segment's
    /// end, and the curve ends where that end turned tangential to second
    /// order (`Tracer::field_point`).
    fn tangency_interior(&self, id: ConditionId) -> bool {
        self.tangential_end(id).is_some()
    }

    /// The segment and end (`true`: its arrival) whose tangency `id` is the
    /// interior contact of ([`Self::tangency_interior`]), if it is one.
    pub(super) fn tangential_end(&self, id: ConditionId) -> Option<(usize, bool)> {
        let (ViolationKind::Interior, segment, Some(b)) = id else {
            return None;
        };
        let excluded = &self.excluded[..self.excluded_len];
        if excluded.contains(&(ViolationKind::Arrival, segment, Some(b))) {
            Some((segment, true))
        } else if excluded.contains(&(ViolationKind::Departure, segment, Some(b))) {
            Some((segment, false))
        } else {
            None
        }
    }

    /// The scale of margin `id` at `(p, points)` ([`condition_scale`]).
    fn scale_of(&self, p: &M::Params, points: &[SwitchingPoint], id: ConditionId) -> f64 {
        let (kind, segment, boundary) = id;
        let condition = Condition::Margin {
            kind,
            segment,
            boundary,
        };
        condition_scale::<M>(p, condition, self.structure.as_ref(), points)
    }

    /// The smallest over the companions of each one's margin over its
    /// scale plus [`COMPANION_SLACK`] (negative: it has left rounding, and
    /// the curve its motion's region), with the condition; `+∞` without
    /// companions. The interior contact of a tangential arrival or
    /// departure ([`Self::tangency_interior`]) has [`SAME_EVENT`] instead
    /// (absolute: the depth of an extremum a rounding's square root inside
    /// the segment's end). A companion the walk does not evaluate, or
    /// cannot (NaN), does not count.
    pub fn companion(
        &mut self,
        p: &M::Params,
        points: &[SwitchingPoint],
    ) -> (f64, Option<ConditionId>) {
        let mut best = (f64::INFINITY, None);
        let n = self.companions().len();
        if n == 0 || self.sim.set_params(*p).is_err() {
            return best;
        }
        let Some(structure) = &self.structure else {
            return best;
        };
        let mut margins = [None; MAX_EXCLUDED];
        admissible::margins_of(
            &self.sim,
            structure,
            points,
            self.companions(),
            &mut margins[..n],
        );
        for (&id, margin) in self.companions().iter().zip(&margins[..n]) {
            let Some(m) = margin.filter(|m| m.is_finite()) else {
                continue;
            };
            let scale = self.scale_of(p, points, id);
            let v = if self.tangency_interior(id) {
                (m + SAME_EVENT) / scale
            } else {
                m / scale + COMPANION_SLACK
            };
            if v < best.0 {
                best = (v, Some(id));
            }
        }
        best
    }

    fn exclude(&mut self, id: ConditionId) {
        if self.excluded_len < MAX_EXCLUDED && !self.excluded[..self.excluded_len].contains(&id) {
            self.excluded[self.excluded_len] = id;
            self.excluded_len += 1;
        }
    }

    /// The smooth margin of the stick end `id` (`orbit::admissible::margin_of`:
    /// `as ∓ Fnf` at the stick's interior extrema of `Fnf`, or the exit's
    /// rate if smaller), `None` where the walk has none.
    fn stick_end_margin(
        &self,
        structure: &Structure,
        points: &[SwitchingPoint],
        id: ConditionId,
    ) -> Option<f64> {
        admissible::margin_of(&self.sim, structure, points, id)
    }

    /// Leave out of [`Self::other`] every condition that vanishes with the
    /// curve's own at `(points, p)` (a point of the curve): margin within
    /// [`SAME_EVENT`] of zero (absolute, in the quantity's unit; a stick's
    /// end by its smooth margin, as [`Self::other`] watches it). A
    /// transition where a segment shrinks to nothing makes its duration,
    /// its departure and arrival and the force criteria there vanish
    /// together, all along the curve: they are one event, not a
    /// codimension-two point. Each is still watched, to rounding relative
    /// to its scale ([`Self::companion`], [`COMPANION_SLACK`]): within 1e-6
    /// of zero is not vanishing with the curve's own (near a band's tip
    /// the band's other border is as close over much of the box).
    pub fn exclude_companions(&mut self, p: &M::Params, points: &[SwitchingPoint]) {
        let (Condition::Margin { .. }, Some(structure)) = (self.condition, self.structure.clone())
        else {
            return;
        };
        if self.sim.set_params(*p).is_err() {
            return;
        }
        for c in admissible::conditions(&self.sim, &structure, points) {
            let id = (c.kind, c.segment, c.boundary);
            // The event search's margin of a stick's end is its phase
            // tolerance wherever the stick ends as claimed: no measure of
            // how near an early end is.
            if c.kind == ViolationKind::StickEnd {
                continue;
            }
            if c.margin.abs() <= SAME_EVENT {
                self.exclude(id);
            }
        }
        for i in 0..self.stick_ends {
            let id = self.walk_excluded[i];
            if self
                .stick_end_margin(&structure, points, id)
                .is_some_and(|m| m.abs() <= SAME_EVENT)
            {
                self.exclude(id);
            }
        }
        // A departure or arrival tangential all along the curve puts the
        // velocity's extremum at that end of the segment: whether rounding
        // places it just inside (an interior contact of that boundary, margin
        // zero) or just outside (none) changes from point to point. It is
        // the same event as the tangency, not a second condition.
        for i in 0..self.excluded_len {
            if let (ViolationKind::Arrival | ViolationKind::Departure, segment, Some(b)) =
                self.excluded[i]
            {
                self.exclude((ViolationKind::Interior, segment, Some(b)));
            }
        }
        self.sync_excluded();
    }

    /// The condition's value at `(points, p)`: zero on the curve, NaN
    /// where it cannot be evaluated.
    pub fn value(&mut self, p: &M::Params, points: &[SwitchingPoint]) -> f64 {
        match self.condition {
            Condition::Eigen(_) if self.half > 0 => {
                mirrored_half_map::<M>(p, &self.steps, self.half, self.shift, points)
                    .ok()
                    .map_or(f64::NAN, |rdg| {
                        eigen_value(TransitionKind::PeriodDoubling, &rdg)
                    })
            }
            Condition::Eigen(kind) => monodromy_spectral::<M>(p, &self.steps, self.shift, points)
                .ok()
                .map_or(f64::NAN, |dp| {
                    eigen_value(kind, &dp) * exit_rates::<M>(p, &self.steps, self.shift, points)
                }),
            Condition::Margin {
                kind,
                segment,
                boundary,
            } => {
                let Some(structure) = &self.structure else {
                    return f64::NAN;
                };
                if self.sim.set_params(*p).is_err() {
                    return f64::NAN;
                }
                admissible::margin_of(&self.sim, structure, points, (kind, segment, boundary))
                    .unwrap_or(f64::NAN)
            }
            Condition::RestGrazing { boundary } => rest_margin::<M>(p, self.rest_domain, boundary),
            Condition::NormalField {
                segment,
                arrival,
                rate,
            } => normal_field_at::<M>(p, &self.steps, points, segment, arrival, rate),
        }
    }

    /// The smallest margin of the conditions that must hold along the curve
    /// besides its own (NaN counts as −∞), with the condition (kind,
    /// segment, boundary): for a `Margin` curve every other condition of the
    /// motion (those that vanish with it left out, see
    /// [`Self::exclude_companions`]); for an `Eigen` curve every condition;
    /// for `RestGrazing` the domain's other boundary (segment 0).
    ///
    /// A stick's end is watched by its smooth margin (`as ∓ Fnf` at the
    /// stick's interior extrema of `Fnf`, or the exit's rate if smaller),
    /// not by the
    /// event search's phase difference: that one is the phase tolerance
    /// (`1e-7` of the phase, a constant `2e-6` at phase 20) wherever the
    /// stick ends as claimed, so on a motion with a stick it would be the
    /// smallest margin all along the curve and hide the one that falls to
    /// zero at a codimension-two end.
    pub fn other(
        &mut self,
        p: &M::Params,
        points: &[SwitchingPoint],
    ) -> (f64, Option<ConditionId>) {
        let key = |m: f64| if m.is_nan() { f64::NEG_INFINITY } else { m };
        if let Condition::RestGrazing { boundary } = self.condition {
            let dom = M::info(p).domains[self.rest_domain];
            return [dom.lower, dom.upper]
                .into_iter()
                .flatten()
                .filter(|&k| k != boundary)
                .map(|k| {
                    (
                        key(rest_margin::<M>(p, self.rest_domain, k)),
                        Some((ViolationKind::Interior, 0, Some(k))),
                    )
                })
                .fold((f64::INFINITY, None), |a, b| if b.0 < a.0 { b } else { a });
        }
        let Some(structure) = &self.structure else {
            return (f64::NEG_INFINITY, None);
        };
        if self.sim.set_params(*p).is_err() {
            return (f64::NEG_INFINITY, None);
        }
        let mut best = match admissible::worst_margin_except(
            &self.sim,
            structure,
            points,
            &self.walk_excluded,
        ) {
            Some(w) => (key(w.margin), Some((w.kind, w.segment, w.boundary))),
            None => (f64::INFINITY, None),
        };
        for i in 0..self.stick_ends {
            let id = self.walk_excluded[i];
            if self.excluded[..self.excluded_len].contains(&id) {
                continue;
            }
            if let Some(m) = self.stick_end_margin(structure, points, id) {
                if key(m) < best.0 {
                    best = (key(m), Some(id));
                }
            }
        }
        best
    }

    /// [`Self::other`] as the admissibility walk measures it, a stick's
    /// end by the event search (its phase difference plus the phase
    /// tolerance): what a sweep sees, whose sign says where the motion
    /// stops existing. Its zeros, not its magnitude, locate a
    /// codimension-two end.
    pub fn other_event(
        &mut self,
        p: &M::Params,
        points: &[SwitchingPoint],
    ) -> (f64, Option<ConditionId>) {
        let (Condition::Margin { .. } | Condition::Eigen(_), Some(structure)) =
            (self.condition, &self.structure)
        else {
            return self.other(p, points);
        };
        if self.sim.set_params(*p).is_err() {
            return (f64::NEG_INFINITY, None);
        }
        let key = |m: f64| if m.is_nan() { f64::NEG_INFINITY } else { m };
        match admissible::worst_margin_except(
            &self.sim,
            structure,
            points,
            &self.excluded[..self.excluded_len],
        ) {
            Some(w) => (key(w.margin), Some((w.kind, w.segment, w.boundary))),
            None => (f64::INFINITY, None),
        }
    }

    /// An evaluator of the same motion for `condition` (a second condition
    /// that vanishes with this one at a codimension-two point).
    pub fn with(&self, condition: Condition) -> Self {
        let mut e = self.clone();
        e.condition = condition;
        // The second condition's test function is the whole cycle's.
        e.half = 0;
        e
    }
}

/// The scale of a condition's value at `p`: what `|g|` is compared with
/// (velocities over the boundaries' velocities and `L W`, forces and
/// accelerations over the forcing amplitude and the static bound, phases
/// over 2π, test functions over `1 + |tr DP| + |det DP|`).
pub fn condition_scale<M: Model>(
    p: &M::Params,
    condition: Condition,
    structure: Option<&Structure>,
    points: &[SwitchingPoint],
) -> f64 {
    let osc = M::oscillator(p);
    let w = osc.frequency.abs();
    let mut v = 0.0f64;
    for k in 0..M::info(p).boundaries.len() {
        v = v.max(M::boundary_velocity(p, k).abs());
    }
    let length = || crate::orbit::periodic::PeriodicSolver::<M>::length_scale(p, points);
    // Velocities: the boundaries' and the motion's `L W`.
    let velocity = || v.max(length() * w).max(1e-300);
    // Forces and accelerations: the forcing, the spring over `L`, the
    // static bound and the damping over the velocities.
    let force = || {
        let s = M::static_bound(p).unwrap_or(0.0).abs();
        (osc.amplitude.abs() + osc.stiffness.abs() * length() + s + w * v).max(1e-300)
    };
    match condition {
        Condition::Eigen(_) => {
            let steps = structure.map_or(&[][..], |s| s.steps());
            let shift = std::f64::consts::TAU * structure.map_or(1, |s| s.periods()) as f64;
            monodromy_spectral::<M>(p, steps, shift, points)
                .ok()
                .map_or(1.0, |dp| {
                    (1.0 + dp.trace().abs() + dp.determinant().abs())
                        * exit_rates::<M>(p, steps, shift, points).abs()
                })
        }
        Condition::RestGrazing { .. } => velocity(),
        // An acceleration, or its rate (over time: one more factor W).
        Condition::NormalField { rate: false, .. } => force(),
        Condition::NormalField { rate: true, .. } => force() * w.max(1.0),
        Condition::Margin { kind, .. } => match kind {
            ViolationKind::Duration => std::f64::consts::TAU,
            ViolationKind::Interior => velocity(),
            _ => force(),
        },
    }
}
