//! Known stable motions seen stroboscopically, and a settle that stops as
//! soon as a simulation enters one's neighbourhood (the "seed, continue,
//! match" search of Datseris & Wagemakers' Attractors.jl, on exact states).
//!
//! A periodic motion of `N` forcing periods meets the stroboscopic section
//! `W t ≡ φ0 (mod 2π)` in `N` states `(x, v, location)`, computed here from
//! its switching points by the closed-form flow ([`Simulator::state_at`]). A
//! simulation that reaches a small ball around one of them, in the same
//! domain (or on the stick), is on its way to that motion: the search stops
//! there instead of simulating until the motion repeats and refining it.

use crate::dynamics::simulate::{Location, Segment, Simulator};
use crate::model::Model;
use crate::orbit::attractor::{find_or_stop, Attractor, AttractorOptions, Settle};
use crate::orbit::motion::{segment_at, Motion, OrbitError};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// The neighbourhood's radius, relative to the motion's length scale, is at
/// most this (a motion far from any bifurcation).
pub const MAX_RADIUS: f64 = 5e-2;

/// The radius is also at most this fraction of the contraction margin
/// `1 − ρ` (`ρ` the largest eigenvalue modulus): the neighbourhood shrinks as
/// the motion approaches a bifurcation.
pub const CONTRACTION_FRACTION: f64 = 0.1;

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
            StroboscopicState { x, v, location }
        })
        .collect()
}

/// One known motion: its stroboscopic states and neighbourhood.
#[derive(Clone, Debug, PartialEq)]
struct Entry {
    id: usize,
    states: Vec<StroboscopicState>,
    /// Forcing periods of the motion.
    periods: u32,
    /// Length scale: the larger of the motion's extents in `x` and `v / W`.
    scale: f64,
    /// Largest eigenvalue modulus (`None`: not a stable, admissible motion).
    rho: Option<f64>,
    /// Neighbourhood radius (a length; zero for a motion that is not stable).
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
    /// gets no neighbourhood (radius 0). A stable one's is the max-norm ball
    /// in `(x, v / W)` around each stroboscopic state of radius
    /// `r = min(L · min(1e-2, 0.1 (1 − ρ)), D / 4)`, `L` its length scale,
    /// `ρ` its largest eigenvalue modulus and `D` the distance from its
    /// states to the nearest state of another known motion.
    ///
    /// Why: within the ball the `N`-period stroboscopic map is its
    /// linearisation `DP` (eigenvalues those of the motion's monodromy) plus a
    /// remainder of relative size `O(r / L)`; with `r / L ≤ (1 − ρ) / 10`
    /// that remainder cannot undo the contraction by `ρ`, *provided the map
    /// is smooth in the ball*. A non-smooth transition nearby (a stick that
    /// appears or vanishes) breaks that: at `W = 3.9482584517, Q0 = 70` two
    /// stable period-1 motions and a stable period-2 motion that alternates
    /// between their structures lie within `3e-4 L` of one another. The
    /// radius is therefore also kept below a quarter of the distance to any
    /// other known motion, and [`settle`] stops only once the distance has
    /// contracted over one return of the motion (see there).
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
        let states = stroboscopic_states(sim, motion, self.phase0);
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
        self.entries.push(Entry {
            id,
            states,
            periods,
            scale,
            rho,
            radius: 0.0,
            reach: if reach.is_nan() { 0.0 } else { reach.max(0.0) },
            extent,
        });
        self.update_radii();
    }

    /// Every radius, from the motion itself and its distance to the others.
    fn update_radii(&mut self) {
        let w = self.frequency;
        let dist = |a: &StroboscopicState, b: &StroboscopicState| {
            (a.x - b.x).abs().max((a.v - b.v).abs() / w)
        };
        let radii: Vec<f64> = self
            .entries
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let Some(rho) = e.rho else {
                    return 0.0;
                };
                let own = e.scale * MAX_RADIUS.min(CONTRACTION_FRACTION * (1.0 - rho));
                let apart = self
                    .entries
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .flat_map(|(_, o)| o.states.iter())
                    .flat_map(|b| e.states.iter().map(move |a| dist(a, b)))
                    .fold(f64::INFINITY, f64::min);
                own.min(0.25 * apart).min(e.reach)
            })
            .collect();
        for (e, r) in self.entries.iter_mut().zip(radii) {
            e.radius = r;
        }
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

    /// The neighbourhood radius of motion `id` (a length; `v` is compared as `v / W`).
    pub fn radius(&self, id: usize) -> Option<f64> {
        self.entry(id).map(|e| e.radius)
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

    /// The known motion whose neighbourhood holds the state of segment `seg`
    /// at `phase`, if `phase ≡ φ0 (mod 2π)` and there is one. Allocates nothing.
    pub fn near<M: Model>(&self, sim: &Simulator<M>, seg: &Segment, phase: f64) -> Option<usize> {
        self.nearest(sim, seg, phase)
            .map(|(i, _)| self.entries[i].id)
    }

    /// Like [`KnownMotions::near`]: the entry's index and the distance.
    fn nearest<M: Model>(
        &self,
        sim: &Simulator<M>,
        seg: &Segment,
        phase: f64,
    ) -> Option<(usize, f64)> {
        let turns = ((phase - self.phase0) / TAU).round();
        if (phase - self.phase0 - turns * TAU).abs() > 1e-9 * phase.abs().max(1.0) {
            return None;
        }
        let (x, v) = sim.state_at(seg, phase);
        let w = self.frequency;
        let mut best: Option<(usize, f64)> = None;
        for (i, e) in self.entries.iter().enumerate() {
            for s in &e.states {
                let d = (x - s.x).abs().max((v - s.v).abs() / w);
                if s.location == seg.location && d <= e.radius && best.is_none_or(|(_, b)| d < b) {
                    best = Some((i, d));
                }
            }
        }
        best
    }
}

