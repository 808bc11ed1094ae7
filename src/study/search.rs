//! Every coexisting stable motion at one parameter point: a global search in
//! the manner of Attractors.jl's global continuation (Datseris &
//! Wagemakers, "seed, continue, match").
//!
//! `K` deterministic, well-spread starts at phase 0 are simulated one after
//! the other. Each stops as soon as its stroboscopic state enters the
//! neighbourhood of a motion already known ([`KnownMotions`]): the caller's
//! motions and those found by the earlier starts. A start that approaches
//! none settles as [`crate::orbit::attractor::find`] does; a stable periodic
//! motion it finds that is new (neither known nor found before: same
//! structure up to rotation, same switching points to `1e-6`) is kept, and
//! is known from then on.

use crate::dynamics::simulate::Simulator;
use crate::model::Model;
use crate::orbit::attractor::{Attractor, AttractorOptions};
use crate::orbit::known::{settle, KnownMotions, Settled};
use crate::orbit::motion::Motion;

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// The search's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SearchOptions {
    /// Starts simulated (`--starts K`): rest, then a Halton sequence.
    pub starts: usize,
    /// Options of each start's settling.
    pub attractor: AttractorOptions,
    /// The box of starts extends the known motions' extent (and the
    /// boundaries' velocities) by this fraction of its size on every side.
    pub margin: f64,
}

/// Default number of starts.
pub const DEFAULT_STARTS: usize = 16;

impl Default for SearchOptions {
    fn default() -> Self {
        Self {
            starts: DEFAULT_STARTS,
            attractor: AttractorOptions {
                max_periods: 600,
                ..AttractorOptions::default()
            },
            margin: 0.5,
        }
    }
}

/// What the starts did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SearchStats {
    /// Starts simulated.
    pub starts: usize,
    /// Forcing periods simulated, over all starts.
    pub periods: u64,
    /// Starts stopped in the neighbourhood of a motion the caller knew.
    pub stopped_known: usize,
    /// Starts stopped in the neighbourhood of a motion found by an earlier start.
    pub stopped_found: usize,
    /// Starts that settled (by cycle detection and Newton) on a motion the
    /// caller knew or one found before, without entering its neighbourhood.
    pub matched: usize,
    /// Starts that found a new stable motion.
    pub new: usize,
    /// Starts that settled on something else: no motion, a permanent stick,
    /// an autonomous cycle, or a periodic motion that is not stable.
    pub other: usize,
    /// Starts whose settling failed (did not settle, Newton failed, the
    /// simulation failed).
    pub failed: usize,
}

/// The new motions and what the search cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Search {
    /// New stable periodic motions, refined by Newton, admissible, in the
    /// canonical rotation [`crate::orbit::attractor::find`] gives.
    pub motions: Vec<Motion>,
    /// What the starts did.
    pub stats: SearchStats,
}

/// Every new stable periodic motion reached from `opts.starts` starts at
/// `sim`'s parameters, `known` being the stable motions already known (each
/// with the caller's id).
pub fn coexisting<M: Model>(
    sim: &Simulator<M>,
    known: &[(usize, Motion)],
    opts: &SearchOptions,
) -> Vec<Motion> {
    search(sim, known, opts).motions
}

/// [`coexisting`], with what the starts did.
pub fn search<M: Model>(
    sim: &Simulator<M>,
    known: &[(usize, Motion)],
    opts: &SearchOptions,
) -> Search {
    // Internal ids: the caller's motions first (by position), then the new ones.
    let given: Vec<(usize, Motion)> = known
        .iter()
        .enumerate()
        .map(|(i, (_, m))| (i, m.clone()))
        .collect();
    let mut neighbourhoods = KnownMotions::from_motions(sim, &given, 0.0);
    let mut stats = SearchStats::default();
    let mut found: Vec<Motion> = Vec::new();
    for (x, v) in starts(sim, &neighbourhoods, opts.starts, opts.margin) {
        stats.starts += 1;
        let Ok(start) = sim.start(x, v, 0.0) else {
            stats.failed += 1;
            continue;
        };
        let settling = settle(sim, &neighbourhoods, start, opts.attractor);
        stats.periods += u64::from(settling.periods);
        match settling.outcome {
            Ok(Settled::Known(id)) if id < given.len() => stats.stopped_known += 1,
            Ok(Settled::Known(_)) => stats.stopped_found += 1,
            Ok(Settled::Attractor(a)) => match *a {
                Attractor::Periodic(m) => {
                    if !m.stability.is_some_and(|s| s.is_stable()) || !m.is_admissible() {
                        stats.other += 1;
                    } else if given
                        .iter()
                        .map(|(_, g)| g)
                        .chain(&found)
                        .any(|g| same_motion(g, &m, 1e-6))
                    {
                        stats.matched += 1;
                    } else {
                        stats.new += 1;
                        neighbourhoods.insert(sim, given.len() + found.len(), &m);
                        found.push(m);
                    }
                }
                _ => stats.other += 1,
            },
            Err(_) => stats.failed += 1,
        }
    }
    Search {
        motions: found,
        stats,
    }
}

