//! `stickslip sweep`: periodic motions along one parameter, their
//! transitions, coexisting motions.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use stickslip::output::figure::sweep::{plot_sweep, View};
use stickslip::output::sweep_table;
use stickslip::study::sweep::{sweep, SweepOptions};
use stickslip::Model;

use stickslip::model::registry::ModelVisitor;
use stickslip::model::smooth::SmoothModel;
use stickslip::orbit::equilibrium::Verdict;
use stickslip::output::figure::law::plot_law_sweep;
use stickslip::output::text::{law_sweep_csv, law_sweep_table};
use stickslip::study::law::sweep_law;

use super::args::{check_plot_path, declined, Assignments, ModelArgs, ParamRange, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `sweep`.
#[derive(Args, Clone)]
pub struct SweepArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The swept parameter and its grid, `NAME=from:to:count` (e.g. `W=0.2:9:200`).
    #[arg(long)]
    param: String,
    /// The other parameters, e.g. `--set Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Print JSON (schema in the guide, "One-parameter studies").
    #[arg(long)]
    json: bool,
    /// Draw the sweep into FILE (.svg or .png): the bifurcation diagram, or
    /// the frequency response with `--view frc`. For a smooth law itself:
    /// steady sliding and every cycle's point on `v = 0`, with the Hopf
    /// points and the stick-slip cycle's ends.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// What `--plot` draws: `diagram` (switching phases and displacements,
    /// eigenvalues) or `frc` (each motion's amplitude, max |x| and max |v|
    /// over its cycle, against the parameter).
    #[arg(long, value_enum, default_value_t = ViewArg::Diagram)]
    view: ViewArg,
    /// Write the motions at the grid values as CSV, one row per motion:
    /// the parameter, structure, N, start_Wt, start_x, stable, |λ|max,
    /// max_abs_x, max_abs_v. For a smooth law itself: the parameter, kind
    /// (steady_sliding, stick_slip, slip), x, stable, period, stick,
    /// multiplier.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// Leave out unstable motions: the branches' unstable stretches and the
    /// unstable motions at the grid points (the view of sweeps before
    /// arclength continuation). Bifurcations and transitions stay.
    #[arg(long)]
    no_unstable: bool,
    /// Starts of the global search for coexisting motions (simulations from
    /// K well-spread initial conditions, each stopped as soon as it nears a
    /// known stable motion); 0 turns the search off.
    #[arg(long, value_name = "K", default_value_t = SweepOptions::default().starts)]
    starts: usize,
    /// Run the global search at every k-th grid value (and just past every
    /// transition); 0: only past transitions.
    #[arg(long, value_name = "k", default_value_t = SweepOptions::default().every)]
    every: usize,
    /// Follow no branch of a motion of more than M mappings (default: every
    /// one). A period-doubling cascade into chaos otherwise follows branches
    /// of hundreds of mappings; the longer motions are still named where a
    /// simulation past a transition finds them.
    #[arg(long, value_name = "M")]
    max_mappings: Option<usize>,
    /// Follow no branch born by period doubling whose period exceeds N
    /// forcing periods (0: no limit); each one not followed is listed as
    /// cut. The cascade's accumulation point is estimated from the
    /// doublings located.
    #[arg(long, value_name = "N", default_value_t = stickslip::study::sweep::MAX_PERIOD)]
    max_period: u32,
}

/// The figures `sweep --plot` draws.
#[derive(Clone, Copy, ValueEnum)]
enum ViewArg {
    /// The bifurcation diagram.
    Diagram,
    /// The frequency response: amplitudes against the parameter.
    Frc,
}

/// The sweep as text or JSON, and its figure.
pub fn run(args: SweepArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let model = args.model.lookup("paper");
    model
        .visit(SweepCmd { args })?
        .unwrap_or_else(|| Err(declined(&model)))
}

struct SweepCmd {
    args: SweepArgs,
}

impl ModelVisitor for SweepCmd {
    type Output = Result<Outcome, CliError>;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        Some(WithModel::run::<M>(self, base))
    }
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some(self.law::<M>(base))
    }
}

impl SweepCmd {
    /// The `--set` pairs, the swept `--param` (left free by `--set`), and
    /// the model's parameters with the pairs applied.
    fn parameters<M: stickslip::FrictionOscillator>(
        &self,
        base: M::Params,
    ) -> Result<(Assignments, ParamRange, M::Params), CliError> {
        let set = Assignments::parse(&self.args.set)?;
        let range = ParamRange::parse(&self.args.param)?;
        set.leave_free(&range.name, "--param")?;
        let base = set.params::<M>(base)?;
        Ok((set, range, base))
    }

    /// The smooth law itself: steady sliding and every cycle at each value,
    /// the Hopf point and the stick-slip cycle's ends located.
    fn law<M: SmoothModel>(self, base: M::Params) -> Result<Outcome, CliError> {
        let (_, r, base) = self.parameters::<M>(base)?;
        let mut sweep = sweep_law::<M>(base, &r.name, r.from, r.to, r.count)?;
        if self.args.no_unstable {
            for p in &mut sweep.points {
                p.cycles.retain(|c| c.verdict == Verdict::Stable);
            }
        }
        if let Some(path) = &self.args.plot {
            plot_law_sweep(&sweep, path).map_err(CliError::Figure)?;
        }
        if let Some(path) = &self.args.csv {
            std::fs::write(path, law_sweep_csv(&sweep)).map_err(|source| CliError::Write {
                path: path.clone(),
                source,
            })?;
        }
        Ok(Outcome::ok(if self.args.json {
            serde_json::to_string_pretty(&sweep)?
        } else {
            law_sweep_table(&sweep)
        }))
    }
}

impl WithModel for SweepCmd {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let (set, range, base) = self.parameters::<M>(base)?;
        let ParamRange {
            name,
            from,
            to,
            count,
        } = range;
        let opts = SweepOptions {
            starts: self.args.starts,
            every: self.args.every,
            max_mappings: self.args.max_mappings,
            max_period: (self.args.max_period > 0).then_some(self.args.max_period),
            ..SweepOptions::default()
        };
        let sw = sweep::<M>(base, &name, from, to, count, opts)?;
        let unstable = !self.args.no_unstable;
        if let Some(path) = &self.args.plot {
            let title = format!("{} sweep of {name} ({set})", M::info(&base).name);
            let view = match self.args.view {
                ViewArg::Diagram => View::Diagram,
                ViewArg::Frc => View::Frc,
            };
            plot_sweep(&sw, &title, path, unstable, view).map_err(CliError::Figure)?;
        }
        if let Some(path) = &self.args.csv {
            let shown = if unstable {
                sw.clone()
            } else {
                sw.stable_only()
            };
            std::fs::write(path, sweep_table::csv(&shown)).map_err(|source| CliError::Write {
                path: path.clone(),
                source,
            })?;
        }
        let stdout = if self.args.json {
            if unstable {
                sweep_table::json(&sw)?
            } else {
                sweep_table::json(&sw.stable_only())?
            }
        } else {
            sweep_table::text(&sw, from, to, count, &set.to_string(), unstable)
        };
        Ok(Outcome::ok(stdout))
    }
}
