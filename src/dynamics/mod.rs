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

pub mod crossing;
pub mod integrate;
pub mod response;
pub mod simulate;
pub mod tangent;
