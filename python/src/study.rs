//! The analyses over parameters: `sweep` (and, as the CLI has them, `map`,
//! `curves`, `lyapunov`, `basins`), each returning the CLI's JSON.

use pyo3::prelude::*;
use stickslip::output::sweep_table;
use stickslip::study::sweep::{sweep_values, SweepOptions};
use stickslip::Model;

use crate::command::{params, with_model, Command};
use crate::failure::Failure;

/// Add this module's functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    Ok(())
}

struct Sweep {
    set: Vec<(String, f64)>,
    name: String,
    values: Vec<f64>,
    starts: usize,
    every: usize,
    unstable: bool,
}

impl Command for Sweep {
    type Output = String;
    fn run<M: Model>(self) -> Result<String, Failure> {
        let opts = SweepOptions {
            starts: self.starts,
            every: self.every,
            ..SweepOptions::default()
        };
        let base = params::<M>(&self.set)?;
        let sw = sweep_values::<M>(base, &self.name, &self.values, opts)?;
        let sw = if self.unstable { sw } else { sw.stable_only() };
        Ok(sweep_table::json(&sw)?)
    }
}

/// `stickslip sweep --json`: parameter `name` over `values` (increasing).
// One argument per Python keyword.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (model, set, name, values, starts = None, every = None, unstable = true))]
pub fn sweep(
    py: Python<'_>,
    model: &str,
    set: Vec<(String, f64)>,
    name: String,
    values: Vec<f64>,
    starts: Option<usize>,
    every: Option<usize>,
    unstable: bool,
) -> PyResult<String> {
    let defaults = SweepOptions::default();
    let cmd = Sweep {
        set,
        name,
        values,
        starts: starts.unwrap_or(defaults.starts),
        every: every.unwrap_or(defaults.every),
        unstable,
    };
    Ok(py.detach(|| with_model(model, cmd))?)
}
