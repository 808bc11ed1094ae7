//! The orbit layer: periodic motions and what they are.
//!
//! * [`structure`] — mapping structures `P_{σm … σ1}` (SPEC §6);
//! * [`periodic`] — Newton on the block-cyclic mapping system;
//! * [`family`] — minimum-norm Newton onto a neutral family (DP has eigenvalue 1);
//! * [`admissible`] — admissibility of a solved motion, with signed margins;
//! * [`extrema`] — the velocity extrema of a flow segment, from the closed form;
//! * [`stability`] — the monodromy matrix and its eigenvalues;
//! * [`motion`] — a solved, checked periodic motion;
//! * [`attractor`] — what a simulation settles on: a motion, a stick, a family;
//! * [`steady`] — a domain's steady forced response in closed form (the no-motion regime);
//! * [`known`] — known stable motions seen stroboscopically, and a settle that stops near one;
//! * [`lyapunov`] — Lyapunov exponents of the stroboscopic map from the exact tangent map.
//!
//! Depends on [`crate::model`](mod@crate::model) and [`crate::dynamics`].

pub mod admissible;
pub mod attractor;
pub mod extrema;
pub mod family;
pub mod guess;
pub mod known;
pub mod lyapunov;
pub mod motion;
pub mod periodic;
pub mod stability;
pub mod steady;
pub mod structure;
