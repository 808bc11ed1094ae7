//! The model layer: what a generated model is to the rest of the library.
//!
//! Every model file generates one family of types:
//!
//! ```text
//!                    FrictionOscillator      Params, identity(p), oscillator(p)
//!                    /                \
//!               Model                  SmoothModel
//!   info(p): &ModelInfo, flows,       info(p): &SmoothInfo, belt(),
//!   mappings, fields, forces          static_bound(), kinetic()
//! ```
//!
//! * [`FrictionOscillator`] — every generated model: its run-time `Params`,
//!   its [`Identity`] (name, doc, parameters, the free ones) and its linear
//!   part ([`Oscillator`]);
//! * [`Model`] — a piecewise-linear model or scene, solved in closed form;
//!   its [`ModelInfo`] is an [`Identity`] plus domains, boundaries, mappings.
//!   Every analysis is generic over `M: Model`;
//! * [`SmoothModel`] — a model with a smooth friction law, integrated
//!   numerically; its [`SmoothInfo`] is an [`Identity`] plus the law. Its
//!   `pieces` scenes are ordinary [`Model`]s.
//!
//! One registry holds them all: [`crate::models::ALL`] lists an [`Entry`] per
//! model and scene, saying which kind it is, and [`crate::models::visit`]
//! runs a [`ModelVisitor`] — one method per kind — with the one chosen by name.
//!
//! The modules:
//!
//! * [`info`] — the static descriptions ([`Identity`], [`ModelInfo`]: parameters,
//!   domains, boundaries, mappings), written by the generator;
//! * [`param`] — run-time parameter sets, their bounds and checks;
//! * [`oscillator`] — the [`FrictionOscillator`] trait, the linear part and the
//!   effective coefficients of a domain;
//! * [`piecewise`] — the [`Model`] trait every piecewise-linear model implements;
//! * [`smooth`] — the [`SmoothModel`] trait of models with a smooth law;
//! * [`registry`] — the registry's [`Entry`] and [`ModelVisitor`];
//! * [`homogeneous`] — the closed-form homogeneous solution the generated flows call;
//! * [`loaded`] — models loaded at run time: a model file compiled to
//!   machine code by the generator's run-time back end, behind the same
//!   traits ([`loaded::Loaded`], [`loaded::LoadedSmooth`]).
//!
//! The compiled-in models themselves are [`crate::models`]. Nothing here
//! depends on a layer above (dynamics, orbit, study, output).

pub mod homogeneous;
pub mod info;
pub mod loaded;
pub mod oscillator;
pub mod param;
pub mod piecewise;
pub mod registry;
pub mod smooth;

pub use info::{
    Bound, BoundaryInfo, DomainInfo, Identity, MappingInfo, MappingKind, ModelInfo, ParamInfo, Side,
};
pub use oscillator::{Coefficients, ForcedResponse, FrictionOscillator, Oscillator, Regime};
pub use param::{ParamError, ParamSet};
pub use piecewise::{MappingEval, Model, Phase, StickForces};
pub use registry::{Entry, ModelVisitor};
pub use smooth::{SmoothInfo, SmoothModel};
