//! The bordered (pseudo-arclength) system of a structure's mapping equations
//! with the parameter as an unknown, solved by elimination along the cycle.
//!
//! Unknowns: the switching points `u_k = (x_k, W t_k)`, `k = 0..m`, with
//! periodicity substituted (as [`crate::orbit::periodic::PeriodicSolver`]),
//! and the parameter `λ`. Equations: the `2m` mapping residuals
//! `f_k(u_k, u_{k+1}, λ) = 0` and one border row `⟨b, X⟩ = target` (the
//! pseudo-arclength condition, or `λ = bound`). Linearized, mapping `k` gives
//! `δu_{k+1} = A_k δu_k + g_k + h_k δλ` with `A_k = −N_k⁻¹ P_k`,
//! `g_k = −N_k⁻¹ f_k`, `h_k = −N_k⁻¹ ∂f_k/∂λ` (`P_k`, `N_k` the exact
//! generated blocks). Forward, `δu_k = M_k δu_0 + c_k + e_k δλ`; closing the
//! cycle, `(I − M_m) δu_0 − e_m δλ = c_m`, and the border row, accumulated in
//! the same pass, is the third equation: a 3×3 solve that stays regular at a
//! fold, where `I − DP = I − M_m` is singular. O(m) work on 2×2 blocks, no
//! heap allocation after construction.
//!
//! `∂f_k/∂λ` is a central difference of `Model::residual` in `λ` with step
//! `h = 1e-6 max(1, |λ|)` (truncation error O(h²) ≈ 1e-12 relative): it only
//! enters the Newton direction and the tangent, never the residual, so the
//! points solve the equations exactly; a fold or branch point is located on
//! `det(I − DP)`, which does not involve it.
//!
//! An autonomous cycle ([`Structure::is_autonomous`]) is held with its
//! return at `W t = 0` and its first point's phase `−W T`: the unknowns are
//! the same, the first phase carrying the period, and the return's
//! linearization is `δu_m = (δx_0, 0)` instead of `δu_0`, so the closing
//! block is `diag(1, 0) − M_m`. Its `DP` has the trivial eigenvalue 1 along
//! the flow; the test functions and the stability see the reduced map
//! `diag(μ, 0)`, `μ = tr DP − 1` the nontrivial multiplier (SPEC §14), so a
//! fold of cycles is where `μ` passes 1 and the branch turns.
//!
//! The inner product on `(u, λ)` is scaled: displacements over the motion's
//! length scale `L`, phases in radians, each switching point weighted `1/m`,
//! and `λ` over the bounds' span `S`.

use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

use crate::model::{Model, ParamSet};
use crate::orbit::periodic::{arrival, closing, cycle_monodromy, cycle_shift, SwitchingPoint};
use crate::orbit::structure::Structure;

/// A point of the extended space: switching points and the parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// The switching points.
    pub points: Vec<SwitchingPoint>,
    /// The parameter.
    pub value: f64,
}

/// A vector of the extended space: `(δx_k, δ(W t_k))` and `δλ`.
#[derive(Clone, Debug, PartialEq)]
pub struct Vector {
    /// `(δx_k, δ(W t_k))`.
    pub du: Vec<Vector2<f64>>,
    /// `δλ`.
    pub dl: f64,
}

impl Vector {
    /// The zero vector for `m` switching points.
    pub fn zeros(m: usize) -> Self {
        Self {
            du: vec![Vector2::zeros(); m],
            dl: 0.0,
        }
    }

    /// The unit vector along `λ`.
    pub fn parameter(m: usize) -> Self {
        Self {
            du: vec![Vector2::zeros(); m],
            dl: 1.0,
        }
    }

    /// `−v`.
    pub fn neg(&self) -> Self {
        Self {
            du: self.du.iter().map(|d| -d).collect(),
            dl: -self.dl,
        }
    }
}

/// Why a linear solve failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Singular {
    /// Mapping `k`'s arrival block is singular (grazing) or not finite.
    Arrival(usize),
    /// The 3×3 bordered system is singular.
    Border,
}

impl Singular {
    /// Why, in words.
    pub fn describe(self) -> String {
        match self {
            Singular::Arrival(k) => format!(
                "mapping {k}: the arrival is tangent to the boundary (∂f/∂(x, Wt) at the arrival singular or not finite)"
            ),
            Singular::Border => "the bordered system is singular".into(),
        }
    }
}

