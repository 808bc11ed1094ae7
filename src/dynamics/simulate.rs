//! Exact event-driven simulation with stick (SPEC §3, §8).
//!
//! Inside a domain the motion is the generated closed-form flow, always
//! evaluated from the segment's start (no error accumulates along a
//! segment). The next switching phase is the first root of `v − V_b` for the
//! domain's two boundaries, located by [`crate::dynamics::crossing::first_root`], whose
//! step rule cannot miss a crossing: the bound it needs on `|v''|` comes from
//! the linear ODE that the acceleration `a` and its rate `a'` satisfy in a
//! domain, `(a, a')' = M (a, a') + (0, −A0 W² cos W t)` with
//! `M = [[0, 1], [−c_j, −2 d_j]]`, hence by Grönwall in the norm
//! `max(ω|a|, |a'|)`, `ω = sqrt(c_j)` (scale-invariant: both rates are 1/time)
//! `|a'| ≤ (max(ω|a0|, |a0'|) + Δt A0 W²) e^{(ω + 2|d_j|) Δt}`.
//! On the stick boundary the force criteria decide pass or stick; a stick
//! ends at the first phase where `Fnf = ±as` (bound `|Fnf''| ≤ A0` in phase).

use serde::Serialize;

use crate::dynamics::crossing::{first_root, touch_extremum, Probe, Root, RootKind};
use crate::dynamics::response::Response;
use crate::model::param::{ParamError, ParamSet};
use crate::model::{Coefficients, Model, ModelInfo, Oscillator};

/// Where the motion is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Location {
    /// In domain `j` (index, lowest band first).
    Domain(usize),
    /// Stuck on the stick boundary.
    Stick,
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Location::Domain(j) => write!(f, "domain {j} (index, lowest band first)"),
            Location::Stick => f.write_str("stick"),
        }
    }
}

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// The flow passes through the boundary.
    Pass,
    /// The flow arrives on the stick boundary and sticks.
    StickOnset,
    /// A stick ends (`Fnf = ±as`).
    StickEnd,
    /// The flow touches the boundary tangentially and stays on its side.
    Graze,
}

/// One recorded event.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Event {
    /// Phase `W t`.
    pub phase: f64,
    /// Displacement.
    pub x: f64,
    /// Velocity (the boundary's velocity, except at a graze).
    pub v: f64,
    /// Boundary index.
    pub boundary: usize,
    /// What happened.
    pub kind: EventKind,
    /// Location before.
    pub before: Location,
    /// Location after.
    pub after: Location,
}

/// The start of the current segment: the flow (or stick) from here.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Segment {
    /// Displacement at the start.
    pub x: f64,
    /// Velocity at the start.
    pub v: f64,
    /// Phase at the start.
    pub phase: f64,
    /// Domain or stick.
    pub location: Location,
    /// Events are searched after this phase (the start itself, or a graze).
    pub search_from: f64,
}

/// Why a simulation stopped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The parameters are invalid.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// An input state is NaN or infinite.
    #[error("the initial state ({x}, {v}) at phase {phase} is not finite")]
    BadStart {
        /// x
        x: f64,
        /// v
        v: f64,
        /// phase
        phase: f64,
    },
    /// The state became NaN or infinite (e.g. growth under negative damping):
    /// where (phase, time, domain or stick), and the last finite state of
    /// the segment (bisected to the rounding of the phase).
    #[error(
        "the motion blows up (no longer finite) at W t = {phase:.9e} (t = {time:.6e}) in {location}: \
         (x, v) = ({x:.3e}, {v:.3e}) there; last finite state x = {last_x:.6e}, v = {last_v:.6e} \
         at W t = {last_phase:.9e}"
    )]
    NotFinite {
        /// Phase `W t` where the state, its acceleration or the bound on
        /// the acceleration's rate is no longer finite.
        phase: f64,
        /// Time `t = phase / W`.
        time: f64,
        /// Where: the domain or the stick.
        location: Location,
        /// x there (NaN or infinite; finite if only the acceleration or
        /// the bound overflowed: then `last_*` is this state).
        x: f64,
        /// v there.
        v: f64,
        /// Largest phase of the segment at which the state is still finite.
        last_phase: f64,
        /// x at `last_phase`.
        last_x: f64,
        /// v at `last_phase`.
        last_v: f64,
    },
    /// More events than allowed before the end phase (chattering or a too long run).
    #[error("more than {limit} events before phase {phase}")]
    TooManyEvents {
        /// The limit.
        limit: usize,
        /// Where the run stopped.
        phase: f64,
    },
    /// The event search cannot go on from here: the domain is too stiff for
    /// the step rule (more than [`MAX_STEPS_PER_PERIOD`] steps per forcing
    /// period), or the phase is so large that its rounding exceeds the step.
    #[error("cannot locate the events from phase {phase} in {location:?}: {reason}")]
    Unresolvable {
        /// Phase where the search stopped.
        phase: f64,
        /// Where.
        location: Location,
        /// Why, in words.
        reason: String,
    },
}

