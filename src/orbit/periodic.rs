//! Periodic motions of a given mapping structure by Newton's method (SPEC §6).
//!
//! The unknowns are the switching points `(x_k, W t_k)`, `k = 0..m`, with
//! periodicity `x_m = x_0`, `W t_m = W t_0 + 2πN` substituted, so that the
//! 2m+2 equations of SPEC §6 become 2m equations in 2m unknowns. Their
//! Jacobian is block-cyclic-bidiagonal — block row `k` holds `∂f_k/∂u_k` and
//! `∂f_k/∂u_{k+1}` — and a Newton step solves it by eliminating along the
//! cycle: `δu_{k+1} = A_k δu_k + g_k` with `A_k = −(∂f_k/∂u_{k+1})⁻¹ ∂f_k/∂u_k`,
//! then `(I − A_{m−1}⋯A_0) δu_0 = G` (a 2×2 solve) and forward substitution.
//! O(m) work with 2×2 blocks and no heap allocation (the workspace is
//! allocated once per solver).

use nalgebra::{Matrix2, Vector2};
use serde::Serialize;

use crate::model::{MappingEval, MappingKind, Model, ModelInfo, Phase};
use crate::orbit::structure::Structure;

/// A switching point: the start of one mapping.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SwitchingPoint {
    /// Phase `W t`.
    pub phase: f64,
    /// Displacement.
    pub x: f64,
}

/// The arrival of mapping `k` of a cycle: point `k + 1`, or for the last
/// mapping the first point one cycle later (its phase advanced by `shift`,
/// 2π times the cycle's forcing periods).
#[inline]
pub fn arrival(points: &[SwitchingPoint], k: usize, shift: f64) -> SwitchingPoint {
    if k + 1 < points.len() {
        points[k + 1]
    } else {
        SwitchingPoint {
            phase: points[0].phase + shift,
            x: points[0].x,
        }
    }
}

/// The phase from the first of `points` to the return of the cycle of
/// `structure` to it ([`Structure::shift`]): `2π N`, or an autonomous
/// cycle's `W T`.
pub fn cycle_shift(structure: &Structure, points: &[SwitchingPoint]) -> f64 {
    structure.shift(points.first().map_or(f64::NAN, |q| q.phase))
}

/// How the return's deviation follows the first point's in the
/// elimination along the cycle (`δu_m = B δu_0`, ordered `(x, W t)`): the
/// identity, or for an autonomous cycle (held with its return at
/// `W t = 0`) `diag(1, 0)`.
pub fn closing(structure: &Structure) -> Matrix2<f64> {
    if structure.is_autonomous() {
        Matrix2::new(1.0, 0.0, 0.0, 0.0)
    } else {
        Matrix2::identity()
    }
}

/// An autonomous cycle's nontrivial Floquet multiplier from its monodromy:
/// the eigenvalues sum to the trace and one is the trivial 1 along the
/// flow, so the other is `tr DP − 1` (SPEC §14).
pub fn nontrivial_multiplier(dp: &Matrix2<f64>) -> f64 {
    dp.trace() - 1.0
}

/// `DP` as reported for a cycle of `structure`: itself, or for an
/// autonomous cycle the reduced map `diag(0, μ)` (the trivial eigenvalue 1
/// replaced by 0), so that stability and the test functions need no case
/// of their own.
pub fn reported(structure: &Structure, dp: Matrix2<f64>) -> Matrix2<f64> {
    if structure.is_autonomous() {
        Matrix2::new(0.0, 0.0, 0.0, nontrivial_multiplier(&dp))
    } else {
        dp
    }
}

