//! What a generated piecewise-linear model is to the runtime: the [`Model`]
//! trait, the values it returns ([`MappingEval`], [`StickForces`]) and the
//! visitor that reaches a model chosen at run time by name.
//!
//! Analyses are generic over `M: Model`; they never refer to a model by name.

use nalgebra::{Matrix2, Vector2};
use serde::Serialize;

use super::info::ModelInfo;
use super::oscillator::{Coefficients, Oscillator};
use super::param::ParamSet;

/// Forces on the stick boundary at a point `(x, W t)` (SPEC §3, Eqs. 2, 24–25).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StickForces {
    /// `Fnf = A0 cos(W t) - 2 d V - c x`.
    pub non_friction: f64,
    /// `F_in` of the domain above: `Fnf - f_above(V)` (the paper's `F1_in`).
    pub input_above: f64,
    /// `F_in` of the domain below: `Fnf - f_below(V)` (the paper's `F3_in`).
    pub input_below: f64,
    /// `F_out` above: `Fnf - as` (the paper's `F1_out`).
    pub output_above: f64,
    /// `F_out` below: `Fnf + as` (the paper's `F3_out`).
    pub output_below: f64,
}

/// A mapping's residual and its Jacobian blocks at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MappingEval {
    /// `f ∈ R²` (SPEC Eqs. 37–38).
    pub residual: Vector2<f64>,
    /// `∂f/∂(x_i, W t_i)`: columns ordered `(x, W t)`.
    pub d_prev: Matrix2<f64>,
    /// `∂f/∂(x_{i+1}, W t_{i+1})`: columns ordered `(x, W t)`.
    pub d_next: Matrix2<f64>,
}

impl MappingEval {
    /// Returned for an out-of-range mapping index.
    pub const NAN: Self = Self {
        residual: Vector2::new(f64::NAN, f64::NAN),
        d_prev: Matrix2::new(f64::NAN, f64::NAN, f64::NAN, f64::NAN),
        d_next: Matrix2::new(f64::NAN, f64::NAN, f64::NAN, f64::NAN),
    };

    /// The local Poincaré-map Jacobian `DP_σ = -(∂f/∂next)⁻¹ ∂f/∂prev`
    /// (SPEC §7, Eq. B.2), ordered `(W t, x)` as in the paper, or `None`
    /// where `∂f/∂next` is singular (grazing: the flow is tangent to the boundary).
    pub fn local_jacobian(&self) -> Option<Matrix2<f64>> {
        // Reorder the columns from (x, Wt) to (Wt, x): DP is in (Wt, x).
        let swap = Matrix2::new(0.0, 1.0, 1.0, 0.0);
        let next = self.d_next * swap;
        let prev = self.d_prev * swap;
        let inv = next.try_inverse()?;
        let dp = -(inv * prev);
        // Rows come out ordered like the unknowns of `next`, (Wt, x).
        dp.iter().all(|v| v.is_finite()).then_some(dp)
    }
}

/// A generated model: closed-form flows, mapping residuals with analytic
/// Jacobians, vector fields and force criteria, all specialized at build time.
///
/// Indices are those of [`ModelInfo`]: domains and boundaries lowest first,
/// mappings in `INFO.mappings` order. An out-of-range index yields NaN.
pub trait Model: Copy + Default + Send + Sync + 'static {
    /// The run-time parameters.
    type Params: ParamSet;
    /// The static description.
    const INFO: &'static ModelInfo;

    /// Effective coefficients of domain `domain`.
    fn coefficients(p: &Self::Params, domain: usize) -> Coefficients;
    /// Velocity of boundary `boundary`.
    fn boundary_velocity(p: &Self::Params, boundary: usize) -> f64;
    /// The oscillator's linear part.
    fn oscillator(p: &Self::Params) -> Oscillator;
    /// `as`, when the model has a stick boundary.
    fn static_bound(p: &Self::Params) -> Option<f64>;
    /// `[x, v]` at phase `phi1` of the flow in `domain` from `(x0, v0)` at phase `phi0`.
    fn flow(p: &Self::Params, domain: usize, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2];
    /// `[F, DF]`: the normal vector field of `domain` and its rate along the flow.
    fn normal_field(p: &Self::Params, domain: usize, x: f64, y: f64, phi: f64) -> [f64; 2];
    /// Forces on the stick boundary at `(x, phi)`.
    fn stick_forces(p: &Self::Params, x: f64, phi: f64) -> Option<StickForces>;
    /// Residual of mapping `mapping` from `(x0, phi0)` to `(x1, phi1)`.
    fn residual(
        p: &Self::Params,
        mapping: usize,
        x0: f64,
        phi0: f64,
        x1: f64,
        phi1: f64,
    ) -> Vector2<f64>;
    /// Residual and Jacobian blocks of mapping `mapping`.
    fn mapping(
        p: &Self::Params,
        mapping: usize,
        x0: f64,
        phi0: f64,
        x1: f64,
        phi1: f64,
    ) -> MappingEval;
}

/// Something to do with a model chosen at run time by name (see [`crate::models::visit`]).
pub trait ModelVisitor {
    /// What it returns.
    type Output;
    /// Do it with model `M`.
    fn visit<M: Model>(self) -> Self::Output;
}
