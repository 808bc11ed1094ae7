//! Two-parameter continuation of a transition: the curve in a parameter
//! plane along which one condition of a motion vanishes (SPEC §6, §7).
//!
//! The unknowns are the motion's switching points and both parameters; the
//! equations are the mapping equations, the condition (an admissibility
//! margin, an eigenvalue test function, or the grazing of the no-motion
//! regime's steady response), and the pseudo-arclength row. A curve is
//! followed both ways to the box's edge, back to itself, or to a
//! codimension-two point where a second condition vanishes too.
//!
//! * [`extended`]: the `(2m + 2)`-square system (mapping equations,
//!   condition, border row) by a dense LU on a preallocated workspace; the
//!   mapping blocks exact, `∂F/∂λ` and `∇g` central differences. A corrector
//!   step and a tangent allocate nothing.
//! * `condition`: each [`Condition`] as a function of `(u, λ)`. A margin is
//!   computed by the admissibility walk with no event search (the closed
//!   form's interior margin, smooth in the points; see
//!   `orbit::admissible::margin_of`); `det(I ∓ DP)`, `det DP − 1` from the
//!   generated blocks; the rest regime's margin from
//!   [`crate::orbit::steady::steady_response`].
//! * `trace`: predictor–corrector with the step control of
//!   [`crate::bifurcation::continuation`]; ends on the box's edge (solved
//!   with that parameter fixed), back at the start (a closed curve: no
//!   ends), where another condition's margin vanishes (codimension two:
//!   for a margin curve every other admissibility condition but those that
//!   vanish with its own at the start; for an eigenvalue curve every
//!   condition, and a Neimark–Sacker pair turning real, named `Fold` for a
//!   1:1 and `PeriodDoubling` for a 1:2 resonance; a stick's end watched
//!   by its smooth margin; where the curve's system turns singular at the
//!   point, solved there with both conditions), at the corrector's
//!   failure at the smallest step, or at the point limit. Along a margin
//!   curve the sign changes of `det(I − DP)` and `det(I + DP)` are located
//!   as [`Special`] points (a fold or period-doubling curve met).
//! * `excursion`: the end of a curve whose motion loses an excursion (a
//!   segment from a boundary back to it, shrinking to nothing), solved on
//!   the reduced motion, where the merged segment touches the boundary;
//!   and [`reduced_start`], a transition located where an excursion
//!   shrinks to nothing carried to the reduced motion's curve.
//! * `partner`: branch switching at a codimension-two point
//!   ([`partner_start`]): the start of the second condition's curve
//!   through it, a step along that curve's tangent to the side where the
//!   curve's own margin holds.
//! * [`crossings`]: each crossing of a line solved with the line's
//!   parameter fixed.
//! * [`condition_at_transition`]: the condition to trace from a transition
//!   a one-parameter continuation located.

mod condition;
mod crossing;
mod excursion;
pub mod extended;
mod halves;
mod partner;
mod start;
mod stop;
mod trace;

pub use condition::{condition_scale, COMPANION_SLACK};
pub use crossing::crossings;
pub use excursion::{reduced_start, ReducedStart};
pub use extended::Extended;
pub use partner::{
    codim2_places, inadmissible_point, partner_start, Codim2Place, PartnerStart, ADMISSIBLE_TO,
    PARTNER_STEP,
};
pub use start::{
    codim2_residual, condition_at_transition, condition_value, system, trace, trace_watching,
    unknowns,
};

use crate::bifurcation::TransitionKind;
use crate::orbit::admissible::{ConditionId, ViolationKind};
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::structure::Structure;

