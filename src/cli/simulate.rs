//! `stickslip simulate`: simulate from a start state until the motion
//! settles; name and refine the periodic motion, or certify that none
//! touches a boundary (NM).

use std::f64::consts::TAU;

use clap::Args;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::OrbitError;
use stickslip::output::history::History;
use stickslip::output::report::Report;
use stickslip::Model;

use super::args::{check_plot_path, parse_numbers, with_model, Assignments, OutputArgs, WithModel};
use super::error::CliError;
use super::outcome::{Outcome, SAMPLES_PER_PERIOD};

/// Arguments of `simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    /// Model name (`paper`), or `model::scene`.
    #[arg(long, default_value = "paper")]
    model: String,
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
    with_model(&args.model, simulate)
}

struct Simulate {
    set: Assignments,
    from: [f64; 3],
    periods: Option<u32>,
    output: OutputArgs,
}

impl WithModel for Simulate {
    type Output = Outcome;
    fn run<M: Model>(self) -> Result<Outcome, CliError> {
        let info = M::INFO;
        let p = self.set.params::<M>()?;
        let sim = Simulator::<M>::new(p, SimOptions::default())?;
        let [x, v, phase] = self.from;
        let start = sim.start(x, v, phase)?;
        let mut opts = AttractorOptions::default();
        if let Some(k) = self.periods {
            if k == 0 {
                return Err(CliError::ZeroPeriods);
            }
            opts.max_periods = k;
        }
        let set = &self.set;
        let outcome = Outcome::ok(format!(
            "simulated from (x, v, W t) = ({x}, {v}, {phase}) ({set})\n"
        ));
        let motion = match attractor::find(&sim, start, opts) {
            Ok(Attractor::Periodic(motion)) => motion,
            Err(OrbitError::Inadmissible(motion)) => *motion,
            Ok(Attractor::NoMotion(nm)) => {
                let report = Report::of_no_motion::<M>(&nm);
                let title = format!(
                    "{}: NM, no boundary contact (last simulated forcing period; {set})",
                    info.name
                );
                let history = || {
                    let from = (nm.certified_at - TAU).max(phase);
                    let seg = sim.run(start, from, |_| {})?;
                    Ok(History::simulated(
                        &sim,
                        seg,
                        from,
                        nm.certified_at,
                        SAMPLES_PER_PERIOD,
                    )?)
                };
                return outcome.with_report(&report, history, title, &self.output);
            }
            Ok(Attractor::Stick(stick)) => {
                let report = Report::of_stick::<M>(&stick);
                let title = format!(
                    "{}: permanent stick at x = {:.6} (one forcing period; {set})",
                    info.name, stick.x
                );
                let history = || {
                    let from = stick.since.max(phase);
                    let seg = sim.run(start, from, |_| {})?;
                    Ok(History::simulated(
                        &sim,
                        seg,
                        from,
                        from + TAU,
                        SAMPLES_PER_PERIOD,
                    )?)
                };
                return outcome.with_report(&report, history, title, &self.output);
            }
            Ok(Attractor::Autonomous(cycle)) => {
                let report = Report::of_autonomous(&sim, &cycle);
                let title = format!(
                    "{}: autonomous stick-slip cycle, T = {:.6} ({set})",
                    info.name, cycle.period
                );
                let history = || {
                    let from = cycle.onset.max(phase);
                    let to = from + cycle.period * sim.oscillator().frequency;
                    let seg = sim.run(start, from, |_| {})?;
                    Ok(History::simulated(&sim, seg, from, to, SAMPLES_PER_PERIOD)?)
                };
                return outcome.with_report(&report, history, title, &self.output);
            }
            Err(OrbitError::NotConverged(t)) => {
                let report = Report::of_termination::<M>(&t, None);
                return outcome.with_report(
                    &report,
                    || Err(CliError::NoMotion),
                    String::new(),
                    &self.output,
                );
            }
            Err(e) => return Err(e.into()),
        };
        let report = Report::of_motion(&sim, &motion);
        let title = format!(
            "{}: {}, N = {} (found by simulation; {set})",
            info.name,
            motion.structure.notation(info),
            motion.structure.periods(),
        );
        outcome.with_report(
            &report,
            || Ok(History::of_motion(&sim, &motion, SAMPLES_PER_PERIOD)),
            title,
            &self.output,
        )
    }
}
