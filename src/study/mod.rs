//! The study layer: analyses over parameters, built on the orbit layer.
//!
//! * [`sweep`] — one-parameter continuation with located transitions;
//! * [`search`] — every coexisting stable motion, from many starts;
//! * [`map`] — two-parameter maps of what lives where, parallel and resumable;
//! * [`basins`] — basins of attraction and basin stability, parallel and resumable;
//! * [`diagram`] — the brute-force orbit diagram, swept up and down, with exponents and branches;
//! * [`equilibria`] — steady sliding of an unforced model along a parameter, with its changes of stability located;
//! * [`law`] — a smooth law itself along a parameter: steady sliding and every cycle, the Hopf point and the stick-slip cycle's fold located;
//! * [`trade`] — the speed/accuracy trade of a smooth law's N-piece models;
//! * `record` — the resumable record file that `map` and `basins` keep;
//! * `progress` — how `map` and `basins` report their finished points (a bar, a shared counter).
//!
//! ```
//! use stickslip::models::coulomb::{Coulomb, Params};
//! use stickslip::study::sweep::{sweep, SweepOptions};
//!
//! // Den Hartog's oscillator (V = 0) swept in W: the frequency response.
//! let base = Params { V: 0.0, mus: 0.1, muk: 0.1, Q0: 1.0, ..Params::default() };
//! let s = sweep::<Coulomb>(base, "W", 1.5, 2.5, 5, SweepOptions::default())?;
//! for point in &s.points {
//!     for m in &point.motions {
//!         // Above resonance the amplitude falls with W.
//!         assert!(m.max_abs_x > 0.0 && m.max_abs_x < 1.0, "{m:?}");
//!     }
//! }
//! let amplitudes: Vec<f64> = s.points.iter().map(|p| p.motions[0].max_abs_x).collect();
//! assert!(amplitudes.windows(2).all(|w| w[1] < w[0]));
//! # Ok::<(), stickslip::study::sweep::SweepError>(())
//! ```

pub mod basins;
pub mod curves;
pub mod diagram;
pub mod equilibria;
pub mod law;
pub mod map;
mod progress;
pub(crate) mod record;
pub mod search;
pub mod sweep;
pub mod trade;