/// Whether `a` and `b` are one motion: the same structure up to rotation,
/// with the same switching points to `tol` (`x` relative to the motion's
/// length scale, phases modulo one forcing period, since a motion shifted by
/// whole forcing periods is the same motion). An autonomous cycle shifted
/// by any time is the same cycle: its phases are not compared.
pub fn same_motion(a: &Motion, b: &Motion, tol: f64) -> bool {
    let m = a.structure.len();
    let autonomous = a.structure.is_autonomous();
    if a.structure.periods() != b.structure.periods()
        || b.structure.len() != m
        || a.points.len() != m
        || b.points.len() != m
    {
        return false;
    }
    let scale = a
        .points
        .iter()
        .chain(&b.points)
        .fold(0.0_f64, |s, p| s.max(p.x.abs()))
        .max(f64::MIN_POSITIVE);
    let (sa, sb) = (a.structure.steps(), b.structure.steps());
    (0..m).any(|r| {
        (0..m).all(|k| {
            let (p, q) = (a.points[k], b.points[(k + r) % m]);
            let dphi = (p.phase - q.phase) / TAU;
            sa[k] == sb[(k + r) % m]
                && (p.x - q.x).abs() <= tol * scale
                && (autonomous || (dphi - dphi.round()).abs() * TAU <= tol)
        })
    })
}

/// The `i`-th element of van der Corput's sequence in base `b`.
fn radical_inverse(mut i: usize, b: usize) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= b as f64;
        r += f * (i % b) as f64;
        i /= b;
    }
    r
}

/// `count` starts `(x, v)` at phase 0: rest first, then the Halton sequence
/// (bases 2 and 3) over a box that covers the known motions' `x` and `v`
/// extents, rest, and every boundary's velocity, widened by `margin` times
/// its size on each side. With no motion known the `x` extent is the forced
/// response's scale, `±(|A0| / max(c, W²) + max |V_b| / W)`.
pub fn starts<M: Model>(
    sim: &Simulator<M>,
    known: &KnownMotions,
    count: usize,
    margin: f64,
) -> Vec<(f64, f64)> {
    let osc = sim.oscillator();
    let w = osc.frequency;
    let vb = (0..sim.info().boundaries.len()).map(|k| sim.velocity(k));
    let (vlo, vhi) = vb.fold((0.0_f64, 0.0_f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let [mut x0, mut x1, mut v0, mut v1] = known.extent().unwrap_or_else(|| {
        let l = osc.amplitude.abs() / osc.stiffness.max(w * w) + vlo.abs().max(vhi.abs()) / w;
        [-l, l, 0.0, 0.0]
    });
    x0 = x0.min(0.0);
    x1 = x1.max(0.0);
    v0 = v0.min(vlo);
    v1 = v1.max(vhi);
    let (dx, dv) = (margin * (x1 - x0), margin * (v1 - v0));
    let (x0, x1, v0, v1) = (x0 - dx, x1 + dx, v0 - dv, v1 + dv);
    (0..count)
        .map(|i| {
            if i == 0 {
                (0.0, 0.0)
            } else {
                (
                    x0 + (x1 - x0) * radical_inverse(i, 2),
                    v0 + (v1 - v0) * radical_inverse(i, 3),
                )
            }
        })
        .collect()
}