/// [`monodromy`] of the cycle of `structure` through `points`, as
/// [`reported`]; or the mapping whose arrival is singular.
pub fn cycle_monodromy<M: Model>(
    p: &M::Params,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Result<Matrix2<f64>, usize> {
    let dp = monodromy::<M>(p, structure.steps(), cycle_shift(structure, points), points)?;
    Ok(reported(structure, dp))
}

/// The Poincaré-map Jacobian `DP = DP_{σm} ⋯ DP_{σ1}` of the cycle of
/// mappings `steps` at `points`, ordered `(W t, x)` (SPEC §7, Eq. B.1), or
/// the index of the first mapping whose arrival is tangent to its boundary.
/// A flow arriving at a stick is taken with the stick, free of its arrival
/// time ([`MappingEval::local_jacobian_into_stick`]): a tangential arrival
/// there is no singularity.
pub fn monodromy<M: Model>(
    p: &M::Params,
    steps: &[usize],
    shift: f64,
    points: &[SwitchingPoint],
) -> Result<Matrix2<f64>, usize> {
    chain(M::info(p), steps, 0, |k| {
        evaluate::<M>(p, steps, shift, points, k)
    })
}

/// [`monodromy`] of the cycle taken from its first mapping that is not a
/// stick: `DP_{σ1} DP_{σm} ⋯ DP_{σ2}` when `σ1` is a stick. Its trace,
/// determinant and eigenvalues are `DP`'s (`AB` and `BA`), and a flow
/// arriving at the cycle's first stick is never split from it, so the
/// test functions of [`crate::bifurcation`] are free of that arrival's
/// time everywhere. Its eigenvectors are not `DP`'s.
pub fn monodromy_spectral<M: Model>(
    p: &M::Params,
    steps: &[usize],
    shift: f64,
    points: &[SwitchingPoint],
) -> Result<Matrix2<f64>, usize> {
    let info = M::info(p);
    let start = steps.iter().position(|&s| !is_stick(info, s)).unwrap_or(0);
    chain(info, steps, start, |k| {
        evaluate::<M>(p, steps, shift, points, k)
    })
}

fn evaluate<M: Model>(
    p: &M::Params,
    steps: &[usize],
    shift: f64,
    points: &[SwitchingPoint],
    k: usize,
) -> MappingEval {
    let (a, b) = (points[k], arrival(points, k, shift));
    M::mapping(p, steps[k], a.x, a.phase, b.x, b.phase)
}

fn is_stick(info: &ModelInfo, step: usize) -> bool {
    info.mappings
        .get(step)
        .is_some_and(|m| m.kind == MappingKind::Stick)
}

/// The product of the local Jacobians of `steps` (mapping `k` evaluated by
/// `eval(k)`), the `i`-th factor being mapping `(start + i) mod len`, a
/// flow and the stick after it as one factor. `Err` with the mapping whose
/// arrival is singular.
fn chain(
    info: &ModelInfo,
    steps: &[usize],
    start: usize,
    mut eval: impl FnMut(usize) -> MappingEval,
) -> Result<Matrix2<f64>, usize> {
    let m = steps.len();
    let mut dp = Matrix2::identity();
    let mut i = 0;
    while i < m {
        let k = (start + i) % m;
        let next = (k + 1) % m;
        let e = eval(k);
        if i + 1 < m && is_stick(info, steps[next]) && !is_stick(info, steps[k]) {
            dp = e.local_jacobian_into_stick(&eval(next)).ok_or(next)? * dp;
            i += 2;
        } else {
            dp = e.local_jacobian().ok_or(k)? * dp;
            i += 1;
        }
    }
    Ok(dp)
}

/// Why Newton stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "outcome", rename_all = "snake_case")]
pub enum Termination {
    /// The residual fell below the tolerance.
    Converged {
        /// Newton iterations taken.
        iterations: usize,
        /// Final residual (max norm).
        residual: f64,
    },
    /// The iteration limit was reached or the line search failed.
    NotConverged {
        /// Newton iterations taken.
        iterations: usize,
        /// Final residual (max norm).
        residual: f64,
        /// Why.
        reason: String,
    },
    /// A Jacobian block could not be inverted.
    Singular {
        /// Newton iterations taken.
        iterations: usize,
        /// The mapping whose arrival block is singular (`None`: the cycle matrix).
        segment: Option<usize>,
        /// Why.
        reason: String,
    },
}

impl Termination {
    /// Whether Newton converged.
    pub fn converged(&self) -> bool {
        matches!(self, Termination::Converged { .. })
    }
}

/// Newton's tolerances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Converged when the Newton step is below this in every unknown, each
    /// measured in its natural unit: phases `W t` in radians (dimensionless),
    /// displacements relative to the motion's length scale (the largest of
    /// `|x_k|`, the static deflection `|A0| / max(c, W²)` and the boundary
    /// velocities over `W`). Scale-invariant: the same motion in other units
    /// of length, time or mass converges in the same iterations.
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_iterations: 60,
        }
    }
}

