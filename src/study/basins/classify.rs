//! Which attractor one start reaches: each stable periodic motion is
//! identified once, by a full search from a fixed set of seed starts
//! ([`discover`]), and every start is then simulated only until its
//! stroboscopic point nears one of them
//! ([`settle`](crate::orbit::known::settle)); a start that nears none
//! settles as [`attractor::find`] does, and one that never settles is
//! judged by its largest Lyapunov exponent ([`irregular`]).
//!
//! The known motions depend on the header alone (the seeds are grid points
//! chosen by index), never on the order the starts are computed in: a
//! start's result is the same on any number of threads and after any resume.

use rayon::prelude::*;

use crate::dynamics::simulate::Simulator;
use crate::model::{Model, ModelInfo};
use crate::orbit::attractor::{self, Attractor, AttractorOptions};
use crate::orbit::known::{settle, KnownMotions, Settled};
use crate::orbit::lyapunov::{spectrum, LyapunovOptions, Verdict};
use crate::orbit::motion::{Motion, OrbitError};
use crate::study::map::{motion_label, NO_MOTION, STICK};
use crate::study::search::same_motion;
use stickslip_codegen::structure::with_periods;

use super::file::{BasinHeader, StartResult};

/// Seed starts per axis of the discovery (at most; fewer on a smaller grid).
pub const SEEDS_PER_AXIS: usize = 8;

/// The label of a start that never settled, whose exponent says chaos.
pub const CHAOTIC: &str = "chaotic";
/// The label of a start that never settled, with a zero largest exponent.
pub const QUASI_PERIODIC: &str = "quasi-periodic";
/// The label of a start that did not settle and whose exponent was not computed.
pub const UNSETTLED: &str = "unsettled";

/// The stable periodic motions the run matches its starts against, and their labels.
pub struct Known {
    /// Their stroboscopic neighbourhoods at the run's phase.
    pub motions: KnownMotions,
    /// Each one's label (its id is its position here).
    pub labels: Vec<String>,
    /// The motions themselves, in the same order.
    pub found: Vec<Motion>,
}

/// The attractor options of a run of `periods` forcing periods at most.
pub fn attractor_options(periods: u32) -> AttractorOptions {
    AttractorOptions {
        max_periods: periods,
        ..AttractorOptions::default()
    }
}

/// The seed starts: a `k × k` subgrid (`k ≤` [`SEEDS_PER_AXIS`]) spread over the grid.
pub fn seed_indices(header: &BasinHeader) -> Vec<usize> {
    let pick = |n: usize| -> Vec<usize> {
        let k = n.min(SEEDS_PER_AXIS);
        if k <= 1 {
            return vec![n / 2];
        }
        (0..k).map(|i| i * (n - 1) / (k - 1)).collect()
    };
    let nx = header.x.count;
    let (xs, vs) = (pick(nx), pick(header.v.count));
    vs.iter()
        .flat_map(|&iv| xs.iter().map(move |&ix| iv * nx + ix))
        .collect()
}

/// Switching points of two motions closer than this (relative to the
/// motion's scale, phases in radians) are one motion.
const SAME_MOTION: f64 = 1e-6;

/// Identify the stable periodic motions reached from the seed starts
/// (searched in parallel, kept in seed order, each distinct motion once).
/// Distinct motions of one structure, such as a mirror-image pair of a
/// symmetric oscillator, are told apart in their labels by their first
/// switching point (`distinct_label`).
pub fn discover<M: Model>(sim: &Simulator<M>, header: &BasinHeader) -> Known {
    let opts = attractor_options(header.periods);
    let found: Vec<Option<attractor::Attractor>> = seed_indices(header)
        .par_iter()
        .map(|&i| {
            let (x, v) = header.start(i);
            let seg = sim.start(x, v, header.phase).ok()?;
            attractor::find(sim, seg, opts).ok()
        })
        .collect();
    let mut motions: Vec<Motion> = Vec::new();
    for a in found.into_iter().flatten() {
        let Attractor::Periodic(m) = a else {
            continue;
        };
        let stable = m.stability.is_some_and(|s| s.is_stable()) && m.is_admissible();
        if stable && !motions.iter().any(|k| same_motion(k, &m, SAME_MOTION)) {
            motions.push(m);
        }
    }
    let mut known = Known {
        motions: KnownMotions::new(sim, header.phase),
        labels: Vec::new(),
        found: Vec::new(),
    };
    for m in &motions {
        let twins: Vec<&Motion> = motions
            .iter()
            .filter(|o| o.structure == m.structure)
            .collect();
        let label = if twins.len() > 1 {
            distinct_label(sim.info(), m, &twins)
        } else {
            motion_label(sim.info(), m)
        };
        known.motions.insert(sim, known.labels.len(), m);
        known.labels.push(label);
    }
    known.found = motions;
    known
}

