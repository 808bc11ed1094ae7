//! Autonomous cycles by Newton: the periodic motion of an unforced model
//! (`A0 = 0`, SPEC §14) on a mapping structure, with its period an unknown.
//!
//! The unknowns are the switching points `(x_k, W t_k)` of the cycle's `m`
//! mappings and the cycle's phase length `S = W T`; the residuals are the
//! generated mappings' (two per mapping), the last one arriving at the first
//! point `S` later. Time has no origin, so the phase condition fixes the
//! first point's phase: `W t_0` is not an unknown, and the system stays
//! square (`2m` unknowns: `m` displacements, `m − 1` phases, `S`). Its
//! Jacobian is the generated one, the last mapping's arrival-phase column
//! doubling as `∂/∂S`. A natural first point is a stick's release or onset,
//! whose velocity the boundary fixes.

use nalgebra::{DMatrix, DVector};

use crate::model::Model;
use crate::orbit::periodic::{NewtonOptions, SwitchingPoint};

/// A solved autonomous cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// The switching points; the first keeps the guess's phase.
    pub points: Vec<SwitchingPoint>,
    /// The cycle's phase length `W T`.
    pub shift: f64,
    /// Newton iterations taken.
    pub iterations: usize,
    /// The largest residual component at the last evaluation (before the
    /// final step, which was below the tolerance).
    pub residual: f64,
}

impl Cycle {
    /// The period `T = S / W`.
    pub fn period(&self, frequency: f64) -> f64 {
        self.shift / frequency
    }
}

/// Why Newton did not find the cycle.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AutonomousError {
    /// The forcing is on.
    #[error("the forcing is on (A0 = {0}): a cycle with its period unknown is a motion of the unforced oscillator only; set the forcing amplitude to 0")]
    Forced(f64),
    /// The guess does not fit the structure.
    #[error("the guess has {got} points for a structure of {want} mappings, or is not finite")]
    Guess {
        /// Points given.
        got: usize,
        /// Mappings in the structure.
        want: usize,
    },
    /// The Jacobian is singular (a grazing, or a degenerate guess).
    #[error("the Newton matrix is singular at iteration {0}: the cycle grazes a boundary, or the guess is degenerate")]
    Singular(usize),
    /// No convergence within the iteration limit.
    #[error("Newton did not converge in {iterations} iterations (residual {residual:.3e})")]
    NotConverged {
        /// Iterations taken.
        iterations: usize,
        /// The largest residual component.
        residual: f64,
    },
}

/// Solve the autonomous cycle of the mappings `steps` (applied in order)
/// from the guess `points` (one per mapping, its start) and phase length
/// `shift`. The first point's phase is held (the phase condition).
pub fn solve<M: Model>(
    p: &M::Params,
    steps: &[usize],
    points: &[SwitchingPoint],
    shift: f64,
    opts: NewtonOptions,
) -> Result<Cycle, AutonomousError> {
    let osc = M::oscillator(p);
    if osc.amplitude != 0.0 {
        return Err(AutonomousError::Forced(osc.amplitude));
    }
    let m = steps.len();
    let finite = points
        .iter()
        .all(|q| q.x.is_finite() && q.phase.is_finite())
        && shift.is_finite();
    if m == 0 || points.len() != m || !finite {
        return Err(AutonomousError::Guess {
            got: points.len(),
            want: m,
        });
    }
    // Length scale of the displacements, for a scale-free step criterion.
    let scale = points.iter().map(|q| q.x.abs()).fold(0.0, f64::max).max(
        (0..M::info(p).boundaries.len())
            .map(|b| M::boundary_velocity(p, b).abs() / osc.frequency)
            .fold(0.0, f64::max),
    );
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let mut pts = points.to_vec();
    let mut s = shift;
    let n = 2 * m;
    let mut jac = DMatrix::<f64>::zeros(n, n);
    let mut res = DVector::<f64>::zeros(n);
    // Unknown columns: x_k at 2k; W t_k at 2k − 1 (k ≥ 1); S at the last.
    let x_col = |k: usize| 2 * k;
    let phase_col = |k: usize| if k == 0 { None } else { Some(2 * k - 1) };
    let s_col = n - 1;
    let mut residual = f64::INFINITY;
    for iteration in 0..=opts.max_iterations {
        jac.fill(0.0);
        for k in 0..m {
            let a = pts[k];
            let (next, b) = if k + 1 < m {
                (k + 1, pts[k + 1])
            } else {
                (
                    0,
                    SwitchingPoint {
                        phase: pts[0].phase + s,
                        x: pts[0].x,
                    },
                )
            };
            let e = M::mapping(p, steps[k], a.x, a.phase, b.x, b.phase);
            for r in 0..2 {
                res[2 * k + r] = e.residual[r];
                jac[(2 * k + r, x_col(k))] += e.d_prev[(r, 0)];
                if let Some(c) = phase_col(k) {
                    jac[(2 * k + r, c)] += e.d_prev[(r, 1)];
                }
                jac[(2 * k + r, x_col(next))] += e.d_next[(r, 0)];
                if k + 1 < m {
                    if let Some(c) = phase_col(next) {
                        jac[(2 * k + r, c)] += e.d_next[(r, 1)];
                    }
                } else {
                    jac[(2 * k + r, s_col)] += e.d_next[(r, 1)];
                }
            }
        }
        residual = res.amax();
        if !residual.is_finite() {
            return Err(AutonomousError::Singular(iteration));
        }
        if iteration == opts.max_iterations {
            break;
        }
        let step = jac
            .clone()
            .lu()
            .solve(&(-&res))
            .filter(|d| d.iter().all(|v| v.is_finite()))
            .ok_or(AutonomousError::Singular(iteration))?;
        for k in 0..m {
            pts[k].x += step[x_col(k)];
            if let Some(c) = phase_col(k) {
                pts[k].phase += step[c];
            }
        }
        s += step[s_col];
        let size = (0..m)
            .map(|k| {
                let dx = (step[x_col(k)] / scale).abs();
                dx.max(phase_col(k).map_or(0.0, |c| step[c].abs()))
            })
            .fold(step[s_col].abs(), f64::max);
        if size <= opts.tolerance {
            return Ok(Cycle {
                points: pts,
                shift: s,
                iterations: iteration + 1,
                residual,
            });
        }
    }
    Err(AutonomousError::NotConverged {
        iterations: opts.max_iterations,
        residual,
    })
}