/// Newton's method for one structure, with its workspace.
#[derive(Clone, Debug)]
pub struct PeriodicSolver<M: Model> {
    structure: Structure,
    a: Vec<Matrix2<f64>>,
    g: Vec<Vector2<f64>>,
    delta: Vec<Vector2<f64>>,
    trial: Vec<SwitchingPoint>,
    evals: Vec<MappingEval>,
    trial_evals: Vec<MappingEval>,
    _model: std::marker::PhantomData<M>,
}

/// Error of one Newton step.
#[derive(Clone, Debug, PartialEq)]
pub struct SingularStep {
    /// Segment whose arrival block is singular (`None`: the cycle matrix `I − DP`).
    pub segment: Option<usize>,
    /// Why.
    pub reason: &'static str,
}

impl<M: Model> PeriodicSolver<M> {
    /// A solver for `structure` (allocates its workspace once).
    pub fn new(structure: Structure) -> Self {
        let m = structure.len();
        Self {
            structure,
            a: vec![Matrix2::zeros(); m],
            g: vec![Vector2::zeros(); m],
            delta: vec![Vector2::zeros(); m],
            trial: vec![SwitchingPoint { phase: 0.0, x: 0.0 }; m],
            evals: vec![MappingEval::NAN; m],
            trial_evals: vec![MappingEval::NAN; m],
            _model: std::marker::PhantomData,
        }
    }

    /// The structure.
    pub fn structure(&self) -> &Structure {
        &self.structure
    }

    /// The length scale of a motion with switching points `points`: the
    /// largest of `|x_k|`, the static deflection `|A0| / max(c, W²)` of the
    /// forcing and `|V_b| / W` over the boundaries (so that a motion whose
    /// switching displacements all vanish still has one). A length in the
    /// model's units.
    pub fn length_scale(p: &M::Params, points: &[SwitchingPoint]) -> f64 {
        let osc = M::oscillator(p);
        let w = osc.frequency.abs();
        let mut l = (osc.amplitude / osc.stiffness.abs().max(w * w)).abs();
        for b in 0..M::info(p).boundaries.len() {
            l = l.max((M::boundary_velocity(p, b) / w).abs());
        }
        for q in points {
            l = l.max(q.x.abs());
        }
        if l.is_finite() && l > 0.0 {
            l
        } else {
            1.0
        }
    }

    /// The residual below which a point solves the equations to the rounding
    /// of the closed form, relative to the motion's scales: residuals are
    /// displacements (scale `l`) or velocities (scale `l W`), and `1e-11`
    /// of them is what the flows' rounding leaves after a cycle.
    fn residual_floor(p: &M::Params, points: &[SwitchingPoint]) -> f64 {
        let l = Self::length_scale(p, points);
        let w = M::oscillator(p).frequency.abs();
        1e-11 * l * w.max(1.0)
    }

