//! The analyses over parameters and starts, each returning the CLI's JSON:
//! `sweep` (here), [`map`], [`curves`], [`lyapunov`], [`basins`],
//! [`equilibria`].

mod basins;
mod curves;
mod equilibria;
mod lyapunov;
mod map;

use pyo3::prelude::*;
use stickslip::output::sweep_table;
use stickslip::study::map::{AxisError, GridAxis};
use stickslip::study::sweep::{sweep_values, SweepOptions};
use stickslip::Model;

use crate::command::{params, with_model, Command, ModelSpec};
use crate::failure::Failure;

/// Add this module's functions.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(map::map, m)?)?;
    m.add_function(wrap_pyfunction!(curves::curves, m)?)?;
    m.add_function(wrap_pyfunction!(lyapunov::lyapunov, m)?)?;
    m.add_function(wrap_pyfunction!(basins::basins, m)?)?;
    m.add_function(wrap_pyfunction!(equilibria::equilibria, m)?)?;
    Ok(())
}

/// A grid axis as given from Python, `(name, from, to, count)`, checked as
/// the CLI checks `NAME=FROM:TO:COUNT`: a count of at least 1, finite
/// bounds (the name is checked by the analysis: a parameter of the model).
pub(crate) fn axis(name: &str, from: f64, to: f64, count: i64) -> Result<GridAxis, Failure> {
    let text = format!("{name}={from}:{to}:{count}");
    let Some(count) = usize::try_from(count).ok().filter(|&n| n > 0) else {
        return Err(AxisError::Count {
            text,
            value: count.to_string(),
        }
        .into());
    };
    if let Some(bad) = [from, to].into_iter().find(|b| !b.is_finite()) {
        return Err(AxisError::NotFinite {
            text,
            value: bad.to_string(),
        }
        .into());
    }
    Ok(GridAxis {
        name: name.to_string(),
        from,
        to,
        count,
    })
}

struct Sweep {
    set: Vec<(String, f64)>,
    name: String,
    values: Vec<f64>,
    starts: usize,
    every: usize,
    unstable: bool,
    max_mappings: Option<usize>,
    max_period: Option<u32>,
}

impl Command for Sweep {
    type Output = String;
    fn run<M: Model>(self, base: M::Params) -> Result<String, Failure> {
        let opts = SweepOptions {
            starts: self.starts,
            every: self.every,
            max_mappings: self.max_mappings,
            max_period: self.max_period,
            ..SweepOptions::default()
        };
        let base = params::<M>(base, &self.set)?;
        let sw = sweep_values::<M>(base, &self.name, &self.values, opts)?;
        let sw = if self.unstable { sw } else { sw.stable_only() };
        Ok(sweep_table::json(&sw)?)
    }
}

/// `stickslip sweep --json`: parameter `name` over `values` (increasing).
// One argument per Python keyword.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (model, set, name, values, starts = None, every = None, unstable = true, max_mappings = None, max_period = None))]
pub fn sweep(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    name: String,
    values: Vec<f64>,
    starts: Option<usize>,
    every: Option<usize>,
    unstable: bool,
    max_mappings: Option<usize>,
    max_period: Option<u32>,
) -> PyResult<String> {
    let defaults = SweepOptions::default();
    let cmd = Sweep {
        set,
        name,
        values,
        starts: starts.unwrap_or(defaults.starts),
        every: every.unwrap_or(defaults.every),
        unstable,
        max_mappings,
        // 0: no limit, as on the command line.
        max_period: match max_period {
            None => defaults.max_period,
            Some(0) => None,
            Some(n) => Some(n),
        },
    };
    Ok(py.detach(|| with_model(&model, cmd))?)
}
