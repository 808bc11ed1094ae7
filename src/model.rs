//! What a generated model is to the runtime: the [`Model`] trait and the
//! static [`ModelInfo`] describing its domains, boundaries and mappings.
//!
//! Analyses are generic over `M: Model`; they never refer to a model by name.

use nalgebra::{Matrix2, Vector2};
use serde::Serialize;

use crate::param::{Bound, ParamSet};

/// Effective coefficients of one domain: `x'' + two_d x' + c x = A0 cos(W t) - b` (SPEC Eq. A.1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Coefficients {
    /// `2 d_j = 2 d + f_j'(v)`: effective damping (may be negative).
    pub two_d: f64,
    /// `c_j`.
    pub c: f64,
    /// `b_j = f_j(0)`, the constant part of the friction law.
    pub b: f64,
}

impl Coefficients {
    /// Returned for an out-of-range domain index.
    pub const NAN: Self = Self {
        two_d: f64::NAN,
        c: f64::NAN,
        b: f64::NAN,
    };

    /// Damping regime at these coefficients.
    pub fn regime(&self) -> Regime {
        Regime::classify(self.two_d, self.c)
    }
}

/// The linear part of the oscillator: `x'' + 2 damping x' + stiffness x = amplitude cos(frequency t) - f(x')`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Oscillator {
    /// `m`.
    pub mass: f64,
    /// `d`.
    pub damping: f64,
    /// `c`.
    pub stiffness: f64,
    /// `A0 = Q0 / m`.
    pub amplitude: f64,
    /// `W`.
    pub frequency: f64,
}

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

/// Damping regime of a domain (sign of `d_j² - c_j`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Regime {
    /// `d_j² < c_j`: damped oscillation (or growing, for negative damping).
    Underdamped,
    /// `d_j² = c_j`.
    Critical,
    /// `d_j² > c_j`: two real exponents.
    Overdamped,
}

impl Regime {
    /// The regime of `x'' + two_d x' + c x = 0`.
    pub fn classify(two_d: f64, c: f64) -> Self {
        let d = 0.5 * two_d;
        let w2 = d * d - c;
        if w2 < 0.0 {
            Regime::Underdamped
        } else if w2 > 0.0 {
            Regime::Overdamped
        } else {
            Regime::Critical
        }
    }

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Regime::Underdamped => "underdamped",
            Regime::Critical => "critical",
            Regime::Overdamped => "overdamped",
        }
    }
}

/// Side of a boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Towards higher velocities.
    Above,
    /// Towards lower velocities.
    Below,
}

/// Kind of a mapping (SPEC §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MappingKind {
    /// Leaves a boundary and returns to it (Eq. 34).
    Local,
    /// Crosses a domain (Eq. 35).
    Global,
    /// Sticks on the stick boundary (Eq. 36).
    Stick,
}

/// A parameter as declared in the model file.
#[derive(Clone, Copy, Debug)]
pub struct ParamInfo {
    /// Name.
    pub name: &'static str,
    /// Default value.
    pub default: f64,
    /// Declared bounds.
    pub bounds: &'static [(Bound, f64)],
    /// Doc comment.
    pub doc: &'static str,
    /// Whether this instance takes it at run time (else it is folded into constants).
    pub free: bool,
}

/// A velocity boundary.
#[derive(Clone, Copy, Debug)]
pub struct BoundaryInfo {
    /// Label (`Sigma1`).
    pub label: &'static str,
    /// Its number (`1`), used in mapping names.
    pub number: u32,
    /// Whether static friction acts here.
    pub stick: bool,
    /// Doc comment.
    pub doc: &'static str,
}

/// A domain (velocity band).
#[derive(Clone, Copy, Debug)]
pub struct DomainInfo {
    /// Label (`1`).
    pub label: u32,
    /// Index of the lower boundary (`None`: unbounded).
    pub lower: Option<usize>,
    /// Index of the upper boundary (`None`: unbounded).
    pub upper: Option<usize>,
    /// Regime when fixed at build time (its coefficients do not depend on a free parameter).
    pub fixed_regime: Option<Regime>,
    /// Doc comment.
    pub doc: &'static str,
}

/// A generated mapping.
#[derive(Clone, Copy, Debug)]
pub struct MappingInfo {
    /// `j_βα` (`3_31`; `0_11` for stick).
    pub name: &'static str,
    /// Domain index (`None` for stick).
    pub domain: Option<usize>,
    /// Boundary index it starts on.
    pub from: usize,
    /// Boundary index it ends on.
    pub to: usize,
    /// Local, global or stick.
    pub kind: MappingKind,
    /// For the stick mapping, the side it leaves to.
    pub exit: Option<Side>,
}

/// Static description of a generated model or scene.
#[derive(Clone, Copy, Debug)]
pub struct ModelInfo {
    /// `paper`, or `paper::sweep_w` for a scene.
    pub name: &'static str,
    /// The model's name.
    pub model: &'static str,
    /// The scene's name.
    pub scene: Option<&'static str>,
    /// The model's doc comment.
    pub doc: &'static str,
    /// Every parameter of the model.
    pub params: &'static [ParamInfo],
    /// Indices into `params` of the free ones, in the order of the `Params` fields.
    pub free: &'static [usize],
    /// Boundaries, lowest velocity first.
    pub boundaries: &'static [BoundaryInfo],
    /// Domains, lowest band first.
    pub domains: &'static [DomainInfo],
    /// The generated mappings (the stick mapping appears once per exit side).
    pub mappings: &'static [MappingInfo],
    /// The structures a scene studies.
    pub structures: &'static [&'static str],
}

impl ModelInfo {
    /// Index of the stick boundary.
    pub fn stick_boundary(&self) -> Option<usize> {
        self.boundaries.iter().position(|b| b.stick)
    }

    /// Distinct mapping names, in generation order.
    pub fn mapping_names(&self) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = Vec::new();
        for m in self.mappings {
            if !out.contains(&m.name) {
                out.push(m.name);
            }
        }
        out
    }

    /// Index of the mapping `name`; for the stick mapping, the one leaving to
    /// `exit` (the first of the two when `exit` is `None`).
    pub fn mapping_index(&self, name: &str, exit: Option<Side>) -> Option<usize> {
        self.mappings
            .iter()
            .position(|m| m.name == name && (exit.is_none() || m.exit.is_none() || m.exit == exit))
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
