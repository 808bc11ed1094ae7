//! `stickslip simulate`: simulate from a start state until the motion
//! settles; name and refine the periodic motion, or certify that none
//! touches a boundary (NM).

use clap::Args;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::registry::ModelVisitor;
use stickslip::model::smooth::SmoothModel;
use stickslip::orbit::attractor::AttractorOptions;
use stickslip::orbit::smooth::{simulate as simulate_smooth, SmoothOptions};
use stickslip::output::settled::settle;
use stickslip::output::text::smooth_settled;
use stickslip::Model;

use super::args::{
    check_plot_path, declined, parse_numbers, Assignments, ModelArgs, OutputArgs, WithModel,
};
use super::error::CliError;
use super::outcome::{Outcome, SAMPLES_PER_PERIOD};

/// Arguments of `simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// Parameter values, e.g. `--set W=5,Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Start state `x,v,W t` (default: rest, `0,0,0`).
    #[arg(long, allow_hyphen_values = true)]
    from: Option<String>,
    /// Forcing periods simulated at most (default 3000); for an unforced
    /// smooth law, returns to the section `v = 0`.
    #[arg(long)]
    periods: Option<u32>,
    #[command(flatten)]
    output: OutputArgs,
}

/// What the simulation settles to, its report, CSV and figure.
pub fn run(args: SimulateArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.output.plot.as_deref())?;
    let set = Assignments::parse(&args.set)?;
    let from = match args.from {
        Some(f) => parse_numbers::<3>(&f, "x,v,W t")?,
        None => [0.0; 3],
    };
    if args.periods == Some(0) {
        return Err(CliError::ZeroPeriods);
    }
    let model = args.model.lookup("paper");
    let simulate = Simulate {
        set,
        from,
        periods: args.periods,
        output: args.output,
        model: model.to_string(),
    };
    model
        .visit(simulate)?
        .unwrap_or_else(|| Err(declined(&model)))
}

struct Simulate {
    set: Assignments,
    from: [f64; 3],
    periods: Option<u32>,
    output: OutputArgs,
    model: String,
}

impl ModelVisitor for Simulate {
    type Output = Result<Outcome, CliError>;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        Some(WithModel::run::<M>(self, base))
    }
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some(self.smooth::<M>(base))
    }
}

impl Simulate {
    /// A smooth law by its integrator. Unforced: steady sliding or a
    /// self-excited cycle, by shooting on the section `v = 0`. Forced: the
    /// periodic motion, by shooting on the stroboscopic map.
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Result<Outcome, CliError> {
        for (given, option) in [
            (self.output.plot.is_some(), "--plot"),
            (self.output.csv.is_some(), "--csv"),
        ] {
            if given {
                return Err(CliError::SmoothOutput {
                    option,
                    model: self.model,
                });
            }
        }
        let p = self.set.params::<M>(base)?;
        let [x, v, phase] = self.from;
        let mut options = SmoothOptions::default();
        if let Some(k) = self.periods {
            options.max_returns = k;
        }
        let settled = simulate_smooth::<M>(p, (x, v, phase), options)?;
        Ok(Outcome::ok(if self.output.json {
            serde_json::to_string_pretty(&settled)?
        } else {
            format!(
                "model {} (the law itself, integrated at relative tolerance {:.0e})\n\
                 simulated from (x, v, W t) = ({x}, {v}, {phase}) ({})\n{}",
                M::info(&p).name,
                options.rtol,
                self.set,
                smooth_settled(&settled)
            )
        }))
    }
}

impl WithModel for Simulate {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let p = self.set.params::<M>(base)?;
        let sim = Simulator::<M>::new(p, SimOptions::default())?;
        let [x, v, phase] = self.from;
        let mut opts = AttractorOptions::default();
        if let Some(k) = self.periods {
            opts.max_periods = k;
        }
        let set = &self.set;
        let settled = settle(&sim, (x, v, phase), opts)?;
        let title = settled.title(M::info(&p).name, &set.to_string());
        let history = || {
            settled
                .history(&sim, (x, v, phase), SAMPLES_PER_PERIOD)?
                .ok_or(CliError::NoMotion)
        };
        Outcome::ok(format!(
            "simulated from (x, v, W t) = ({x}, {v}, {phase}) ({set})\n"
        ))
        .with_report(&settled.report, history, title, &self.output)
    }
}
