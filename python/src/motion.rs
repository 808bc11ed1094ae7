//! `simulate` and `orbit`: a periodic motion (or NM, stick, an autonomous
//! cycle) as the CLI's JSON report, and a [`Trajectory`] that samples it.

use std::f64::consts::TAU;

use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::attractor::{self, AttractorOptions};
use stickslip::orbit::guess::points_from_guess;
use stickslip::orbit::motion;
use stickslip::orbit::periodic::NewtonOptions;
use stickslip::orbit::structure::Structure;
use stickslip::output::history::History;
use stickslip::output::report::Report;
use stickslip::output::settled::{settle, Settled, Window};
use stickslip::Model;
use stickslip_codegen::structure::implied_periods;

use crate::command::{params, settings, with_model, Command, ModelSpec};
use crate::failure::{Failure, Kind};

/// The columns of a history: `t, Wt, x, v, a, F, domain` (domain 0: stick).
type Columns = (
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<i64>,
);

/// The same columns as numpy arrays, each moved from its `Vec` (no copy).
type Arrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<i64>>,
);

fn arrays(py: Python<'_>, c: Columns) -> Arrays<'_> {
    (
        c.0.into_pyarray(py),
        c.1.into_pyarray(py),
        c.2.into_pyarray(py),
        c.3.into_pyarray(py),
        c.4.into_pyarray(py),
        c.5.into_pyarray(py),
        c.6.into_pyarray(py),
    )
}

/// Samples a settled result again, with its model and parameters.
trait Source: Send + Sync {
    fn columns(&self, periods: u32, per_period: usize) -> Result<Option<Columns>, Failure>;
    fn title(&self) -> String;
}

struct Held<M: Model> {
    sim: Simulator<M>,
    settled: Settled,
    start: (f64, f64, f64),
    title: String,
}

impl<M: Model> Source for Held<M> {
    fn columns(&self, periods: u32, per_period: usize) -> Result<Option<Columns>, Failure> {
        let periods = periods.max(1);
        let (history, shift) = match &self.settled.window {
            Window::Motion(m) => {
                // One cycle, repeated exactly: a periodic motion repeats.
                let cycle = TAU * m.structure.periods() as f64;
                (History::of_motion(&self.sim, m, per_period), Some(cycle))
            }
            Window::Simulated { from, to } => {
                // A longer window, simulated.
                let mut longer = self.settled.clone();
                longer.window = Window::Simulated {
                    from: *from,
                    to: from + (to - from) * f64::from(periods),
                };
                (
                    longer
                        .history(&self.sim, self.start, per_period)?
                        .ok_or_else(|| Failure::new(Kind::Input, "there is no motion"))?,
                    None,
                )
            }
            Window::None => return Ok(None),
        };
        let w = self.sim.oscillator().frequency;
        let repeats = if shift.is_some() { periods } else { 1 };
        let n = history.samples().count() * repeats as usize;
        let mut c: Columns = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for r in 0..repeats {
            let dphase = shift.unwrap_or(0.0) * f64::from(r);
            for s in history.samples() {
                c.0.push(s.t + dphase / w);
                c.1.push(s.phase + dphase);
                c.2.push(s.x);
                c.3.push(s.v);
                c.4.push(s.a);
                c.5.push(s.friction);
                c.6.push(i64::from(s.domain));
            }
        }
        Ok(Some(c))
    }

    fn title(&self) -> String {
        self.title.clone()
    }
}

/// A result's motion in time, sampled on request (`Motion.history`).
#[pyclass(frozen, module = "stickslip._native")]
pub struct Trajectory {
    source: Box<dyn Source>,
}

#[pymethods]
impl Trajectory {
    /// `periods` cycles of the motion (or the simulated window made
    /// `periods` times longer), `samples` per forcing period: the columns
    /// `t, Wt, x, v, a, F, domain` as numpy arrays (float64, the domain
    /// int64), or `None` when there is no motion.
    #[pyo3(signature = (periods = 1, samples = 400))]
    fn history<'py>(
        &self,
        py: Python<'py>,
        periods: u32,
        samples: usize,
    ) -> PyResult<Option<Arrays<'py>>> {
        if samples == 0 {
            return Err(Failure::new(Kind::Input, "samples must be at least 1").into());
        }
        let columns = py.detach(|| self.source.columns(periods, samples))?;
        Ok(columns.map(|c| arrays(py, c)))
    }

    /// The figure title the CLI gives this result.
    fn title(&self) -> String {
        self.source.title()
    }
}

