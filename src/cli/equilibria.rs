//! `stickslip equilibria`: steady sliding of an unforced model (no forcing,
//! `A0 = 0`), its eigenvalues and stability, at one parameter set or along
//! a parameter with every change of stability located.

use clap::Args;
use stickslip::output::text::equilibria_table;
use stickslip::study::equilibria::Request;

use super::args::{declined, Assignments, ModelArgs, ParamRange};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `equilibria`.
#[derive(Args)]
pub struct EquilibriaArgs {
    /// A piecewise model or scene, or a smooth-law model (its law itself):
    /// `--model NAME` (default `stribeck`) or `--model-file PATH`.
    #[command(flatten)]
    model: ModelArgs,
    /// The parameter and its grid, `NAME=from:to:count` (e.g.
    /// `V=0.2:3:15`); without it, the one parameter set of `--set`.
    #[arg(long)]
    param: Option<String>,
    /// The other parameters; the forcing amplitude must be 0, e.g.
    /// `--set Q0=0`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// The scan, as a table or JSON.
pub fn run(args: EquilibriaArgs) -> Result<Outcome, CliError> {
    let set = Assignments::parse(&args.set)?;
    let range = args.param.as_deref().map(ParamRange::parse).transpose()?;
    if let Some(r) = &range {
        if r.count == 0 || r.count > 1_000_000 {
            return Err(CliError::GridCount {
                text: args.param.clone().unwrap_or_default(),
                count: r.count,
            });
        }
    }
    let model = args.model.lookup("stribeck");
    let request = Request {
        set: set.pairs().to_vec(),
        range: range.map(|r| (r.name, r.from, r.to, r.count)),
    };
    let scan = model.visit(request)?.ok_or_else(|| declined(&model))??;
    Ok(Outcome::ok(if args.json {
        serde_json::to_string_pretty(&scan)?
    } else {
        equilibria_table(&scan)
    }))
}
