//! Known stable motions seen stroboscopically, and a settle that stops as
//! soon as a simulation is *certified* to be on its way to one of them (the
//! "seed, continue, match" search of Datseris & Wagemakers' Attractors.jl,
//! on exact states).
//!
//! A periodic motion of `N` forcing periods meets the stroboscopic section
//! `W t ≡ φ0 (mod 2π)` in `N` states `(x, v, location)`, computed here from
//! its switching points by the closed-form flow ([`Simulator::state_at`]).
//! For each of them the motion's *return* is computed once: the events of
//! one cycle (`N` periods) from that state, and the exact Jacobian `J` of
//! the `N`-period stroboscopic map there (the tangent map of
//! [`crate::dynamics::tangent`] carried along the cycle).
//!
//! A simulation stops early at a known motion only on a certificate, never
//! on a distance alone ([`settle`]): over its last `N` periods it
//! 1. met exactly the motion's events (the same boundaries, kinds and
//!    sides, in the same order: it followed the motion's own mapping
//!    structure, so it lies on the smooth branch of the stroboscopic map
//!    that the motion's `J` linearises), and
//! 2. its deviation from the motion shrank, and by what `J` predicts: with
//!    `e` the deviation a cycle before and `e'` now,
//!    `‖e' − J e‖ ≤ η ‖e‖` with `η = (1 − ρ) / 4` (`ρ` the largest
//!    eigenvalue modulus of `J`), and `‖e'‖ < ‖e‖`.
//!
//! Both are tried only within the motion's [`reach`], where no state can
//! cross a transition and leave the motion's structure in the cycles to
//! come.
//!
//! Nearby motions of another structure fail the first test however close
//! they are (at `W = 3.6176858236, Q0 = 70` the period-1 motion
//! `P_{3_33 4_33}` and the period-2 motion `P_{3_31 0_11 3_13 4_33 3_33
//! 4_33}^2` have stroboscopic states `2e-3` apart); a state passing by, or
//! one still far enough for the map's nonlinearity to matter, fails the
//! second. Anything else simulates on until its cycle repeats and is named
//! by its own structure, as [`crate::orbit::attractor::find`] does.

use nalgebra::{Matrix2, Vector2};

use crate::dynamics::simulate::{Event, EventKind, Location, Segment, Simulator};
use crate::dynamics::tangent::{advance, Tangent};
use crate::model::Model;
use crate::orbit::admissible::{conditions, ViolationKind};
use crate::orbit::attractor::{find_or_stop, Attractor, AttractorOptions, Settle};
use crate::orbit::motion::{segment_at, Motion, OrbitError};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// A certificate is tried only within this distance of a motion's state,
/// relative to the motion's length scale (and within the caller's reach,
/// [`KnownMotions::insert_within`]).
pub const MAX_RADIUS: f64 = 5e-2;

/// The deviation a cycle later may differ from the linear prediction `J e`
/// by at most this fraction of `1 − ρ`, times `‖e‖`: the map is linear to
/// well within its contraction there.
pub const LINEAR_FRACTION: f64 = 0.25;

/// A certificate is tried only within a motion's smallest admissibility
/// margin, converted to a distance in state ([`state_to_margin`]), divided
/// by this ([`reach`]): the margin is what the orbit may deviate by before
/// it crosses a transition and leaves the motion's structure, and a
/// deviation can grow within a period before the motion's contraction
/// takes it back. (In the window W ∈ (3.947843, 3.948674) at Q0 = 70 the
/// period-2 motion alternates between the structures of the two period-1
/// motions, `3e-4` of the length scale from each: a state that follows one
/// period-1 motion's structure for a cycle, contracting as its Jacobian
/// predicts, still goes on to the period-2 motion from outside its reach.)
pub const REACH_FACTOR: f64 = 10.0;

/// How much a margin (a velocity, or a force per unit mass) can change per
/// unit of deviation of the state in the norm of [`KnownMotions`]
/// (`max(|Δx|, |Δv| / W)`): at most `W` for a velocity and
/// `|c_j| + |2 d_j| W` for the force of domain `j`.
pub fn state_to_margin<M: Model>(sim: &Simulator<M>) -> f64 {
    let w = sim.oscillator().frequency.abs();
    (0..sim.info().domains.len())
        .map(|j| {
            let co = sim.coefficients(j);
            co.c.abs() + co.two_d.abs() * w
        })
        .fold(w.max(f64::MIN_POSITIVE), f64::max)
}

