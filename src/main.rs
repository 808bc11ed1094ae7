//! The `stickslip` command-line tool.
#![forbid(unsafe_code)]

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use stickslip::dynamics::simulate::{EventKind, Location, Segment, SimOptions, Simulator};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::{self, OrbitError};
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::output::describe;
use stickslip::output::report::{History, Report};
use stickslip::{models, MappingKind, Model, ModelVisitor, ParamSet};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// Samples per forcing period in `--csv` and `--plot`.
const SAMPLES_PER_PERIOD: usize = 400;

/// Exact periodic motions of friction oscillators, from model files.
#[derive(Parser)]
#[command(name = "stickslip", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Check model files as the build does (parse, check, generate), without
    /// compiling anything: each error as `error:`, `--> FILE:LINE:COL`, the
    /// source line and a caret, on stderr. Exit status 1 on any error.
    Check {
        /// Model files (`models/paper.ssm`).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print the diagnostics as JSON on stdout (for editors).
        #[arg(long)]
        json: bool,
    },
    /// List the compiled-in models and their scenes.
    Models,
    /// Print a model's domains, boundaries and generated mappings.
    Describe {
        /// Model name (`paper`), or `model::scene`.
        #[arg(long, default_value = "paper")]
        model: String,
        /// Parameter values, e.g. `--set W=3.7,Q0=70`.
        #[arg(long, value_delimiter = ',')]
        set: Vec<String>,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Solve a given mapping structure for its periodic motion (Newton),
    /// check it (admissibility) and give its stability.
    Orbit {
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
    },
    /// Simulate from a start state until the motion settles; name and refine
    /// the periodic motion, or certify that none touches a boundary (NM).
    Simulate {
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
    },
    /// Follow periodic motions along one parameter; locate every transition
    /// (grazing, stick onset and vanishing, passable onset, |λ| = 1) and what
    /// lives beyond it; report coexisting motions.
    Sweep(SweepArgs),
    /// Measure the speed/accuracy trade of a smooth-law model: its N-piece
    /// predictions and the integrator at several tolerances against the law
    /// integrated tightly (switching points, amplitude, time).
    Trade {
        /// A model with a smooth `law` (e.g. `stribeck`).
        #[arg(long, default_value = "stribeck")]
        model: String,
        /// Parameter values (those free in the piecewise scenes), e.g. `--set W=1.5,Q0=6`.
        #[arg(long, value_delimiter = ',')]
        set: Vec<String>,
        /// Piece counts (each needs a scene `plN` in the model file).
        #[arg(long, value_delimiter = ',', default_value = "2,4,8,16,32,64")]
        pieces: Vec<u32>,
        /// Integrator tolerances to time against the reference.
        #[arg(long, value_delimiter = ',', default_value = "1e-4,1e-6,1e-8,1e-10")]
        tol: Vec<f64>,
        /// The reference integration's tolerance.
        #[arg(long, default_value_t = 1e-12)]
        reference_tol: f64,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// Draw error against time into FILE (.svg or .png).
        #[arg(long, value_name = "FILE")]
        plot: Option<PathBuf>,
    },
    /// Which motions exist at each point of a grid over two parameters (the
    /// paper's Fig. 11); all cores, resumable, shardable for a cluster.
    Map(MapArgs),
    /// Join the outputs of `map --shard k/n` into one map (and figure),
    /// identical to a single run.
    Merge {
        /// Shard outputs.
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
        /// The merged map.
        #[arg(long, value_name = "FILE")]
        out: PathBuf,
        /// Draw the map into FILE (.svg or .png).
        #[arg(long, value_name = "FILE")]
        plot: Option<PathBuf>,
    },
}

