//! The orbit layer: periodic motions and what they are.
//!
//! * [`structure`] — mapping structures `P_{σm … σ1}` (SPEC §6);
//! * [`periodic`] — Newton on the block-cyclic mapping system;
//! * [`family`] — minimum-norm Newton onto a neutral family (DP has eigenvalue 1);
//! * [`admissible`] — admissibility of a solved motion, with signed margins;
//! * [`extrema`] — the velocity extrema of a flow segment, from the closed form;
//! * [`amplitude`] — a motion's largest `|x|` and `|v|` over its cycle, from the closed form;
//! * [`stability`] — the monodromy matrix and its eigenvalues;
//! * [`motion`] — a solved, checked periodic motion;
//! * [`attractor`] — what a simulation settles on: a motion, a stick, a family;
//! * [`autonomous`] — cycles of an unforced model by Newton, the period an unknown;
//! * [`smooth`] — a smooth law's steady sliding or self-excited cycle, by the integrator and shooting on `v = 0`;
//! * [`equilibrium`] — steady sliding of an unforced oscillator, its linearisation and loss of stability;
//! * [`steady`] — a domain's steady forced response in closed form (the no-motion regime);
//! * [`known`] — known stable motions seen stroboscopically, and a settle that stops near one;
//! * [`lyapunov`] — Lyapunov exponents of the stroboscopic map from the exact tangent map.
//!
//! Depends on [`crate::model`](mod@crate::model) and [`crate::dynamics`].
//!
//! ```
//! use stickslip::dynamics::simulate::{SimOptions, Simulator};
//! use stickslip::models::paper::{Paper, Params};
//! use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
//! use stickslip::orbit::motion::solve;
//! use stickslip::orbit::periodic::NewtonOptions;
//! use stickslip::orbit::structure::Structure;
//! use stickslip::Model;
//!
//! let p = Params { W: 3.7, Q0: 70.0, ..Params::default() };
//! let sim = Simulator::<Paper>::new(p, SimOptions::default())?;
//! // Simulate from rest until the motion settles; it is named and refined.
//! let Attractor::Periodic(m) = attractor::find(&sim, sim.start(0.0, 0.0, 0.0)?, AttractorOptions::default())?
//! else {
//!     panic!("a periodic motion")
//! };
//! assert_eq!(m.structure.notation(Paper::INFO), "P_{3_31 0_11 3_13 4_33}");
//! assert!(m.is_admissible() && m.stability.expect("DP exists").is_stable());
//! // Newton on the same structure from a rough guess finds the same motion.
//! let structure = Structure::parse(Paper::INFO, "P_{3_31 0_11 3_13 4_33}", 1)?;
//! let guess = m.points.iter().map(|q| { let mut q = *q; q.x += 1e-3; q }).collect();
//! let again = solve(&sim, structure, guess, NewtonOptions::default());
//! assert!(again.is_admissible());
//! assert!((again.points[0].x - m.points[0].x).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod admissible;
pub mod amplitude;
pub mod attractor;
pub mod autonomous;
pub mod equilibrium;
pub mod extrema;
pub mod family;
pub mod guess;
pub mod known;
pub mod lyapunov;
pub mod motion;
pub mod periodic;
pub mod smooth;
pub mod stability;
pub mod steady;
pub mod structure;