/// Whether a simulation has reached a known motion: inside its
/// neighbourhood and either on it (to [`ON_MOTION`]) or closer than one
/// return (`N` periods) before by at least the factor `(1 + ρ) / 2`. The
/// contraction is what a state in the motion's basin does; a state on a
/// nearby motion of another structure (which stays at a fixed distance) or
/// one passing by does not.
#[derive(Debug, Default)]
struct Approach {
    /// `(period, entry, distance)` of the recent visits.
    visits: Vec<(u32, usize, f64)>,
    period: u32,
}

impl Approach {
    fn step<M: Model>(
        &mut self,
        known: &KnownMotions,
        sim: &Simulator<M>,
        seg: &Segment,
        phase: f64,
    ) -> Option<usize> {
        let n = self.period;
        self.period += 1;
        let (i, d) = known.nearest(sim, seg, phase)?;
        let e = &known.entries[i];
        if d <= ON_MOTION * e.scale {
            return Some(e.id);
        }
        let q = 0.5 * (1.0 + e.rho.unwrap_or(1.0));
        let back = n.checked_sub(e.periods);
        let contracted = self
            .visits
            .iter()
            .any(|&(p, j, dp)| Some(p) == back && j == i && d <= q * dp);
        if contracted {
            return Some(e.id);
        }
        let longest = known.entries.iter().map(|e| e.periods).max().unwrap_or(1);
        self.visits.retain(|&(p, _, _)| p + longest > n);
        self.visits.push((n, i, d));
        None
    }
}

/// Where a start settles.
#[derive(Clone, Debug, PartialEq)]
pub enum Settled {
    /// It entered the neighbourhood of this known motion.
    Known(usize),
    /// What [`crate::orbit::attractor::find`] finds (no known motion was approached).
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
/// stop as soon as the stroboscopic state has reached a known motion: inside
/// its neighbourhood, and on it or contracting towards it over one return
/// (`N` periods); otherwise settle as [`crate::orbit::attractor::find`]
/// does (cycle detection, Newton refinement), through its stroboscopic hook
/// ([`find_or_stop`]): one simulation, no transient simulated twice.
pub fn settle<M: Model>(
    sim: &Simulator<M>,
    known: &KnownMotions,
    start: Segment,
    opts: AttractorOptions,
) -> Settling {
    let mut approach = Approach::default();
    let mut hook = |seg: &Segment, phase: f64| approach.step(known, sim, seg, phase);
    let outcome = find_or_stop(sim, start, opts, Some(&mut hook)).map(|s| match s {
        Settle::Attractor(a) => Settled::Attractor(a),
        Settle::Stopped(id) => Settled::Known(id),
    });
    Settling {
        outcome,
        periods: approach.period.saturating_sub(1),
    }
}