    /// The rounding of a residual evaluated in closed form at a motion of
    /// length scale `l`: 64 ulps of its displacements (scale `l`) and
    /// velocities (scale `l W`).
    fn rounding(p: &M::Params, l: f64) -> f64 {
        let w = M::oscillator(p).frequency.abs();
        64.0 * f64::EPSILON * l * w.max(1.0)
    }

    /// Size of the Newton step in the workspace, each unknown in its natural
    /// unit: phases in radians, displacements over the length scale `l`;
    /// a component within 8 ulps of its unknown counts as the tolerance
    /// `tol` at most (the phase of a motion many periods from 0 cannot be
    /// resolved to 1e-12 radians: its rounding is the limit).
    fn step_size(&self, points: &[SwitchingPoint], l: f64, tol: f64) -> f64 {
        let ulps = if tol > 0.0 {
            8.0 * f64::EPSILON / tol
        } else {
            0.0
        };
        let mut s = 0.0f64;
        for (d, q) in self.delta.iter().zip(points) {
            // (l ≥ |x_k|: the rounding of x is far below the tolerance.)
            let v = (d[1].abs() / (ulps * q.phase.abs()).max(1.0)).max(d[0].abs() / l);
            if v.is_nan() {
                return f64::NAN;
            }
            s = s.max(v);
        }
        s
    }

    /// The point after point `k` (wrapping with the period shift).
    #[inline]
    fn next(&self, points: &[SwitchingPoint], k: usize) -> SwitchingPoint {
        arrival(points, k, cycle_shift(&self.structure, points))
    }

    /// Mapping `k` evaluated at the current points.
    #[inline]
    pub fn evaluate(&self, p: &M::Params, points: &[SwitchingPoint], k: usize) -> MappingEval {
        let (a, b) = (points[k], self.next(points, k));
        M::mapping(p, self.structure.steps()[k], a.x, a.phase, b.x, b.phase)
    }

    /// Calls `f(k, step, x_k, φ_k, x_{k+1}, φ_{k+1})` for each mapping in
    /// turn until it returns `false`. Mapping k ends where mapping k + 1
    /// starts, so each phase's `sin_cos` is computed once (the last arrival
    /// is the first point a cycle later, computed as [`Self::evaluate`]
    /// does: the same bits as [`Model::mapping`]).
    #[inline]
    fn each_mapping(
        &self,
        points: &[SwitchingPoint],
        mut f: impl FnMut(usize, usize, f64, Phase, f64, Phase) -> bool,
    ) {
        let Some(first) = points.first() else {
            return;
        };
        let steps = self.structure.steps();
        let mut a = Phase::new(first.phase);
        for k in 0..points.len() {
            let next = self.next(points, k);
            let b = Phase::new(next.phase);
            if !f(k, steps[k], points[k].x, a, next.x, b) {
                return;
            }
            a = b;
        }
    }

    /// Largest residual component over all mappings (NaN propagates).
    pub fn residual(&self, p: &M::Params, points: &[SwitchingPoint]) -> f64 {
        let mut r = 0.0f64;
        self.each_mapping(points, |_, step, x0, a, x1, b| {
            for v in M::residual_at(p, step, x0, a, x1, b).iter() {
                if v.is_nan() {
                    r = f64::NAN;
                    return false;
                }
                r = r.max(v.abs());
            }
            true
        });
        r
    }

    /// Evaluate every mapping (residual and Jacobian blocks) at `points` into
    /// `out`; returns the largest residual component (NaN propagates).
    fn evaluate_all(
        &self,
        p: &M::Params,
        points: &[SwitchingPoint],
        out: &mut [MappingEval],
    ) -> f64 {
        let mut r = 0.0f64;
        self.each_mapping(points, |k, step, x0, a, x1, b| {
            let e = M::mapping_at(p, step, x0, a, x1, b);
            for v in e.residual.iter() {
                if v.is_nan() {
                    r = f64::NAN;
                } else if !r.is_nan() {
                    r = r.max(v.abs());
                }
            }
            out[k] = e;
            true
        });
        r
    }