/// How the corrector ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Correction {
    /// Converged after this many iterations.
    Converged {
        /// Newton iterations.
        iterations: usize,
    },
    /// Why not.
    Failed(String),
}

/// The bordered system of one structure, with its workspace.
#[derive(Clone, Debug)]
pub struct Bordered<M: Model> {
    structure: Structure,
    base: M::Params,
    index: usize,
    /// Length scale `L` of displacements.
    pub length: f64,
    /// Span `S` of the parameter.
    pub span: f64,
    weight: f64,
    a: Vec<Matrix2<f64>>,
    g: Vec<Vector2<f64>>,
    h: Vec<Vector2<f64>>,
    /// The last solution of the linear system.
    delta: Vector,
}

impl<M: Model> Bordered<M> {
    /// The system of `structure` for parameter `index` of `base`, with length
    /// scale `length` and parameter span `span` (allocates its workspace).
    pub fn new(
        structure: Structure,
        base: M::Params,
        index: usize,
        length: f64,
        span: f64,
    ) -> Self {
        let m = structure.len();
        Self {
            structure,
            base,
            index,
            length,
            span,
            weight: 1.0 / m as f64,
            a: vec![Matrix2::zeros(); m],
            g: vec![Vector2::zeros(); m],
            h: vec![Vector2::zeros(); m],
            delta: Vector::zeros(m),
        }
    }

    /// The structure.
    pub fn structure(&self) -> &Structure {
        &self.structure
    }

    /// The parameters at `value` (unchecked: a copy of the base with one entry set).
    #[inline]
    pub fn params(&self, value: f64) -> M::Params {
        let mut p = self.base;
        p.set(self.index, value);
        p
    }

    #[inline]
    fn ends(&self, points: &[SwitchingPoint], k: usize) -> (SwitchingPoint, SwitchingPoint) {
        (
            points[k],
            arrival(points, k, cycle_shift(&self.structure, points)),
        )
    }

    /// The scaled inner product's weight of component `(x, W t)`.
    #[inline]
    fn metric(&self) -> Vector2<f64> {
        Vector2::new(self.weight / (self.length * self.length), self.weight)
    }

    /// `⟨a, b⟩` in the scaled metric.
    pub fn dot(&self, a: &Vector, b: &Vector) -> f64 {
        let w = self.metric();
        let mut s = a.dl * b.dl / (self.span * self.span);
        for (x, y) in a.du.iter().zip(&b.du) {
            s += w[0] * x[0] * y[0] + w[1] * x[1] * y[1];
        }
        s
    }

    /// `⟨b, X − Y⟩` in the scaled metric.
    pub fn dot_diff(&self, b: &Vector, x: &State, y: &State) -> f64 {
        let w = self.metric();
        let mut s = b.dl * (x.value - y.value) / (self.span * self.span);
        for ((d, p), q) in b.du.iter().zip(&x.points).zip(&y.points) {
            s += w[0] * d[0] * (p.x - q.x) + w[1] * d[1] * (p.phase - q.phase);
        }
        s
    }

    /// `|X − Y|` in the scaled metric.
    pub fn distance(&self, x: &State, y: &State) -> f64 {
        let w = self.metric();
        let mut s = ((x.value - y.value) / self.span).powi(2);
        for (p, q) in x.points.iter().zip(&y.points) {
            s += w[0] * (p.x - q.x).powi(2) + w[1] * (p.phase - q.phase).powi(2);
        }
        s.sqrt()
    }

    /// Normalize `v` to unit length in the scaled metric.
    pub fn normalize(&self, v: &mut Vector) {
        let n = self.dot(v, v).sqrt();
        if n > 0.0 && n.is_finite() {
            for d in &mut v.du {
                *d /= n;
            }
            v.dl /= n;
        }
    }

    /// `X + s v` into `out` (no allocation when `out` has the right length).
    pub fn advance(x: &State, s: f64, v: &Vector, out: &mut State) {
        for ((o, p), d) in out.points.iter_mut().zip(&x.points).zip(&v.du) {
            *o = SwitchingPoint {
                x: p.x + s * d[0],
                phase: p.phase + s * d[1],
            };
        }
        out.value = x.value + s * v.dl;
    }