/// The event search refuses a domain whose step (at most
/// `W / (2 (sqrt|c_j| + |d_j|))` in phase) would need more than this many
/// steps per forcing period: with a tiny mass, say, the effective damping
/// `d_j` is huge and the search would run for hours (a typed error instead).
pub const MAX_STEPS_PER_PERIOD: f64 = 1e7;

/// Where a graze found at `root` is reported, and where the search resumes
/// after it, so that one tangency is one graze: reported at the touch's
/// extremum ([`touch_extremum`]: the search may find a flat touch a little
/// before it, or, where rounding hides an exact touch, just after it); the
/// search resumes once the touching function is back inside its band by more
/// than the graze tolerance (or turns towards the boundary again), since
/// anything it does before that is the same touch, within the tolerance.
/// The other function is searched on the skipped stretch: if it has a root
/// there (a band narrower than the touch's reach) the graze is reported where
/// found and the search resumes just after it.
fn graze_phase(
    probe: &impl Fn(f64) -> Probe,
    bound: &impl Fn(f64, f64, &Probe) -> f64,
    root: &Root,
    step: f64,
    graze_tol: f64,
    inside: [f64; 2],
) -> (f64, f64) {
    let k = root.which;
    let side = inside[k];
    let at = touch_extremum(probe, root.phase, side, step);
    // Back inside by more than the tolerance, doubling the distance.
    let mut w = (step * 1e-9).max(4.0 * f64::EPSILON * at.abs());
    let resume = loop {
        let b = at + w;
        let p = probe(b);
        let inward = p.dh == 0.0 || (p.dh > 0.0) == (side > 0.0);
        let back_inside = p.h[k] * side > graze_tol || p.h[k].is_nan();
        if back_inside || !inward || w >= step {
            break b;
        }
        w *= 2.0;
    };
    let masked = |phi: f64| {
        let mut p = probe(phi);
        p.h[k] = f64::INFINITY;
        p
    };
    if first_root(&masked, bound, root.phase, resume, step, graze_tol).is_some() {
        return (root.phase, root.phase + step * 1e-9);
    }
    (at, resume)
}

fn unresolved(phase: f64, location: Location) -> SimError {
    SimError::Unresolvable {
        phase,
        location,
        reason: "the phase is too large for its rounding to resolve the event search's step"
            .to_string(),
    }
}

/// Tolerances of the simulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimOptions {
    /// How close to a boundary a tangent touch must come to count as a graze.
    /// A touch is one `Graze` event, at its extremum; the search resumes once
    /// the motion is back inside by more than this.
    pub graze_tol: f64,
    /// At most this many events per call of [`Simulator::run`].
    pub max_events: usize,
}

impl Default for SimOptions {
    fn default() -> Self {
        Self {
            graze_tol: 1e-10,
            max_events: 1_000_000,
        }
    }
}

/// An event-driven simulator for model `M` at fixed parameters.
#[derive(Clone, Debug)]
pub struct Simulator<M: Model> {
    p: M::Params,
    osc: Oscillator,
    coefficients: Vec<Coefficients>,
    velocities: Vec<f64>,
    stick: Option<(usize, f64)>,
    opts: SimOptions,
}

