//! The compiled-in models: their names, parameters, descriptions, and the
//! check of a model file (as `stickslip check` runs it).

use std::path::PathBuf;

use pyo3::prelude::*;
use stickslip::models as catalogue;
use stickslip::models::{ModelRef, UnknownModel};
use stickslip::output::describe::describe as description;
use stickslip::{Bound, Model, ModelVisitor, SmoothModel};

use crate::command::{lookup, params as checked, with_model, Command, ModelSpec};
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

/// A parameter row of every parameter in declaration order.
fn rows(params: &'static [stickslip::model::ParamInfo]) -> Vec<ParamRow> {
    params
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
        .collect()
}

/// A model's name and parameter rows: of a piecewise model, or of a smooth
/// law itself (which `equilibria` studies; the analyses that need closed
/// forms refuse it with a message naming its scenes).
struct Identify;

impl ModelVisitor for Identify {
    type Output = (&'static str, Vec<ParamRow>);
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        let info = M::info(&base);
        Some((info.name, rows(info.params)))
    }
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        let info = M::info(&base);
        Some((info.name, rows(info.params)))
    }
}

fn identify(model: &ModelSpec) -> Result<(&'static str, Vec<ParamRow>), Failure> {
    let model = lookup(model)?;
    model.visit(Identify)?.ok_or_else(|| match model {
        ModelRef::Name(name) => UnknownModel { name }.into(),
        other => Failure::new(Kind::Model, format!("`{other}`: no model")),
    })
}

/// Model `model`'s parameters, in declaration order.
#[pyfunction]
pub fn params(py: Python<'_>, model: ModelSpec) -> PyResult<Vec<ParamRow>> {
    Ok(py.detach(|| identify(&model))?.1)
}

/// The name of the model `model` names (`paper`, `paper::sweep_w`; for a
/// file, the model it declares): loads it, or raises `ModelError` with
/// `stickslip check`'s report.
#[pyfunction]
pub fn name(py: Python<'_>, model: ModelSpec) -> PyResult<String> {
    Ok(py.detach(|| identify(&model))?.0.to_string())
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
