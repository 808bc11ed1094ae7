//! A curve whose motion loses an excursion: one flow segment that leaves a
//! boundary and returns to it (`j_ββ`) between two segments it splits (two
//! flows of one domain, or two sticks on that boundary) shrinks to nothing
//! as the curve runs on. Its departure and arrival turn tangential
//! together, its arrival equation has a double root in the limit, and the
//! curve's own system turns singular: the curve crawls short of the point.
//! There the motion is the *reduced* one (the excursion removed, its two
//! neighbours merged into one segment) touching the boundary inside that
//! merged segment: a flow's velocity extremum on it (the reduced
//! structure's grazing), a stick's `Fnf` extremum on `±as` (its stick
//! vanishing). So the end is solved on the reduced structure, with the
//! curve's condition carried over and the merged segment's margin, and
//! reported with the excursion's two switching points both at the graze (a
//! segment of zero length solves its mapping equation exactly).
//!
//! A sweep that ends a branch where an excursion shrinks to nothing gives
//! a start on the same degenerate point: [`reduced_start`] carries it to the
//! reduced motion, whose curve it is (`study::curves` reports no failed
//! start where the motion's own curve cannot start and that one is traced).
//!
//! Where the reduced motion is two equal halves `T T`, the motion is one
//! born at `T`'s period doubling (its second half's stick or excursion
//! touching there too) and the reduced system is singular (`T T` has a
//! branch point, both halves' margins vanish together): the end is solved
//! on `T` with its period-doubling test function and its merged segment
//! touching, then doubled. On `stribeck8` W = 0.5…3 × Q0 = 1…12 a fold
//! and a stick-vanishing curve of `T'T` (`T'` with its stick split by an
//! excursion) both end so at the point where `T`'s period-doubling and
//! stick-vanishing curves meet.
//!
//! The flows of the smooth laws' N-piece models are continuous across their
//! velocity boundaries, and an eigenvalue test function of the motion tends
//! to the reduced motion's at the end. Measured on `stribeck::pl4` and
//! `stribeck8` (the guide, "Regime maps"): ten of the eleven ends
//! so found lie within 1e-9 of a codimension-two point that other curves
//! locate independently in the same run without this solve.

use crate::bifurcation::bordered::Correction;
use crate::bifurcation::TransitionKind;
use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::{MappingInfo, MappingKind, Model, ModelInfo, ParamSet};
use crate::orbit::admissible::{early_end, ViolationKind, SAME_EVENT};
use crate::orbit::extrema::SegmentFlow;
use crate::orbit::periodic::PeriodicSolver;
use crate::orbit::structure::Structure;

use super::extended::Extended;
use super::start::{system, to_point, unknowns, START_REACH};
use super::stop::PAIR_ITERATIONS;
use super::trace::{Sample, Tracer, HOLDS_TO};
use super::{Condition, CurvePoint, Plane};

/// An excursion shorter than this (in `W t`) may be shrinking to nothing
/// (where the curve cannot go on, which is what this is tried for). One
/// from a stick on a smooth law's model (`as = ak`: it leaves with no
/// acceleration) is still 1.1e-2 long on `stribeck8` where its curve
/// crawls.
const SHORT: f64 = 1e-1;

/// One excursion of a structure of `m` mappings: the segment after
/// `before` leaves boundary `boundary` and returns to it, between `before`
/// and the segment after it, two flows of one domain or two sticks on
/// `boundary`, which merge into mapping `merged` (for two sticks, the
/// second: the merged stick leaves as it does).
#[derive(Clone, Copy, Debug)]
struct Excursion {
    before: usize,
    boundary: usize,
    merged: usize,
    /// Between two sticks (else two flows).
    stick: bool,
}

impl Excursion {
    /// The merged segment (`segment` of the reduced structure) touching
    /// the excursion's boundary: a stick's `Fnf` extremum on `±as`
    /// (`StickEnd`), a flow's velocity extremum on it (`Interior`).
    fn touch(&self, segment: usize) -> Condition {
        Condition::Margin {
            kind: if self.stick {
                ViolationKind::StickEnd
            } else {
                ViolationKind::Interior
            },
            segment,
            boundary: Some(self.boundary),
        }
    }
}

