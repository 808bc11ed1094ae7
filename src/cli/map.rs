//! `stickslip map`: which motions exist at each point of a grid over two
//! parameters; all cores, resumable, shardable.

use std::path::PathBuf;

use clap::Args;
use stickslip::output::figure::map::{draw_map_with_curves, plot_map};
use stickslip::output::map_summary;
use stickslip::study::curves::{curves, CurvesOptions};
use stickslip::study::map::{run_map, GridAxis, MapFile, MapMethod, MapOptions, Shard};
use stickslip::Model;

use super::args::{check_plot_path, with_model, Assignments, ModelArgs, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Options of `map`.
#[derive(Args, Clone)]
pub struct MapArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// Horizontal axis, `NAME=from:to:count` (e.g. `W=0.2:8:100`).
    #[arg(long)]
    x: String,
    /// Vertical axis, `NAME=from:to:count` (e.g. `Q0=0:180:100`).
    #[arg(long)]
    y: String,
    /// The other parameters, e.g. `--set d=0.1`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// The map file, written point by point as they finish.
    #[arg(long, value_name = "FILE", default_value = "map.csv")]
    out: PathBuf,
    /// Continue an interrupted run from its output file.
    #[arg(long)]
    resume: bool,
    /// Compute only part `k` of `n` (`k/n`, k from 0), for a cluster job
    /// array: the 16 × 16-point tiles whose number is `k` mod `n`.
    #[arg(long)]
    shard: Option<String>,
    /// How each point is classified: `continuation` (neighbours' motions
    /// continued by Newton; starts simulated only until they near a known
    /// motion) or `simulation` (every point simulated from its starts until
    /// it settles; about ten times slower, lists fewer coexisting motions).
    #[arg(long, default_value = "continuation", value_parser = ["continuation", "simulation"])]
    method: String,
    /// Draw the map into FILE (.svg or .png) when it is complete.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Also trace the transition curves over the map's box (what `stickslip
    /// curves` does, seeded along the middle line) and draw them over the
    /// classified grid. Tracing can take minutes on a large box.
    #[arg(long, requires = "plot")]
    curves: bool,
}

/// Compute the map (or resume it, or one shard), draw it, summarize it.
pub fn run(args: MapArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let model = args.model.lookup("paper");
    with_model(&model, MapCmd { args })
}

struct MapCmd {
    args: MapArgs,
}

impl WithModel for MapCmd {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let set = Assignments::parse(&self.args.set)?;
        let x = GridAxis::parse_for::<M>(&base, &self.args.x)?;
        let y = GridAxis::parse_for::<M>(&base, &self.args.y)?;
        set.leave_free(&x.name, "--x")?;
        set.leave_free(&y.name, "--y")?;
        let base = set.params::<M>(base)?;
        let shard = self.args.shard.as_deref().map(Shard::parse).transpose()?;
        let opts = MapOptions {
            resume: self.args.resume,
            shard,
            progress: true,
            max_points: None,
            method: MapMethod::parse(&self.args.method).unwrap_or_default(),
        };
        let summary = run_map::<M>(&base, &x, &y, &self.args.out, &opts)?;
        if let Some(plot) = &self.args.plot {
            if self.args.curves && summary.complete {
                let span = |a: &GridAxis| [a.from.min(a.to), a.from.max(a.to)];
                let opts = CurvesOptions {
                    x: (x.name.clone(), span(&x)),
                    y: (y.name.clone(), span(&y)),
                    seeds: Vec::new(),
                    at: Vec::new(),
                };
                let set = curves::<M>(&base, &opts)?;
                draw_map_with_curves(&MapFile::read(&self.args.out)?, Some(&set), plot)?;
            } else {
                plot_map(&self.args.out, plot)?;
            }
        }
        Ok(Outcome::ok(map_summary::text(&summary, &self.args.out)))
    }
}
