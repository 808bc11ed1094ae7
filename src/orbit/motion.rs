//! A periodic motion: a structure, its switching points solved by Newton,
//! checked for admissibility, with its stability.

use nalgebra::Matrix2;

use crate::dynamics::simulate::{Location, Segment, SimError, Simulator};
use crate::model::param::ParamError;
use crate::model::{MappingKind, Model};
use crate::orbit::admissible::{violations, Violation};
use crate::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint, Termination};
use crate::orbit::stability::Stability;
use crate::orbit::structure::{Structure, StructureError};

/// A solution of the mapping equations of a structure, with everything known about it.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// The structure (applied from its first mapping).
    pub structure: Structure,
    /// Point `k` is the start of the `k`-th mapping applied.
    pub points: Vec<SwitchingPoint>,
    /// How Newton ended.
    pub termination: Termination,
    /// `DP` in `(W t, x)` order, when it exists.
    pub dp: Option<Matrix2<f64>>,
    /// Eigenvalues and classification, when `DP` exists.
    pub stability: Option<Stability>,
    /// Violated admissibility conditions (empty for a real motion).
    pub violations: Vec<Violation>,
}

impl Motion {
    /// Converged and admissible: a real motion.
    pub fn is_admissible(&self) -> bool {
        self.termination.converged() && self.violations.is_empty()
    }

    /// The motion if it is real, else why not.
    pub fn into_result(self) -> Result<Motion, OrbitError> {
        if !self.termination.converged() {
            return Err(OrbitError::NotConverged(self.termination));
        }
        if !self.violations.is_empty() {
            return Err(OrbitError::Inadmissible(Box::new(self)));
        }
        Ok(self)
    }
}

/// The segment of simulation that starts at switching point `k` of
/// `points` (of `structure`): mapping `k`'s flow in its domain, or its stick,
/// from the point's displacement at the boundary's velocity.
pub fn segment_at<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    k: usize,
) -> Segment {
    let mi = sim.info().mappings[structure.steps()[k]];
    let location = match (mi.kind, mi.domain) {
        (MappingKind::Stick, _) | (_, None) => Location::Stick,
        (_, Some(j)) => Location::Domain(j),
    };
    let a = points[k];
    Segment {
        x: a.x,
        v: sim.velocity(mi.from),
        phase: a.phase,
        location,
        search_from: a.phase,
    }
}

/// Why no periodic motion was found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OrbitError {
    /// Invalid parameters.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// Invalid structure.
    #[error(transparent)]
    Structure(#[from] StructureError),
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] SimError),
    /// A guess with the wrong number of points, or not finite.
    #[error("bad initial guess: {0}")]
    Guess(String),
    /// Newton did not converge (or hit a singular Jacobian).
    #[error("Newton did not converge: {0:?}")]
    NotConverged(Termination),
    /// Newton converged to a solution that is not a motion.
    #[error("the solution is not a motion: {}", describe_violations(&.0.violations))]
    Inadmissible(Box<Motion>),
    /// The simulation did not settle to a periodic motion or a certified NM.
    #[error(
        "no periodic motion and no certified NM within {periods} forcing periods{}{}",
        if *undamped {
            " (undamped: every domain has zero viscous damping, so transients need not decay; \
             the motion may drift for ever, quasi-periodically or slowly towards a neutral family)"
        } else {
            ""
        },
        instead.as_deref().map_or(String::new(), |i| format!("; {i}"))
    )]
    Unsettled {
        /// Forcing periods simulated.
        periods: u32,
        /// No domain has viscous damping (`2 d_j = 0` everywhere).
        undamped: bool,
        /// What the motion does instead, where it was diagnosed (the
        /// Lyapunov exponents from the same start: chaotic,
        /// quasi-periodic, a longer cycle), and what to run next.
        instead: Option<String>,
    },
    /// The simulation settled on a cycle through more mappings than the
    /// search looks for ([`crate::orbit::attractor::AttractorOptions::max_cycle`]).
    #[error("the cycle is longer than {cap} mappings")]
    CycleTooLong {
        /// The cap, in mappings.
        cap: usize,
        /// Mappings in the cycle seen (events of `periods` forcing periods).
        mappings: usize,
        /// Forcing periods of the cycle seen.
        periods: u32,
    },
    /// No simulation went through the structure, so there is no guess.
    #[error("no simulated motion follows {0}; give a guess")]
    NoSeed(String),
}

fn describe_violations(v: &[Violation]) -> String {
    v.iter()
        .map(|v| {
            format!(
                "segment {}: {} (margin {:.3e})",
                v.segment, v.condition, v.margin
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// Solve `structure` from `guess` and check the result (never fails: the
/// outcome says what happened).
pub fn solve<M: Model>(
    sim: &Simulator<M>,
    structure: Structure,
    points: Vec<SwitchingPoint>,
    opts: NewtonOptions,
) -> Motion {
    solve_with(sim, structure, points, opts, true)
}

/// Like [`solve`]; with `check = false` the admissibility conditions are not
/// evaluated (`violations` stays empty: the caller checks them itself).
pub fn solve_with<M: Model>(
    sim: &Simulator<M>,
    structure: Structure,
    mut points: Vec<SwitchingPoint>,
    opts: NewtonOptions,
    check: bool,
) -> Motion {
    let mut solver = PeriodicSolver::<M>::new(structure);
    let guess = points.clone();
    let mut termination = solver.solve(sim.params(), &mut points, opts);
    // Newton's last evaluations are at its solution: `DP` from them, while
    // the points stay where Newton left them.
    let mut evaluated = termination.converged();
    if !termination.converged() {
        // A neutral family: `I − DP` singular, Newton's step singular or
        // useless, yet solutions nearby. Kept only if `DP` has the eigenvalue 1.
        let mut family = guess;
        if let Some((iterations, residual)) =
            crate::orbit::family::solve_min_norm(&solver, sim.params(), &mut family, opts)
        {
            let neutral = solver
                .poincare_jacobian(sim.params(), &family)
                .is_ok_and(|dp| Stability::of(&dp).has_unit_eigenvalue());
            if neutral {
                points = family;
                termination = Termination::Converged {
                    iterations,
                    residual,
                };
            }
        }
    }
    // Phase origin: 0 <= W t_0 < 2π (an autonomous cycle keeps its return at 0).
    let shift = if solver.structure().is_autonomous() {
        0.0
    } else {
        (points[0].phase / (2.0 * std::f64::consts::PI)).floor() * 2.0 * std::f64::consts::PI
    };
    if shift.is_finite() && shift != 0.0 {
        for pt in &mut points {
            pt.phase -= shift;
        }
        evaluated = false;
    }
    let (dp, stability, violations) = if termination.converged() {
        let dp = if evaluated {
            solver.poincare_jacobian_at_solution(sim.params())
        } else {
            solver.poincare_jacobian(sim.params(), &points)
        }
        .ok();
        let st = dp.as_ref().map(Stability::of);
        let v = if check {
            violations(sim, solver.structure(), &points)
        } else {
            Vec::new()
        };
        (dp, st, v)
    } else {
        (None, None, Vec::new())
    };
    Motion {
        structure: solver.structure().clone(),
        points,
        termination,
        dp,
        stability,
        violations,
    }
}
