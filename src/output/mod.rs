//! The output layer: what a study looks like to a reader.
//!
//! * [`report`] — the report of `orbit` and `simulate`, with its JSON schema;
//! * [`text`] — the text forms: a report, the trade's table;
//! * [`lyapunov_report`] — the Lyapunov spectrum as text or JSON;
//! * [`history`] — a motion's sampled time history, and its CSV;
//! * [`describe`] — a model's description (text and JSON);
//! * [`curves_table`] — a curves run as text or JSON; [`basins_summary`] — a basin run as JSON;
//! * [`sweep_table`] — a sweep as text or JSON; [`map_summary`] — what a map run did;
//! * [`figure`] — the figures (SVG or PNG): a motion's six panels, a sweep,
//!   a map, the trade.
//!
//! Depends on every layer below; nothing below depends on it.

pub mod basins_summary;
pub mod curves_table;
pub mod describe;
pub mod figure;
pub mod history;
pub mod lyapunov_report;
pub mod map_summary;
pub mod report;
pub mod settled;
pub mod sweep_table;
pub mod text;