/// What vanishes along a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Condition {
    /// An admissibility condition's margin (SPEC §6): grazing, stick onset,
    /// stick vanishing, passable onset. Identified as in
    /// [`crate::orbit::admissible::Margin`].
    Margin {
        /// Which condition.
        kind: ViolationKind,
        /// Index of the mapping (in application order).
        segment: usize,
        /// The boundary involved, if any.
        boundary: Option<usize>,
    },
    /// An eigenvalue bifurcation's test function: `Fold` (det(I − DP)),
    /// `PeriodDoubling` (det(I + DP)), `NeimarkSacker` (det DP − 1 with a
    /// complex pair).
    Eigen(TransitionKind),
    /// The no-motion regime's steady response grazes boundary `boundary`
    /// (no switching points: the curve's structure is `None`).
    RestGrazing {
        /// The boundary grazed.
        boundary: usize,
    },
    /// The normal field `F_j` (Eq. 10) at one end of a flow segment, into
    /// its domain at the departure and out of it at the arrival, or its
    /// rate `DF_j` along the flow (Eqs. 21–23), with the same sign. Both
    /// vanish where an interior grazing of the segment merges into that end
    /// as it turns tangential (near it `F ∝ DF²` along the grazing curve):
    /// a codimension-two point the grazing curve runs into, solved with the
    /// two as its conditions (the grazing margin is not smooth there). No
    /// curve is traced on it: where `F` alone vanishes the end's own margin
    /// (`Margin` of kind `Departure` or `Arrival`) is the condition.
    NormalField {
        /// Index of the flow mapping (in application order).
        segment: usize,
        /// At its arrival (else its departure).
        arrival: bool,
        /// The rate `DF_j` (else `F_j`).
        rate: bool,
    },
}

impl Condition {
    /// The admissibility condition a `Margin` names (as the walk of
    /// [`crate::orbit::admissible`] identifies it); `None` for any other.
    pub fn margin_id(self) -> Option<ConditionId> {
        match self {
            Condition::Margin {
                kind,
                segment,
                boundary,
            } => Some((kind, segment, boundary)),
            _ => None,
        }
    }
}

/// The parameter plane: which two parameters are free, and the box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Index of the horizontal parameter (`ParamSet` order).
    pub x: usize,
    /// Index of the vertical parameter.
    pub y: usize,
    /// `[lo, hi]` of the horizontal parameter.
    pub x_range: [f64; 2],
    /// `[lo, hi]` of the vertical parameter.
    pub y_range: [f64; 2],
}

/// A point of a curve: both parameters and the motion's switching points
/// there (empty for [`Condition::RestGrazing`]).
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePoint {
    /// The horizontal parameter.
    pub x: f64,
    /// The vertical parameter.
    pub y: f64,
    /// The switching points of the motion at `(x, y)`.
    pub points: Vec<SwitchingPoint>,
}

/// Why a curve ends.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveEndReason {
    /// It leaves the box.
    BoxEdge,
    /// A second condition vanishes: a codimension-two point. `kind` is the
    /// transition that second condition marks.
    Codim2 {
        /// The second condition's transition.
        kind: TransitionKind,
        /// Its boundary, if any.
        boundary: Option<usize>,
    },
    /// The corrector failed at the smallest step (Newton's reason).
    NewtonFailure(String),
    /// The point limit.
    MaxPoints,
}

/// One end of a curve.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveEnd {
    /// Why it ends.
    pub reason: CurveEndReason,
    /// Where (located to the options' tolerance).
    pub at: CurvePoint,
}

/// A codimension-two point inside a curve, where the curve goes on: for
/// example a fold curve meeting this grazing curve (the motion's stability
/// changes along it).
#[derive(Clone, Debug, PartialEq)]
pub struct Special {
    /// It lies between `points[index]` and `points[index + 1]`.
    pub index: usize,
    /// The transition met.
    pub kind: TransitionKind,
    /// Where.
    pub at: CurvePoint,
}

/// A traced curve.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The transition it marks.
    pub kind: TransitionKind,
    /// The condition that vanishes along it.
    pub condition: Condition,
    /// The boundary involved, if any.
    pub boundary: Option<usize>,
    /// The motion's structure (`None` for the no-motion regime).
    pub structure: Option<Structure>,
    /// Its points in arclength order.
    pub points: Vec<CurvePoint>,
    /// Its two ends (first end at `points[0]`, second at the last point);
    /// empty when the curve closes on itself.
    pub ends: Vec<CurveEnd>,
    /// Codimension-two points inside the curve.
    pub special: Vec<Special>,
}