    /// Largest residual component at `x` (NaN propagates).
    pub fn residual(&self, x: &State) -> f64 {
        let p = self.params(x.value);
        let mut r = 0.0f64;
        for k in 0..x.points.len() {
            let (a, b) = self.ends(&x.points, k);
            let f = M::residual(&p, self.structure.steps()[k], a.x, a.phase, b.x, b.phase);
            for v in f.iter() {
                if v.is_nan() {
                    return f64::NAN;
                }
                r = r.max(v.abs());
            }
        }
        r
    }

    /// Solve the linearized system at `x` with border row `border` and
    /// right-hand side `rhs` for the border (`⟨border, δX⟩ = rhs`); with
    /// `with_residual = false` the mapping residuals are taken as zero (the
    /// tangent). The solution is left in the workspace (`self.delta`).
    /// Returns the largest residual component. No allocation.
    fn solve_linear(
        &mut self,
        x: &State,
        border: &Vector,
        rhs: f64,
        with_residual: bool,
    ) -> Result<f64, Singular> {
        let m = x.points.len();
        let p = self.params(x.value);
        let hstep = 1e-6 * x.value.abs().max(1.0);
        let (pp, pm) = (self.params(x.value + hstep), self.params(x.value - hstep));
        let w = self.metric();
        let mut big = Matrix2::identity();
        let mut c = Vector2::zeros();
        let mut e = Vector2::zeros();
        let mut ru = Vector2::zeros();
        let (mut rc, mut re) = (0.0, 0.0);
        let mut r = 0.0f64;
        for k in 0..m {
            let (a, b) = self.ends(&x.points, k);
            let step = self.structure.steps()[k];
            let ev = M::mapping(&p, step, a.x, a.phase, b.x, b.phase);
            let fp = M::residual(&pp, step, a.x, a.phase, b.x, b.phase);
            let fm = M::residual(&pm, step, a.x, a.phase, b.x, b.phase);
            let fl = (fp - fm) / (2.0 * hstep);
            let inv = ev.d_next.try_inverse().ok_or(Singular::Arrival(k))?;
            let ak = -(inv * ev.d_prev);
            let gk = if with_residual {
                -(inv * ev.residual)
            } else {
                Vector2::zeros()
            };
            let hk = -(inv * fl);
            if !(ak
                .iter()
                .chain(gk.iter())
                .chain(hk.iter())
                .all(|v| v.is_finite()))
            {
                return Err(Singular::Arrival(k));
            }
            for v in ev.residual.iter() {
                r = if v.is_nan() || r.is_nan() {
                    f64::NAN
                } else {
                    r.max(v.abs())
                };
            }
            // Border contribution of δu_k = M_k δu_0 + c_k + e_k δλ.
            let s = border.du[k].component_mul(&w);
            ru += big.transpose() * s;
            rc += s.dot(&c);
            re += s.dot(&e);
            big = ak * big;
            c = ak * c + gk;
            e = ak * e + hk;
            self.a[k] = ak;
            self.g[k] = gk;
            self.h[k] = hk;
        }
        // The return: δu_m = δu_0, or (δx_0, 0) for an autonomous cycle
        // (its return held at W t = 0).
        let cycle = closing(&self.structure) - big;
        let sys = Matrix3::new(
            cycle[(0, 0)],
            cycle[(0, 1)],
            -e[0],
            cycle[(1, 0)],
            cycle[(1, 1)],
            -e[1],
            ru[0],
            ru[1],
            re + border.dl / (self.span * self.span),
        );
        let sol = sys
            .lu()
            .solve(&Vector3::new(c[0], c[1], rhs - rc))
            .filter(|s| s.iter().all(|v| v.is_finite()))
            .ok_or(Singular::Border)?;
        let dl = sol[2];
        self.delta.dl = dl;
        self.delta.du[0] = Vector2::new(sol[0], sol[1]);
        for k in 0..m - 1 {
            self.delta.du[k + 1] = self.a[k] * self.delta.du[k] + self.g[k] + self.h[k] * dl;
        }
        Ok(r)
    }

