//! What a generated piecewise-linear model is to the runtime: the [`Model`]
//! trait and the values it returns ([`MappingEval`], [`StickForces`]).
//!
//! Analyses are generic over `M: Model`; they never refer to a model by name.

use nalgebra::{Matrix2, Vector2};
use serde::Serialize;

use super::info::ModelInfo;
use super::oscillator::{Coefficients, FrictionOscillator};

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

/// A phase `W t` together with its cosine and sine: the forcing's value at a
/// switching point. Adjacent mappings of a cycle share their switching point,
/// so a cycle's solver computes each `sin_cos` once ([`Model::mapping_at`])
/// where [`Model::mapping`] computes it at both ends of every mapping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Phase {
    phi: f64,
    cos: f64,
    sin: f64,
}

impl Phase {
    /// The phase `phi = W t` and its `cos`, `sin`.
    #[inline]
    pub fn new(phi: f64) -> Self {
        let (sin, cos) = libm::sincos(phi);
        Self { phi, cos, sin }
    }
    /// `W t`.
    #[inline]
    pub fn phi(&self) -> f64 {
        self.phi
    }
    /// `cos(W t)`.
    #[inline]
    pub fn cos(&self) -> f64 {
        self.cos
    }
    /// `sin(W t)`.
    #[inline]
    pub fn sin(&self) -> f64 {
        self.sin
    }
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

    /// `DP_stick · DP_flow` of a flow mapping (`self`, Eq. 38) arriving at
    /// the stick mapping `stick` (Eq. 37) that follows it, ordered
    /// `(W t, x)`, free of the arrival's time, or `None` where the stick's
    /// `∂f/∂next` is singular.
    ///
    /// The stick starts where the flow's position equation puts it: its
    /// start enters only through `x_i − V t_i` (`∂f/∂prev` of Eq. 37 is the
    /// row `(1, −V/W)` over a zero row), which is `−f1`'s `∂f/∂next` row of
    /// Eq. 38 wherever the arrival's velocity is the boundary's. So
    /// `(∂f_stick/∂prev)(∂f_flow/∂next)⁻¹ = (a₀₀ / b₀₀) e₁e₁ᵀ` on the motion,
    /// and the product is `(∂f_stick/∂next)⁻¹ (a₀₀ / b₀₀) e₁ (∂f1_flow/∂prev)`.
    /// The factors' own product has `(v − V) / a` in place of the zero (`v`
    /// the flow's velocity at its arrival, `a` its acceleration): zero on
    /// the motion, but off it (a Newton iterate, a finite-difference
    /// stencil) a pole where the arrival turns tangential, as at a passable
    /// stick onset of a law with `mus g = F0`.
    pub fn local_jacobian_into_stick(&self, stick: &MappingEval) -> Option<Matrix2<f64>> {
        let swap = Matrix2::new(0.0, 1.0, 1.0, 0.0);
        let gain = stick.d_prev[(0, 0)] / self.d_next[(0, 0)];
        let inv = stick.d_next.try_inverse()?;
        // (x, W t) columns: e₁ times the flow's position row.
        let row = Matrix2::new(
            gain * self.d_prev[(0, 0)],
            gain * self.d_prev[(0, 1)],
            0.0,
            0.0,
        );
        let dp = swap * (inv * row) * swap;
        dp.iter().all(|v| v.is_finite()).then_some(dp)
    }
}

/// A generated piecewise-linear model: closed-form flows, mapping residuals
/// with analytic Jacobians, vector fields and force criteria, all specialized
/// at build time. Its parameters and linear part are those of the
/// [`FrictionOscillator`] it is.
///
/// Indices are those of [`ModelInfo`]: domains and boundaries lowest first,
/// mappings in `info(p).mappings` order. An out-of-range index yields NaN.
pub trait Model: FrictionOscillator {
    /// The description: the identity and the domains, boundaries and mappings.
    fn info(p: &Self::Params) -> &'static ModelInfo;

