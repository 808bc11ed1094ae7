//! `orbit_diagram`: the brute-force bifurcation diagram (stroboscopic
//! samples swept up and down, the largest exponent, the sweep's branches at
//! the section), as `stickslip orbit-diagram --json`.

use pyo3::prelude::*;
use stickslip::study::diagram::{
    orbit_diagram as diagram, overlay_branches, DiagramError, DiagramOptions,
};
use stickslip::Model;

use crate::command::{params, with_model, Command, ModelSpec};
use crate::failure::{Failure, Kind};

struct Diagram {
    set: Vec<(String, f64)>,
    name: String,
    range: (f64, f64, usize),
    opts: DiagramOptions,
    branches: bool,
}

impl Command for Diagram {
    type Output = (String, Vec<String>);
    fn run<M: Model>(self, base: M::Params) -> Result<Self::Output, Failure> {
        let base = params::<M>(base, &self.set)?;
        let (from, to, count) = self.range;
        let mut d =
            diagram::<M>(base, &self.name, from, to, count, self.opts).map_err(|e| match e {
                DiagramError::Params(p) => p.into(),
                DiagramError::Range(_) => Failure::new(Kind::Input, e),
                DiagramError::NoSamples => Failure::new(Kind::Input, "periods must be at least 1"),
            })?;
        let mut notes = Vec::new();
        if self.branches {
            notes.extend(overlay_branches::<M>(base, &mut d));
        }
        Ok((serde_json::to_string_pretty(&d)?, notes))
    }
}

/// `stickslip orbit-diagram --json`: parameter `name` over `count` values
/// from `from` to `to`, swept up and down.
// One argument per Python keyword.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (model, set, name, from_, to, count, transient = None, periods = None, lyapunov = None, branches = true))]
pub fn orbit_diagram(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    name: String,
    from_: f64,
    to: f64,
    count: usize,
    transient: Option<u32>,
    periods: Option<u32>,
    lyapunov: Option<u32>,
    branches: bool,
) -> PyResult<(String, Vec<String>)> {
    let d = DiagramOptions::default();
    let opts = DiagramOptions {
        transient: transient.unwrap_or(d.transient),
        periods: periods.unwrap_or(d.periods),
        lyapunov: lyapunov.unwrap_or(d.lyapunov),
        ..d
    };
    let cmd = Diagram {
        set,
        name,
        range: (from_, to, count),
        opts,
        branches,
    };
    Ok(py.detach(|| with_model(&model, cmd))?)
}
