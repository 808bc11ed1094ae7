//! Lyapunov exponents of the stroboscopic (Poincaré) map along a simulated
//! trajectory, from the exact tangent map.
//!
//! The exponents are those of the stroboscopic map `P` (one forcing period),
//! from the exact tangent map of [`crate::dynamics::tangent`]: after a
//! transient, the tangent basis is carried over one forcing period and
//! re-orthonormalised (Gram–Schmidt on 2×2: `J Q = Q' R`); the exponents are
//! the averages of `ln R_ii` per unit time (and per forcing period). The
//! error is the standard error of the mean of the largest exponent over 10
//! blocks of the run (of the second too where it is finite).
//!
//! A stick collapses the velocity direction (the tangent map has rank one):
//! the second exponent is then `−∞` exactly (reported as `f64::NEG_INFINITY`).
//!
//! The verdict:
//! * **periodic** when the stroboscopic points repeat (to 1e-8 relative) with
//!   a period of at most [`MAX_REPEAT`] forcing periods over the last
//!   `2 N` (at least 8) points; the motion is then named and refined by
//!   [`crate::orbit::attractor::find`] and the exponents are the Floquet
//!   exponents `ln|μ_i| / (N T)` of the tangent map over one cycle at the
//!   refined motion (exact, not a time average);
//! * **stick**: a permanent stick ([`crate::orbit::attractor::permanent_stick`]);
//!   **NM**: no boundary contact, certified by the attractor search;
//! * **chaotic**: the largest exponent exceeds `3 × error + ln(10) / (n T)`
//!   (`n T` the accumulation time);
//! * **quasi-periodic**: the largest exponent is within that margin of zero
//!   and the points do not repeat;
//! * **cycle longer than [`MAX_REPEAT`]**: the largest exponent is negative
//!   beyond the margin and the points do not repeat within `MAX_REPEAT`
//!   periods (or the transient was too short for them to settle).

use nalgebra::Matrix2;

use crate::dynamics::simulate::{EventKind, Segment, SimError, Simulator};
use crate::dynamics::tangent::{advance, Tangent};
use crate::model::Model;
use crate::orbit::attractor::{find, permanent_stick, Attractor, AttractorOptions};
use crate::orbit::motion::{segment_at, Motion};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// Longest cycle, in forcing periods, recognised by the repeat of the
/// stroboscopic points.
pub const MAX_REPEAT: u32 = 32;

/// Relative tolerance of the repeat of the stroboscopic points.
const REPEAT_TOL: f64 = 1e-8;

/// Blocks over which the spread of the exponents is measured.
const BLOCKS: u32 = 10;

/// How long to run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LyapunovOptions {
    /// Forcing periods simulated (and discarded) before the exponents are
    /// accumulated.
    pub transient: u32,
    /// Forcing periods over which the exponents are accumulated.
    pub periods: u32,
}

impl Default for LyapunovOptions {
    fn default() -> Self {
        Self {
            transient: 1000,
            periods: 10_000,
        }
    }
}

/// What the trajectory settles on, judged from its exponents and its
/// stroboscopic points.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// A periodic motion: its structure (`P_{…}`) and forcing periods `N`.
    Periodic {
        /// The structure `P_{…}`.
        structure: String,
        /// Forcing periods of one cycle.
        n: u32,
    },
    /// The largest exponent is positive beyond its error bar.
    Chaotic,
    /// The largest exponent is zero within its error bar and the points do
    /// not repeat.
    QuasiPeriodic,
    /// No boundary contact (NM).
    NoMotion,
    /// A stick that never ends.
    Stick,
    /// The largest exponent is negative beyond its error bar, but the
    /// stroboscopic points do not repeat within `longer_than` forcing
    /// periods: a longer cycle (or a transient too long for the run).
    LongCycle {
        /// [`MAX_REPEAT`].
        longer_than: u32,
    },
}

impl Verdict {
    /// The verdict's name in JSON: `periodic`, `chaotic`, `quasi_periodic`,
    /// `NM`, `stick` or `long_cycle`.
    pub fn label(&self) -> &'static str {
        match self {
            Verdict::Periodic { .. } => "periodic",
            Verdict::Chaotic => "chaotic",
            Verdict::QuasiPeriodic => "quasi_periodic",
            Verdict::NoMotion => "NM",
            Verdict::Stick => "stick",
            Verdict::LongCycle { .. } => "long_cycle",
        }
    }
}

