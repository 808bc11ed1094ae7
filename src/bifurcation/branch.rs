//! What continuation produces: a branch of periodic motions of one
//! structure, its points in arclength order, how it ends at each side, and
//! the eigenvalue bifurcations located on it.

use nalgebra::Matrix2;

use crate::bifurcation::TransitionKind;
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::stability::Stability;
use crate::orbit::structure::Structure;

/// One point of a branch: a solution of the structure's mapping equations at
/// one parameter value, admissible (every margin of SPEC §6 positive, or
/// zero at a located end).
#[derive(Clone, Debug, PartialEq)]
pub struct BranchPoint {
    /// The parameter value.
    pub value: f64,
    /// The switching points (phases continuous along the branch, not reduced mod 2π).
    pub points: Vec<SwitchingPoint>,
    /// `DP` ordered `(W t, x)`, as [`crate::orbit::motion::Motion::dp`].
    pub dp: Matrix2<f64>,
    /// Eigenvalues of `DP` and the classification.
    pub stability: Stability,
}

/// Why a branch ends.
#[derive(Clone, Debug, PartialEq)]
pub enum EndReason {
    /// The parameter reached a bound of [`super::continuation::ContinuationOptions::bounds`];
    /// the end point lies on the bound.
    ParameterBound,
    /// An admissibility condition starts to fail there (a non-smooth
    /// transition, SPEC §3); `boundary` is the boundary involved (index).
    Transition {
        /// Grazing, stick onset, stick vanishing or passable onset.
        kind: TransitionKind,
        /// The boundary involved, if any.
        boundary: Option<usize>,
    },
    /// The branch returned to its start: it is a closed curve.
    ClosedLoop,
    /// The corrector failed even at the smallest step; why.
    NewtonFailure(String),
    /// [`super::continuation::ContinuationOptions::max_points`] points were computed.
    MaxPoints,
}

impl EndReason {
    /// The name used in JSON and in the text report.
    pub fn name(&self) -> &'static str {
        match self {
            EndReason::ParameterBound => "parameter_bound",
            EndReason::Transition { kind, .. } => kind.name(),
            EndReason::ClosedLoop => "closed_loop",
            EndReason::NewtonFailure(_) => "newton_failure",
            EndReason::MaxPoints => "max_points",
        }
    }
}

/// One end of a branch.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchEnd {
    /// Why it ends.
    pub reason: EndReason,
    /// The last good point (also a point of the branch, at its end).
    pub at: BranchPoint,
}

/// An eigenvalue bifurcation located on a branch.
#[derive(Clone, Debug, PartialEq)]
pub struct Bifurcation {
    /// Fold, branch point, period doubling or Neimark–Sacker.
    pub kind: TransitionKind,
    /// The located point (it is `Branch::points[index]`).
    pub at: BranchPoint,
    /// The critical eigenvalue `[re, im]`, `im >= 0`.
    pub eigenvalue: [f64; 2],
    /// Position of `at` in [`Branch::points`].
    pub index: usize,
}

/// A branch of periodic motions of one structure.
#[derive(Clone, Debug, PartialEq)]
pub struct Branch {
    /// The structure.
    pub structure: Structure,
    /// Its points in arclength order; unstable ones kept.
    pub points: Vec<BranchPoint>,
    /// For a branch followed both ways, `ends[0]` is at `points[0]` and
    /// `ends[1]` at `points.last()`; a branch followed one way (born at a
    /// bifurcation) has one end, at `points.last()`; a closed loop has one
    /// end with [`EndReason::ClosedLoop`].
    pub ends: Vec<BranchEnd>,
    /// The eigenvalue bifurcations on it, in the order of `points`.
    pub bifurcations: Vec<Bifurcation>,
}
