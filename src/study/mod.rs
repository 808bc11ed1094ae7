//! The study layer: analyses over parameters, built on the orbit layer.
//!
//! * [`sweep`] — one-parameter continuation with located transitions;
//! * [`search`] — every coexisting stable motion, from many starts;
//! * [`map`] — two-parameter maps of what lives where, parallel and resumable;
//! * [`basins`] — basins of attraction and basin stability, parallel and resumable;
//! * [`diagram`] — the brute-force orbit diagram, swept up and down, with exponents and branches;
//! * [`trade`] — the speed/accuracy trade of a smooth law's N-piece models;
//! * `record` — the resumable record file that `map` and `basins` keep;
//! * `progress` — how `map` and `basins` report their finished points (a bar, a shared counter).

pub mod basins;
pub mod curves;
pub mod diagram;
pub mod map;
mod progress;
pub(crate) mod record;
pub mod search;
pub mod sweep;
pub mod trade;