    /// The Newton direction from the evaluations in the workspace, by
    /// elimination along the cycle. Returns `A_{m−1}⋯A_0` (ordered `(x, W t)`).
    fn eliminate(&mut self) -> Result<Matrix2<f64>, SingularStep> {
        let m = self.evals.len();
        let mut product = Matrix2::identity();
        let mut acc = Vector2::zeros();
        for k in 0..m {
            let e = &self.evals[k];
            let inv = e.d_next.try_inverse().ok_or(SingularStep {
                segment: Some(k),
                reason: "the arrival is tangent to the boundary (grazing): ∂f/∂(x, Wt) at the arrival is singular",
            })?;
            let a = -(inv * e.d_prev);
            let g = -(inv * e.residual);
            if !(a.iter().all(|v| v.is_finite()) && g.iter().all(|v| v.is_finite())) {
                return Err(SingularStep {
                    segment: Some(k),
                    reason: "the mapping's Jacobian is not finite",
                });
            }
            self.a[k] = a;
            self.g[k] = g;
            product = a * product;
            acc = a * acc + g;
        }
        // The return: δu_m = δu_0, or (δx_0, 0) for an autonomous cycle
        // (held with its return at W t = 0; the first phase carries −W T).
        let cycle = closing(&self.structure) - product;
        let inv = cycle.try_inverse().ok_or(SingularStep {
            segment: None,
            reason: "I − DP is singular: an eigenvalue of the Poincaré map equals 1 (saddle-node)",
        })?;
        self.delta[0] = inv * acc;
        for k in 0..m - 1 {
            self.delta[k + 1] = self.a[k] * self.delta[k] + self.g[k];
        }
        Ok(product)
    }

    /// Compute the Newton direction at `points` into the workspace
    /// (no allocation). Returns the product `A_{m−1}⋯A_0` (ordered `(x, W t)`).
    pub fn direction(
        &mut self,
        p: &M::Params,
        points: &[SwitchingPoint],
    ) -> Result<Matrix2<f64>, SingularStep> {
        let mut evals = std::mem::take(&mut self.evals);
        self.evaluate_all(p, points, &mut evals);
        self.evals = evals;
        self.eliminate()
    }

    /// One damped Newton step in place; returns the new residual. No allocation.
    pub fn step(
        &mut self,
        p: &M::Params,
        points: &mut [SwitchingPoint],
        current: f64,
    ) -> Result<f64, SingularStep> {
        self.direction(p, points)?;
        let mut lambda = 1.0;
        loop {
            for ((t, pt), d) in self.trial.iter_mut().zip(points.iter()).zip(&self.delta) {
                *t = SwitchingPoint {
                    x: pt.x + lambda * d[0],
                    phase: pt.phase + lambda * d[1],
                };
            }
            let r = self.residual(p, &self.trial);
            if r < current || lambda < 1e-3 || current.is_nan() {
                if r.is_finite() {
                    points.copy_from_slice(&self.trial);
                    return Ok(r);
                }
                return Ok(current);
            }
            lambda *= 0.5;
        }
    }

