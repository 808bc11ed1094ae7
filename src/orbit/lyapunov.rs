//! Lyapunov exponents of the stroboscopic (Poincaré) map along a simulated
//! trajectory, from the exact tangent map (issue 13).
//!
//! INTERFACE STUB: the types and the signature are fixed so that the
//! orbit diagram and the basins can be built against them; the body is
//! being written (see `dynamics::tangent`).

use crate::dynamics::simulate::{SimError, Simulator};
use crate::model::Model;
use crate::orbit::attractor::Attractor;

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
}

/// The Lyapunov spectrum of the stroboscopic map from `start = (x, v, W t)`.
pub fn spectrum<M: Model>(
    sim: &Simulator<M>,
    start: (f64, f64, f64),
    opts: LyapunovOptions,
) -> Result<Spectrum, LyapunovError> {
    let _ = (sim, start, opts);
    unimplemented!("issue 13: being written")
}