/// What `simulate` and `orbit` return: the report as JSON, the failure
/// line (Newton did not converge, not admissible), notes, the trajectory.
type Answer = (String, Option<String>, Vec<String>, Trajectory);

fn answer<M: Model>(
    sim: Simulator<M>,
    settled: Settled,
    start: (f64, f64, f64),
    title: String,
    notes: Vec<String>,
) -> Answer {
    let json = settled.report.to_json();
    let failure = settled.report.failure();
    let source = Box::new(Held {
        sim,
        settled,
        start,
        title,
    });
    (json, failure, notes, Trajectory { source })
}

struct Simulate {
    set: Vec<(String, f64)>,
    start: (f64, f64, f64),
    periods: Option<u32>,
}

impl Command for Simulate {
    type Output = Answer;
    fn run<M: Model>(self, base: M::Params) -> Result<Answer, Failure> {
        let sim = Simulator::<M>::new(params::<M>(base, &self.set)?, SimOptions::default())?;
        let mut opts = AttractorOptions::default();
        if let Some(k) = self.periods {
            if k == 0 {
                return Err(Failure::new(Kind::Input, "periods must be at least 1"));
            }
            opts.max_periods = k;
        }
        let settled = settle(&sim, self.start, opts)?;
        let title = settled.title(sim.info().name, &settings(&self.set));
        Ok(answer(sim, settled, self.start, title, Vec::new()))
    }
}

/// `stickslip simulate`: from `start = (x, v, W t)` until the motion settles.
#[pyfunction]
#[pyo3(signature = (model, set, start, periods = None))]
pub fn simulate(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    start: (f64, f64, f64),
    periods: Option<u32>,
) -> PyResult<Answer> {
    let cmd = Simulate {
        set,
        start,
        periods,
    };
    Ok(py.detach(|| with_model(&model, cmd))?)
}

struct Orbit {
    set: Vec<(String, f64)>,
    structure: String,
    periods: u32,
    guess: Option<(f64, f64)>,
}

impl Command for Orbit {
    type Output = Answer;
    fn run<M: Model>(self, base: M::Params) -> Result<Answer, Failure> {
        let sim = Simulator::<M>::new(params::<M>(base, &self.set)?, SimOptions::default())?;
        let info = sim.info();
        let structure = Structure::parse(info, &self.structure, self.periods).map_err(|e| {
            Failure::new(
                Kind::Structure,
                format!("structure `{}`: {e}", self.structure),
            )
        })?;
        let mut notes = Vec::new();
        let from_guess = match self.guess {
            None => None,
            Some((phase, x)) => match points_from_guess(&sim, &structure, phase, x) {
                Ok(points) => Some(points),
                Err(why) => {
                    notes.push(format!(
                        "guess=({phase}, {x}): {why}; seeding by simulation instead"
                    ));
                    None
                }
            },
        };
        let points = match from_guess {
            Some(points) => points,
            None => attractor::seed(&sim, &structure).ok_or_else(|| {
                Failure::new(
                    Kind::Seed,
                    format!(
                        "no simulated motion follows {}; give the first switching point with guess=(Wt, x)",
                        structure.notation(info)
                    ),
                )
            })?,
        };
        let motion = motion::solve(&sim, structure, points, NewtonOptions::default());
        let report = Report::of_motion(&sim, &motion);
        let heading = format!(
            "{}, N = {}",
            motion.structure.notation(info),
            motion.structure.periods()
        );
        let title = format!("{}: {heading} ({})", info.name, settings(&self.set));
        let start = motion
            .points
            .first()
            .map_or((0.0, 0.0, 0.0), |p| (p.x, 0.0, p.phase));
        let window = if matches!(report, Report::NotConverged(_)) {
            Window::None
        } else {
            Window::Motion(Box::new(motion))
        };
        let settled = Settled {
            report,
            heading,
            note: None,
            window,
        };
        Ok(answer(sim, settled, start, title, notes))
    }
}

/// `stickslip orbit`: Newton on `structure` (applied right to left), seeded
/// from `guess = (W t, x)` or by simulation.
#[pyfunction]
#[pyo3(signature = (model, set, structure, periods = None, guess = None))]
pub fn orbit(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    structure: String,
    periods: Option<u32>,
    guess: Option<(f64, f64)>,
) -> PyResult<Answer> {
    // As on the command line: 1, or `k` for a block repeated `k` times.
    let periods = periods.unwrap_or_else(|| implied_periods(&structure));
    let cmd = Orbit {
        set,
        structure,
        periods,
        guess,
    };
    Ok(py.detach(|| with_model(&model, cmd))?)
}