/// Options of `map`.
#[derive(Args, Clone)]
struct MapArgs {
    /// Model name (`paper`), or `model::scene`.
    #[arg(long, default_value = "paper")]
    model: String,
    /// Horizontal axis, `NAME=from:to:count` (e.g. `W=0.2:8:100`).
    #[arg(long)]
    x: String,
    /// Vertical axis, `NAME=from:to:count` (e.g. `Q0=0:180:100`).
    #[arg(long)]
    y: String,
    /// The other parameters, e.g. `--set d=0.1`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// The map file, written point by point as they finish.
    #[arg(long, value_name = "FILE", default_value = "map.csv")]
    out: PathBuf,
    /// Continue an interrupted run from its output file.
    #[arg(long)]
    resume: bool,
    /// Compute only part `k` of `n` (`k/n`, k from 0), for a cluster job array.
    #[arg(long)]
    shard: Option<String>,
    /// Draw the map into FILE (.svg or .png) when it is complete.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

struct MapCmd {
    args: MapArgs,
}

impl ModelVisitor for MapCmd {
    type Output = Result<Outcome, String>;
    fn visit<M: Model>(self) -> Self::Output {
        use stickslip::output::map_plot::plot_map;
        use stickslip::study::map::{run_map, GridAxis, MapOptions, Shard};
        let set = parse_assignments(&self.args.set)?;
        let x = GridAxis::parse_for::<M>(&self.args.x).map_err(|e| e.to_string())?;
        let y = GridAxis::parse_for::<M>(&self.args.y).map_err(|e| e.to_string())?;
        let base = params::<M>(&set)?;
        let shard = self
            .args
            .shard
            .as_deref()
            .map(Shard::parse)
            .transpose()
            .map_err(|e| e.to_string())?;
        let opts = MapOptions {
            resume: self.args.resume,
            shard,
            progress: true,
            max_points: None,
        };
        let summary =
            run_map::<M>(&base, &x, &y, &self.args.out, &opts).map_err(|e| e.to_string())?;
        if let Some(plot) = &self.args.plot {
            plot_map(&self.args.out, plot).map_err(|e| e.to_string())?;
        }
        Ok(Outcome::ok(summary_text(&summary, &self.args.out)))
    }
}

fn summary_text(s: &stickslip::study::map::Summary, out: &std::path::Path) -> String {
    let mut text = format!(
        "{}: {} of {} grid points ({} computed now, {} already done) in {:.2} s{}\n",
        out.display(),
        s.already_done + s.computed,
        s.shard_points,
        s.computed,
        s.already_done,
        s.elapsed.as_secs_f64(),
        if s.complete {
            ""
        } else {
            " — incomplete: run again with --resume"
        }
    );
    for (label, count) in &s.labels {
        text.push_str(&format!("  {count:>6}  {label}\n"));
    }
    text
}

/// Output options of `orbit` and `simulate`.
#[derive(Args, Clone)]
struct SweepArgs {
    /// Model name (`paper`), or `model::scene`.
    #[arg(long, default_value = "paper")]
    model: String,
    /// The swept parameter and its grid, `NAME=from:to:count` (e.g. `W=0.2:9:200`).
    #[arg(long)]
    param: String,
    /// The other parameters, e.g. `--set Q0=70`.
    #[arg(long, value_delimiter = ',')]
    set: Vec<String>,
    /// Print JSON (schema in the README, "Bifurcations and maps").
    #[arg(long)]
    json: bool,
    /// Draw the bifurcation diagram into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Output options of `orbit` and `simulate`.
#[derive(Args, Clone)]
struct OutputArgs {
    /// Print JSON (schema in the README, "Periodic motions").
    #[arg(long)]
    json: bool,
    /// Draw the six panels of the motion into FILE (.svg or .png).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Write one period of the motion (or the last simulated forcing period
    /// for NM) as CSV: `t,Wt,x,v,a,domain,F`.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
}

/// Parse `NAME=VALUE` pairs.
fn parse_assignments(items: &[String]) -> Result<Vec<(String, f64)>, String> {
    items
        .iter()
        .map(|item| {
            let (name, value) = item
                .split_once('=')
                .ok_or_else(|| format!("`{item}`: expected NAME=VALUE"))?;
            let v: f64 = value
                .trim()
                .parse()
                .map_err(|_| format!("`{item}`: `{value}` is not a number"))?;
            Ok((name.trim().to_string(), v))
        })
        .collect()
}

/// Parse `N` comma-separated numbers named by `what`.
fn parse_numbers<const N: usize>(text: &str, what: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != N {
        return Err(format!(
            "`{text}`: expected {what} ({N} comma-separated numbers)"
        ));
    }
    let mut out = [0.0f64; N];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = p
            .parse()
            .map_err(|_| format!("`{text}`: `{p}` is not a number (expected {what})"))?;
        if !o.is_finite() {
            return Err(format!("`{text}`: `{p}` is not finite (expected {what})"));
        }
    }
    Ok(out)
}

/// The model's parameters: its defaults with `set` applied, checked.
fn params<M: Model>(set: &[(String, f64)]) -> Result<M::Params, String> {
    let pairs: Vec<(&str, f64)> = set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    M::Params::from_pairs(M::INFO, &pairs).map_err(|e| e.to_string())
}

/// What a command prints, notes on stderr, and whether it failed.
struct Outcome {
    stdout: String,
    notes: Vec<String>,
    failure: Option<String>,
}

impl Outcome {
    fn ok(stdout: String) -> Self {
        Self {
            stdout,
            notes: Vec::new(),
            failure: None,
        }
    }
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
) -> Result<Vec<SwitchingPoint>, String> {
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
        if (into * acc).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(format!(
                "there the flow does not leave {} into domain {}, where {} runs (acceleration {acc:.3e})",
                info.boundaries[first.from].label, info.domains[j].label, first.name
            ));
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
        let Some((event, next)) = sim.next_event(&seg, limit).map_err(|e| e.to_string())? else {
            return Err(format!(
                "the simulated motion does not reach the end of mapping {k} ({}) in time",
                mi.name
            ));
        };
        seg = next;
        if event.kind == EventKind::Graze {
            continue;
        }
        let want = location_of::<M>(steps[(k + 1) % m]);
        if event.boundary != mi.to || event.after != want {
            return Err(format!(
                "the simulated motion ends mapping {k} ({}) on {} and goes on in {}, but the structure needs {} and then {}",
                mi.name,
                info.boundaries[event.boundary].label,
                location_name::<M>(event.after),
                info.boundaries[mi.to].label,
                location_name::<M>(want)
            ));
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

/// Print `report`; for a motion, write the CSV and the figure.
fn finish(
    report: &Report,
    history: impl FnOnce() -> Result<History, String>,
    title: String,
    output: &OutputArgs,
    mut outcome: Outcome,
) -> Result<Outcome, String> {
    outcome.stdout = if output.json {
        report.to_json()
    } else {
        format!("{}{report}", outcome.stdout)
    };
    if output.csv.is_some() || output.plot.is_some() {
        if report.is_motion() {
            let history = history()?;
            if let Some(path) = &output.csv {
                std::fs::write(path, history.to_csv())
                    .map_err(|e| format!("cannot write `{}`: {e}", path.display()))?;
                outcome.notes.push(format!("wrote {}", path.display()));
            }
            if let Some(path) = &output.plot {
                stickslip::output::plot::plot(&history, &title, path)?;
                outcome.notes.push(format!("wrote {}", path.display()));
            }
        } else {
            outcome
                .notes
                .push("no CSV or figure written: there is no motion to show".to_string());
        }
    }
    outcome.failure = report.failure();
    Ok(outcome)
}

/// The parameters the user set, for figure titles.
fn set_text(set: &[(String, f64)]) -> String {
    if set.is_empty() {
        "default parameters".to_string()
    } else {
        set.iter()
            .map(|(n, v)| format!("{n} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

struct Orbit {
    set: Vec<(String, f64)>,
    structure: String,
    periods: u32,
    guess: Option<(f64, f64)>,
    output: OutputArgs,
}

impl ModelVisitor for Orbit {
    type Output = Result<Outcome, String>;
    fn visit<M: Model>(self) -> Self::Output {
        let info = M::INFO;
        let p = params::<M>(&self.set)?;
        let sim = Simulator::<M>::new(p, SimOptions::default()).map_err(|e| e.to_string())?;
        let structure = Structure::parse(info, &self.structure, self.periods)
            .map_err(|e| format!("structure `{}`: {e}", self.structure))?;
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
            None => attractor::seed(&sim, &structure).ok_or_else(|| {
                format!(
                    "no simulated motion follows {}; give the first switching point with --guess W t,x",
                    structure.notation(info)
                )
            })?,
        };
        let motion = motion::solve(&sim, structure, points, NewtonOptions::default());
        let report = Report::of_motion(&sim, &motion);
        let title = format!(
            "{}: {}, N = {} ({})",
            info.name,
            motion.structure.notation(info),
            motion.structure.periods(),
            set_text(&self.set)
        );
        finish(
            &report,
            || Ok(History::of_motion(&sim, &motion, SAMPLES_PER_PERIOD)),
            title,
            &self.output,
            outcome,
        )
    }
}

struct Simulate {
    set: Vec<(String, f64)>,
    from: [f64; 3],
    periods: Option<u32>,
    output: OutputArgs,
}

impl ModelVisitor for Simulate {
    type Output = Result<Outcome, String>;
    fn visit<M: Model>(self) -> Self::Output {
        let info = M::INFO;
        let p = params::<M>(&self.set)?;
        let sim = Simulator::<M>::new(p, SimOptions::default()).map_err(|e| e.to_string())?;
        let [x, v, phase] = self.from;
        let start = sim.start(x, v, phase).map_err(|e| e.to_string())?;
        let mut opts = AttractorOptions::default();
        if let Some(k) = self.periods {
            if k == 0 {
                return Err("--periods must be at least 1".to_string());
            }
            opts.max_periods = k;
        }
        let outcome = Outcome::ok(format!(
            "simulated from (x, v, W t) = ({x}, {v}, {phase}) ({})\n",
            set_text(&self.set)
        ));
        let set = set_text(&self.set);
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
                    let seg = sim.run(start, from, |_| {}).map_err(|e| e.to_string())?;
                    History::simulated(&sim, seg, from, nm.certified_at, SAMPLES_PER_PERIOD)
                        .map_err(|e| e.to_string())
                };
                return finish(&report, history, title, &self.output, outcome);
            }
            Ok(Attractor::Stick(stick)) => {
                let report = Report::of_stick::<M>(&stick);
                let title = format!(
                    "{}: permanent stick at x = {:.6} (one forcing period; {set})",
                    info.name, stick.x
                );
                let history = || {
                    let from = stick.since.max(phase);
                    let seg = sim.run(start, from, |_| {}).map_err(|e| e.to_string())?;
                    History::simulated(&sim, seg, from, from + TAU, SAMPLES_PER_PERIOD)
                        .map_err(|e| e.to_string())
                };
                return finish(&report, history, title, &self.output, outcome);
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
                    let seg = sim.run(start, from, |_| {}).map_err(|e| e.to_string())?;
                    History::simulated(&sim, seg, from, to, SAMPLES_PER_PERIOD)
                        .map_err(|e| e.to_string())
                };
                return finish(&report, history, title, &self.output, outcome);
            }
            Err(OrbitError::NotConverged(t)) => {
                let report = Report::of_termination::<M>(&t, None);
                return finish(
                    &report,
                    || Err("there is no motion".to_string()),
                    String::new(),
                    &self.output,
                    outcome,
                );
            }
            Err(e) => return Err(e.to_string()),
        };
        let report = Report::of_motion(&sim, &motion);
        let title = format!(
            "{}: {}, N = {} (found by simulation; {set})",
            info.name,
            motion.structure.notation(info),
            motion.structure.periods(),
        );
        finish(
            &report,
            || Ok(History::of_motion(&sim, &motion, SAMPLES_PER_PERIOD)),
            title,
            &self.output,
            outcome,
        )
    }
}

struct Describe {
    set: Vec<(String, f64)>,
    json: bool,
}

impl ModelVisitor for Describe {
    type Output = Result<String, String>;
    fn visit<M: Model>(self) -> Self::Output {
        let pairs: Vec<(&str, f64)> = self.set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let p = M::Params::from_pairs(M::INFO, &pairs).map_err(|e| e.to_string())?;
        let d = describe::describe::<M>(&p);
        if self.json {
            serde_json::to_string_pretty(&d).map_err(|e| e.to_string())
        } else {
            Ok(d.to_string())
        }
    }
}

fn run(cli: Cli) -> Result<Outcome, String> {
    // A figure format we cannot write is an error before any work.
    if let Command::Orbit { output, .. } | Command::Simulate { output, .. } = &cli.command {
        if let Some(path) = &output.plot {
            stickslip::output::plot::Format::of(path)?;
        }
    }
    match cli.command {
        // Its own exit status and output: see `check`.
        Command::Check { files, json } => Err(format!(
            "internal: `check` {} file(s) (json: {json}) reached the wrong driver",
            files.len()
        )),
        Command::Models => {
            let mut out = String::new();
            for info in models::ALL {
                let free: Vec<&str> = info.free.iter().map(|&i| info.params[i].name).collect();
                let first_doc = info.doc.lines().next().unwrap_or("");
                out.push_str(&format!(
                    "{:<20} {} domains, {} boundaries, {} mappings; free: {}\n",
                    info.name,
                    info.domains.len(),
                    info.boundaries.len(),
                    info.mapping_names().len(),
                    free.join(", ")
                ));
                if info.scene.is_none() && !first_doc.is_empty() {
                    out.push_str(&format!("{:<20} {}\n", "", first_doc));
                }
            }
            Ok(Outcome::ok(out))
        }
        Command::Describe { model, set, json } => {
            let set = parse_assignments(&set)?;
            models::visit(&model, Describe { set, json })
                .unwrap_or_else(|| Err(unknown_model(&model)))
                .map(Outcome::ok)
        }
        Command::Orbit {
            model,
            structure,
            set,
            periods,
            guess,
            output,
        } => {
            let set = parse_assignments(&set)?;
            let guess = guess
                .map(|g| parse_numbers::<2>(&g, "W t,x").map(|[phase, x]| (phase, x)))
                .transpose()?;
            let orbit = Orbit {
                set,
                structure,
                periods,
                guess,
                output,
            };
            models::visit(&model, orbit).unwrap_or_else(|| Err(unknown_model(&model)))
        }
        Command::Simulate {
            model,
            set,
            from,
            periods,
            output,
        } => {
            let set = parse_assignments(&set)?;
            let from = match from {
                Some(f) => parse_numbers::<3>(&f, "x,v,W t")?,
                None => [0.0; 3],
            };
            let simulate = Simulate {
                set,
                from,
                periods,
                output,
            };
            models::visit(&model, simulate).unwrap_or_else(|| Err(unknown_model(&model)))
        }
        Command::Map(args) => {
            if let Some(path) = &args.plot {
                stickslip::output::plot::Format::of(path)?;
            }
            let model = args.model.clone();
            models::visit(&model, MapCmd { args }).unwrap_or_else(|| Err(unknown_model(&model)))
        }
        Command::Merge { inputs, out, plot } => {
            if let Some(path) = &plot {
                stickslip::output::plot::Format::of(path)?;
            }
            let summary = stickslip::study::map::merge(&inputs, &out).map_err(|e| e.to_string())?;
            if let Some(plot) = &plot {
                stickslip::output::map_plot::plot_map(&out, plot).map_err(|e| e.to_string())?;
            }
            Ok(Outcome::ok(summary_text(&summary, &out)))
        }
        Command::Trade {
            model,
            set,
            pieces,
            tol,
            reference_tol,
            json,
            plot,
        } => {
            if let Some(path) = &plot {
                stickslip::output::plot::Format::of(path)?;
            }
            let set = parse_assignments(&set)?;
            let measure = stickslip::study::trade::Measure {
                set: &set,
                pieces: &pieces,
                tols: &tol,
                reference_tol,
            };
            let trade = models::visit_smooth(&model, measure)
                .unwrap_or_else(|| {
                    let names: Vec<&str> = models::SMOOTH.iter().map(|i| i.name).collect();
                    Err(stickslip::study::trade::TradeError::Input(format!(
                        "`{model}` is not a model with a smooth law; compiled-in: {}",
                        names.join(", ")
                    )))
                })
                .map_err(|e| e.to_string())?;
            if let Some(path) = &plot {
                stickslip::output::trade_plot::plot_trade(&trade, path)?;
            }
            if json {
                Ok(Outcome::ok(
                    serde_json::to_string_pretty(&trade).map_err(|e| e.to_string())?,
                ))
            } else {
                Ok(Outcome::ok(stickslip::output::trade_plot::table(&trade)))
            }
        }
        Command::Sweep(args) => {
            if let Some(path) = &args.plot {
                stickslip::output::plot::Format::of(path)?;
            }
            let model = args.model.clone();
            models::visit(&model, SweepCmd { args }).unwrap_or_else(|| Err(unknown_model(&model)))
        }
    }
}

/// Parse `NAME=from:to:count`.
fn parse_range(text: &str) -> Result<(String, f64, f64, usize), String> {
    let bad = || format!("`{text}`: expected NAME=from:to:count, e.g. W=0.2:9:200");
    let (name, range) = text.split_once('=').ok_or_else(bad)?;
    let parts: Vec<&str> = range.split(':').map(str::trim).collect();
    let [a, b, n] = parts.as_slice() else {
        return Err(bad());
    };
    let a: f64 = a.parse().map_err(|_| bad())?;
    let b: f64 = b.parse().map_err(|_| bad())?;
    let n: usize = n.parse().map_err(|_| bad())?;
    Ok((name.trim().to_string(), a, b, n))
}

struct SweepCmd {
    args: SweepArgs,
}

impl ModelVisitor for SweepCmd {
    type Output = Result<Outcome, String>;
    fn visit<M: Model>(self) -> Self::Output {
        let set = parse_assignments(&self.args.set)?;
        let (name, from, to, count) = parse_range(&self.args.param)?;
        let base = params::<M>(&set)?;
        let sw =
            stickslip::study::sweep::sweep::<M>(base, &name, from, to, count, Default::default())
                .map_err(|e| e.to_string())?;
        if let Some(path) = &self.args.plot {
            let title = format!("{} sweep of {name} ({})", M::INFO.name, set_text(&set));
            stickslip::output::sweep_plot::plot_sweep(&sw, &title, path)?;
        }
        let stdout = if self.args.json {
            let points: Vec<serde_json::Value> = sw
                .points
                .iter()
                .map(|p| {
                    let mut o = serde_json::Map::new();
                    o.insert(name.clone(), serde_json::json!(p.value));
                    o.insert("motions".into(), serde_json::json!(p.motions));
                    serde_json::Value::Object(o)
                })
                .collect();
            let transitions: Vec<serde_json::Value> = sw
                .transitions
                .iter()
                .map(|t| {
                    let mut o = serde_json::Map::new();
                    o.insert(name.clone(), serde_json::json!(t.value));
                    o.insert("from".into(), serde_json::json!(t.from));
                    o.insert("to".into(), serde_json::json!(t.to));
                    o.insert("kind".into(), serde_json::json!(t.kind));
                    o.insert("boundary".into(), serde_json::json!(t.boundary));
                    serde_json::Value::Object(o)
                })
                .collect();
            let doc =
                serde_json::json!({ "param": name, "points": points, "transitions": transitions });
            serde_json::to_string_pretty(&doc).map_err(|e| e.to_string())?
        } else {
            let mut out = format!(
                "sweep of {name} over [{from}, {to}] ({count} points), {}\n\n",
                set_text(&set)
            );
            out.push_str("transitions:\n");
            for t in &sw.transitions {
                out.push_str(&format!(
                    "  {name} = {:<18.12} {:<16} {} -> {}{}\n",
                    t.value,
                    serde_json::to_value(t.kind)
                        .ok()
                        .and_then(|v| v.as_str().map(String::from))
                        .unwrap_or_default(),
                    t.from,
                    t.to,
                    t.boundary
                        .as_ref()
                        .map_or(String::new(), |b| format!(" (on {b})"))
                ));
            }
            out.push_str("\nmotions:\n");
            for p in &sw.points {
                let names: Vec<String> = p
                    .motions
                    .iter()
                    .map(|m| {
                        let n = if m.n > 1 {
                            format!("^{}", m.n)
                        } else {
                            String::new()
                        };
                        let st = if m.stable { "" } else { " (unstable)" };
                        format!("{}{n}{st}", m.structure)
                    })
                    .collect();
                out.push_str(&format!(
                    "  {name} = {:<10.6} {}\n",
                    p.value,
                    names.join("  +  ")
                ));
            }
            out
        };
        Ok(Outcome::ok(stdout))
    }
}

fn unknown_model(model: &str) -> String {
    let names: Vec<&str> = models::ALL.iter().map(|i| i.name).collect();
    format!("unknown model `{model}`; compiled-in: {}", names.join(", "))
}

/// `stickslip check`: every file through the generator's one entry point
/// (that of `build.rs` and `model!(file = ...)`), all errors reported.
fn check(files: &[PathBuf], json: bool) -> ExitCode {
    let mut errors = 0;
    let mut reports = Vec::new();
    for file in files {
        let origin = file.display().to_string();
        let result = stickslip_codegen::check_file(file, &origin);
        match result {
            Ok(generated) => reports.push(serde_json::json!({
                "file": origin,
                "ok": true,
                "model": generated.name,
                "diagnostics": [],
            })),
            Err(report) => {
                errors += report.errors.len();
                if !json {
                    eprint!("{}", report.render());
                }
                let diagnostics: Vec<serde_json::Value> =
                    report.errors.iter().map(diagnostic_json).collect();
                reports.push(serde_json::json!({
                    "file": origin,
                    "ok": false,
                    "model": null,
                    "diagnostics": diagnostics,
                }));
            }
        }
    }
    let n = files.len();
    let summary = format!(
        "checked {n} file{}: {errors} error{}",
        if n == 1 { "" } else { "s" },
        if errors == 1 { "" } else { "s" }
    );
    if json {
        let doc = serde_json::json!({
            "checked": n,
            "errors": errors,
            "files": reports,
        });
        match serde_json::to_string_pretty(&doc) {
            Ok(text) => println!("{text}"),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::FAILURE;
            }
        }
    } else {
        eprintln!("{summary}");
    }
    if errors == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// One diagnostic for `check --json`: lines and columns 1-based, columns in
/// characters, the end exclusive; `null` position for a file-wide error.
fn diagnostic_json(e: &stickslip_codegen::Located) -> serde_json::Value {
    let (line, column, end_line, end_column) = match e.position {
        Some(p) => (
            Some(p.line),
            Some(p.column),
            Some(p.end_line),
            Some(p.end_column),
        ),
        None => (None, None, None, None),
    };
    serde_json::json!({
        "severity": e.severity.as_str(),
        "message": e.message,
        "file": e.file,
        "line": line,
        "column": column,
        "end_line": end_line,
        "end_column": end_column,
        "rendered": e.rendered,
    })
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Command::Check { files, json } = &cli.command {
        return check(files, *json);
    }
    match run(cli) {
        Ok(outcome) => {
            let out = outcome.stdout;
            print!("{out}");
            if !out.ends_with('\n') {
                println!();
            }
            for note in &outcome.notes {
                eprintln!("{note}");
            }
            match outcome.failure {
                None => ExitCode::SUCCESS,
                Some(reason) => {
                    eprintln!("error: {reason}");
                    ExitCode::FAILURE
                }
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
