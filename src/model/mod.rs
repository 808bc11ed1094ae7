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
//! ```
//! use stickslip::models::paper::{Paper, Params};
//! use stickslip::{FrictionOscillator, Model, ParamSet};
//!
//! // Parameters by name, checked (bounds, boundary order, static ≥ kinetic).
//! let p = Params::from_pairs(Paper::INFO, &[("W", 3.7), ("Q0", 70.0)])?;
//! assert_eq!(p.W, 3.7);
//! assert!(Params::from_pairs(Paper::INFO, &[("W", -1.0)]).is_err());
//! // Domain 1's effective damping 2 d_j and stiffness (SPEC Eq. A.1).
//! let j = Paper::INFO.domains.iter().position(|d| d.label == 1).expect("domain 1");
//! let co = Paper::coefficients(&p, j);
//! assert!((co.two_d - 0.10).abs() < 1e-12 && (co.c - 30.0).abs() < 1e-12);
//! // Its closed-form flow from (x, v) = (0, 3.5) at W t = 0 to W t = 0.1.
//! let [x, v] = Paper::flow(&p, j, 0.0, 3.5, 0.0, 0.1);
//! assert!(x > 0.0 && v.is_finite());
//! assert_eq!(Paper::oscillator(&p).frequency, 3.7);
//! # Ok::<(), stickslip::ParamError>(())
//! ```
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
pub use oscillator::{
    forced_rounding, set_forced_rounding, Coefficients, ForcedResponse, ForcedRounding,
    FrictionOscillator, Oscillator, Regime,
};
pub use param::{ParamError, ParamSet};
pub use piecewise::{MappingEval, Model, Phase, StickForces};
pub use registry::{Entry, ModelVisitor};
pub use smooth::{SmoothInfo, SmoothModel};
