//! `stickslip orbit`: solve a given mapping structure for its periodic motion
//! (Newton), check it (admissibility) and give its stability.

use std::cmp::Ordering;
use std::f64::consts::TAU;

use clap::Args;
use stickslip::dynamics::simulate::{
    EventKind, Location, Segment, SimError, SimOptions, Simulator,
};
use stickslip::orbit::attractor;
use stickslip::orbit::motion;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::output::history::History;
use stickslip::output::report::Report;
use stickslip::{MappingKind, Model};

use super::args::{check_plot_path, parse_numbers, with_model, Assignments, OutputArgs, WithModel};
use super::error::CliError;
use super::outcome::{Outcome, SAMPLES_PER_PERIOD};

/// Arguments of `orbit`.
#[derive(Args)]
pub struct OrbitArgs {
    /// Model name (`paper`), or `model::scene`.
    #[arg(long, default_value = "paper")]
    model: String,
    /// The structure, e.g. `P_{3_31 0_11 3_13 4_33}` (applied right to left).
    #[arg(long)]
    structure: String,
    /// Parameter values, e.g. `--set W=3.7,Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Forcing periods per cycle (the period N of the motion).
    #[arg(long, default_value_t = 1)]
    periods: u32,
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
    let orbit = Orbit {
        set,
        structure: args.structure,
        periods: args.periods,
        guess,
        output: args.output,
    };
    with_model(&args.model, orbit)
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
    fn run<M: Model>(self) -> Result<Outcome, CliError> {
        let info = M::INFO;
        let p = self.set.params::<M>()?;
        let sim = Simulator::<M>::new(p, SimOptions::default())?;
        let structure =
            Structure::parse(info, &self.structure, self.periods).map_err(|source| {
                CliError::Structure {
                    text: self.structure.clone(),
                    source,
                }
            })?;
        let mut outcome = Outcome::ok(String::new());
        let from_guess = match self.guess {
            None => None,
            Some((phase, x)) => match seed_from_guess(&sim, &structure, phase, x) {
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
        let title = format!(
            "{}: {}, N = {} ({})",
            info.name,
            motion.structure.notation(info),
            motion.structure.periods(),
            self.set
        );
        outcome.with_report(
            &report,
            || Ok(History::of_motion(&sim, &motion, SAMPLES_PER_PERIOD)),
            title,
            &self.output,
        )
    }
}

/// Why the flow from a `--guess` does not follow the structure.
#[derive(Debug, thiserror::Error)]
enum Departure {
    /// The first mapping's flow does not leave its start boundary into its domain.
    #[error(
        "there the flow does not leave {boundary} into domain {domain}, where {mapping} runs (acceleration {acceleration:.3e})"
    )]
    NotLeaving {
        boundary: &'static str,
        domain: u32,
        mapping: &'static str,
        acceleration: f64,
    },
    /// Mapping `index` does not end within the simulated time.
    #[error("the simulated motion does not reach the end of mapping {index} ({mapping}) in time")]
    Late { index: usize, mapping: &'static str },
    /// Mapping `index` ends on another boundary, or goes on elsewhere.
    #[error(
        "the simulated motion ends mapping {index} ({mapping}) on {boundary} and goes on in {after}, but the structure needs {want_boundary} and then {want_after}"
    )]
    Elsewhere {
        index: usize,
        mapping: &'static str,
        boundary: &'static str,
        after: String,
        want_boundary: &'static str,
        want_after: String,
    },
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] SimError),
}

/// Where the flow of mapping `index` runs.
fn location_of<M: Model>(index: usize) -> Location {
    let mi = &M::INFO.mappings[index];
    match (mi.kind, mi.domain) {
        (MappingKind::Stick, _) | (_, None) => Location::Stick,
        (_, Some(j)) => Location::Domain(j),
    }
}

fn location_name<M: Model>(location: Location) -> String {
    match location {
        Location::Domain(j) => format!("domain {}", M::INFO.domains[j].label),
        Location::Stick => "stick".to_string(),
    }
}

/// Switching points of `structure` from its first one, `(W t, x)` on the
/// first mapping's start boundary: simulate from there and read the next
/// events. Fails (with the reason) when the flow does not follow the structure.
fn seed_from_guess<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    phase: f64,
    x: f64,
) -> Result<Vec<SwitchingPoint>, Departure> {
    let info = M::INFO;
    let steps = structure.steps();
    let m = steps.len();
    let first = &info.mappings[steps[0]];
    let v0 = sim.velocity(first.from);
    let location = location_of::<M>(steps[0]);
    if let Location::Domain(j) = location {
        let acc = M::normal_field(sim.params(), j, x, v0, phase)[0];
        let into = if info.domains[j].lower == Some(first.from) {
            1.0
        } else {
            -1.0
        };
        // Leaving into the domain, strictly (NaN included in the refusal).
        if (into * acc).partial_cmp(&0.0) != Some(Ordering::Greater) {
            return Err(Departure::NotLeaving {
                boundary: info.boundaries[first.from].label,
                domain: info.domains[j].label,
                mapping: first.name,
                acceleration: acc,
            });
        }
    }
    let mut seg = Segment {
        x,
        v: v0,
        phase,
        location,
        search_from: phase,
    };
    let limit = phase + TAU * (2 * structure.periods() + 1) as f64;
    let mut points = vec![SwitchingPoint { phase, x }];
    let mut k = 0;
    while k < m {
        let mi = &info.mappings[steps[k]];
        let Some((event, next)) = sim.next_event(&seg, limit)? else {
            return Err(Departure::Late {
                index: k,
                mapping: mi.name,
            });
        };
        seg = next;
        if event.kind == EventKind::Graze {
            continue;
        }
        let want = location_of::<M>(steps[(k + 1) % m]);
        if event.boundary != mi.to || event.after != want {
            return Err(Departure::Elsewhere {
                index: k,
                mapping: mi.name,
                boundary: info.boundaries[event.boundary].label,
                after: location_name::<M>(event.after),
                want_boundary: info.boundaries[mi.to].label,
                want_after: location_name::<M>(want),
            });
        }
        if k + 1 < m {
            points.push(SwitchingPoint {
                phase: event.phase,
                x: event.x,
            });
        }
        k += 1;
    }
    Ok(points)
}
