//! The output layer: what a study looks like to a reader.
//!
//! * [`report`] — text, JSON and CSV of motions and simulations;
//! * [`describe`] — a model's description (text and JSON);
//! * figures: [`plot`] (a motion's six panels), [`sweep_plot`], [`map_plot`],
//!   [`trade_plot`].
//!
//! Depends on every layer below; nothing below depends on it.

pub mod describe;
pub mod map_plot;
pub mod plot;
pub mod report;
pub mod sweep_plot;
pub mod trade_plot;
