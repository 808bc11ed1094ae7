//! A command run with the model Python names (compiled in, or a model file
//! or text loaded at run time): the parameters as `(name, value)` pairs
//! checked by the model, the work generic over it.

use std::path::PathBuf;

use stickslip::models::{ModelRef, UnknownModel};
use stickslip::{Model, ModelVisitor, ParamSet};

use crate::failure::{Failure, Kind};

/// How Python names a model: `("name", "paper", None)`, `("file", PATH,
/// SCENE)` or `("source", TEXT, SCENE)` (`Model`, `Model.from_file`,
/// `Model.from_source`).
pub type ModelSpec = (String, String, Option<String>);

/// The model a [`ModelSpec`] names, for the library's lookup.
pub fn lookup((kind, what, scene): &ModelSpec) -> Result<ModelRef, Failure> {
    match kind.as_str() {
        "name" => Ok(ModelRef::Name(what.clone())),
        "file" => Ok(ModelRef::File {
            path: PathBuf::from(what),
            scene: scene.clone(),
        }),
        "source" => Ok(ModelRef::Source {
            text: what.clone(),
            origin: "<source>".to_string(),
            scene: scene.clone(),
        }),
        other => Err(Failure::new(
            Kind::Input,
            format!("`{other}`: a model is a name, a file or a source"),
        )),
    }
}

/// Something to run with a piecewise-linear model `M`.
pub trait Command {
    /// What it returns.
    type Output;
    /// Run with model `M`, whose defaults are `base`.
    fn run<M: Model>(self, base: M::Params) -> Result<Self::Output, Failure>;
}

struct Piecewise<C>(C);

impl<C: Command> ModelVisitor for Piecewise<C> {
    type Output = Result<C::Output, Failure>;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        Some(self.0.run::<M>(base))
    }
}

/// Run `command` with the model `model` names (`paper`, `model::scene`, a
/// file or a text, through the library's one lookup).
pub fn with_model<C: Command>(model: &ModelSpec, command: C) -> Result<C::Output, Failure> {
    let model = lookup(model)?;
    model.visit(Piecewise(command))?.unwrap_or_else(|| {
        Err(match model {
            ModelRef::Name(name) => UnknownModel { name }.into(),
            other => Failure::new(
                Kind::Model,
                format!(
                    "`{other}` has a smooth law: load one of its piecewise-linear scenes \
                     (`scene=`, a `pieces: N` scene)"
                ),
            ),
        })
    })
}

/// Model `M`'s parameters: its defaults `base` with `pairs` applied, checked.
pub fn params<M: stickslip::FrictionOscillator>(
    base: M::Params,
    pairs: &[(String, f64)],
) -> Result<M::Params, Failure> {
    let pairs: Vec<(&str, f64)> = pairs.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    Ok(base.with_pairs(M::identity(&base), &pairs)?)
}

/// The pairs as the CLI's headings show them: `W = 5, Q0 = 70`, or
/// `default parameters`.
pub fn settings(pairs: &[(String, f64)]) -> String {
    if pairs.is_empty() {
        return "default parameters".to_string();
    }
    let items: Vec<String> = pairs.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    items.join(", ")
}
