//! `stickslip orbit-diagram`: the brute-force bifurcation diagram —
//! stroboscopic samples after a transient at each parameter value, swept up
//! and down — with the largest Lyapunov exponent and the sweep's branches.

use std::path::PathBuf;

use clap::Args;
use stickslip::output::figure::diagram::plot_diagram;
use stickslip::study::diagram::{
    orbit_diagram, overlay_branches, Column, DiagramOptions, OrbitDiagram,
};
use stickslip::Model;

use super::args::{check_plot_path, with_model, Assignments, ModelArgs, ParamRange, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `orbit-diagram`.
#[derive(Args, Clone)]
pub struct DiagramArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The parameter and its grid, `NAME=from:to:count` (e.g. `W=3.9:4:200`).
    #[arg(long)]
    param: String,
    /// The other parameters, e.g. `--set Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Stroboscopic samples kept at each value (one per forcing period).
    #[arg(long, value_name = "K", default_value_t = DiagramOptions::default().periods)]
    periods: u32,
    /// Forcing periods simulated and discarded at each value before the samples.
    #[arg(long, value_name = "T", default_value_t = DiagramOptions::default().transient)]
    transient: u32,
    /// Forcing periods of the largest Lyapunov exponent at each value (0: none).
    #[arg(long, value_name = "L", default_value_t = DiagramOptions::default().lyapunov)]
    lyapunov: u32,
    /// Do not run `sweep` over the range for the periodic branches.
    #[arg(long)]
    no_branches: bool,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Draw the diagram into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// The diagram as text or JSON, and its figure.
pub fn run(args: DiagramArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.plot.as_deref())?;
    let model = args.model.lookup("paper");
    with_model(&model, DiagramCmd { args })
}

struct DiagramCmd {
    args: DiagramArgs,
}

impl WithModel for DiagramCmd {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let a = &self.args;
        let set = Assignments::parse(&a.set)?;
        let range = ParamRange::parse(&a.param)?;
        set.leave_free(&range.name, "--param")?;
        let base = set.params::<M>(base)?;
        let opts = DiagramOptions {
            transient: a.transient,
            periods: a.periods,
            lyapunov: a.lyapunov,
            ..DiagramOptions::default()
        };
        let mut diagram =
            orbit_diagram::<M>(base, &range.name, range.from, range.to, range.count, opts)?;
        let mut notes = Vec::new();
        if !a.no_branches {
            notes.extend(overlay_branches::<M>(base, &mut diagram));
        }
        if let Some(plot) = &a.plot {
            let title = format!(
                "{}: orbit diagram over {}, {}",
                M::info(&base).name,
                range.name,
                set
            );
            plot_diagram(&diagram, &title, plot).map_err(CliError::Figure)?;
        }
        let stdout = if a.json {
            serde_json::to_string_pretty(&diagram)?
        } else {
            text(&diagram)
        };
        let mut out = Outcome::ok(stdout);
        out.notes = notes;
        Ok(out)
    }
}

/// Distinct values among `xs` (to 1e-6 relative to their spread, at least 1e-9).
fn clusters(xs: &[f64]) -> usize {
    let mut s: Vec<f64> = xs.iter().copied().filter(|x| x.is_finite()).collect();
    s.sort_by(f64::total_cmp);
    let tol = 1e-6 * (1.0 + s.first().map_or(0.0, |a| a.abs()));
    s.windows(2).filter(|w| w[1] - w[0] > tol).count() + usize::from(!s.is_empty())
}

/// What the samples show: their number of distinct points, or no repetition.
fn shape(c: &Column) -> String {
    if let Some(e) = &c.error {
        return format!("error: {e}");
    }
    let n = clusters(&c.x);
    let k = c.x.len();
    if n >= k.min(32) && k >= 32 {
        "no repetition in the samples".to_string()
    } else {
        format!("{n} distinct point{}", if n == 1 { "" } else { "s" })
    }
}

fn describe(c: &Column) -> String {
    let what = shape(c);
    match c.exponent {
        Some(e) => format!("{what}, largest exponent {e:.6}"),
        None => what,
    }
}

fn text(d: &OrbitDiagram) -> String {
    let mut s = format!(
        "orbit diagram over {} ({} values; samples at W t = 0 mod 2π)\n\n{:>14}  {:<44}  {}\n",
        d.param,
        d.up.len(),
        d.param,
        "increasing",
        "decreasing"
    );
    for (u, w) in d.up.iter().zip(d.down.iter().rev()) {
        let (a, b) = (describe(u), describe(w));
        let mark = if shape(u) == shape(w) { "" } else { "  *" };
        s.push_str(&format!("{:>14.8}  {a:<44}  {b}{mark}\n", u.value));
    }
    if !d.branches.is_empty() {
        s.push_str("\nbranches (sweep):\n");
        for b in &d.branches {
            s.push_str(&format!(
                "  {} (N = {}), {} points\n",
                b.structure,
                b.n,
                b.points.len()
            ));
        }
    }
    s.push_str("\n(*: the two directions show different shapes there: hysteresis)\n");
    s
}
