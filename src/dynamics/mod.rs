//! The dynamics layer: motion in time from a state.
//!
//! * [`crossing`] — the event search on a closed-form flow, which cannot miss
//!   a crossing (Taylor exclusion with a Grönwall bound);
//! * [`simulate`] — exact event-driven simulation of a piecewise-linear model
//!   (flows, crossings, stick, grazing);
//! * [`response`] — the closed-form motion of one segment, its start's
//!   forced response computed once (what the event search evaluates);
//! * [`integrate`] — Dormand–Prince integration of a smooth friction law, with
//!   belt-speed events and stick by force criteria.
//!
//! Depends only on [`crate::model`](mod@crate::model).
//!
//! ```
//! use stickslip::dynamics::simulate::{EventKind, SimOptions, Simulator};
//! use stickslip::models::paper::{Paper, Params};
//!
//! // Ten forcing periods from rest at W = 3.7, Q0 = 70, every event listed.
//! let p = Params { W: 3.7, Q0: 70.0, ..Params::default() };
//! let sim = Simulator::<Paper>::new(p, SimOptions::default())?;
//! let mut events = Vec::new();
//! let start = sim.start(0.0, 0.0, 0.0)?;
//! sim.run(start, 10.0 * std::f64::consts::TAU, |e| events.push(*e))?;
//! // The mass sticks to the belt (v = V = 3) and slips again, every period.
//! assert!(events.iter().any(|e| e.kind == EventKind::StickOnset));
//! assert!(events.iter().all(|e| e.phase >= 0.0 && e.x.is_finite()));
//! # Ok::<(), stickslip::dynamics::simulate::SimError>(())
//! ```

pub mod crossing;
pub mod integrate;
pub mod response;
pub mod simulate;
pub mod tangent;