    /// The tangent at `x`, oriented so that `⟨t, prev⟩ > 0`, into `out`
    /// (unit length). No allocation.
    pub fn tangent(&mut self, x: &State, prev: &Vector, out: &mut Vector) -> Result<(), Singular> {
        self.solve_linear(x, prev, 1.0, false)?;
        out.du.copy_from_slice(&self.delta.du);
        out.dl = self.delta.dl;
        self.normalize(out);
        if self.dot(out, prev) < 0.0 {
            for d in &mut out.du {
                *d = -*d;
            }
            out.dl = -out.dl;
        }
        Ok(())
    }

    /// The product `A_{m−1} ⋯ A_0` of the last linear solve (`DP` ordered
    /// `(x, W t)`), and the blocks `A_k`.
    pub fn blocks(&self) -> &[Matrix2<f64>] {
        &self.a
    }

    /// Newton on the mapping equations and `⟨border, X⟩ = ⟨border, anchor⟩`
    /// (the hyperplane through `anchor` normal to `border`), from `x`
    /// (modified in place). Converged when the Newton step is below `tol` in
    /// every unknown in its natural unit (phases in radians, displacements
    /// over `L`, the parameter over `S`). No allocation.
    pub fn correct(
        &mut self,
        x: &mut State,
        border: &Vector,
        anchor: &State,
        tol: f64,
        max_iterations: usize,
    ) -> Correction {
        let ulps = 8.0 * f64::EPSILON / tol.max(f64::MIN_POSITIVE);
        let mut last = f64::INFINITY;
        // The residual of the closed forms' rounding (as PeriodicSolver):
        // displacements of scale L, velocities of scale L W.
        let w = M::oscillator(&self.params(x.value)).frequency.abs();
        let floor = 1e-11 * self.length * w.max(1.0);
        let mut at_floor = false;
        for it in 0..max_iterations {
            let rhs = -self.dot_diff(border, x, anchor);
            match self.solve_linear(x, border, rhs, true) {
                Ok(r) if r.is_finite() => {
                    if r == 0.0 && rhs == 0.0 {
                        return Correction::Converged { iterations: it };
                    }
                    at_floor = r <= floor && rhs.abs() <= 1e-12;
                }
                Ok(_) => return Correction::Failed("the residual is not finite".into()),
                Err(s) => return Correction::Failed(s.describe()),
            }
            let mut size = (self.delta.dl / self.span).abs();
            for (q, d) in x.points.iter_mut().zip(&self.delta.du) {
                let v =
                    (d[1].abs() / (ulps * q.phase.abs()).max(1.0)).max(d[0].abs() / self.length);
                size = size.max(v);
                q.x += d[0];
                q.phase += d[1];
            }
            x.value += self.delta.dl;
            if size.is_nan() {
                return Correction::Failed("the Newton step is not finite".into());
            }
            if size <= tol {
                return Correction::Converged { iterations: it + 1 };
            }
            // Near a branch point the system is nearly singular and Newton
            // converges only linearly: fail only when the step grows.
            if it >= 3 && size > last && size > 1e3 * tol {
                if at_floor {
                    // The point solves the equations to rounding; the steps
                    // only slide along a nearly singular direction (a
                    // branch point): it is as good as the equations allow.
                    return Correction::Converged { iterations: it + 1 };
                }
                return Correction::Failed(format!(
                    "the corrector does not converge (Newton step {size:.3e} after {} iterations)",
                    it + 1
                ));
            }
            last = size;
        }
        if last <= 1e3 * tol || at_floor {
            return Correction::Converged {
                iterations: max_iterations,
            };
        }
        Correction::Failed(format!(
            "no convergence in {max_iterations} iterations (last Newton step {last:.3e})"
        ))
    }

    /// `DP` ordered `(W t, x)` at `x` (product of the local Jacobians), or
    /// the mapping whose arrival is singular. For an autonomous cycle, the
    /// reduced map `diag(0, μ)` with `μ = tr DP − 1` (the trivial
    /// eigenvalue 1 along the flow replaced by 0).
    pub fn poincare_jacobian(&self, x: &State) -> Result<Matrix2<f64>, usize> {
        cycle_monodromy::<M>(&self.params(x.value), &self.structure, &x.points)
    }
}
