//! A command run with the compiled-in model chosen by name: the parameters
//! as `(name, value)` pairs checked by the model, the work generic over it.

use stickslip::models::{self, UnknownModel};
use stickslip::{Model, ModelVisitor, ParamSet};

use crate::failure::Failure;

/// Something to run with a piecewise-linear model `M`.
pub trait Command {
    /// What it returns.
    type Output;
    /// Run with model `M`.
    fn run<M: Model>(self) -> Result<Self::Output, Failure>;
}

struct Piecewise<C>(C);

impl<C: Command> ModelVisitor for Piecewise<C> {
    type Output = Result<C::Output, Failure>;
    fn piecewise<M: Model>(self) -> Option<Self::Output> {
        Some(self.0.run::<M>())
    }
}

/// Run `command` with model `name` (`paper`, or `model::scene`).
pub fn with_model<C: Command>(name: &str, command: C) -> Result<C::Output, Failure> {
    models::visit(name, Piecewise(command)).unwrap_or_else(|| {
        Err(UnknownModel {
            name: name.to_string(),
        }
        .into())
    })
}

/// Model `M`'s parameters: its defaults with `pairs` applied, checked.
pub fn params<M: Model>(pairs: &[(String, f64)]) -> Result<M::Params, Failure> {
    let pairs: Vec<(&str, f64)> = pairs.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    Ok(M::Params::from_pairs(M::INFO, &pairs)?)
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