    /// Solve from `guess` (modified in place). Each iteration evaluates the
    /// mappings once: the evaluation at an accepted trial point is the next
    /// iteration's Jacobian. Backtracking (residuals only) only when the full
    /// step does not decrease the residual.
    ///
    /// Converged when the Newton step, each unknown in its natural unit (see
    /// [`NewtonOptions::tolerance`]), is below the tolerance (the step is
    /// then taken), or the residual is exactly zero. The residuals
    /// themselves are displacements, velocities or forces per unit mass, so
    /// no absolute bound on them could serve every choice of units.
    pub fn solve(
        &mut self,
        p: &M::Params,
        points: &mut [SwitchingPoint],
        opts: NewtonOptions,
    ) -> Termination {
        assert_eq!(
            points.len(),
            self.structure.len(),
            "one switching point per mapping"
        );
        let mut evals = std::mem::take(&mut self.evals);
        let mut r = self.evaluate_all(p, points, &mut evals);
        self.evals = evals;
        if !r.is_finite() {
            return Termination::NotConverged {
                iterations: 0,
                residual: r,
                reason: "the residual at the initial guess is not finite".into(),
            };
        }
        // The size of the last Newton step (natural units).
        let mut last_step = f64::INFINITY;
        for it in 0..opts.max_iterations {
            if r == 0.0 {
                return Termination::Converged {
                    iterations: it,
                    residual: r,
                };
            }
            if let Err(s) = self.eliminate() {
                return Termination::Singular {
                    iterations: it,
                    segment: s.segment,
                    reason: s.reason.into(),
                };
            }
            let l = Self::length_scale(p, points);
            let size = self.step_size(points, l, opts.tolerance);
            last_step = size;
            if size <= opts.tolerance && r <= Self::rounding(p, l) {
                // A step below the tolerance that corrects a residual at the
                // rounding of the closed form itself: it is that rounding's
                // noise, and taking it (one more evaluation of every
                // mapping) cannot make the point any better.
                return Termination::Converged {
                    iterations: it,
                    residual: r,
                };
            }
            if size > 1e-2 && r <= Self::residual_floor(p, points) {
                // The point solves the equations to the rounding of the
                // closed form, yet Newton proposes to move it by a sizeable
                // fraction of the motion: `I − DP` is (nearly) singular, the
                // point is one of a family of motions (eigenvalue 1 of `DP`),
                // and the step would only slide along the family.
                return Termination::Converged {
                    iterations: it,
                    residual: r,
                };
            }
            for ((t, pt), d) in self.trial.iter_mut().zip(points.iter()).zip(&self.delta) {
                *t = SwitchingPoint {
                    x: pt.x + d[0],
                    phase: pt.phase + d[1],
                };
            }
            let mut trial_evals = std::mem::take(&mut self.trial_evals);
            let rt = self.evaluate_all(p, &self.trial, &mut trial_evals);
            self.trial_evals = trial_evals;
            if size <= opts.tolerance {
                // The point is within about `size` of the solution: take the
                // (round-off sized) step unless it makes the residual worse.
                if rt <= r {
                    points.copy_from_slice(&self.trial);
                    std::mem::swap(&mut self.evals, &mut self.trial_evals);
                    r = rt;
                }
                return Termination::Converged {
                    iterations: it + 1,
                    residual: r,
                };
            }
            if rt < r {
                points.copy_from_slice(&self.trial);
                std::mem::swap(&mut self.evals, &mut self.trial_evals);
                r = rt;
                continue;
            }
            // Backtrack on the residual alone.
            let mut lambda = 0.5;
            let mut accepted = None;
            while lambda >= 1e-3 {
                for ((t, pt), d) in self.trial.iter_mut().zip(points.iter()).zip(&self.delta) {
                    *t = SwitchingPoint {
                        x: pt.x + lambda * d[0],
                        phase: pt.phase + lambda * d[1],
                    };
                }
                let rl = self.residual(p, &self.trial);
                if rl < r {
                    accepted = Some(rl);
                    break;
                }
                lambda *= 0.5;
            }
            match accepted {
                Some(_) => {
                    points.copy_from_slice(&self.trial);
                    let mut evals = std::mem::take(&mut self.evals);
                    r = self.evaluate_all(p, points, &mut evals);
                    self.evals = evals;
                }
                None if size <= 1e3 * opts.tolerance => {
                    // Stagnation at round-off: the step is within a factor
                    // 1e3 of the tolerance and no fraction of it decreases
                    // the residual.
                    return Termination::Converged {
                        iterations: it + 1,
                        residual: r,
                    };
                }
                None if r <= Self::residual_floor(p, points) => {
                    // No decrease, but the residual is already at the
                    // rounding of the closed form: the step is large only
                    // along a direction where `I − DP` is singular (a
                    // family of motions, eigenvalue 1 of `DP`), and the
                    // point solves the equations as well as they can be.
                    return Termination::Converged {
                        iterations: it + 1,
                        residual: r,
                    };
                }
                None => {
                    return Termination::NotConverged {
                        iterations: it + 1,
                        residual: r,
                        reason: "the line search found no decrease".into(),
                    };
                }
            }
        }
        Termination::NotConverged {
            iterations: opts.max_iterations,
            residual: r,
            reason: format!(
                "no convergence in {} iterations (last Newton step {last_step:.3e} in natural units)",
                opts.max_iterations
            ),
        }
    }

