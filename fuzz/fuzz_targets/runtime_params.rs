//! Arbitrary f64 parameters, start states, structures and guesses into the
//! runtime entry points: `ParamSet::check`, `Simulator::new`, `start`, a
//! bounded `run`, `Structure::parse` + `motion::solve`, `attractor::find`.
//! Every call must return (a value or a typed error), never panic or hang.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../harness.rs"]
mod harness;

fuzz_target!(|data: &[u8]| harness::runtime(data));