/// The label of `motion` among `twins`, motions of its structure: the
/// structure followed by its first switching point's `x`, with as many
/// digits (at least 4) as tell the twins apart, e.g.
/// `P_{0_11 1_11 0_11 2_11} (x1 = 1.4508)`.
pub fn distinct_label(info: &ModelInfo, motion: &Motion, twins: &[&Motion]) -> String {
    let x = |m: &Motion| m.points.first().map_or(f64::NAN, |p| p.x);
    let digits = (4..=12)
        .find(|&d| {
            let mine = format!("{:.*}", d, x(motion));
            twins
                .iter()
                .filter(|t| !same_motion(t, motion, SAME_MOTION))
                .all(|t| format!("{:.*}", d, x(t)) != mine)
        })
        .unwrap_or(12);
    format!(
        "{} (x1 = {:.*})",
        motion_label(info, motion),
        digits,
        x(motion)
    )
}

/// The label of an attractor found by a full search.
pub fn attractor_label(info: &ModelInfo, a: &Attractor) -> String {
    match a {
        Attractor::Periodic(m) => motion_label(info, m),
        Attractor::NoMotion(_) => NO_MOTION.to_string(),
        Attractor::Stick(_) => STICK.to_string(),
        Attractor::Autonomous(c) => {
            let kind = if c.stick > 0.0 { "stick-slip" } else { "slip" };
            c.motion(info).map_or_else(
                || format!("autonomous {kind} cycle"),
                |m| format!("{kind} cycle {}", motion_label(info, &m)),
            )
        }
    }
}

/// Where start `index` of the run goes.
pub fn classify<M: Model>(
    sim: &Simulator<M>,
    known: &Known,
    header: &BasinHeader,
    index: usize,
) -> StartResult {
    let (x, v) = header.start(index);
    let (attractor, exponent) = match sim.start(x, v, header.phase) {
        Err(_) => ("simulation_error".to_string(), None),
        Ok(seg) => {
            let settling = settle(sim, &known.motions, seg, attractor_options(header.periods));
            match settling.outcome {
                Ok(Settled::Known(id)) => (known.labels[id].clone(), None),
                Ok(Settled::Attractor(a)) => (settled_label(sim.info(), known, &a), None),
                Err(OrbitError::Unsettled { .. }) => irregular(sim, header, (x, v)),
                Err(OrbitError::Inadmissible(_)) => ("inadmissible".to_string(), None),
                Err(OrbitError::NotConverged(_)) => ("not_converged".to_string(), None),
                Err(OrbitError::Simulation(_)) => ("simulation_error".to_string(), None),
                Err(OrbitError::CycleTooLong { .. }) => ("cycle_too_long".to_string(), None),
                Err(_) => ("error".to_string(), None),
            }
        }
    };
    StartResult {
        index,
        x,
        v,
        attractor,
        exponent,
    }
}

/// The label of an attractor a start settled on without a certificate:
/// a known motion's label if it is that motion, else its own, told apart
/// from a known motion of its structure by its first switching point.
fn settled_label(info: &ModelInfo, known: &Known, a: &Attractor) -> String {
    let Attractor::Periodic(m) = a else {
        return attractor_label(info, a);
    };
    if let Some(i) = known
        .found
        .iter()
        .position(|k| same_motion(k, m, SAME_MOTION))
    {
        return known.labels[i].clone();
    }
    let twins: Vec<&Motion> = known
        .found
        .iter()
        .filter(|k| k.structure == m.structure)
        .chain(std::iter::once(m))
        .collect();
    if twins.len() > 1 {
        distinct_label(info, m, &twins)
    } else {
        attractor_label(info, a)
    }
}

/// What a start that never settled reaches, from its Lyapunov spectrum:
/// the label and the largest exponent. The one call of the spectrum in a
/// basin run; without exponents (`lyapunov = 0` in the header) the start
/// is `unsettled`.
pub fn irregular<M: Model>(
    sim: &Simulator<M>,
    header: &BasinHeader,
    (x, v): (f64, f64),
) -> (String, Option<f64>) {
    if header.lyapunov == 0 {
        return (UNSETTLED.to_string(), None);
    }
    let opts = LyapunovOptions {
        transient: header.periods,
        periods: header.lyapunov,
    };
    match spectrum(sim, (x, v, header.phase), opts) {
        Err(_) => (UNSETTLED.to_string(), None),
        Ok(s) => {
            let label = match &s.verdict {
                Verdict::Chaotic => CHAOTIC.to_string(),
                Verdict::QuasiPeriodic => QUASI_PERIODIC.to_string(),
                Verdict::Periodic { structure, n } => with_periods(structure, *n),
                Verdict::NoMotion => NO_MOTION.to_string(),
                Verdict::Stick => STICK.to_string(),
                Verdict::LongCycle { longer_than } => {
                    format!("cycle longer than {longer_than} periods")
                }
            };
            (label, Some(s.exponents[0]))
        }
    }
}