    /// Effective coefficients of domain `domain`.
    fn coefficients(p: &Self::Params, domain: usize) -> Coefficients;
    /// Velocity of boundary `boundary`.
    fn boundary_velocity(p: &Self::Params, boundary: usize) -> f64;
    /// `as`, when the model has a stick boundary.
    fn static_bound(p: &Self::Params) -> Option<f64>;
    /// `[x, v]` at phase `phi1` of the flow in `domain` from `(x0, v0)` at phase `phi0`.
    fn flow(p: &Self::Params, domain: usize, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2];
    /// `[F, DF]`: the normal vector field of `domain` and its rate along the flow.
    fn normal_field(p: &Self::Params, domain: usize, x: f64, y: f64, phi: f64) -> [f64; 2];
    /// Forces on the stick boundary at `(x, phi)`.
    fn stick_forces(p: &Self::Params, x: f64, phi: f64) -> Option<StickForces>;
    /// Residual of mapping `mapping` from `(x0, phi0)` to `(x1, phi1)`.
    #[inline]
    fn residual(
        p: &Self::Params,
        mapping: usize,
        x0: f64,
        phi0: f64,
        x1: f64,
        phi1: f64,
    ) -> Vector2<f64> {
        Self::residual_at(p, mapping, x0, Phase::new(phi0), x1, Phase::new(phi1))
    }
    /// [`Model::residual`] at phases whose `cos`, `sin` are already known.
    fn residual_at(
        p: &Self::Params,
        mapping: usize,
        x0: f64,
        a: Phase,
        x1: f64,
        b: Phase,
    ) -> Vector2<f64>;
    /// Residual and Jacobian blocks of mapping `mapping`.
    #[inline]
    fn mapping(
        p: &Self::Params,
        mapping: usize,
        x0: f64,
        phi0: f64,
        x1: f64,
        phi1: f64,
    ) -> MappingEval {
        Self::mapping_at(p, mapping, x0, Phase::new(phi0), x1, Phase::new(phi1))
    }
    /// [`Model::mapping`] at phases whose `cos`, `sin` are already known.
    fn mapping_at(
        p: &Self::Params,
        mapping: usize,
        x0: f64,
        a: Phase,
        x1: f64,
        b: Phase,
    ) -> MappingEval;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flow of Eq. 38 arriving at velocity `v` with acceleration `acc`
    /// (`W = 2`), and the stick of Eq. 37 on the boundary `V = 0.4` after it.
    fn flow_and_stick(v: f64, acc: f64) -> (MappingEval, MappingEval) {
        let (w, belt) = (2.0, 0.4);
        let flow = MappingEval {
            residual: Vector2::new(0.0, v - belt),
            d_prev: Matrix2::new(0.7, -1.3, 0.4, 2.1),
            d_next: Matrix2::new(-1.0, v / w, 0.0, acc / w),
        };
        let stick = MappingEval {
            residual: Vector2::zeros(),
            d_prev: Matrix2::new(1.0, -belt / w, 0.0, 0.0),
            d_next: Matrix2::new(-1.0, belt / w, -3.0, 0.9),
        };
        (flow, stick)
    }

    /// On the motion (`v = V`) the pair factor is the product of the two
    /// local Jacobians; off it, where the arrival is nearly tangential, the
    /// product has the pole `(v − V) / a` and the pair factor does not.
    #[test]
    fn a_flow_into_a_stick_is_its_product_without_the_arrival_pole() {
        for acc in [0.3, -2.0, 1e-3] {
            let (flow, stick) = flow_and_stick(0.4, acc);
            let product =
                stick.local_jacobian().expect("regular") * flow.local_jacobian().expect("regular");
            let pair = flow.local_jacobian_into_stick(&stick).expect("regular");
            let scale = product.abs().max();
            assert!(
                (pair - product).abs().max() <= 1e-13 * scale,
                "a = {acc}: {pair} against {product}"
            );
        }
        let (on, stick) = flow_and_stick(0.4, 0.3);
        let exact = on.local_jacobian_into_stick(&stick).expect("regular");
        let (off, _) = flow_and_stick(0.4 + 1e-9, 1e-12);
        let product =
            stick.local_jacobian().expect("regular") * off.local_jacobian().expect("regular");
        assert!(product.abs().max() > 1e2, "the pole: {product}");
        assert_eq!(off.local_jacobian_into_stick(&stick), Some(exact));
    }
}
