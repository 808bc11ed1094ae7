//! `stickslip basins`: which attractor each start `(x, v)` at a phase
//! reaches, the basin fractions of a grid, and basin stability from random
//! starts; all cores, resumable.

use std::path::PathBuf;

use clap::Args;
use stickslip::output::basins_summary;
use stickslip::output::figure::basins::plot_basin_file;
use stickslip::study::basins::{run_basins, BasinOptions, BasinSettings, Basins};
use stickslip::study::map::GridAxis;
use stickslip::Model;

use super::args::{check_plot_path, with_model, Assignments, ModelArgs, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Options of `basins`.
#[derive(Args, Clone)]
pub struct BasinsArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The parameters, e.g. `--set W=3.948,Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// The starts' displacements, `x=from:to:count` (e.g. `x=-2:2:200`).
    #[arg(long)]
    x: String,
    /// The starts' velocities, `v=from:to:count` (e.g. `v=-3:3:200`).
    #[arg(long)]
    y: String,
    /// The forcing phase `W t` of every start (and of the stroboscopic section).
    #[arg(
        long,
        value_name = "Wt",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    phase: f64,
    /// Random starts in the grid's box for the basin stability (0: none).
    #[arg(long, default_value_t = 1000)]
    samples: usize,
    /// Seed of the random starts.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Forcing periods simulated at most from each start.
    #[arg(long, default_value_t = stickslip::study::basins::MAX_PERIODS)]
    periods: u32,
    /// Forcing periods of the Lyapunov exponent of a start that never
    /// settles (0: call it `unsettled` without one).
    #[arg(long, default_value_t = stickslip::study::basins::LYAPUNOV_PERIODS)]
    lyapunov: u32,
    /// The basin file, written start by start as they finish, so that a run
    /// killed at any moment resumes (`--resume`); never overwritten.
    /// Without it no file is written.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Continue an interrupted run from its file (`--out`).
    #[arg(long)]
    resume: bool,
    /// Draw the basins into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Compute the basins (or resume them), draw them, summarize them.
pub fn run(args: BasinsArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let model = args.model.lookup("paper");
    with_model(&model, BasinsCmd { args })
}

struct BasinsCmd {
    args: BasinsArgs,
}

impl WithModel for BasinsCmd {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let a = &self.args;
        let set = Assignments::parse(&a.set)?;
        let params = set.params::<M>(base)?;
        let x = GridAxis::parse(&a.x)?;
        let v = GridAxis::parse(&a.y)?;
        let settings = BasinSettings {
            phase: a.phase,
            samples: a.samples,
            seed: a.seed,
            periods: a.periods,
            lyapunov: a.lyapunov,
        };
        let opts = BasinOptions {
            resume: a.resume,
            progress: !a.json,
            max_points: None,
        };
        let basins = run_basins::<M>(&params, &x, &v, &settings, a.out.as_deref(), &opts)?;
        if let Some(plot) = &a.plot {
            plot_basin_file(&basins.to_file(), plot)?;
        }
        let stdout = if a.json {
            basins_summary::json(&basins)?
        } else {
            text(&basins)
        };
        Ok(Outcome::ok(stdout))
    }
}

/// The summary: the run, then one line per attractor.
fn text(b: &Basins) -> String {
    let h = &b.header;
    let mut s = format!(
        "{}: {} of {} starts ({} computed now, {} already done) in {:.2} s{}\n",
        b.file
            .as_ref()
            .map_or("basins".to_string(), |f| f.display().to_string()),
        b.already_done + b.computed,
        h.len(),
        b.computed,
        b.already_done,
        b.elapsed.as_secs_f64(),
        if b.complete {
            ""
        } else {
            " — incomplete: run again with --resume"
        }
    );
    s.push_str(&format!(
        "grid {} × {} over x = {}:{}, v = {}:{} at W t = {}; {} random starts (seed {})\n",
        h.x.count, h.v.count, h.x.from, h.x.to, h.v.from, h.v.to, h.phase, h.samples, h.seed
    ));
    s.push_str("  grid share   points   stability [95 % CI]        attractor\n");
    for a in &b.attractors {
        let exponent = a
            .exponent
            .map_or(String::new(), |e| format!("  (largest exponent {e:.6})"));
        s.push_str(&format!(
            "  {:>9.4} %  {:>7}   {:.4} [{:.4}, {:.4}]   {}{exponent}\n",
            100.0 * a.fraction,
            a.points,
            a.stability,
            a.interval[0],
            a.interval[1],
            a.name
        ));
    }
    s
}