impl<M: Model> Simulator<M> {
    /// A simulator at parameters `p` (checked).
    pub fn new(p: M::Params, opts: SimOptions) -> Result<Self, SimError> {
        p.check()?;
        let info = M::info(&p);
        let coefficients = (0..info.domains.len())
            .map(|j| M::coefficients(&p, j))
            .collect();
        let velocities = (0..info.boundaries.len())
            .map(|k| M::boundary_velocity(&p, k))
            .collect();
        let stick = info
            .stick_boundary()
            .and_then(|k| M::static_bound(&p).map(|s| (k, s)));
        Ok(Self {
            p,
            osc: M::oscillator(&p),
            coefficients,
            velocities,
            stick,
            opts,
        })
    }

    /// Move to parameters `p` (checked), reusing the storage: no
    /// allocation (a continuation in parameters evaluates many).
    pub fn set_params(&mut self, p: M::Params) -> Result<(), SimError> {
        p.check()?;
        for (j, c) in self.coefficients.iter_mut().enumerate() {
            *c = M::coefficients(&p, j);
        }
        for (k, v) in self.velocities.iter_mut().enumerate() {
            *v = M::boundary_velocity(&p, k);
        }
        self.stick = M::info(&p)
            .stick_boundary()
            .and_then(|k| M::static_bound(&p).map(|s| (k, s)));
        self.osc = M::oscillator(&p);
        self.p = p;
        Ok(())
    }

    /// The parameters.
    pub fn params(&self) -> &M::Params {
        &self.p
    }

