//! `stickslip curves`: two-parameter transition curves, their codimension-two
//! points, their exact crossings of given lines, and the regime map drawn
//! from them.

use std::path::PathBuf;

use clap::Args;
use stickslip::output::curves_table;
use stickslip::output::figure::regime::plot_regimes;
use stickslip::study::curves::{curves_with, regions, CurvesOptions, CurvesSettings};
use stickslip::Model;

use super::args::{check_plot_path, with_model, Assignments, ModelArgs, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `curves`.
#[derive(Args, Clone)]
pub struct CurvesArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The horizontal parameter and its range, `NAME=from:to` (e.g. `W=0.2:8`).
    #[arg(long)]
    x: String,
    /// The vertical parameter and its range, `NAME=from:to` (e.g. `Q0=0:180`).
    #[arg(long)]
    y: String,
    /// The other parameters, e.g. `--set d=0.1`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// A seed line, `NAME=VALUE`: `Q0=70` sweeps along the horizontal
    /// parameter at Q0 = 70 (repeatable; default: the box's middle
    /// horizontal line). More lines are added automatically.
    #[arg(long, value_name = "NAME=VALUE")]
    seed: Vec<String>,
    /// Report where every curve crosses these lines, `NAME=v1,v2,...`
    /// (repeatable), solved exactly.
    #[arg(long, value_name = "NAME=V1,V2,...")]
    at: Vec<String>,
    /// Print JSON (schema in the guide, "Regime maps").
    #[arg(long)]
    json: bool,
    /// Draw the regime map from the curves into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Grid values of each line's sweep (the transitions the curves start
    /// from are located on these sweeps).
    #[arg(long, value_name = "N", default_value_t = CurvesSettings::default().count)]
    count: usize,
    /// Extra seed lines spread evenly over the box, this many each way.
    #[arg(long, value_name = "K", default_value_t = CurvesSettings::default().spread)]
    spread: usize,
    /// Sweep the box's four edges too (the default): every curve that
    /// leaves the box crosses one.
    // Read only by clap: `--edges` is accepted (the default) and the later
    // of `--edges` / `--no-edges` wins.
    #[arg(long, overrides_with = "no_edges")]
    edges: bool,
    /// Do not sweep the box's edges: fewer curves, shorter runs (the guide,
    /// "Regime maps").
    #[arg(long, overrides_with = "edges")]
    no_edges: bool,
    /// Trace the transitions of motions of at most this many mappings (the
    /// long cycles of period-adding cascades cost a continuation of that
    /// many switching points each).
    #[arg(long, value_name = "M", default_value_t = CurvesSettings::default().max_mappings)]
    max_mappings: usize,
    /// Short sweeps across every curve the lines traced, at this many places
    /// along it, each new transition found there traced: the bands no line
    /// crosses (a period-adding cascade between two curves). 0 (the
    /// default) turns them off; each costs a sweep and the curves it finds.
    #[arg(long, value_name = "K", default_value_t = CurvesSettings::default().probes)]
    probes: usize,
    /// Trace at most this many curves by branch switching at the
    /// codimension-two points of the curves found (the second condition's
    /// curve through each); 0 turns it off.
    #[arg(long, value_name = "K", default_value_t = CurvesSettings::default().max_partners)]
    max_partners: usize,
}

/// The curves as text or JSON, and the regime map.
pub fn run(args: CurvesArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let model = args.model.lookup("paper");
    with_model(&model, CurvesCmd { args })
}

struct CurvesCmd {
    args: CurvesArgs,
}

/// `NAME=from:to` of `--x`/`--y`.
fn parse_range(option: &'static str, text: &str) -> Result<(String, [f64; 2]), CliError> {
    let bad = || CliError::BoxRange {
        option,
        text: text.to_string(),
    };
    let (name, range) = text.split_once('=').ok_or_else(bad)?;
    let (lo, hi) = range.split_once(':').ok_or_else(bad)?;
    let lo: f64 = lo.trim().parse().map_err(|_| bad())?;
    let hi: f64 = hi.trim().parse().map_err(|_| bad())?;
    Ok((name.trim().to_string(), [lo, hi]))
}

/// `NAME=v1,v2,...` of `--seed`/`--at`: the name and its values.
fn parse_lines(option: &'static str, text: &str) -> Result<(String, Vec<f64>), CliError> {
    let bad = || CliError::LineValues {
        option,
        text: text.to_string(),
    };
    let (name, values) = text.split_once('=').ok_or_else(bad)?;
    let values = values
        .split(',')
        .map(|v| v.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((name.trim().to_string(), values))
}

impl WithModel for CurvesCmd {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let set = Assignments::parse(&self.args.set)?;
        let base = set.params::<M>(base)?;
        let mut opts = CurvesOptions {
            x: parse_range("--x", &self.args.x)?,
            y: parse_range("--y", &self.args.y)?,
            seeds: Vec::new(),
            at: Vec::new(),
        };
        set.leave_free(&opts.x.0, "--x")?;
        set.leave_free(&opts.y.0, "--y")?;
        for text in &self.args.seed {
            let (name, values) = parse_lines("--seed", text)?;
            for v in values {
                let line = opts.line("--seed", &name, v)?;
                opts.seeds.push(line);
            }
        }
        for text in &self.args.at {
            let (name, values) = parse_lines("--at", text)?;
            for v in values {
                let line = opts.line("--at", &name, v)?;
                opts.at.push(line);
            }
        }
        let settings = CurvesSettings {
            count: self.args.count,
            spread: self.args.spread,
            edges: !self.args.no_edges,
            max_mappings: self.args.max_mappings,
            probes: self.args.probes,
            max_partners: self.args.max_partners,
            ..CurvesSettings::default()
        };
        let found = curves_with::<M>(&base, &opts, &settings)?;
        if let Some(path) = &self.args.plot {
            let cut = regions::<M>(&base, &found, 400, 300);
            let title = format!("{} regime map ({set})", M::info(&base).name);
            plot_regimes(&found, &cut, &title, path).map_err(CliError::Figure)?;
        }
        let stdout = if self.args.json {
            curves_table::json(&found)?
        } else {
            curves_table::text(&found, &set.to_string())
        };
        Ok(Outcome::ok(stdout))
    }
}
