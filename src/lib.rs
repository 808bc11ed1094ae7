//! # stickslip
//!
//! Exact periodic motions of periodically forced friction oscillators with
//! piecewise-linear kinetic friction and a static-friction jump, from
//! declarative model files (`models/*.ssm`, see the README).
//!
//! Each model is compiled at build time into specialized Rust: closed-form
//! flows valid in every damping regime, mapping residuals with exact
//! Jacobians, normal vector fields and force criteria. The runtime reaches
//! them through the [`Model`] trait.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

// Generated code names this crate `::stickslip`, inside it as in user crates.
extern crate self as stickslip;

pub use nalgebra;

pub mod model;
pub mod models;

pub mod bifurcation;
pub mod dynamics;
pub mod orbit;
pub mod output;
pub mod study;

pub use model::{
    Bound, BoundaryInfo, Coefficients, DomainInfo, Entry, FrictionOscillator, Identity,
    MappingEval, MappingInfo, MappingKind, Model, ModelInfo, ModelVisitor, Oscillator, ParamError,
    ParamInfo, ParamSet, Phase, Regime, Side, SmoothInfo, SmoothModel, StickForces,
};

/// Generate a model inline, or from a model file of your crate:
///
/// ```ignore
/// stickslip::model!(file = "models/my_model.ssm");
/// stickslip::model! { model tiny { /* ... */ } }
/// ```
///
/// Either form expands to `pub mod NAME { ... }` with the same items as the
/// built-in models (see [`models`]).
pub use stickslip_macros::model;

#[doc(hidden)]
pub use stickslip_macros::model_source;