    /// The model's description ([`Model::info`] at these parameters).
    pub fn info(&self) -> &'static ModelInfo {
        M::info(&self.p)
    }

    /// The oscillator.
    pub fn oscillator(&self) -> Oscillator {
        self.osc
    }

    /// Effective coefficients of domain `j` (computed once, at construction).
    pub fn coefficients(&self, j: usize) -> Coefficients {
        self.coefficients[j]
    }

    /// The simulation's tolerances.
    pub fn options(&self) -> SimOptions {
        self.opts
    }

    /// Velocity of boundary `k`.
    pub fn velocity(&self, k: usize) -> f64 {
        self.velocities[k]
    }

    /// The stick boundary and its static bound `as`, if the model has one.
    pub fn stick(&self) -> Option<(usize, f64)> {
        self.stick
    }

    /// `(x, v)` at `phase` of the segment started at `seg`.
    #[inline]
    pub fn state_at(&self, seg: &Segment, phase: f64) -> (f64, f64) {
        match seg.location {
            Location::Domain(j) => {
                let [x, v] = M::flow(&self.p, j, seg.x, seg.v, seg.phase, phase);
                (x, v)
            }
            Location::Stick => (
                seg.x + seg.v * (phase - seg.phase) / self.osc.frequency,
                seg.v,
            ),
        }
    }

    /// Acceleration at a state.
    pub fn acceleration(&self, location: Location, x: f64, v: f64, phase: f64) -> f64 {
        match location {
            Location::Domain(j) => M::normal_field(&self.p, j, x, v, phase)[0],
            Location::Stick => 0.0,
        }
    }

    /// The segment that starts at `(x, v, phase)`: the domain containing `v`;
    /// on a boundary, the side the vector field points to; on the stick
    /// boundary, the force criteria of SPEC §3.
    pub fn start(&self, x: f64, v: f64, phase: f64) -> Result<Segment, SimError> {
        if !(x.is_finite() && v.is_finite() && phase.is_finite()) {
            return Err(SimError::BadStart { x, v, phase });
        }
        let info = self.info();
        let location = match self.velocities.iter().position(|&vb| vb == v) {
            None => Location::Domain(
                info.domains
                    .iter()
                    .position(|d| {
                        d.lower.is_none_or(|k| self.velocities[k] < v)
                            && d.upper.is_none_or(|k| v < self.velocities[k])
                    })
                    .expect("the bands tile the velocity axis"),
            ),
            Some(k) => {
                let (above, below) = (k + 1, k);
                match self.stick {
                    // At rest relative to the belt static friction holds the
                    // mass while `|Fnf| ≤ as` (SPEC §3: a stick needs `|Fnf| = as`
                    // to end); beyond that it slips to the side `Fnf` points to.
                    Some((s, bound_s)) if s == k => {
                        let f = M::stick_forces(&self.p, x, phase).expect("stick boundary");
                        if f.non_friction > bound_s {
                            Location::Domain(above)
                        } else if f.non_friction < -bound_s {
                            Location::Domain(below)
                        } else {
                            Location::Stick
                        }
                    }
                    _ => {
                        let a = M::normal_field(&self.p, above, x, v, phase)[0];
                        Location::Domain(if a >= 0.0 { above } else { below })
                    }
                }
            }
        };
        Ok(Segment {
            x,
            v,
            phase,
            location,
            search_from: phase,
        })
    }

    /// The next event of the segment `seg` before `phase_limit`, with the
    /// segment that follows it; `None` if none occurs before the limit.
    /// Allocates nothing.
    pub fn next_event(
        &self,
        seg: &Segment,
        phase_limit: f64,
    ) -> Result<Option<(Event, Segment)>, SimError> {
        let w = self.osc.frequency;
        match seg.location {
            Location::Domain(j) => {
                let info = self.info().domains[j];
                let co = self.coefficients[j];
                let lo = info.lower.map(|k| self.velocities[k]);
                let hi = info.upper.map(|k| self.velocities[k]);
                // The segment's forced response, computed once: each probe is
                // then one sincos and one homogeneous solution (the generated
                // flow recomputes the start's response on every call).
                let response = Response::new(co, self.osc, seg.x, seg.v, seg.phase);
                let probe = |phi: f64| {
                    let (v, a, da) = match &response {
                        Some(r) => {
                            let s = r.at(phi);
                            (s.v, s.a, s.da)
                        }
                        None => {
                            let [x, v] = M::flow(&self.p, j, seg.x, seg.v, seg.phase, phi);
                            let [a, da] = M::normal_field(&self.p, j, x, v, phi);
                            (v, a, da)
                        }
                    };
                    Probe {
                        h: [
                            lo.map_or(f64::INFINITY, |l| v - l),
                            hi.map_or(f64::INFINITY, |h| v - h),
                        ],
                        dh: a / w,
                        ddh: da / (w * w),
                    }
                };
                // Grönwall in the norm max(ω|a|, |a'|), ω = sqrt|c_j|: the matrix
                // [[0, ω], [−c_j/ω, −2 d_j]] has norm max(ω, |c_j|/ω + 2|d_j|), a
                // rate in 1/time, so the bound scales with the problem's units
                // (in max(|a|, |a'|) the rate max(1, c_j + 2|d_j|) mixes units
                // and its exponential overflows for stiff or slow systems).
                let omega = match co.c.abs().sqrt() {
                    o if o > 0.0 => o,
                    _ => 1.0,
                };
                let rate = omega.max(co.c.abs() / omega + co.two_d.abs());
                let forcing = self.osc.amplitude.abs() * w * w;
                let bound = |_phi: f64, delta: f64, p: &Probe| {
                    let dt = delta / w;
                    let u0 = (omega * p.dh * w).abs().max((p.ddh * w * w).abs());
                    (u0 + dt * forcing) * (rate * dt).exp() / (w * w)
                };
                let step = (std::f64::consts::FRAC_PI_4)
                    .min(w * 0.5 / (co.c.abs().sqrt() + 0.5 * co.two_d.abs()));
                // A segment that starts on a boundary leaves it: rounding can make
                // `v - V_b` look like it returns within a few ulps of the start.
                // Such a root (within 1e-9 of the start, on the boundary left) is
                // the departure itself, not an event.
                // A tangent departure (zero acceleration on leaving, as after a
                // stick whose static bound equals the kinetic level) touches the
                // boundary it leaves: a graze there within 1e-6 is the departure too.
                // After a tangent departure `v − V_b ≈ a' τ²/2` is below the
                // rounding of the closed form for τ up to about sqrt(ε |v| / |a'|):
                // the noise can change its sign there. Such a root is no arrival:
                // an arrival on the upper boundary needs `a ≥ 0`, on the lower one
                // `a ≤ 0`, and the acceleration there points back into the domain.
                let departure = |r: &crate::dynamics::crossing::Root| {
                    let k = if r.which == 0 { info.lower } else { info.upper };
                    let left = k.is_some_and(|k| self.velocities[k] == seg.v);
                    let window = if r.kind == RootKind::Graze {
                        1e-6
                    } else {
                        1e-9
                    };
                    let a = probe(r.phase).dh;
                    let receding = r.kind == RootKind::Crossing
                        && if r.which == 0 { a > 0.0 } else { a < 0.0 };
                    left && (receding || r.phase - seg.phase <= window * seg.phase.abs().max(1.0))
                };
                let steps = std::f64::consts::TAU / step;
                if steps.is_nan() || steps > MAX_STEPS_PER_PERIOD {
                    return Err(SimError::Unresolvable {
                        phase: seg.search_from,
                        location: seg.location,
                        reason: format!(
                            "domain {j} is too stiff for exact event location ({steps:.3e} steps \
                             per forcing period; 2 d_j = {:e}, c_j = {:e}, W = {w:e})",
                            co.two_d, co.c
                        ),
                    });
                }
                // Inside the band: v − V_lower > 0, v − V_upper < 0.
                let inside = [1.0, -1.0];
                let mut from = seg.search_from;
                let root = loop {
                    match first_root(&probe, &bound, from, phase_limit, step, self.opts.graze_tol) {
                        Some(r) if departure(&r) => {
                            from = r.phase + 1e-9 * seg.phase.abs().max(1.0)
                        }
                        other => break other,
                    }
                };
                let Some(root) = root else {
                    self.check_finite(seg, phase_limit)?;
                    return Ok(None);
                };
                if root.kind == RootKind::Unresolved {
                    return Err(unresolved(root.phase, seg.location));
                }
                let (x, v) = self.state_at(seg, root.phase);
                if root.kind == RootKind::NotFinite || !(x.is_finite() && v.is_finite()) {
                    return Err(self.blow_up(seg, root.phase));
                }
                let k = if root.which == 0 {
                    info.lower
                } else {
                    info.upper
                }
                .expect("root of a present boundary");
                let vb = self.velocities[k];
                if root.kind == RootKind::Graze {
                    let (at, resume) =
                        graze_phase(&probe, &bound, &root, step, self.opts.graze_tol, inside);
                    let (x, v) = self.state_at(seg, at);
                    let event = Event {
                        phase: at,
                        x,
                        v,
                        boundary: k,
                        kind: EventKind::Graze,
                        before: seg.location,
                        after: seg.location,
                    };
                    let next = Segment {
                        search_from: resume,
                        ..*seg
                    };
                    return Ok(Some((event, next)));
                }
                let upward = root.which == 1;
                let other = if upward { j + 1 } else { j - 1 };
                let (kind, after) = match self.stick {
                    Some((s, _)) if s == k => {
                        let f = M::stick_forces(&self.p, x, root.phase).expect("stick boundary");
                        // Arriving from above: pass iff both input forces push down;
                        // from below: pass iff both push up; otherwise stick (Eqs. 17-19, 26-28).
                        let pass = if upward {
                            f.input_above > 0.0
                        } else {
                            f.input_below < 0.0
                        };
                        if pass {
                            (EventKind::Pass, Location::Domain(other))
                        } else {
                            (EventKind::StickOnset, Location::Stick)
                        }
                    }
                    _ => (EventKind::Pass, Location::Domain(other)),
                };
                let event = Event {
                    phase: root.phase,
                    x,
                    v: vb,
                    boundary: k,
                    kind,
                    before: seg.location,
                    after,
                };
                let next = Segment {
                    x,
                    v: vb,
                    phase: root.phase,
                    location: after,
                    search_from: root.phase,
                };
                Ok(Some((event, next)))
            }
            Location::Stick => {
                let (k, bound_s) = self.stick.expect("stuck only on a stick boundary");
                let vs = self.velocities[k];
                let (a0, c) = (self.osc.amplitude, self.osc.stiffness);
                let probe = |phi: f64| {
                    let x = seg.x + vs * (phi - seg.phase) / w;
                    let fnf = M::stick_forces(&self.p, x, phi)
                        .expect("stick boundary")
                        .non_friction;
                    Probe {
                        h: [fnf - bound_s, fnf + bound_s],
                        dh: -a0 * phi.sin() - c * vs / w,
                        ddh: -a0 * phi.cos(),
                    }
                };
                let bound = |_phi: f64, _delta: f64, _p: &Probe| a0.abs();
                // Stuck: |Fnf| < as, so Fnf − as < 0 and Fnf + as > 0.
                let inside = [-1.0, 1.0];
                let step = std::f64::consts::FRAC_PI_4;
                // A stick holds only while `|Fnf| < as`. Where a stick starts
                // with `Fnf` at or beyond a bound and moving outwards (a flow that
                // arrives where `|Fnf|` is the kinetic level and `as = ak`), or
                // beyond it by rounding, it ends at once; the root search below
                // would instead take the return of `Fnf` to the bound for the end.
                let p0 = probe(seg.search_from);
                let exit = if seg.search_from > phase_limit {
                    None
                } else if p0.h[0] > 0.0 || (p0.h[0] == 0.0 && p0.dh > 0.0) {
                    Some(0)
                } else if p0.h[1] < 0.0 || (p0.h[1] == 0.0 && p0.dh < 0.0) {
                    Some(1)
                } else {
                    None
                };
                let root = exit.map(|which| crate::dynamics::crossing::Root {
                    phase: seg.search_from,
                    which,
                    kind: RootKind::Crossing,
                });
                let root = root.or_else(|| {
                    first_root(
                        &probe,
                        &bound,
                        seg.search_from,
                        phase_limit,
                        step,
                        self.opts.graze_tol,
                    )
                });
                let Some(root) = root else {
                    return Ok(None);
                };
                if root.kind == RootKind::Unresolved {
                    return Err(unresolved(root.phase, seg.location));
                }
                let (x, _) = self.state_at(seg, root.phase);
                if root.kind == RootKind::NotFinite || !x.is_finite() {
                    return Err(self.blow_up(seg, root.phase));
                }
                if root.kind == RootKind::Graze {
                    // |Fnf| touches as without exceeding it: the stick persists.
                    let (at, resume) =
                        graze_phase(&probe, &bound, &root, step, self.opts.graze_tol, inside);
                    let (x, _) = self.state_at(seg, at);
                    let event = Event {
                        phase: at,
                        x,
                        v: vs,
                        boundary: k,
                        kind: EventKind::Graze,
                        before: Location::Stick,
                        after: Location::Stick,
                    };
                    let next = Segment {
                        search_from: resume,
                        ..*seg
                    };
                    return Ok(Some((event, next)));
                }
                let after = Location::Domain(if root.which == 0 { k + 1 } else { k });
                let event = Event {
                    phase: root.phase,
                    x,
                    v: vs,
                    boundary: k,
                    kind: EventKind::StickEnd,
                    before: Location::Stick,
                    after,
                };
                let next = Segment {
                    x,
                    v: vs,
                    phase: root.phase,
                    location: after,
                    search_from: root.phase,
                };
                Ok(Some((event, next)))
            }
        }
    }

    fn check_finite(&self, seg: &Segment, phase: f64) -> Result<(), SimError> {
        let (x, v) = self.state_at(seg, phase);
        if x.is_finite() && v.is_finite() {
            Ok(())
        } else {
            Err(self.blow_up(seg, phase))
        }
    }

    /// The error for a segment whose state is no longer finite at `phase`:
    /// the last finite state is located by bisection between the segment's
    /// start (finite) and `phase`, to the rounding of the phase.
    fn blow_up(&self, seg: &Segment, phase: f64) -> SimError {
        let finite = |phi: f64| {
            let (x, v) = self.state_at(seg, phi);
            x.is_finite() && v.is_finite()
        };
        let (mut lo, mut hi) = (seg.phase, phase);
        if finite(hi) {
            // Only the bound on the rate overflowed: the state itself is finite here.
            lo = hi;
        } else {
            loop {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if finite(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
        }
        let (x, v) = self.state_at(seg, phase);
        let (last_x, last_v) = self.state_at(seg, lo);
        SimError::NotFinite {
            phase,
            time: phase / self.osc.frequency,
            location: seg.location,
            x,
            v,
            last_phase: lo,
            last_x,
            last_v,
        }
    }

    /// Simulate from `seg` to `phase_end`, calling `on_event` for every event;
    /// returns the segment in force at `phase_end`.
    pub fn run(
        &self,
        mut seg: Segment,
        phase_end: f64,
        mut on_event: impl FnMut(&Event),
    ) -> Result<Segment, SimError> {
        for _ in 0..self.opts.max_events {
            match self.next_event(&seg, phase_end)? {
                None => return Ok(seg),
                Some((event, next)) => {
                    on_event(&event);
                    seg = next;
                }
            }
        }
        Err(SimError::TooManyEvents {
            limit: self.opts.max_events,
            phase: seg.search_from,
        })
    }
}
