//! The smooth law itself: what a simulation by the integrator settles to
//! (`stickslip simulate` of a model with a smooth law and no scene), and
//! its sweep (`stickslip sweep` of such a model: steady sliding and every
//! cycle at each value, the Hopf point and the stick-slip cycle's end).

use pyo3::prelude::*;
use stickslip::orbit::smooth::{simulate, SmoothOptions};
use stickslip::study::law::sweep_law_at;
use stickslip::{ModelVisitor, SmoothModel};

use crate::command::{lookup, params, ModelSpec};
use crate::failure::{Failure, Kind};

/// The simulation of a smooth law at `set` from `start`.
struct Settle {
    set: Vec<(String, f64)>,
    start: (f64, f64, f64),
    periods: Option<u32>,
}

impl ModelVisitor for Settle {
    type Output = Result<String, Failure>;
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some((|| {
            let p = params::<M>(base, &self.set)?;
            let mut options = SmoothOptions::default();
            if let Some(k) = self.periods {
                if k == 0 {
                    return Err(Failure::new(Kind::Input, "periods must be at least 1"));
                }
                options.max_returns = k;
            }
            let settled = simulate::<M>(p, self.start, options)?;
            serde_json::to_string_pretty(&settled).map_err(Failure::from)
        })())
    }
}

/// `stickslip simulate --json` of the smooth law itself; `None` when the
/// model is piecewise-linear (a compiled-in scene or a file's scene).
#[pyfunction]
#[pyo3(signature = (model, set, start, periods = None))]
pub fn simulate_law(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    start: (f64, f64, f64),
    periods: Option<u32>,
) -> PyResult<Option<String>> {
    let model = lookup(&model)?;
    let request = Settle {
        set,
        start,
        periods,
    };
    let out = py.detach(|| -> Result<_, Failure> { Ok(model.visit(request)?) })?;
    Ok(out.transpose()?)
}

/// The sweep of a smooth law along `name` at `values`, at `set`.
struct Swept {
    set: Vec<(String, f64)>,
    name: String,
    values: Vec<f64>,
}

impl ModelVisitor for Swept {
    type Output = Result<String, Failure>;
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some((|| {
            let p = params::<M>(base, &self.set)?;
            let sweep = sweep_law_at::<M>(p, &self.name, &self.values)?;
            serde_json::to_string_pretty(&sweep).map_err(Failure::from)
        })())
    }
}

/// `stickslip sweep --json` of the smooth law itself along `name` at
/// `values`; `None` when the model is piecewise-linear.
#[pyfunction]
#[pyo3(signature = (model, set, name, values))]
pub fn sweep_law(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    name: String,
    values: Vec<f64>,
) -> PyResult<Option<String>> {
    if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
        return Err(
            Failure::new(Kind::Input, format!("values: {bad} is not a finite number")).into(),
        );
    }
    if values.windows(2).any(|w| w[1] <= w[0]) {
        return Err(Failure::new(Kind::Input, "values: must be strictly increasing").into());
    }
    let model = lookup(&model)?;
    let request = Swept { set, name, values };
    let out = py.detach(|| -> Result<_, Failure> { Ok(model.visit(request)?) })?;
    Ok(out.transpose()?)
}