impl Curve {
    /// Whether `at` (one of this curve's points) is where an excursion of
    /// its motion shrank to nothing: two consecutive switching points equal
    /// (the last and the first one cycle on), as the `excursion` pass reports
    /// an end it solved on the reduced motion.
    pub fn shrunk_excursion(&self, at: &CurvePoint) -> bool {
        let shift =
            std::f64::consts::TAU * self.structure.as_ref().map_or(1, |s| s.periods()) as f64;
        let p = &at.points;
        let n = p.len();
        n >= 2
            && (0..n).any(|i| {
                let (a, b, wrap) = if i + 1 < n {
                    (&p[i], &p[i + 1], 0.0)
                } else {
                    (&p[0], &p[n - 1], shift)
                };
                // Across the cycle's wrap the phase is `φ - shift`: equal to
                // a few ulps of `φ`.
                a.x == b.x
                    && (a.phase + wrap - b.phase).abs()
                        <= 4.0 * f64::EPSILON * b.phase.abs().max(1.0)
            })
    }
}

/// Settings of a curve's continuation. Steps are arclengths in the scaled
/// metric of [`crate::bifurcation::ContinuationOptions`], each parameter
/// over its range's span.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveOptions {
    /// The first step.
    pub initial_step: f64,
    /// Below this step the corrector's failure ends the curve.
    pub min_step: f64,
    /// The largest step.
    pub max_step: f64,
    /// At most this many points per direction.
    pub max_points: usize,
    /// Every point satisfies the mapping equations and the condition to this.
    pub tolerance: f64,
    /// Codimension-two points and crossings are located to this in the parameters.
    pub location_tolerance: f64,
}

impl Default for CurveOptions {
    fn default() -> Self {
        Self {
            initial_step: 1e-2,
            min_step: 1e-9,
            max_step: 0.05,
            max_points: 20_000,
            tolerance: 1e-12,
            location_tolerance: 1e-10,
        }
    }
}

/// A line of the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Line {
    /// The vertical line `x = value`.
    X(f64),
    /// The horizontal line `y = value`.
    Y(f64),
}

/// Why a curve could not be traced.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// Bad plane or options.
    #[error("bad curve options: {0}")]
    Options(String),
    /// The start does not lie on the condition's curve (Newton's reason).
    #[error("the start is not on the curve: {0}")]
    Start(String),
    /// The condition cannot be evaluated there.
    #[error("the condition cannot be evaluated: {0}")]
    Condition(String),
    /// The motion is an autonomous cycle, whose period is an unknown.
    #[error("an autonomous cycle (no forcing): its period is an unknown, which the curves' extended systems do not carry; `stickslip map` shows the regimes over the two parameters, and `stickslip sweep` locates this transition along one")]
    Autonomous,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::paper::Paper;

    fn at(points: &[(f64, f64)]) -> CurvePoint {
        CurvePoint {
            x: 1.0,
            y: 1.0,
            points: points
                .iter()
                .map(|&(x, phase)| SwitchingPoint { x, phase })
                .collect(),
        }
    }

    /// Two equal consecutive switching points, or the last equal to the
    /// first one cycle on (two forcing periods: `4π`), mark a shrunk
    /// excursion; distinct points, however near, do not.
    #[test]
    fn a_shrunk_excursion_is_two_equal_switching_points_even_across_the_wrap() {
        let s = Structure::parse(Paper::INFO, "P_{3_33 4_33 3_33 4_33}", 2).unwrap();
        let curve = Curve {
            kind: TransitionKind::Grazing,
            condition: Condition::Eigen(TransitionKind::Fold),
            boundary: None,
            structure: Some(s),
            points: Vec::new(),
            ends: Vec::new(),
            special: Vec::new(),
        };
        let tau2 = 2.0 * std::f64::consts::TAU;
        let phi = 0.3 + tau2 - 1e-3;
        assert!(curve.shrunk_excursion(&at(&[(0.1, 0.3), (0.2, 1.0), (0.2, 1.0), (0.4, 5.0)])));
        assert!(curve.shrunk_excursion(&at(&[
            (0.5, phi - tau2),
            (0.2, 1.0),
            (0.3, 5.0),
            (0.5, phi)
        ])));
        assert!(!curve.shrunk_excursion(&at(&[
            (0.1, 0.3),
            (0.2, 1.0),
            (0.2, 1.0 + 1e-12),
            (0.4, 5.0)
        ])));
        assert!(!curve.shrunk_excursion(&at(&[
            (0.5, 0.3),
            (0.2, 1.0),
            (0.3, 5.0),
            (0.5, 0.3 + tau2 - 1e-9)
        ])));
        assert!(!curve.shrunk_excursion(&at(&[(0.1, 0.3)])));
    }
}
