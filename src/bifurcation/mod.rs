//! Bifurcation analysis along one parameter: branches of periodic motions
//! followed by pseudo-arclength continuation through folds, their unstable
//! parts kept, the eigenvalue bifurcations (fold, branch point, period
//! doubling, Neimark–Sacker) located by test functions on the eigenvalues of
//! `DP`, the branches born there, and the non-smooth transitions (SPEC §3)
//! that end a branch.
//!
//! ```
//! use stickslip::bifurcation::{follow, ContinuationOptions, EndReason, Start, TransitionKind};
//! use stickslip::dynamics::simulate::{SimOptions, Simulator};
//! use stickslip::models::paper::{Paper, Params};
//! use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
//! use stickslip::ParamSet;
//!
//! // The stick-slip motion at W = 3.7, Q0 = 70, followed along W in [3.6, 3.9].
//! let p = Params { W: 3.7, Q0: 70.0, ..Params::default() };
//! let sim = Simulator::<Paper>::new(p, SimOptions::default())?;
//! let Attractor::Periodic(m) = attractor::find(&sim, sim.start(0.0, 0.0, 0.0)?, AttractorOptions::default())?
//! else {
//!     panic!("a periodic motion")
//! };
//! let w = Params::index_of("W").expect("a parameter");
//! let start = Start { structure: m.structure.clone(), value: 3.7, points: m.points.clone(), direction: None };
//! let opts = ContinuationOptions { bounds: (3.6, 3.9), ..ContinuationOptions::default() };
//! let branch = follow::<Paper>(&p, w, &start, &opts)?;
//! // Upwards it ends where its stick onset turns passable, located to 1e-12.
//! let end = branch.ends.iter().find(|e| e.at.value > 3.7).expect("an upper end");
//! assert!(matches!(end.reason, EndReason::Transition { kind: TransitionKind::PassableOnset, .. }));
//! assert!((end.at.value - 3.7550059120).abs() < 1e-8);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use serde::Serialize;

pub mod bordered;
pub mod branch;
pub mod continuation;
pub mod curve;
mod detect;
mod locate;
pub mod switching;

pub use branch::{Bifurcation, Branch, BranchEnd, BranchPoint, EndReason};
pub use continuation::{
    follow, transition_kind, ContinuationError, ContinuationOptions, Direction, Start,
};
pub use switching::born;

/// What happens to a motion at a point of a branch: a non-smooth transition
/// (an admissibility condition of SPEC §6 starts to fail) or an eigenvalue
/// bifurcation (an eigenvalue of `DP` reaches the unit circle).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TransitionKind {
    /// An arc touches a boundary tangentially (GB in the paper).
    Grazing,
    /// A passing flow starts to stick.
    StickOnset,
    /// A stick shrinks to nothing or ends early.
    StickVanishing,
    /// A sticking arrival starts to pass through the stick boundary.
    PassableOnset,
    /// Eigenvalue +1 at a turning point of the branch (saddle-node).
    Fold,
    /// Eigenvalue +1 where the branch goes on and another crosses it
    /// (symmetry-breaking pitchfork).
    BranchPoint,
    /// Eigenvalue −1: a motion of twice the period is born.
    PeriodDoubling,
    /// A complex pair of eigenvalues on the unit circle: a torus is born.
    NeimarkSacker,
    /// Steady sliding of an unforced oscillator changes stability: a pair
    /// of eigenvalues of the equilibrium crosses the imaginary axis (a Hopf
    /// point of a smooth law), or the equilibrium crosses a breakpoint of a
    /// piecewise law where the law's slope jumps.
    SteadySliding,
}

impl TransitionKind {
    /// The name used in JSON and in the text report (`stick_onset`, ...).
    pub fn name(self) -> &'static str {
        match self {
            TransitionKind::Grazing => "grazing",
            TransitionKind::StickOnset => "stick_onset",
            TransitionKind::StickVanishing => "stick_vanishing",
            TransitionKind::PassableOnset => "passable_onset",
            TransitionKind::Fold => "fold",
            TransitionKind::BranchPoint => "branch_point",
            TransitionKind::PeriodDoubling => "period_doubling",
            TransitionKind::NeimarkSacker => "neimark_sacker",
            TransitionKind::SteadySliding => "steady_sliding_stability",
        }
    }

    /// Whether this is an eigenvalue bifurcation (not a non-smooth transition).
    pub fn is_eigenvalue(self) -> bool {
        matches!(
            self,
            TransitionKind::Fold
                | TransitionKind::BranchPoint
                | TransitionKind::PeriodDoubling
                | TransitionKind::NeimarkSacker
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_the_json_names() {
        for k in [
            TransitionKind::Grazing,
            TransitionKind::StickOnset,
            TransitionKind::StickVanishing,
            TransitionKind::PassableOnset,
            TransitionKind::Fold,
            TransitionKind::BranchPoint,
            TransitionKind::PeriodDoubling,
            TransitionKind::NeimarkSacker,
        ] {
            assert_eq!(serde_json::to_value(k).unwrap(), k.name());
        }
    }
}
