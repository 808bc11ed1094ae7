//! `stickslip trade`: the speed/accuracy trade of a smooth-law model, its
//! N-piece predictions and the integrator against a tight reference.

use std::path::PathBuf;

use clap::Args;
use stickslip::models::ModelRef;
use stickslip::output::figure::trade::plot_trade;
use stickslip::output::text::{threshold_table, trade_table};
use stickslip::study::trade::{Measure, MeasureThresholds};

use super::args::{check_plot_path, Assignments, ModelArgs, ParamRange};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `trade`.
#[derive(Args)]
pub struct TradeArgs {
    /// A model with a smooth `law`: `--model NAME` (default `stribeck`) or
    /// `--model-file PATH`.
    #[command(flatten)]
    model: ModelArgs,
    /// Parameter values (those free in the piecewise scenes), e.g. `--set W=1.5,Q0=6`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Piece counts (each needs a scene `plN` in the model file).
    #[arg(long, value_delimiter = ',', default_value = "2,4,8,16,32,64")]
    pieces: Vec<u32>,
    /// Integrator tolerances to time against the reference.
    #[arg(long, value_delimiter = ',', default_value = "1e-4,1e-6,1e-8,1e-10")]
    tol: Vec<f64>,
    /// The reference integration's tolerance.
    #[arg(long, default_value_t = 1e-12)]
    reference_tol: f64,
    /// Measure instead where steady sliding changes stability along a
    /// parameter, `NAME=from:to:count` (e.g. `vd=0.2:3:15`): each N-piece
    /// scene's threshold against the law's own, and the observed order.
    #[arg(long, value_name = "NAME=FROM:TO:COUNT", conflicts_with = "plot")]
    threshold: Option<String>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Draw error against time into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Measure the trade; a table or JSON, and its figure.
pub fn run(args: TradeArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let set = Assignments::parse(&args.set)?;
    let model = args.model.lookup("stribeck");
    let declined = || match &model {
        ModelRef::Name(name) => CliError::NotSmooth { name: name.clone() },
        _ => CliError::NotSmoothFile {
            model: model.to_string(),
        },
    };
    if let Some(text) = &args.threshold {
        let r = ParamRange::parse(text)?;
        if r.count == 0 || r.count > 1_000_000 {
            return Err(CliError::GridCount {
                text: text.clone(),
                count: r.count,
            });
        }
        let measure = MeasureThresholds {
            model: &model,
            set: set.pairs(),
            range: (r.name, r.from, r.to, r.count),
            pieces: &args.pieces,
        };
        let t = model.visit(measure)?.ok_or_else(declined)??;
        return Ok(Outcome::ok(if args.json {
            serde_json::to_string_pretty(&t)?
        } else {
            threshold_table(&t)
        }));
    }
    let measure = Measure {
        model: &model,
        set: set.pairs(),
        pieces: &args.pieces,
        tols: &args.tol,
        reference_tol: args.reference_tol,
    };
    let trade = model.visit(measure)?.ok_or_else(declined)??;
    if let Some(path) = &args.plot {
        plot_trade(&trade, path).map_err(CliError::Figure)?;
    }
    Ok(Outcome::ok(if args.json {
        serde_json::to_string_pretty(&trade)?
    } else {
        trade_table(&trade)
    }))
}
