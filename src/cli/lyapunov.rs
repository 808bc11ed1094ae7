//! `stickslip lyapunov`: the Lyapunov spectrum of the stroboscopic map along
//! the simulated trajectory, from the exact tangent map, with a verdict.

use clap::Args;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::lyapunov::{spectrum, LyapunovError, LyapunovOptions};
use stickslip::output::lyapunov_report::LyapunovReport;
use stickslip::Model;

use super::args::{parse_numbers, with_model, Assignments, ModelArgs, WithModel};
use super::error::CliError;
use super::outcome::Outcome;

/// Arguments of `lyapunov`.
#[derive(Args)]
pub struct LyapunovArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// Parameter values, e.g. `--set W=2.38,Q0=3`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Start state `x,v,W t` (default: rest, `0,0,0`).
    #[arg(long, allow_hyphen_values = true)]
    from: Option<String>,
    /// Forcing periods simulated and discarded first.
    #[arg(long, default_value_t = LyapunovOptions::default().transient)]
    transient: u32,
    /// Forcing periods over which the exponents are accumulated (at least 1;
    /// 10 or more for an error estimate).
    #[arg(long, default_value_t = LyapunovOptions::default().periods)]
    periods: u32,
    /// Print JSON: `{"exponents", "per_period", "error", "attractor",
    /// "structure", ...}`, with `"-inf"` for an exponent of minus infinity.
    #[arg(long)]
    json: bool,
}

/// The spectrum, as text or JSON.
pub fn run(args: LyapunovArgs) -> Result<Outcome, CliError> {
    let set = Assignments::parse(&args.set)?;
    let from = match args.from {
        Some(f) => parse_numbers::<3>(&f, "x,v,W t")?,
        None => [0.0; 3],
    };
    if args.periods == 0 {
        return Err(CliError::ZeroPeriods);
    }
    let job = Lyapunov {
        set,
        from,
        opts: LyapunovOptions {
            transient: args.transient,
            periods: args.periods,
        },
        json: args.json,
    };
    with_model(&args.model.lookup("paper"), job)
}

struct Lyapunov {
    set: Assignments,
    from: [f64; 3],
    opts: LyapunovOptions,
    json: bool,
}

impl WithModel for Lyapunov {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let p = self.set.params::<M>(base)?;
        let sim = Simulator::<M>::new(p, SimOptions::default())?;
        let [x, v, phase] = self.from;
        let s = spectrum(&sim, (x, v, phase), self.opts).map_err(|e| match e {
            LyapunovError::Sim(e) => CliError::Simulation(e),
            LyapunovError::NoPeriods => CliError::ZeroPeriods,
        })?;
        let report = LyapunovReport::of(&s, self.opts);
        if self.json {
            return Ok(Outcome::ok(serde_json::to_string_pretty(&report)?));
        }
        let set = &self.set;
        let head = format!(
            "{}: from (x, v, W t) = ({x}, {v}, {phase}) ({set})\n",
            M::info(&p).name
        );
        Ok(Outcome::ok(head + &report.text(&s)))
    }
}