/// The smallest admissibility margin of `motion` (SPEC §6) that measures
/// its distance to a transition: every condition but the stick end's, whose
/// margin is the phase tolerance of the event search (about `1e-7 W t`) for
/// every stick that ends where it should, however far the motion is from a
/// transition (the stick that ends early is a violation, never a small
/// margin). NaN counts as the smallest; `None` for no conditions.
pub fn guard_margin<M: Model>(sim: &Simulator<M>, motion: &Motion) -> Option<f64> {
    conditions(sim, &motion.structure, &motion.points)
        .iter()
        .filter(|c| c.kind != ViolationKind::StickEnd)
        .map(|c| {
            if c.margin.is_nan() {
                f64::NEG_INFINITY
            } else {
                c.margin
            }
        })
        .reduce(f64::min)
}

/// How far from `motion` (a length in the norm of [`KnownMotions`]) a state
/// is certain to keep its structure for a while: its smallest margin
/// ([`guard_margin`]) over [`REACH_FACTOR`] · [`state_to_margin`]; zero for
/// a motion with no margin (or a violated one).
pub fn reach<M: Model>(sim: &Simulator<M>, motion: &Motion) -> f64 {
    guard_margin(sim, motion)
        .map_or(0.0, |m| m / (REACH_FACTOR * state_to_margin(sim)))
        .max(0.0)
}

/// A state of a motion at a stroboscopic phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StroboscopicState {
    /// Displacement.
    pub x: f64,
    /// Velocity.
    pub v: f64,
    /// Domain or stick.
    pub location: Location,
}

/// The states of `motion` at `W t ≡ phase0 (mod 2π)`: `N` of them for a
/// motion of `N` forcing periods, in time order from the first such phase at
/// or after the motion's first switching point. Each is the flow of the
/// mapping in force there, from its switching point (a stick mapping moves
/// with the belt).
pub fn stroboscopic_states<M: Model>(
    sim: &Simulator<M>,
    motion: &Motion,
    phase0: f64,
) -> Vec<StroboscopicState> {
    located_states(sim, motion, phase0)
        .into_iter()
        .map(|(_, s)| s)
        .collect()
}

/// [`stroboscopic_states`], each with the segment in force there and its phase.
fn located_states<M: Model>(
    sim: &Simulator<M>,
    motion: &Motion,
    phase0: f64,
) -> Vec<((Segment, f64), StroboscopicState)> {
    let steps = motion.structure.steps();
    let pts = &motion.points;
    let m = steps.len();
    let n = motion.structure.periods() as usize;
    if m == 0 || pts.len() != m {
        return Vec::new();
    }
    let cycle = TAU * n as f64;
    let first = pts[0].phase;
    let base = phase0 + TAU * ((first - phase0) / TAU).ceil();
    let mut k = 0;
    (0..n)
        .map(|i| {
            let phi = base + TAU * i as f64;
            // The mapping in force at `phi`: the last switching point at or before it.
            while k + 1 < m && pts[k + 1].phase <= phi {
                k += 1;
            }
            let seg = segment_at(sim, &motion.structure, pts, k);
            let location = seg.location;
            debug_assert!(phi < first + cycle);
            let (x, v) = sim.state_at(&seg, phi);
            ((seg, phi), StroboscopicState { x, v, location })
        })
        .collect()
}

/// What a certificate compares of an event: the boundary, what happened,
/// and the locations before and after.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Signature {
    boundary: usize,
    kind: EventKind,
    before: Location,
    after: Location,
}

impl Signature {
    fn of(e: &Event) -> Self {
        Self {
            boundary: e.boundary,
            kind: e.kind,
            before: e.before,
            after: e.after,
        }
    }
}

/// One cycle of a known motion from one of its stroboscopic states.
#[derive(Clone, Debug, PartialEq)]
struct Return {
    /// The events of the cycle (grazes left out), in time order.
    events: Vec<Signature>,
    /// The exact Jacobian of the `N`-period stroboscopic map at the state,
    /// in `(x, v)`.
    jacobian: Matrix2<f64>,
}

