//! Arguments several subcommands share: the model (`--model NAME`, or
//! `--model-file PATH --scene S`) and its lookup, `--set NAME=VALUE`,
//! number lists, `--param NAME=from:to:count`, the `--plot` path check and
//! the output options of `orbit` and `simulate`.

use std::fmt;
use std::path::{Path, PathBuf};

use clap::Args;
use stickslip::models::ModelRef;
use stickslip::output::figure::Format;
use stickslip::{Model, ModelVisitor, ParamSet};

use super::error::CliError;

/// Which model: compiled in, by name, or a model file loaded and compiled
/// to machine code now (no build).
#[derive(Args, Clone)]
pub struct ModelArgs {
    /// A compiled-in model (`paper`), or `model::scene` [default: paper;
    /// stribeck for `trade`].
    #[arg(long, value_name = "NAME", conflicts_with = "model_file")]
    model: Option<String>,
    /// A model file (`my_law.ssm`) to load instead: checked as `stickslip
    /// check` checks it and compiled to machine code in milliseconds.
    #[arg(long, value_name = "PATH")]
    model_file: Option<PathBuf>,
    /// With `--model-file`: one of its model's scenes.
    #[arg(long, value_name = "SCENE", requires = "model_file")]
    scene: Option<String>,
}

impl ModelArgs {
    /// The model named, `default` when none is.
    pub fn lookup(&self, default: &str) -> ModelRef {
        match &self.model_file {
            Some(path) => ModelRef::File {
                path: path.clone(),
                scene: self.scene.clone(),
            },
            None => ModelRef::Name(self.model.clone().unwrap_or_else(|| default.to_string())),
        }
    }
}

/// Output options of `orbit` and `simulate`.
#[derive(Args, Clone)]
pub struct OutputArgs {
    /// Print JSON (schema in the guide, "Periodic motions").
    #[arg(long)]
    pub json: bool,
    /// Draw the six panels of the motion into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Write one period of the motion (or the last simulated forcing period
    /// for NM) as CSV: `t,Wt,x,v,a,domain,F`.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
}

/// The `--set NAME=VALUE` pairs, in the order given.
pub struct Assignments(Vec<(String, f64)>);

impl Assignments {
    /// Parse `NAME=VALUE` items (`--set W=3.7,Q0=70` gives two).
    pub fn parse(items: &[String]) -> Result<Self, CliError> {
        items
            .iter()
            .map(|item| {
                let (name, value) = item
                    .split_once('=')
                    .ok_or_else(|| CliError::Assignment { item: item.clone() })?;
                let v: f64 = value
                    .trim()
                    .parse()
                    .map_err(|_| CliError::AssignmentValue {
                        item: item.clone(),
                        value: value.to_string(),
                    })?;
                Ok((name.trim().to_string(), v))
            })
            .collect::<Result<_, _>>()
            .map(Self)
    }

    /// Refuse an item naming `name`, which `by` (`--param`, `--x`, `--y`)
    /// varies.
    pub fn leave_free(&self, name: &str, by: &'static str) -> Result<(), CliError> {
        match self.0.iter().find(|(n, _)| n == name) {
            Some((n, _)) => Err(CliError::SetVaried {
                name: n.clone(),
                by,
            }),
            None => Ok(()),
        }
    }

    /// The pairs.
    pub fn pairs(&self) -> &[(String, f64)] {
        &self.0
    }

    /// Model `M`'s parameters: its defaults `base` with these applied, checked.
    pub fn params<M: stickslip::FrictionOscillator>(
        &self,
        base: M::Params,
    ) -> Result<M::Params, CliError> {
        let pairs: Vec<(&str, f64)> = self.0.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        Ok(base.with_pairs(M::identity(&base), &pairs)?)
    }
}

/// The parameters the user set, for headings and figure titles:
/// `W = 3.7, Q0 = 70`, or `default parameters`.
impl fmt::Display for Assignments {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return f.write_str("default parameters");
        }
        let items: Vec<String> = self.0.iter().map(|(n, v)| format!("{n} = {v}")).collect();
        f.write_str(&items.join(", "))
    }
}

