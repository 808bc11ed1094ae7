//! `stickslip simulate`: simulate from a start state until the motion
//! settles; name and refine the periodic motion, or certify that none
//! touches a boundary (NM).

use clap::Args;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::attractor::AttractorOptions;
use stickslip::output::settled::settle;
use stickslip::Model;

use super::args::{
    check_plot_path, parse_numbers, with_model, Assignments, ModelArgs, OutputArgs, WithModel,
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
    /// Forcing periods simulated at most (default 3000).
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
    let simulate = Simulate {
        set,
        from,
        periods: args.periods,
        output: args.output,
    };
    with_model(&args.model.lookup("paper"), simulate)
}

struct Simulate {
    set: Assignments,
    from: [f64; 3],
    periods: Option<u32>,
    output: OutputArgs,
}

impl WithModel for Simulate {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let p = self.set.params::<M>(base)?;
        let sim = Simulator::<M>::new(p, SimOptions::default())?;
        let [x, v, phase] = self.from;
        let mut opts = AttractorOptions::default();
        if let Some(k) = self.periods {
            if k == 0 {
                return Err(CliError::ZeroPeriods);
            }
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