/// The return of the motion from the state `(seg, phase)` on it: simulated
/// over `periods` forcing periods with the tangent map. `None` where the
/// cycle is not one of `mappings` events with a derivative at each (a
/// tangency on the motion: no certificate there).
fn motion_return<M: Model>(
    sim: &Simulator<M>,
    (seg, phase): (Segment, f64),
    periods: u32,
    mappings: usize,
) -> Option<Return> {
    let (x, v) = sim.state_at(&seg, phase);
    let start = Segment {
        x,
        v,
        phase,
        search_from: seg.search_from.max(phase),
        ..seg
    };
    let mut tangent = Tangent::new(Matrix2::identity());
    let mut events = Vec::with_capacity(mappings);
    advance(
        sim,
        start,
        phase + TAU * periods as f64,
        &mut tangent,
        |e| {
            if e.kind != EventKind::Graze {
                events.push(Signature::of(e));
            }
        },
    )
    .ok()?;
    let regular = tangent.singular == 0 && tangent.matrix.iter().all(|v| v.is_finite());
    (regular && events.len() == mappings).then_some(Return {
        events,
        jacobian: tangent.matrix,
    })
}

/// One known motion: its stroboscopic states, their returns, and where a
/// certificate is tried.
#[derive(Clone, Debug, PartialEq)]
struct Entry {
    id: usize,
    states: Vec<StroboscopicState>,
    /// The return from each state (empty: the motion certifies nothing, a
    /// start reaching it is named by its own cycle).
    returns: Vec<Return>,
    /// Forcing periods of the motion.
    periods: u32,
    /// Length scale: the larger of the motion's extents in `x` and `v / W`.
    scale: f64,
    /// Largest eigenvalue modulus (`None`: not a stable, admissible motion).
    rho: Option<f64>,
    /// Distance within which a certificate is tried (a length; zero for a
    /// motion that is not stable).
    radius: f64,
    /// Largest radius allowed by the caller ([`KnownMotions::insert_within`]).
    reach: f64,
    /// `[x_min, x_max, v_min, v_max]` over the switching points and states.
    extent: [f64; 4],
}

/// A state closer to a motion than this, relative to its length scale, is
/// on it (the switching points themselves are known to about `1e-10`).
const ON_MOTION: f64 = 1e-9;

/// Known stable motions at one stroboscopic phase `φ0`.
#[derive(Clone, Debug, PartialEq)]
pub struct KnownMotions {
    phase0: f64,
    frequency: f64,
    entries: Vec<Entry>,
}

impl KnownMotions {
    /// None yet, seen at `W t ≡ phase0 (mod 2π)`, for the simulator's `W`.
    pub fn new<M: Model>(sim: &Simulator<M>, phase0: f64) -> Self {
        Self {
            phase0,
            frequency: sim.oscillator().frequency,
            entries: Vec::new(),
        }
    }

    /// The motions `known` (each with the caller's id).
    pub fn from_motions<M: Model>(
        sim: &Simulator<M>,
        known: &[(usize, Motion)],
        phase0: f64,
    ) -> Self {
        let mut k = Self::new(sim, phase0);
        for (id, m) in known {
            k.insert(sim, *id, m);
        }
        k
    }

    /// Add `motion` under `id`. A motion that is not stable and admissible
    /// certifies nothing (radius 0). A stable one's certificates are tried
    /// within `L · MAX_RADIUS` of its stroboscopic states (`L` its length
    /// scale) and within its [`reach`], in the max-norm of `(x, v / W)`;
    /// see the module doc for what they check.
    pub fn insert<M: Model>(&mut self, sim: &Simulator<M>, id: usize, motion: &Motion) {
        self.insert_within(sim, id, motion, f64::INFINITY);
    }

    /// [`insert`](Self::insert), with the radius also at most `reach` (a
    /// length): for a motion near a transition, where a state farther than
    /// `reach` from it may cross the transition and go elsewhere although
    /// the map is contracting there.
    pub fn insert_within<M: Model>(
        &mut self,
        sim: &Simulator<M>,
        id: usize,
        motion: &Motion,
        reach: f64,
    ) {
        let located = located_states(sim, motion, self.phase0);
        let states: Vec<StroboscopicState> = located.iter().map(|&(_, s)| s).collect();
        let w = self.frequency;
        let info = sim.info();
        let mut extent = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut widen = |x: f64, v: f64| {
            extent[0] = extent[0].min(x);
            extent[1] = extent[1].max(x);
            extent[2] = extent[2].min(v);
            extent[3] = extent[3].max(v);
        };
        for (pt, &s) in motion.points.iter().zip(motion.structure.steps()) {
            widen(pt.x, sim.velocity(info.mappings[s].from));
        }
        for s in &states {
            widen(s.x, s.v);
        }
        let scale = (extent[1] - extent[0]).max((extent[3] - extent[2]) / w);
        let periods = motion.structure.periods();
        let rho = motion
            .stability
            .filter(|s| {
                s.is_stable()
                    && motion.is_admissible()
                    && scale.is_finite()
                    && scale > 0.0
                    && states.len() == periods as usize
            })
            .map(|s| s.largest_modulus);
        let returns: Vec<Return> = match rho {
            Some(_) => located
                .iter()
                .map_while(|&(at, _)| motion_return(sim, at, periods, motion.structure.len()))
                .collect(),
            None => Vec::new(),
        };
        let returns = if returns.len() == states.len() {
            returns
        } else {
            Vec::new()
        };
        let reach = if reach.is_nan() { 0.0 } else { reach.max(0.0) };
        let radius = match rho {
            Some(_) => (scale * MAX_RADIUS)
                .min(reach)
                .min(self::reach(sim, motion)),
            None => 0.0,
        };
        self.entries.push(Entry {
            id,
            states,
            returns,
            periods,
            scale,
            rho,
            radius,
            reach,
            extent,
        });
    }

