//! The sampled time history behind `--csv` and `--plot`: one period of a
//! motion, or a simulated stretch, piece by piece; and its CSV form.

use std::fmt::Write as _;

use serde::Serialize;

use crate::dynamics::simulate::{Location, Segment, SimError, Simulator};
use crate::model::Model;
use crate::orbit::motion::{segment_at, Motion};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// One sample of a time history.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time `t = W t / W`.
    pub t: f64,
    /// Phase `W t`.
    pub phase: f64,
    /// Displacement.
    pub x: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration `x''` (0 while stuck).
    pub a: f64,
    /// The domain's label, 0 while stuck (as in the stick mapping `0_11`).
    pub domain: u32,
    /// Friction force per unit mass: `A0 cos W t − 2 d v − c x − x''`, the
    /// kinetic law `f(v)` in a domain and `Fnf` while stuck.
    pub friction: f64,
}

/// A stretch of motion in one domain, or stuck.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Where.
    pub location: Location,
    /// The domain's label, 0 while stuck.
    pub label: u32,
    /// Whether it starts at a switching point (an event of the motion).
    pub switching: bool,
    /// Its samples, both ends included.
    pub samples: Vec<Sample>,
}

/// A sampled time history: one period of a motion, or a simulated stretch.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// Consecutive pieces; consecutive pieces share their switching instant.
    pub pieces: Vec<Piece>,
    /// The boundaries at the edges of the visited bands, `(label, v)`.
    pub boundaries: Vec<(&'static str, f64)>,
}

impl History {
    fn boundaries_of<M: Model>(sim: &Simulator<M>, pieces: &[Piece]) -> Vec<(&'static str, f64)> {
        let info = sim.info();
        let mut ks: Vec<usize> = Vec::new();
        for piece in pieces {
            let edges = match piece.location {
                Location::Domain(j) => [info.domains[j].lower, info.domains[j].upper],
                Location::Stick => [info.stick_boundary(), None],
            };
            for k in edges.into_iter().flatten() {
                if !ks.contains(&k) {
                    ks.push(k);
                }
            }
        }
        ks.sort_unstable();
        ks.into_iter()
            .map(|k| (info.boundaries[k].label, sim.velocity(k)))
            .collect()
    }

    /// Samples of the segment `seg` (evaluated from its start) on
    /// `[from, to]`: both ends, and every phase `origin + 2π i / per_period`
    /// strictly between.
    fn piece<M: Model>(
        sim: &Simulator<M>,
        seg: &Segment,
        from: f64,
        to: f64,
        origin: f64,
        per_period: usize,
        switching: bool,
    ) -> Piece {
        let info = sim.info();
        let osc = sim.oscillator();
        let label = match seg.location {
            Location::Domain(j) => info.domains[j].label,
            Location::Stick => 0,
        };
        let step = TAU / per_period.max(1) as f64;
        let sample = |phase: f64| {
            let (x, v) = sim.state_at(seg, phase);
            let a = sim.acceleration(seg.location, x, v, phase);
            Sample {
                t: phase / osc.frequency,
                phase,
                x,
                v,
                a,
                domain: label,
                friction: osc.amplitude * phase.cos()
                    - 2.0 * osc.damping * v
                    - osc.stiffness * x
                    - a,
            }
        };
        let mut samples = vec![sample(from)];
        let mut i = ((from - origin) / step).floor() as i64 + 1;
        loop {
            let phase = origin + i as f64 * step;
            if phase >= to {
                break;
            }
            if phase > from {
                samples.push(sample(phase));
            }
            i += 1;
        }
        if to > from {
            samples.push(sample(to));
        }
        Piece {
            location: seg.location,
            label,
            switching,
            samples,
        }
    }

    /// One cycle (`N` forcing periods) of a periodic motion, each mapping's
    /// segment evaluated from its switching point, `per_period` samples per
    /// forcing period plus every switching point (at a switching instant the
    /// segment ending there and the one starting there each give a sample).
    pub fn of_motion<M: Model>(sim: &Simulator<M>, motion: &Motion, per_period: usize) -> Self {
        let m = motion.points.len();
        let cycle = TAU * motion.structure.periods() as f64;
        let origin = motion.points[0].phase;
        let pieces: Vec<Piece> = (0..m)
            .map(|k| {
                let a = motion.points[k];
                let end = if k + 1 < m {
                    motion.points[k + 1].phase
                } else {
                    origin + cycle
                };
                let seg = segment_at(sim, &motion.structure, &motion.points, k);
                Self::piece(sim, &seg, a.phase, end, origin, per_period, true)
            })
            .collect();
        let boundaries = Self::boundaries_of(sim, &pieces);
        Self { pieces, boundaries }
    }

    /// The simulated motion on `[from, to]`, starting with `seg` (the
    /// segment in force at `from`, possibly started earlier); a new piece at
    /// every event (grazes do not split a piece).
    pub fn simulated<M: Model>(
        sim: &Simulator<M>,
        mut seg: Segment,
        from: f64,
        to: f64,
        per_period: usize,
    ) -> Result<Self, SimError> {
        let mut pieces = Vec::new();
        let mut start = from;
        let mut switching = false;
        loop {
            let next = sim.next_event(&seg, to)?;
            let end = next.as_ref().map_or(to, |(e, _)| e.phase);
            match next {
                Some((_, n)) if n.phase == seg.phase && n.location == seg.location => {
                    // A graze: the same segment goes on.
                    seg = n;
                    continue;
                }
                _ => {}
            }
            pieces.push(Self::piece(
                sim, &seg, start, end, from, per_period, switching,
            ));
            match next {
                None => break,
                Some((_, n)) => {
                    seg = n;
                    start = end;
                    switching = true;
                }
            }
        }
        let boundaries = Self::boundaries_of(sim, &pieces);
        Ok(Self { pieces, boundaries })
    }

    /// Every sample in time order.
    pub fn samples(&self) -> impl Iterator<Item = &Sample> {
        self.pieces.iter().flat_map(|p| p.samples.iter())
    }

    /// CSV: `t,Wt,x,v,a,domain,F`, one row per sample.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("t,Wt,x,v,a,domain,F\n");
        for s in self.samples() {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{}",
                s.t, s.phase, s.x, s.v, s.a, s.domain, s.friction
            );
        }
        out
    }
}