/// The excursions of `steps` shorter than [`SHORT`] at `x`, shortest first.
fn excursions(info: &ModelInfo, steps: &[usize], shift: f64, x: &[f64]) -> Vec<Excursion> {
    let m = steps.len();
    let mut out: Vec<(f64, Excursion)> = Vec::new();
    if m < 3 {
        return Vec::new();
    }
    for k in 0..m {
        let mi = info.mappings[steps[k]];
        let (before, after) = ((k + m - 1) % m, (k + 1) % m);
        let (mb, ma) = (info.mappings[steps[before]], info.mappings[steps[after]]);
        if mi.domain.is_none() || mi.from != mi.to || mb.to != mi.from || ma.from != mi.from {
            continue;
        }
        let stick = mb.kind == MappingKind::Stick;
        let merged = if stick {
            (ma.kind == MappingKind::Stick).then_some(steps[after])
        } else {
            let flow = |q: &MappingInfo| q.kind != MappingKind::Stick && q.domain == mb.domain;
            (flow(&ma) && mb.domain.is_some())
                .then(|| {
                    info.mappings
                        .iter()
                        .position(|q| flow(q) && q.from == mb.from && q.to == ma.to)
                })
                .flatten()
        };
        let Some(merged) = merged else {
            continue;
        };
        let end = if after == 0 {
            x[1] + shift
        } else {
            x[2 * after + 1]
        };
        let length = end - x[2 * k + 1];
        if length.is_finite() && length < SHORT {
            let e = Excursion {
                before,
                boundary: mi.from,
                merged,
                stick,
            };
            out.push((length, e));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.into_iter().map(|(_, e)| e).collect()
}

/// Whether `condition` (a margin of segment `segment`) measures the
/// excursion `e` of a structure of `m` mappings shrinking to nothing: the
/// excursion's duration, departure or arrival, its contact with its own
/// boundary, or the force criterion at its arrival.
fn shrinks(condition: Condition, e: &Excursion, m: usize) -> bool {
    let Condition::Margin {
        kind,
        segment,
        boundary,
    } = condition
    else {
        return false;
    };
    (segment + m - e.before) % m == 1
        && match kind {
            ViolationKind::Duration
            | ViolationKind::Departure
            | ViolationKind::Arrival
            | ViolationKind::StickOnset
            | ViolationKind::Pass => true,
            ViolationKind::Interior => boundary == Some(e.boundary),
            ViolationKind::StickEnd | ViolationKind::Other => false,
        }
}

/// The switching points of a reduced motion `T T … T` repeat `T`'s when
/// they agree turn by turn to this (relative to the motion's length scale,
/// and radians once the turn's phase is taken off): the corrector's
/// tolerance, with room.
const REPEATS: f64 = 1e-7;

/// The start of a curve on the reduced motion ([`reduced_start`]).
#[derive(Clone, Debug)]
pub struct ReducedStart {
    /// The reduced structure: the excursion and the segment after it
    /// dropped, the segment before it replaced by the merged one (the
    /// others in the motion's order); `T` where that is two equal halves
    /// `T T`.
    pub structure: Structure,
    /// The start, on the curve, on the line through the original start
    /// with the parameter `fixed` held.
    pub point: CurvePoint,
    /// The merged segment touching the excursion's boundary: a stick's
    /// `Fnf` extremum on `±as` (`StickEnd`), a flow's velocity extremum on
    /// it (`Interior`).
    pub condition: Condition,
}

/// A transition located on a branch of `structure` at `start` where one of
/// its excursions shrinks to nothing (`condition` that excursion's
/// duration, departure or arrival, its contact with its own boundary, or
/// the force criterion at its arrival; the excursion shorter than 0.1
/// in `W t`), carried to the reduced motion (the excursion removed, its two
/// neighbours merged into one segment): the start of
/// the curve on which the merged segment touches the boundary, solved with
/// the plane's parameter `fixed` held (0: `x`, 1: `y`) to `tolerance`.
///
/// The motion's own system is singular at such a point (its excursion's
/// arrival equation has a double root), and a sweep locates the point only
/// to the square root of its tolerance: on `stribeck8` (`as = ak`: the
/// excursion leaves its stick with no acceleration) the excursions at the
/// located transitions still last 1.1e-3…1.3e-3 rad, and no corrector
/// converges from them; the reduced motion's equations are regular there.
/// `None` if `condition` is no such excursion's, or if the reduced solve
/// does not converge within 1e-4 of the box from `start` (the
/// transition is then something else, an excursion arriving tangentially).
pub fn reduced_start<M: Model>(
    base: &M::Params,
    plane: &Plane,
    structure: &Structure,
    start: &CurvePoint,
    condition: Condition,
    fixed: usize,
    tolerance: f64,
) -> Option<ReducedStart> {
    let steps = structure.steps();
    let m = steps.len();
    if start.points.len() != m {
        return None;
    }
    let shift = std::f64::consts::TAU * structure.periods() as f64;
    let x = unknowns(start);
    let e = excursions(M::info(base), steps, shift, &x)
        .into_iter()
        .find(|e| shrinks(condition, e, m))?;
    let (k, after) = ((e.before + 1) % m, (e.before + 2) % m);
    let mut reduced = Vec::with_capacity(m - 2);
    let mut points = Vec::with_capacity(m - 2);
    let mut merged = 0;
    for j in (0..m).filter(|&j| j != k && j != after) {
        if j == e.before {
            merged = reduced.len();
        }
        reduced.push(if j == e.before { e.merged } else { steps[j] });
        points.push(start.points[j]);
    }
    let periods = structure.periods();
    let structure = Structure::from_indices(M::info(base), &reduced, periods).ok()?;
    let guess = CurvePoint {
        points,
        ..start.clone()
    };
    let mut sys = system::<M>(base, plane, Some(&structure), &guess, e.touch(merged)).ok()?;
    let anchor = unknowns(&guess);
    let mut y = anchor.clone();
    let mut border = vec![0.0; y.len()];
    sys.axis(fixed, &mut border);
    if !matches!(
        sys.correct(&mut y, &border, &anchor, tolerance, 40),
        Correction::Converged { .. }
    ) {
        return None;
    }
    let n = y.len();
    let spans = sys.spans();
    let moved = ((y[n - 2] - start.x) / spans[0]).hypot((y[n - 1] - start.y) / spans[1]);
    if moved > START_REACH {
        return None;
    }
    // A reduced motion `T T … T` of `r` equal turns is `T`'s where its
    // switching points repeat too: the same curve as `T`'s, named so.
    let length = PeriodicSolver::<M>::length_scale(&sys.params(&y), &to_point(&y).points);
    let m = reduced.len();
    let turns = (1..=m).rev().find(|&r| {
        m % r == 0 && periods as usize % r == 0 && {
            let d = m / r;
            let turn = shift / r as f64;
            (d..m).all(|j| {
                let (i, t) = (j % d, (j / d) as f64);
                reduced[j] == reduced[i]
                    && (y[2 * j] - y[2 * i]).abs() <= REPEATS * length
                    && (y[2 * j + 1] - y[2 * i + 1] - t * turn).abs() <= REPEATS
            })
        }
    })?;
    let d = m / turns;
    let structure =
        Structure::from_indices(M::info(base), &reduced[..d], periods / turns as u32).ok()?;
    let mut y_t = y[..2 * d].to_vec();
    y_t.extend_from_slice(&y[n - 2..]);
    Some(ReducedStart {
        structure,
        point: to_point(&y_t),
        condition: e.touch(merged % d),
    })
}

/// The curve's condition carried over to the reduced structure, whose
/// segment 0 is the merged one and whose segment `i ≥ 1` is the motion's
/// `(before + 2 + i) mod m`; `None` for a condition of the excursion or of
/// its neighbours but their outer ends.
fn carried(condition: Condition, e: &Excursion, m: usize) -> Option<Condition> {
    match condition {
        Condition::Eigen(_) => Some(condition),
        Condition::Margin {
            kind,
            segment,
            boundary,
        } => {
            let r = (segment + m - e.before) % m;
            let segment = match (r, kind) {
                (0, ViolationKind::Departure) | (2, ViolationKind::Arrival) => 0,
                (0..=2, _) => return None,
                _ => r - 2,
            };
            Some(Condition::Margin {
                kind,
                segment,
                boundary,
            })
        }
        Condition::RestGrazing { .. } | Condition::NormalField { .. } => None,
    }
}

impl<M: Model> Tracer<'_, M> {
    /// Where the curve's motion loses an excursion shrinking to nothing
    /// (see the module): solved from `prev` on the reduced structure with
    /// the curve's condition and the merged segment's interior margin on
    /// the excursion's boundary, both parameters free. Accepted as
    /// [`Self::pair_point`] accepts: converged, in the box, ahead of `prev`
    /// in the plane within `bound`, the condition held there to
    /// [`HOLDS_TO`] of its scale, and every other condition of the reduced
    /// motion holding to [`SAME_EVENT`]. Returned in the curve's unknowns,
    /// the excursion's two switching points at the graze.
    pub(super) fn excursion_point(&mut self, prev: &Sample, bound: f64) -> Option<Sample> {
        excursions(
            self.sys.eval.sim.info(),
            &self.sys.eval.steps,
            self.sys.eval.shift,
            &prev.x,
        )
        .into_iter()
        .find_map(|e| self.reduced_point(prev, bound, &e))
    }

    /// [`Self::excursion_point`] for the excursion `e`.
    fn reduced_point(&mut self, prev: &Sample, bound: f64, e: &Excursion) -> Option<Sample> {
        let steps = self.sys.eval.steps.clone();
        let shift = self.sys.eval.shift;
        let periods = self.sys.eval.structure.as_ref()?.periods();
        let condition = self.sys.eval.condition;
        let m = steps.len();
        let n = prev.x.len();
        let own = carried(condition, e, m)?;
        // The motion rotated to start at `before`, then the excursion and
        // its arrival's point dropped.
        let rotated = |i: usize| {
            let j = (e.before + i) % m;
            let wrap = if e.before + i >= m { shift } else { 0.0 };
            (prev.x[2 * j], prev.x[2 * j + 1] + wrap)
        };
        let mut reduced_steps = vec![e.merged];
        let mut y = Vec::with_capacity(n - 4);
        let (x0, p0) = rotated(0);
        y.extend([x0, p0]);
        for i in 3..m {
            reduced_steps.push(steps[(e.before + i) % m]);
            let (xi, pi) = rotated(i);
            y.extend([xi, pi]);
        }
        y.extend([prev.x[n - 2], prev.x[n - 1]]);
        // The merged segment touches the boundary.
        let touch = e.touch(0);
        let structure =
            Structure::from_indices(self.sys.eval.sim.info(), &reduced_steps, periods).ok()?;
        let y = match self.solve_on(prev, bound, &structure, y.clone(), own, touch) {
            Some(y) => y,
            // A reduced motion of two equal halves, `T T`: where the motion
            // is one born at `T`'s period doubling, its halves coincide at
            // the end (its other half's stick or excursion touching there
            // too), and the reduced system is singular (`T T` has a branch
            // point there, and both halves' margins vanish together): solved
            // on `T` with its period-doubling test function, then doubled.
            None => {
                let half = reduced_steps.len() / 2;
                let (first, second) = reduced_steps.split_at(half);
                if half == 0 || first != second || periods % 2 != 0 {
                    return None;
                }
                let t =
                    Structure::from_indices(self.sys.eval.sim.info(), first, periods / 2).ok()?;
                let mut z: Vec<f64> = y[..2 * half].to_vec();
                z.extend_from_slice(&y[y.len() - 2..]);
                let pd = Condition::Eigen(TransitionKind::PeriodDoubling);
                let z = self.solve_on(prev, bound, &t, z, pd, touch)?;
                let mut y = z[..2 * half].to_vec();
                for i in 0..half {
                    y.extend([z[2 * i], z[2 * i + 1] + 0.5 * shift]);
                }
                y.extend_from_slice(&z[2 * half..]);
                y
            }
        };
        let k = y.len();
        // The graze, nearest the excursion's departure at `prev`.
        let mut p = *self.sys.base();
        p.set(self.plane.x, y[k - 2]);
        p.set(self.plane.y, y[k - 1]);
        let near = rotated(1).1;
        let end = if k > 4 { y[3] } else { y[1] + shift };
        let (xg, pg) = graze::<M>(&p, e, [y[0], y[1]], end, near)?;
        // Back to the curve's unknowns: rotated index `i` is the motion's
        // `(before + i) mod m`.
        let mut rot = Vec::with_capacity(n);
        rot.extend([y[0], y[1], xg, pg, xg, pg]);
        rot.extend_from_slice(&y[2..k - 2]);
        let mut x = vec![0.0; n];
        for i in 0..m {
            let j = (e.before + i) % m;
            let wrap = if e.before + i >= m { shift } else { 0.0 };
            x[2 * j] = rot[2 * i];
            x[2 * j + 1] = rot[2 * i + 1] - wrap;
        }
        x[n - 2] = y[k - 2];
        x[n - 1] = y[k - 1];
        self.examine(x, prev.t.clone()).ok()
    }
}

impl<M: Model> Tracer<'_, M> {
    /// The solution from `y` on `structure` of the mapping equations with
    /// `own` and `second` (both parameters free), if it converges, lies in
    /// the box, holds `own` to [`HOLDS_TO`] of its scale, lies ahead of
    /// `prev` in the plane within `bound`, and every other condition of
    /// that motion holds there to [`SAME_EVENT`].
    fn solve_on(
        &self,
        prev: &Sample,
        bound: f64,
        structure: &Structure,
        mut y: Vec<f64>,
        own: Condition,
        second: Condition,
    ) -> Option<Vec<f64>> {
        let mut sys = system::<M>(
            self.sys.base(),
            &self.plane,
            Some(structure),
            &to_point(&y),
            own,
        )
        .ok()?;
        sys.pair = Some(sys.eval.with(second));
        let done = sys.correct_pair(&mut y, self.opts.tolerance, PAIR_ITERATIONS);
        sys.pair = None;
        if !matches!(done, Correction::Converged { .. })
            || self.out_of_box(&y)
            || sys.held(&y) > HOLDS_TO
        {
            return None;
        }
        if !self.ahead_within(prev, &y, bound) {
            return None;
        }
        self.holding_on(sys, y)
    }

    /// Whether the parameters of `y` (a point of any structure, its last
    /// two unknowns the plane's) lie ahead of `prev` along its tangent and
    /// within `bound` of it in the plane (each parameter over its span).
    pub(super) fn ahead_within(&self, prev: &Sample, y: &[f64], bound: f64) -> bool {
        let n = prev.x.len();
        self.ahead_along(&prev.x[n - 2..], &prev.t[n - 2..], y, bound)
    }

    /// [`Self::ahead_within`] from the plane point `from` along the plane
    /// direction `dir` (each two values: the parameters).
    pub(super) fn ahead_along(&self, from: &[f64], dir: &[f64], y: &[f64], bound: f64) -> bool {
        let k = y.len();
        let spans = self.sys.spans();
        let ahead = (0..2)
            .map(|a| (y[k - 2 + a] - from[a]) * dir[a] / (spans[a] * spans[a]))
            .sum::<f64>();
        let far = self.plane_distance(&y[k - 2..], from);
        ahead > 0.0 && far <= bound
    }

    /// `y` examined on `sys` (another structure's system), if every other
    /// condition of that motion holds there to [`SAME_EVENT`].
    pub(super) fn holding_on(&self, sys: Extended<M>, y: Vec<f64>) -> Option<Vec<f64>> {
        let k = y.len();
        let mut other = Tracer {
            sys,
            opts: self.opts,
            plane: self.plane,
        };
        let at = other.examine(y, vec![0.0; k]).ok()?;
        (at.other >= -SAME_EVENT).then_some(at.x)
    }
}