    /// The stroboscopic phase `φ0`.
    pub fn phase0(&self) -> f64 {
        self.phase0
    }

    /// How many motions are known.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The stroboscopic states of motion `id`.
    pub fn states(&self, id: usize) -> Option<&[StroboscopicState]> {
        self.entry(id).map(|e| e.states.as_slice())
    }

    /// The distance from motion `id` within which a certificate is tried
    /// (a length; `v` is compared as `v / W`).
    pub fn radius(&self, id: usize) -> Option<f64> {
        self.entry(id).map(|e| e.radius)
    }

    /// Whether motion `id` can certify a start at all: stable, admissible,
    /// and regular along its cycle (a tangency on the motion has no
    /// derivative to predict the contraction with).
    pub fn certifies(&self, id: usize) -> bool {
        self.entry(id)
            .is_some_and(|e| e.rho.is_some() && !e.returns.is_empty())
    }

    /// The length scale of motion `id`.
    pub fn scale(&self, id: usize) -> Option<f64> {
        self.entry(id).map(|e| e.scale)
    }

    /// `[x_min, x_max, v_min, v_max]` over every known motion's switching
    /// points and stroboscopic states; `None` if none is known.
    pub fn extent(&self) -> Option<[f64; 4]> {
        self.entries.iter().map(|e| e.extent).reduce(|a, b| {
            [
                a[0].min(b[0]),
                a[1].max(b[1]),
                a[2].min(b[2]),
                a[3].max(b[3]),
            ]
        })
    }

    fn entry(&self, id: usize) -> Option<&Entry> {
        self.entries.iter().find(|e| e.id == id)
    }

    /// The longest motion known, in forcing periods (the history a
    /// certificate needs).
    fn longest(&self) -> u32 {
        self.entries.iter().map(|e| e.periods).max().unwrap_or(1)
    }

    /// Whether `phase ≡ φ0 (mod 2π)`.
    fn on_section(&self, phase: f64) -> bool {
        let turns = ((phase - self.phase0) / TAU).round();
        (phase - self.phase0 - turns * TAU).abs() <= 1e-9 * phase.abs().max(1.0)
    }

    /// The max-norm of a deviation `(dx, dv)` in `(x, v / W)`.
    fn norm(&self, d: Vector2<f64>) -> f64 {
        d[0].abs().max(d[1].abs() / self.frequency)
    }

    /// The known motion within whose radius the state of segment `seg` at
    /// `phase` lies (the nearest, in the same domain or on the stick), if
    /// `phase ≡ φ0 (mod 2π)`. Being near is no verdict: [`settle`] stops
    /// only on a certificate. Allocates nothing.
    pub fn near<M: Model>(&self, sim: &Simulator<M>, seg: &Segment, phase: f64) -> Option<usize> {
        if !self.on_section(phase) {
            return None;
        }
        let (x, v) = sim.state_at(seg, phase);
        let mut best: Option<(usize, f64)> = None;
        for e in &self.entries {
            for s in &e.states {
                let d = self.norm(Vector2::new(x - s.x, v - s.v));
                if s.location == seg.location && d <= e.radius && best.is_none_or(|(_, b)| d < b) {
                    best = Some((e.id, d));
                }
            }
        }
        best.map(|(id, _)| id)
    }