    /// `DP` at the points the last [`solve`](Self::solve) returned, from the
    /// evaluations it made there (none made anew): the value
    /// [`poincare_jacobian`](Self::poincare_jacobian) gives at those points,
    /// to the bit. Valid only right after a `solve` that converged.
    pub fn poincare_jacobian_at_solution(
        &self,
        p: &M::Params,
    ) -> Result<Matrix2<f64>, SingularStep> {
        chain(M::info(p), self.structure.steps(), 0, |k| self.evals[k])
            .map(|dp| reported(&self.structure, dp))
            .map_err(|k| SingularStep {
                segment: Some(k),
                reason: "the arrival is tangent to the boundary (grazing)",
            })
    }

    /// The Poincaré-map Jacobian `DP = DP_{σm} ⋯ DP_{σ1}` at `points`,
    /// ordered `(W t, x)` (SPEC §7, Eq. B.1), or why it does not exist.
    pub fn poincare_jacobian(
        &mut self,
        p: &M::Params,
        points: &[SwitchingPoint],
    ) -> Result<Matrix2<f64>, SingularStep> {
        cycle_monodromy::<M>(p, &self.structure, points).map_err(|k| SingularStep {
            segment: Some(k),
            reason: "the arrival is tangent to the boundary (grazing)",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::paper::{Paper, Params};

    /// The shared phases of [`PeriodicSolver::evaluate_all`] and
    /// [`PeriodicSolver::residual`] give the same bits as each mapping
    /// evaluated alone by [`Model::mapping`] (its own `sin_cos` at both
    /// ends), at phases near 0 and far from it.
    #[test]
    fn shared_phases_give_the_bits_of_each_mapping_alone() {
        let p = Params {
            W: 5.0,
            Q0: 70.0,
            ..Params::default()
        };
        let structure =
            Structure::parse(Paper::INFO, "3_31 0_11 3_13 4_33 3_33 4_33", 2).expect("a structure");
        let solver = PeriodicSolver::<Paper>::new(structure);
        for origin in [0.0, 1.0e3, -37.5] {
            let points: Vec<SwitchingPoint> = (0..6)
                .map(|k| SwitchingPoint {
                    phase: origin + 0.9 * k as f64 + 0.1 * (k * k) as f64,
                    x: 0.3 * (k as f64 - 2.5),
                })
                .collect();
            let mut out = vec![MappingEval::NAN; points.len()];
            let r = solver.evaluate_all(&p, &points, &mut out);
            let mut alone_max = 0.0f64;
            for (k, e) in out.iter().enumerate() {
                let alone = solver.evaluate(&p, &points, k);
                assert_eq!(
                    format!("{e:?}"),
                    format!("{alone:?}"),
                    "mapping {k} at {origin}"
                );
                alone_max = alone.residual.iter().fold(alone_max, |m, v| m.max(v.abs()));
            }
            assert!(alone_max > 0.0, "the points are no motion: a residual");
            assert_eq!(r.to_bits(), alone_max.to_bits(), "at {origin}");
            assert_eq!(solver.residual(&p, &points).to_bits(), alone_max.to_bits());
        }
    }
}