/// Where the merged segment of `e` from `(x, φ)` = `start` to phase `end`
/// touches the excursion's boundary: a flow's velocity extremum (the one
/// nearest phase `near`), a stick's extremum of `Fnf` (the one its smooth
/// margin takes, `orbit::admissible`'s).
fn graze<M: Model>(
    p: &M::Params,
    e: &Excursion,
    start: [f64; 2],
    end: f64,
    near: f64,
) -> Option<(f64, f64)> {
    let osc = M::oscillator(p);
    if e.stick {
        let sim = Simulator::<M>::new(*p, SimOptions::default()).ok()?;
        let (_, _, phase) = early_end(&sim, e.boundary, start[0], start[1], end)?;
        let v0 = M::boundary_velocity(p, e.boundary);
        return Some((start[0] + v0 * (phase - start[1]) / osc.frequency, phase));
    }
    let mi = M::info(p).mappings[e.merged];
    let flow = SegmentFlow::new(
        osc,
        M::coefficients(p, mi.domain?),
        start[0],
        M::boundary_velocity(p, mi.from),
        start[1],
    )?;
    let mut best: Option<(f64, f64)> = None;
    flow.acceleration_zeros(
        start[1],
        end,
        |_| false,
        |z| {
            if best.is_none_or(|b| (z.phase - near).abs() < (b.1 - near).abs()) {
                best = Some((z.state.x, z.phase));
            }
        },
    );
    best
}
