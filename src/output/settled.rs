//! What a simulation from a start state settles to, as a reader sees it:
//! the report, the heading of its figure, and the window of time its
//! history shows (one period of the motion, or the last simulated forcing
//! period). The `simulate` subcommand and the Python package both use it.

use std::f64::consts::TAU;

use crate::dynamics::simulate::{SimError, Simulator};
use crate::model::Model;
use crate::orbit::attractor::{self, Attractor, AttractorOptions};
use crate::orbit::lyapunov::{spectrum, LyapunovOptions};
use crate::orbit::motion::{Motion, OrbitError};
use crate::output::history::History;
use crate::output::lyapunov_report::verdict_text;
use crate::output::report::Report;

/// What the history of a settled simulation shows.
#[derive(Clone, Debug)]
pub enum Window {
    /// A periodic motion (admissible or not): one period of it, from its
    /// switching points.
    Motion(Box<Motion>),
    /// The simulation itself on `[from, to]` (phases): the last forcing
    /// period of NM, one period of a permanent stick, one autonomous cycle.
    Simulated {
        /// First phase shown.
        from: f64,
        /// Last phase shown.
        to: f64,
    },
    /// Nothing to show: no motion was found.
    None,
}

/// A simulation settled: its report, figure heading and history window.
#[derive(Clone, Debug)]
pub struct Settled {
    /// The report (`--json` prints it).
    pub report: Report,
    /// The figure heading, without the model name and parameters.
    pub heading: String,
    /// Said of the window in the title, before the parameters.
    pub note: Option<&'static str>,
    /// What the history shows.
    pub window: Window,
}

/// Simulate from `(x, v)` at phase `phase` until the motion settles
/// ([`attractor::find`]) and say what it settled to. A motion that is not
/// admissible is reported (its report says why); Newton that does not
/// converge is a report too, with no window. Only a failing simulation or
/// a bad start is an error.
pub fn settle<M: Model>(
    sim: &Simulator<M>,
    (x, v, phase): (f64, f64, f64),
    opts: AttractorOptions,
) -> Result<Settled, OrbitError> {
    let start = sim.start(x, v, phase)?;
    let (report, heading, note, window) = match attractor::find(sim, start, opts) {
        Ok(Attractor::Periodic(motion)) => motion_parts(sim, motion),
        Err(OrbitError::Inadmissible(motion)) => motion_parts(sim, *motion),
        Ok(Attractor::NoMotion(nm)) => (
            Report::of_no_motion::<M>(sim.params(), &nm),
            "NM, no boundary contact".to_string(),
            Some("last simulated forcing period"),
            Window::Simulated {
                from: (nm.certified_at - TAU).max(phase),
                to: nm.certified_at,
            },
        ),
        Ok(Attractor::Stick(stick)) => {
            let from = stick.since.max(phase);
            (
                Report::of_stick(sim.info(), &stick),
                format!("permanent stick at x = {:.6}", stick.x),
                Some("one forcing period"),
                Window::Simulated {
                    from,
                    to: from + TAU,
                },
            )
        }
        Ok(Attractor::Autonomous(cycle)) => {
            let from = cycle.onset.max(phase);
            (
                Report::of_autonomous(sim, &cycle),
                format!(
                    "autonomous {} cycle, T = {:.6}",
                    if cycle.stick > 0.0 {
                        "stick-slip"
                    } else {
                        "slip"
                    },
                    cycle.period
                ),
                None,
                Window::Simulated {
                    from,
                    to: from + cycle.period * sim.oscillator().frequency,
                },
            )
        }
        Err(OrbitError::NotConverged(t)) => (
            Report::of_termination::<M>(&t, None),
            String::new(),
            None,
            Window::None,
        ),
        Err(OrbitError::Unsettled {
            periods,
            undamped,
            instead: None,
        }) if periods >= DIAGNOSED_FROM => {
            return Err(OrbitError::Unsettled {
                periods,
                undamped,
                instead: diagnose(sim, (x, v, phase)),
            })
        }
        Err(e) => return Err(e),
    };
    Ok(Settled {
        report,
        heading,
        note,
        window,
    })
}

type Parts = (Report, String, Option<&'static str>, Window);

/// A simulation capped below this many forcing periods is not diagnosed:
/// the cap was the user's, and the diagnosis runs thousands of periods.
pub const DIAGNOSED_FROM: u32 = 1000;

/// What a motion that did not settle does instead: the verdict of its
/// Lyapunov exponents from the same start (the exact tangent map), and
/// what to run next. `None` where they cannot be computed.
fn diagnose<M: Model>(sim: &Simulator<M>, start: (f64, f64, f64)) -> Option<String> {
    let opts = LyapunovOptions::default();
    let s = spectrum(sim, start, opts).ok()?;
    Some(format!(
        "what it does instead, from the exact tangent map over {} forcing periods: {}, \
         largest exponent {:+.6e} ± {:.1e} per unit time. Next: `stickslip lyapunov` from the \
         same start for the spectrum, `stickslip orbit-diagram` along a parameter for where it \
         begins",
        opts.periods,
        verdict_text(&s.verdict),
        s.exponents[0],
        s.error
    ))
}

fn motion_parts<M: Model>(sim: &Simulator<M>, motion: Motion) -> Parts {
    let heading = format!(
        "{}, N = {}",
        motion.structure.notation(sim.info()),
        motion.structure.periods()
    );
    (
        Report::of_motion(sim, &motion),
        heading,
        Some("found by simulation"),
        Window::Motion(Box::new(motion)),
    )
}

impl Settled {
    /// The figure title: `MODEL: HEADING (NOTE; SETTINGS)`.
    pub fn title(&self, model: &str, settings: &str) -> String {
        match self.note {
            Some(note) => format!("{model}: {} ({note}; {settings})", self.heading),
            None => format!("{model}: {} ({settings})", self.heading),
        }
    }

    /// The samples of its window, `per_period` per forcing period; `start`
    /// is the start state of the simulation (`(x, v, phase)`), from which a
    /// simulated window is simulated again. `None` when there is no window.
    pub fn history<M: Model>(
        &self,
        sim: &Simulator<M>,
        (x, v, phase): (f64, f64, f64),
        per_period: usize,
    ) -> Result<Option<History>, SimError> {
        match &self.window {
            Window::Motion(motion) => Ok(Some(History::of_motion(sim, motion, per_period))),
            Window::Simulated { from, to } => {
                let start = sim.start(x, v, phase)?;
                let seg = sim.run(start, *from, |_| {})?;
                Ok(Some(History::simulated(sim, seg, *from, *to, per_period)?))
            }
            Window::None => Ok(None),
        }
    }
}