/// The Lyapunov spectrum of the stroboscopic map along one trajectory.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// The exponents per unit time, largest first (`-inf` where a stick
    /// collapses a direction).
    pub exponents: [f64; 2],
    /// The exponents per forcing period (`exponents × 2π/W`).
    pub per_period: [f64; 2],
    /// The convergence estimate of the exponents (per unit time).
    pub error: f64,
    /// What the trajectory settles on.
    pub verdict: Verdict,
    /// The attractor, when the verdict is periodic, NM or stick.
    pub attractor: Option<Attractor>,
    /// The state `(x, v, W t)` at the end of the run.
    pub end: (f64, f64, f64),
}

/// Why the spectrum could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LyapunovError {
    /// The simulation failed.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// No forcing period to accumulate over.
    #[error("the number of forcing periods to accumulate over must be at least 1 (got 0)")]
    NoPeriods,
}

/// The Lyapunov spectrum of the stroboscopic map from `start = (x, v, W t)`.
pub fn spectrum<M: Model>(
    sim: &Simulator<M>,
    start: (f64, f64, f64),
    opts: LyapunovOptions,
) -> Result<Spectrum, LyapunovError> {
    if opts.periods == 0 {
        return Err(LyapunovError::NoPeriods);
    }
    let w = sim.oscillator().frequency;
    let period = TAU / w;
    let (x0, v0, phi0) = start;
    let mut seg = sim.start(x0, v0, phi0)?;
    let strobe = |k: u64| phi0 + k as f64 * TAU;
    let mut k = 0u64;
    for _ in 0..opts.transient {
        k += 1;
        let mut t = Tangent::new(Matrix2::identity());
        seg = advance(sim, seg, strobe(k), &mut t, |_| {})?;
    }
    let n = opts.periods;
    let blocks = BLOCKS.min(n);
    let mut block_sums = [[0.0f64; 2]; BLOCKS as usize];
    let mut block_len = [0u32; BLOCKS as usize];
    let mut sums = [0.0f64; 2];
    let mut collapsed = false;
    let mut q = Matrix2::identity();
    let keep = 3 * MAX_REPEAT as usize;
    let mut points: Vec<(f64, f64)> = Vec::with_capacity(keep);
    let mut quiet = 0u32;
    for i in 0..n {
        k += 1;
        let mut t = Tangent::new(q);
        let mut events = 0u32;
        seg = advance(sim, seg, strobe(k), &mut t, |e| {
            if e.kind != EventKind::Graze {
                events += 1;
            }
        })?;
        quiet = if events == 0 { quiet + 1 } else { 0 };
        let (r, q_next) = gram_schmidt(&t.matrix);
        q = q_next;
        collapsed |= t.collapsed;
        let logs = [r[0].ln(), r[1].ln()];
        let b = (i as u64 * blocks as u64 / n as u64) as usize;
        block_len[b] += 1;
        for c in 0..2 {
            sums[c] += logs[c];
            block_sums[b][c] += logs[c];
        }
        if points.len() == keep {
            points.remove(0);
        }
        points.push((seg.x, seg.v));
    }
    let total = n as f64 * period;
    let mut exponents = [sums[0] / total, sums[1] / total];
    if collapsed {
        exponents[1] = f64::NEG_INFINITY;
    }
    let error = (0..2)
        .filter(|&c| exponents[c].is_finite())
        .map(|c| standard_error(&block_sums[..blocks as usize], &block_len, c, period))
        .fold(0.0f64, f64::max);
    let end = (seg.x, seg.v, seg.phase);
    let margin = 3.0 * error + 10f64.ln() / total;

    let mut found = None;
    if let Some(stick) = permanent_stick(sim, &seg) {
        found = Some(Attractor::Stick(stick));
    } else if repeat(&points).is_some() || quiet >= MAX_REPEAT {
        let options = AttractorOptions {
            max_periods: 4 * MAX_REPEAT + 200,
            ..AttractorOptions::default()
        };
        found = find(sim, seg, options).ok();
    }
    let (verdict, exponents) = match &found {
        Some(Attractor::Periodic(motion)) => {
            let floquet = floquet_exponents(sim, motion)?;
            let verdict = Verdict::Periodic {
                structure: motion.structure.notation(sim.info()),
                n: motion.structure.periods(),
            };
            (verdict, floquet.unwrap_or(exponents))
        }
        Some(Attractor::NoMotion(_)) => (Verdict::NoMotion, exponents),
        Some(Attractor::Stick(_)) => (Verdict::Stick, exponents),
        _ => {
            let verdict = if exponents[0] > margin {
                Verdict::Chaotic
            } else if exponents[0] >= -margin {
                Verdict::QuasiPeriodic
            } else {
                Verdict::LongCycle {
                    longer_than: MAX_REPEAT,
                }
            };
            (verdict, exponents)
        }
    };
    let attractor = match found {
        Some(a @ (Attractor::Periodic(_) | Attractor::NoMotion(_) | Attractor::Stick(_))) => {
            Some(a)
        }
        _ => None,
    };
    Ok(Spectrum {
        exponents,
        per_period: [exponents[0] * period, exponents[1] * period],
        error,
        verdict,
        attractor,
        end,
    })
}