    /// The motion that the trajectory whose recent history is `history`
    /// (stroboscopic state `now` at period `n`) is certified to go to: see
    /// the module doc.
    fn certify(&self, history: &History, n: u32, now: &Sample) -> Option<usize> {
        for e in &self.entries {
            let Some(rho) = e.rho else { continue };
            if e.returns.is_empty() {
                continue;
            }
            for (s, ret) in e.states.iter().zip(&e.returns) {
                if s.location != now.location {
                    continue;
                }
                let dev = Vector2::new(now.x - s.x, now.v - s.v);
                let d = self.norm(dev);
                if d > e.radius {
                    continue;
                }
                if d <= ON_MOTION * e.scale {
                    return Some(e.id);
                }
                let Some(back) = n.checked_sub(e.periods) else {
                    continue;
                };
                let Some(before) = history.states.iter().find(|p| p.period == back) else {
                    continue;
                };
                if before.location != s.location {
                    continue;
                }
                let prev = Vector2::new(before.x - s.x, before.v - s.v);
                let dp = self.norm(prev);
                if d >= dp {
                    continue;
                }
                let followed = history
                    .events
                    .iter()
                    .filter(|&&(p, _)| p > back && p <= n)
                    .map(|&(_, sig)| sig)
                    .eq(ret.events.iter().copied());
                if !followed {
                    continue;
                }
                let miss = self.norm(dev - ret.jacobian * prev);
                if miss <= LINEAR_FRACTION * (1.0 - rho) * dp {
                    return Some(e.id);
                }
            }
        }
        None
    }
}

/// A stroboscopic state of a simulation: its period (from the start), state
/// and location.
#[derive(Clone, Copy, Debug)]
struct Sample {
    period: u32,
    x: f64,
    v: f64,
    location: Location,
}

/// What a simulation did over its last few periods: its stroboscopic states
/// and its events (each with the period it ended in), as far back as the
/// longest known motion's cycle.
#[derive(Debug, Default)]
struct History {
    states: Vec<Sample>,
    events: Vec<(u32, Signature)>,
    period: u32,
}

impl History {
    /// Record period `n`'s end at `(seg, phase)` with the events met since the
    /// previous stroboscopic phase, and say whether it certifies a known motion.
    fn step<M: Model>(
        &mut self,
        known: &KnownMotions,
        sim: &Simulator<M>,
        seg: &Segment,
        phase: f64,
        events: &[Event],
    ) -> Option<usize> {
        let n = self.period;
        self.period += 1;
        if !known.on_section(phase) {
            return None;
        }
        let (x, v) = sim.state_at(seg, phase);
        let now = Sample {
            period: n,
            x,
            v,
            location: seg.location,
        };
        self.events.extend(
            events
                .iter()
                .filter(|e| e.kind != EventKind::Graze)
                .map(|e| (n, Signature::of(e))),
        );
        let found = known.certify(self, n, &now);
        let longest = known.longest();
        self.states.push(now);
        self.states.retain(|s| s.period + longest > n);
        self.events.retain(|&(p, _)| p + longest > n);
        found
    }
}

/// Where a start settles.
#[derive(Clone, Debug, PartialEq)]
pub enum Settled {
    /// It was certified to go to this known motion.
    Known(usize),
    /// What [`crate::orbit::attractor::find`] finds (no known motion was certified).
    Attractor(Box<Attractor>),
}

/// The outcome of [`settle`] and its cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Settling {
    /// Where the start settled, or why nothing was found.
    pub outcome: Result<Settled, OrbitError>,
    /// Whole forcing periods simulated (stroboscopic phases passed after the start).
    pub periods: u32,
}

/// Simulate from `start` (at a phase `≡ φ0 (mod 2π)`) period by period and
/// stop as soon as a certificate says which known motion it goes to (the
/// module doc: the motion's own events over its last cycle, and a
/// deviation that shrank as the motion's exact Jacobian predicts);
/// otherwise settle as [`crate::orbit::attractor::find`] does (cycle
/// detection, Newton refinement), through its stroboscopic hook
/// ([`find_or_stop`]): one simulation, no transient simulated twice.
pub fn settle<M: Model>(
    sim: &Simulator<M>,
    known: &KnownMotions,
    start: Segment,
    opts: AttractorOptions,
) -> Settling {
    let mut history = History::default();
    let mut hook =
        |seg: &Segment, phase: f64, events: &[Event]| history.step(known, sim, seg, phase, events);
    let outcome = find_or_stop(sim, start, opts, Some(&mut hook)).map(|s| match s {
        Settle::Attractor(a) => Settled::Attractor(a),
        Settle::Stopped(id) => Settled::Known(id),
    });
    Settling {
        outcome,
        periods: history.period.saturating_sub(1),
    }
}
