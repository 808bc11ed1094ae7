//! `equilibria`: steady sliding of an unforced model, its eigenvalues and
//! stability, at one parameter set or along a parameter with every change
//! of stability located (`stickslip equilibria`, the library's
//! [`Request`]). A smooth-law model is taken as the law itself.

use pyo3::prelude::*;
use stickslip::models::UnknownModel;
use stickslip::study::equilibria::Request;

use crate::command::{lookup, ModelSpec};
use crate::failure::{Failure, Kind};

/// `stickslip equilibria --json`: at the parameters `set`, or along
/// `range = (name, from, to, count)`.
#[pyfunction]
#[pyo3(signature = (model, set, range = None))]
pub fn equilibria(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    range: Option<(String, f64, f64, i64)>,
) -> PyResult<String> {
    let range = match range {
        Some((name, from, to, count)) => {
            let axis = super::axis(&name, from, to, count)?;
            Some((axis.name, axis.from, axis.to, axis.count))
        }
        None => None,
    };
    let model = lookup(&model)?;
    let request = Request { set, range };
    let scan = py.detach(|| -> Result<_, Failure> {
        match model.visit(request)? {
            Some(scan) => Ok(scan?),
            None => Err(match &model {
                stickslip::models::ModelRef::Name(name) => {
                    UnknownModel { name: name.clone() }.into()
                }
                other => Failure::new(Kind::Model, format!("`{other}`: no model to study")),
            }),
        }
    })?;
    Ok(serde_json::to_string_pretty(&scan).map_err(Failure::from)?)
}
