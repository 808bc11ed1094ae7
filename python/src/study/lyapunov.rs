//! `lyapunov`: the Lyapunov spectrum of the stroboscopic map along the
//! simulated trajectory, with its verdict (`stickslip lyapunov`).

use pyo3::prelude::*;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::lyapunov::{spectrum, LyapunovOptions};
use stickslip::output::lyapunov_report::LyapunovReport;
use stickslip::Model;

use crate::command::{params, with_model, Command, ModelSpec};
use crate::failure::Failure;

struct Lyapunov {
    set: Vec<(String, f64)>,
    start: (f64, f64, f64),
    opts: LyapunovOptions,
}

impl Command for Lyapunov {
    type Output = String;
    fn run<M: Model>(self, base: M::Params) -> Result<String, Failure> {
        let sim = Simulator::<M>::new(params::<M>(base, &self.set)?, SimOptions::default())?;
        let s = spectrum(&sim, self.start, self.opts)?;
        Ok(serde_json::to_string_pretty(&LyapunovReport::of(
            &s, self.opts,
        ))?)
    }
}

/// `stickslip lyapunov --json`: from `start = (x, v, W t)`, `transient`
/// forcing periods discarded, then `periods` accumulated (defaults as the CLI's).
#[pyfunction]
#[pyo3(signature = (model, set, start, transient = None, periods = None))]
pub fn lyapunov(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    start: (f64, f64, f64),
    transient: Option<u32>,
    periods: Option<u32>,
) -> PyResult<String> {
    let defaults = LyapunovOptions::default();
    let cmd = Lyapunov {
        set,
        start,
        opts: LyapunovOptions {
            transient: transient.unwrap_or(defaults.transient),
            periods: periods.unwrap_or(defaults.periods),
        },
    };
    Ok(py.detach(|| with_model(&model, cmd))?)
}
