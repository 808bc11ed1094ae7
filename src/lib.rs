//! # stickslip
//!
//! Exact periodic motions of periodically forced friction oscillators with
//! piecewise-linear kinetic friction and a static-friction jump, from
//! declarative model files (`models/*.ssm`; the guide, "Writing a model").
//!
//! Each model is compiled at build time into specialized Rust: closed-form
//! flows valid in every damping regime, mapping residuals with exact
//! Jacobians, normal vector fields and force criteria. The runtime reaches
//! them through the [`Model`] trait.
//!
//! The library is built in layers, each using only those below it; each
//! layer's page has a runnable example:
//!
//! | layer | what it does | example |
//! |---|---|---|
//! | [`model`](mod@model), [`models`] | the generated models: parameters, flows, mappings | [`model`](mod@model) |
//! | [`dynamics`] | motion in time: exact event-driven simulation | [`dynamics`] |
//! | [`orbit`] | periodic motions: Newton, admissibility, stability, attractors | [`orbit`] |
//! | [`bifurcation`] | branches by continuation, bifurcations, two-parameter curves | [`bifurcation`] |
//! | [`study`] | sweeps, maps, curves, basins, orbit diagrams, the trade | [`study`] |
//! | [`output`] | text, JSON, CSV and figures | |
//!
//! ```
//! use stickslip::models::paper::{Paper, Params};
//! use stickslip::study::sweep::{sweep, SweepOptions};
//!
//! // The paper's model at Q0 = 70, W swept over [3.6, 3.8]: where the
//! // stick-slip motion P_{3_31 0_11 3_13 4_33} gains a slip above the belt.
//! let base = Params { Q0: 70.0, ..Params::default() };
//! let s = sweep::<Paper>(base, "W", 3.6, 3.8, 9, SweepOptions::default())?;
//! let end = s
//!     .transitions
//!     .iter()
//!     .find(|t| t.from == "P_{3_31 0_11 3_13 4_33}" && t.to == "P_{3_31 0_11 1_11 3_13 4_33}")
//!     .expect("the transition lies in the window");
//! assert!((end.value - 3.7550059120).abs() < 1e-8);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The user's guide (`docs/guide/`) explains each capability with a worked
//! example; the model language is in its chapter "Writing a model".
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
