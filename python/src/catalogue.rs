//! The compiled-in models: their names, parameters, descriptions, and the
//! check of a model file (as `stickslip check` runs it).

use std::path::PathBuf;

use pyo3::prelude::*;
use stickslip::models as catalogue;
use stickslip::output::describe::describe as description;
use stickslip::{Bound, Model};

use crate::command::{params as checked, with_model, Command, ModelSpec};
use crate::failure::{Failure, Kind};

/// The names of the compiled-in piecewise-linear models and scenes.
#[pyfunction]
pub fn models() -> Vec<&'static str> {
    catalogue::piecewise_names()
}

/// A parameter: name, default, bounds as `(op, value)`, doc, whether free.
type ParamRow = (
    &'static str,
    f64,
    Vec<(&'static str, f64)>,
    &'static str,
    bool,
);

struct Params;

impl Command for Params {
    type Output = Vec<ParamRow>;
    fn run<M: Model>(self, base: M::Params) -> Result<Self::Output, Failure> {
        Ok(M::info(&base)
            .params
            .iter()
            .map(|p| {
                let bounds = p
                    .bounds
                    .iter()
                    .map(|(op, b)| {
                        let op = match op {
                            Bound::Gt => ">",
                            Bound::Ge => ">=",
                            Bound::Lt => "<",
                            Bound::Le => "<=",
                        };
                        (op, *b)
                    })
                    .collect();
                (p.name, p.default, bounds, p.doc, p.free)
            })
            .collect())
    }
}

/// Model `model`'s parameters, in declaration order.
#[pyfunction]
pub fn params(py: Python<'_>, model: ModelSpec) -> PyResult<Vec<ParamRow>> {
    Ok(py.detach(|| with_model(&model, Params))?)
}

struct Name;

impl Command for Name {
    type Output = &'static str;
    fn run<M: Model>(self, base: M::Params) -> Result<Self::Output, Failure> {
        Ok(M::info(&base).name)
    }
}

/// The name of the model `model` names (`paper`, `paper::sweep_w`; for a
/// file, the model it declares): loads it, or raises `ModelError` with
/// `stickslip check`'s report.
#[pyfunction]
pub fn name(py: Python<'_>, model: ModelSpec) -> PyResult<String> {
    Ok(py.detach(|| with_model(&model, Name))?.to_string())
}

struct Describe(Vec<(String, f64)>);

impl Command for Describe {
    type Output = (String, String);
    fn run<M: Model>(self, base: M::Params) -> Result<Self::Output, Failure> {
        let d = description::<M>(&checked::<M>(base, &self.0)?);
        Ok((d.to_string(), serde_json::to_string_pretty(&d)?))
    }
}

/// `stickslip describe` of `model` at the parameters: `(text, json)`.
#[pyfunction]
pub fn describe(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
) -> PyResult<(String, String)> {
    Ok(py.detach(|| with_model(&model, Describe(set)))?)
}

/// Check a model file as the build does: the model's name, or `ModelError`
/// with every error located (`file:line:col`, as `stickslip check` prints).
#[pyfunction]
pub fn check(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    let origin = path.display().to_string();
    let checked = py.detach(|| stickslip_codegen::check_file(&path, &origin));
    match checked {
        Ok(generated) => Ok(generated.name),
        Err(report) => Err(Failure::new(Kind::Model, report.render().trim_end()).into()),
    }
}
