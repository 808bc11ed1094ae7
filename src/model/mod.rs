//! The model layer: what a generated model is to the rest of the library.
//!
//! * [`info`] — the static description of a model (parameters, domains,
//!   boundaries, mappings), written by the generator;
//! * [`param`] — run-time parameter sets, their bounds and checks;
//! * [`oscillator`] — the linear part and the effective coefficients of a domain;
//! * [`piecewise`] — the [`Model`] trait every piecewise-linear model implements;
//! * [`smooth`] — the [`SmoothModel`](smooth::SmoothModel) trait of models with a smooth law;
//! * [`homogeneous`] — the closed-form homogeneous solution the generated flows call.
//!
//! The compiled-in models themselves are [`crate::models`]. Nothing here
//! depends on a layer above (dynamics, orbit, study, output).

pub mod homogeneous;
pub mod info;
pub mod oscillator;
pub mod param;
pub mod piecewise;
pub mod smooth;

pub use info::{
    Bound, BoundaryInfo, DomainInfo, MappingInfo, MappingKind, ModelInfo, ParamInfo, Side,
};
pub use oscillator::{Coefficients, Oscillator, Regime};
pub use param::{ParamError, ParamSet};
pub use piecewise::{MappingEval, Model, ModelVisitor, StickForces};
