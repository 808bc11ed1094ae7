//! `stickslip merge`: join the outputs of `map --shard k/n` into one map.

use std::path::PathBuf;

use clap::Args;
use stickslip::output::figure::map::plot_map;
use stickslip::output::map_summary;
use stickslip::study::map::merge;

use super::args::check_plot_path;
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `merge`.
#[derive(Args)]
pub struct MergeArgs {
    /// Shard outputs.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// The merged map.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Draw the map into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Merge the shards, draw the map, summarize it.
pub fn run(args: MergeArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let summary = merge(&args.inputs, &args.out)?;
    if let Some(plot) = &args.plot {
        plot_map(&args.out, plot)?;
    }
    Ok(Outcome::ok(map_summary::text(&summary, &args.out)))
}