/// Gram–Schmidt on the columns of `a`: `(|R_11|, |R_22|)` and the new
/// orthonormal basis. A zero second column (a stick) gives `R_22 = 0` and the
/// basis completed by the normal of the first.
fn gram_schmidt(a: &Matrix2<f64>) -> ([f64; 2], Matrix2<f64>) {
    let (a1, a2) = (a.column(0), a.column(1));
    let r11 = a1.norm();
    let q1 = if r11 > 0.0 {
        a1 / r11
    } else {
        nalgebra::Vector2::new(1.0, 0.0)
    };
    let u = a2 - q1 * q1.dot(&a2);
    let r22 = u.norm();
    // The second column is the normal of the first (same orientation as u
    // where u is not zero): exact orthonormality without a division by r22.
    let normal = nalgebra::Vector2::new(-q1[1], q1[0]);
    let q2 = if normal.dot(&u) < 0.0 {
        -normal
    } else {
        normal
    };
    ([r11, r22], Matrix2::new(q1[0], q2[0], q1[1], q2[1]))
}

/// The standard error of the mean of the block exponents (column `c`).
fn standard_error(sums: &[[f64; 2]], len: &[u32], c: usize, period: f64) -> f64 {
    let b = sums.len();
    if b < 2 {
        return f64::NAN;
    }
    let means: Vec<f64> = (0..b)
        .map(|i| sums[i][c] / (len[i] as f64 * period))
        .collect();
    let mean = means.iter().sum::<f64>() / b as f64;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (b - 1) as f64;
    (var / b as f64).sqrt()
}

/// The smallest `N <= MAX_REPEAT` with `p_i = p_{i-N}` (to [`REPEAT_TOL`]
/// relative) over the last `max(2N, 8)` points.
fn repeat(points: &[(f64, f64)]) -> Option<u32> {
    let scale = 1.0
        + points
            .iter()
            .map(|p| p.0.abs().max(p.1.abs()))
            .fold(0.0f64, f64::max);
    let len = points.len();
    (1..=MAX_REPEAT).find(|&n| {
        let n = n as usize;
        let span = (2 * n).max(8);
        len >= n + span
            && (len - span..len).all(|i| {
                let (a, b) = (points[i], points[i - n]);
                (a.0 - b.0).abs().max((a.1 - b.1).abs()) <= REPEAT_TOL * scale
            })
    })
}

/// The exponents `ln|μ_i| / (N T)` from the eigenvalues `μ_i` of the tangent
/// map over one cycle of `motion`, started halfway along its first mapping
/// (away from the switching points); `None` if the motion has no points.
fn floquet_exponents<M: Model>(
    sim: &Simulator<M>,
    motion: &Motion,
) -> Result<Option<[f64; 2]>, SimError> {
    let points = &motion.points;
    let Some(first) = points.first() else {
        return Ok(None);
    };
    let n = motion.structure.periods();
    let cycle = n as f64 * TAU;
    let next = points.get(1).map_or(first.phase + cycle, |p| p.phase);
    let mid = 0.5 * (first.phase + next);
    let seg0 = segment_at(sim, &motion.structure, points, 0);
    let (x, v) = sim.state_at(&seg0, mid);
    let seg = Segment {
        x,
        v,
        phase: mid,
        search_from: mid,
        ..seg0
    };
    let mut t = Tangent::new(Matrix2::identity());
    advance(sim, seg, mid + cycle, &mut t, |_| {})?;
    let time = cycle / sim.oscillator().frequency;
    let m = t.matrix;
    let (tr, det) = (m.trace(), m.determinant());
    let moduli = if t.collapsed {
        [tr.abs(), 0.0]
    } else {
        let disc = 0.25 * tr * tr - det;
        if disc >= 0.0 {
            let big = 0.5 * tr + disc.sqrt().copysign(tr);
            [big.abs(), if big == 0.0 { 0.0 } else { (det / big).abs() }]
        } else {
            let r = det.abs().sqrt();
            [r, r]
        }
    };
    let mut e = [moduli[0].ln() / time, moduli[1].ln() / time];
    if e[1] > e[0] {
        e.swap(0, 1);
    }
    Ok(Some(e))
}
