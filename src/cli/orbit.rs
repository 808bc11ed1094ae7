//! `stickslip orbit`: solve a given mapping structure for its periodic motion
//! (Newton), check it (admissibility) and give its stability.

use clap::Args;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::attractor;
use stickslip::orbit::guess::points_from_guess;
use stickslip::orbit::motion;
use stickslip::orbit::periodic::NewtonOptions;
use stickslip::orbit::structure::Structure;
use stickslip::output::history::History;
use stickslip::output::report::Report;
use stickslip::Model;
use stickslip_codegen::structure::implied_periods;

use super::args::{
    check_plot_path, parse_numbers, with_model, Assignments, ModelArgs, OutputArgs, WithModel,
};
use super::error::CliError;
use super::outcome::{Outcome, SAMPLES_PER_PERIOD};

/// Arguments of `orbit`.
#[derive(Args)]
pub struct OrbitArgs {
    #[command(flatten)]
    model: ModelArgs,
    /// The structure, e.g. `P_{3_31 0_11 3_13 4_33}` (applied right to left).
    #[arg(long)]
    structure: String,
    /// Parameter values, e.g. `--set W=3.7,Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Forcing periods per cycle (the period N of the motion); by default
    /// 1, or `k` for a repeated block `(P_{…})^{×k}`. With the forcing off
    /// (amplitude 0) the period is an unknown and this is ignored.
    #[arg(long)]
    periods: Option<u32>,
    /// The first switching point `W t,x` (the start of the first mapping
    /// applied); the others follow by simulation. Without it the structure
    /// is seeded by simulation.
    #[arg(long, allow_hyphen_values = true)]
    guess: Option<String>,
    #[command(flatten)]
    output: OutputArgs,
}

/// The motion of the structure, its report, CSV and figure.
pub fn run(args: OrbitArgs) -> Result<Outcome, CliError> {
    check_plot_path(args.output.plot.as_deref())?;
    let set = Assignments::parse(&args.set)?;
    let guess = args
        .guess
        .map(|g| parse_numbers::<2>(&g, "W t,x").map(|[phase, x]| (phase, x)))
        .transpose()?;
    let periods = args
        .periods
        .unwrap_or_else(|| implied_periods(&args.structure));
    let orbit = Orbit {
        set,
        structure: args.structure,
        periods,
        guess,
        output: args.output,
    };
    with_model(&args.model.lookup("paper"), orbit)
}

struct Orbit {
    set: Assignments,
    structure: String,
    periods: u32,
    guess: Option<(f64, f64)>,
    output: OutputArgs,
}

impl WithModel for Orbit {
    type Output = Outcome;
    fn run<M: Model>(self, base: M::Params) -> Result<Outcome, CliError> {
        let p = self.set.params::<M>(base)?;
        let info = M::info(&p);
        let sim = Simulator::<M>::new(p, SimOptions::default())?;
        let parse_error = |source| CliError::Structure {
            text: self.structure.clone(),
            source,
        };
        let mut structure =
            Structure::parse(info, &self.structure, self.periods.max(1)).map_err(parse_error)?;
        // Unforced: a cycle whose period is an unknown (SPEC §14).
        if M::oscillator(&p).amplitude == 0.0 {
            structure = Structure::autonomous(info, structure.steps()).map_err(parse_error)?;
        }
        let mut outcome = Outcome::ok(String::new());
        let from_guess = match self.guess {
            None => None,
            Some((phase, x)) => match points_from_guess(&sim, &structure, phase, x) {
                Ok(points) => Some(points),
                Err(why) => {
                    outcome.notes.push(format!(
                        "note: --guess {phase},{x}: {why}; seeding by simulation instead"
                    ));
                    None
                }
            },
        };
        let points = match from_guess {
            Some(points) => points,
            None => attractor::seed(&sim, &structure).ok_or_else(|| CliError::NoSeed {
                structure: structure.notation(info),
            })?,
        };
        let motion = motion::solve(&sim, structure, points, NewtonOptions::default());
        let report = Report::of_motion(&sim, &motion);
        let title = if motion.structure.is_autonomous() {
            format!(
                "{}: {}, T = {:.6} ({})",
                info.name,
                motion.structure.notation(info),
                stickslip::orbit::periodic::cycle_shift(&motion.structure, &motion.points)
                    / M::oscillator(&p).frequency,
                self.set
            )
        } else {
            format!(
                "{}: {}, N = {} ({})",
                info.name,
                motion.structure.notation(info),
                motion.structure.periods(),
                self.set
            )
        };
        outcome.with_report(
            &report,
            || Ok(History::of_motion(&sim, &motion, SAMPLES_PER_PERIOD)),
            title,
            &self.output,
        )
    }
}