/// Parse `N` comma-separated finite numbers, `what` they are (`x,v,W t`).
pub fn parse_numbers<const N: usize>(text: &str, what: &'static str) -> Result<[f64; N], CliError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(CliError::NumberCount {
            text: text.to_string(),
            what,
            count: N,
        });
    }
    let mut out = [0.0f64; N];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = p.parse().map_err(|_| CliError::NotANumber {
            text: text.to_string(),
            part: p.to_string(),
            what,
        })?;
        if !o.is_finite() {
            return Err(CliError::NotFinite {
                text: text.to_string(),
                part: p.to_string(),
                what,
            });
        }
    }
    Ok(out)
}

/// A parameter and its grid, `NAME=from:to:count`.
pub struct ParamRange {
    /// The parameter.
    pub name: String,
    /// First value.
    pub from: f64,
    /// Last value.
    pub to: f64,
    /// Number of points.
    pub count: usize,
}

impl ParamRange {
    /// Parse `NAME=from:to:count` (checked further by the sweep).
    pub fn parse(text: &str) -> Result<Self, CliError> {
        let bad = || CliError::Range {
            text: text.to_string(),
        };
        let (name, range) = text.split_once('=').ok_or_else(bad)?;
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [from, to, count] = parts.as_slice() else {
            return Err(bad());
        };
        Ok(Self {
            name: name.trim().to_string(),
            from: from.parse().map_err(|_| bad())?,
            to: to.parse().map_err(|_| bad())?,
            count: count.parse().map_err(|_| bad())?,
        })
    }
}

/// A subcommand that runs with a piecewise-linear model chosen by name.
pub trait WithModel {
    /// What it returns.
    type Output;
    /// Run with model `M`, whose defaults are `base`.
    fn run<M: Model>(self, base: M::Params) -> Result<Self::Output, CliError>;
}

/// The registry's visitor for a [`WithModel`] command: piecewise models only
/// (a smooth-law model is, to these commands, an unknown name).
struct Piecewise<C>(C);

impl<C: WithModel> ModelVisitor for Piecewise<C> {
    type Output = Result<C::Output, CliError>;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        Some(self.0.run::<M>(base))
    }
}

/// Run `command` with the model `model` names: compiled in (`paper`, or
/// `model::scene`) or loaded from a file.
pub fn with_model<C: WithModel>(model: &ModelRef, command: C) -> Result<C::Output, CliError> {
    model
        .visit(Piecewise(command))?
        .unwrap_or_else(|| Err(declined(model)))
}

/// Why a visitor declined `model`: a name that is not compiled in, or a
/// smooth law where a piecewise model is needed.
pub fn declined(model: &ModelRef) -> CliError {
    match model {
        ModelRef::Name(name) => {
            CliError::UnknownModel(stickslip::models::UnknownModel { name: name.clone() })
        }
        _ => CliError::SmoothFile {
            model: model.to_string(),
        },
    }
}

/// A `--plot` path we can write a figure to: a figure format by extension
/// (`.svg`, `.png`), not a directory, in a directory that exists. Every
/// subcommand that draws checks its path with this before any work.
pub fn check_plot_path(path: Option<&Path>) -> Result<(), CliError> {
    let Some(path) = path else {
        return Ok(());
    };
    if Format::of(path).is_err() {
        return Err(CliError::PlotFormat {
            path: path.to_path_buf(),
        });
    }
    if path.is_dir() {
        return Err(CliError::PlotIsDirectory {
            path: path.to_path_buf(),
        });
    }
    match path.parent() {
        Some(directory) if !directory.as_os_str().is_empty() && !directory.is_dir() => {
            Err(CliError::PlotDirectory {
                path: path.to_path_buf(),
                directory: directory.to_path_buf(),
            })
        }
        _ => Ok(()),
    }
}
