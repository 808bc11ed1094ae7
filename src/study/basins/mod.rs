//! Basins of attraction: which attractor each initial state
//! `(x, v)` at the stroboscopic phase `W t = φ0` reaches, over a grid, and
//! basin stability by random sampling (Menck et al. 2013).
//!
//! Every stable periodic motion is identified once ([`discover`]: full
//! searches from a fixed subgrid of seed starts), and every start is
//! simulated only until its stroboscopic point nears one of them
//! ([`crate::orbit::known::settle`], the "seed, continue, match" of
//! Attractors.jl on exact states); a start that nears none settles as
//! [`crate::orbit::attractor::find`] does (a periodic motion by its
//! structure, NM, a permanent stick), and one that never settles is judged
//! by its largest Lyapunov exponent: `chaotic` or `quasi-periodic`
//! ([`classify::irregular`]). The basin fraction of an attractor is its
//! share of the grid; its basin stability is its share of `S` starts drawn
//! uniformly from the grid's box by a seeded [`sample::SplitMix64`], with a
//! 95 % Wilson interval ([`sample::wilson`]).
//!
//! [`run_basins`] computes on all cores and appends each start's line to
//! the output file as soon as it is known, so that a run killed at any
//! moment resumes (`resume`) without losing or repeating a start; at the
//! end the file is rewritten sorted by index, atomically. A start's result
//! depends on the header alone, so the file is the same byte for byte on
//! any number of threads and after any number of resumes.
//!
//! # File format
//!
//! ```text
//! # stickslip basins model=paper x=x=-2:2:200 y=v=-2:3:200 phase=0.0 samples=1000 seed=1 periods=600 lyapunov=2000 params=m=1.0,...
//! index,x,v,attractor,exponent
//! 0,-2.0,-2.0,"P_{3_31 0_11 3_13 4_33}",
//! 40017,0.4119...,1.27...,"chaotic",0.0213
//! ```
//!
//! Indices below `nx · nv` are grid points (`index = iv · nx + ix`); the
//! next `S` are the random samples, the `k`-th at
//! [`sample::random_start`]`(seed, k, …)`. The exponent (per unit time) is
//! given for starts that never settled.

mod classify;
mod error;
mod file;
pub mod sample;

use std::collections::BTreeMap;
use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;
use serde::Serialize;

use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::Model;
use crate::study::map::{AxisError, GridAxis};
use crate::study::progress::Progress;
use crate::study::record;

pub use classify::{
    attractor_label, classify, discover, irregular, seed_indices, Known, CHAOTIC, QUASI_PERIODIC,
    SEEDS_PER_AXIS, UNSETTLED,
};
pub use error::BasinsError;
pub use file::{BasinFile, BasinHeader, StartResult};

use error::io_err;
use file::write_canonical;
use sample::{wilson, Z95};

/// Forcing periods simulated at most from each start, by default.
pub const MAX_PERIODS: u32 = 600;
/// Forcing periods of the exponent of a start that never settled, by default.
pub const LYAPUNOV_PERIODS: u32 = 2000;

/// What a basin run computes besides the grid (all of it in the file's header).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasinSettings {
    /// The stroboscopic phase `W t` of every start.
    pub phase: f64,
    /// Random starts for basin stability.
    pub samples: usize,
    /// Their seed.
    pub seed: u64,
    /// Forcing periods simulated at most from each start.
    pub periods: u32,
    /// Forcing periods of the exponent of a start that never settled (0: none computed).
    pub lyapunov: u32,
}

impl Default for BasinSettings {
    fn default() -> Self {
        Self {
            phase: 0.0,
            samples: 1000,
            seed: 1,
            periods: MAX_PERIODS,
            lyapunov: LYAPUNOV_PERIODS,
        }
    }
}

/// How [`run_basins`] runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BasinOptions {
    /// Continue the run whose (possibly partial) output is already in the file.
    pub resume: bool,
    /// Show a progress bar on stderr (only when stderr is a terminal).
    pub progress: bool,
    /// Stop after computing this many starts, leaving the file as a killed
    /// run would (unsorted, resumable). For tests and time-boxed jobs.
    pub max_points: Option<usize>,
}

/// One attractor and its basin.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AttractorBasin {
    /// `P_{…}` (with `^N`), `NM`, `stick`, `chaotic`, `quasi-periodic`, or
    /// why none was reached (`unsettled`, …).
    pub name: String,
    /// Grid points in its basin.
    pub points: usize,
    /// Their share of the grid.
    pub fraction: f64,
    /// Random samples in its basin.
    pub samples: usize,
    /// Their share of the samples (basin stability).
    pub stability: f64,
    /// The 95 % Wilson interval of the basin stability.
    pub interval: [f64; 2],
    /// The mean largest Lyapunov exponent (per unit time) of its starts,
    /// where computed (starts that never settled).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exponent: Option<f64>,
    /// Its first start `(x, v)` (grid first, then samples), to check it from.
    pub example: (f64, f64),
}

/// What a basin run did.
#[derive(Clone, Debug, PartialEq)]
pub struct Basins {
    /// What was computed.
    pub header: BasinHeader,
    /// The attractors, largest grid basin first (then by stability, then by name).
    pub attractors: Vec<AttractorBasin>,
    /// Starts found already computed in the file.
    pub already_done: usize,
    /// Starts computed by this call.
    pub computed: usize,
    /// Whether every start is in the file, which is then sorted and final.
    pub complete: bool,
    /// Wall time of the computation.
    pub elapsed: Duration,
    /// Every start computed so far, by index.
    pub starts: Vec<StartResult>,
    /// The basin file, if the run keeps one.
    pub file: Option<PathBuf>,
}

impl Basins {
    /// The starts as a basin file holds them (for a figure of a run kept in
    /// memory).
    pub fn to_file(&self) -> BasinFile {
        BasinFile {
            header: self.header.clone(),
            starts: self.starts.clone(),
            valid_len: 0,
        }
    }
}

/// Open `out` for a run of `header`: a new file with its header, or, with
/// `resume`, the file of the same run with the starts it holds read into
/// `done` (a partial last line cut off). An existing file is never
/// overwritten.
fn open_output(
    out: &Path,
    header: &BasinHeader,
    resume: bool,
    done: &mut BTreeMap<usize, StartResult>,
) -> Result<File, BasinsError> {
    let existing = match fs::read(out) {
        Ok(bytes) => Some(bytes),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(io_err(out)(e)),
    };
    let file = match existing {
        Some(_) if !resume => return Err(BasinsError::OutputExists(out.to_path_buf())),
        Some(bytes) => match BasinFile::parse(out, &bytes)? {
            Some(previous) => {
                if let Some(what) = header.difference(&previous.header) {
                    return Err(BasinsError::Mismatch {
                        path: out.to_path_buf(),
                        what,
                    });
                }
                for s in previous.starts {
                    match done.get(&s.index) {
                        Some(q) if q.to_line() != s.to_line() => {
                            return Err(BasinsError::Conflict {
                                path: out.to_path_buf(),
                                index: s.index,
                            })
                        }
                        _ => {
                            done.insert(s.index, s);
                        }
                    }
                }
                record::reopen(out, previous.valid_len).map_err(io_err(out))?
            }
            None => record::start(out, &header.to_lines(), false).map_err(io_err(out))?,
        },
        None => record::start(out, &header.to_lines(), true).map_err(io_err(out))?,
    };
    Ok(file)
}

/// One attractor's starts while summarizing: grid points, samples, the sum
/// and count of finite exponents, and its first start.
#[derive(Clone, Copy)]
struct Tally {
    points: usize,
    samples: usize,
    sum: f64,
    with: usize,
    example: (f64, f64),
}

/// The attractors of the starts of `file` and their basins.
pub fn summarize(header: &BasinHeader, starts: &[StartResult]) -> Vec<AttractorBasin> {
    let grid = header.grid_len();
    let mut by: BTreeMap<&str, Tally> = BTreeMap::new();
    let mut sorted: Vec<&StartResult> = starts.iter().collect();
    sorted.sort_by_key(|s| s.index);
    let (mut on_grid, mut sampled) = (0, 0);
    for s in sorted {
        let e = by.entry(&s.attractor).or_insert(Tally {
            points: 0,
            samples: 0,
            sum: 0.0,
            with: 0,
            example: (s.x, s.v),
        });
        if s.index < grid {
            e.points += 1;
            on_grid += 1;
        } else {
            e.samples += 1;
            sampled += 1;
        }
        if let Some(x) = s.exponent.filter(|x| x.is_finite()) {
            e.sum += x;
            e.with += 1;
        }
    }
    let share = |k: usize, n: usize| if n == 0 { 0.0 } else { k as f64 / n as f64 };
    let mut out: Vec<AttractorBasin> = by
        .into_iter()
        .map(|(name, t)| AttractorBasin {
            name: name.to_string(),
            points: t.points,
            fraction: share(t.points, on_grid),
            samples: t.samples,
            stability: share(t.samples, sampled),
            interval: wilson(t.samples, sampled, Z95),
            exponent: (t.with > 0).then(|| t.sum / t.with as f64),
            example: t.example,
        })
        .collect();
    out.sort_by(|a, b| {
        b.points
            .cmp(&a.points)
            .then(b.samples.cmp(&a.samples))
            .then_with(|| a.name.cmp(&b.name))
    });
    out
}

/// Check a grid axis of the state variable `expected` (`x` or `v`).
fn check_axis(
    axis: &GridAxis,
    option: &'static str,
    expected: &'static str,
) -> Result<(), BasinsError> {
    if axis.name != expected {
        return Err(BasinsError::AxisVariable {
            option,
            text: axis.spec(),
            expected,
        });
    }
    if axis.count == 0 {
        return Err(AxisError::Count {
            text: axis.spec(),
            value: "0".into(),
        }
        .into());
    }
    if !(axis.from.is_finite() && axis.to.is_finite()) {
        return Err(AxisError::NotFinite {
            text: axis.spec(),
            value: format!("{}:{}", axis.from, axis.to),
        }
        .into());
    }
    Ok(())
}

/// The basins of `M` at `params` over the grid `x × v` of starts at phase
/// `settings.phase`, and `settings.samples` random starts, on all cores,
/// into the file `out` if one is given (one line per start as soon as it is
/// known), else in memory only.
///
/// Without `resume`, an existing `out` is an error: a file is never
/// overwritten. With it, the starts already in `out` are kept (a partial
/// last line is dropped) after the header is checked to describe the same
/// run, and only the rest are computed. When every start is in the file, it
/// is rewritten sorted. `resume` without a file is an error.
pub fn run_basins<M: Model>(
    params: &M::Params,
    x: &GridAxis,
    v: &GridAxis,
    settings: &BasinSettings,
    out: Option<&Path>,
    opts: &BasinOptions,
) -> Result<Basins, BasinsError> {
    run_basins_counting::<M>(params, x, v, settings, out, opts, None)
}

/// [`run_basins`], counting into `counter` the starts that are in the file
/// (set first to those already there, then one more as each finishes; out
/// of [`BasinHeader::len`]), for a caller that shows its own progress while
/// the run goes on (the Python package). `opts.progress` still decides the
/// terminal bar.
pub fn run_basins_counting<M: Model>(
    params: &M::Params,
    x: &GridAxis,
    v: &GridAxis,
    settings: &BasinSettings,
    out: Option<&Path>,
    opts: &BasinOptions,
    counter: Option<&AtomicU64>,
) -> Result<Basins, BasinsError> {
    let start = Instant::now();
    check_axis(x, "--x", "x")?;
    check_axis(v, "--y", "v")?;
    if !settings.phase.is_finite() {
        return Err(BasinsError::Phase(settings.phase));
    }
    if x.count.checked_mul(v.count).is_none() {
        return Err(AxisError::TooLarge(x.count, v.count).into());
    }
    let sim = Simulator::<M>::new(*params, SimOptions::default())?;
    let header = BasinHeader::new::<M>(
        params,
        x,
        v,
        settings.phase,
        settings.samples,
        settings.seed,
        settings.periods,
        settings.lyapunov,
    );
    let total = header.len();

    let mut done: BTreeMap<usize, StartResult> = BTreeMap::new();
    let file = match out {
        Some(out) => Some(open_output(out, &header, opts.resume, &mut done)?),
        None if opts.resume => return Err(BasinsError::ResumeWithoutFile),
        None => None,
    };
    let already_done = done.len();
    let todo: Vec<usize> = (0..total).filter(|i| !done.contains_key(i)).collect();

    let known = if todo.is_empty() {
        None
    } else {
        Some(discover(&sim, &header))
    };
    let bar = Progress::new(
        progress_bar(opts.progress, total as u64, already_done as u64),
        counter,
        already_done as u64,
    );
    let file = file.map(Mutex::new);
    let new_starts: Mutex<Vec<StartResult>> = Mutex::new(Vec::with_capacity(todo.len()));
    let write_error: Mutex<Option<io::Error>> = Mutex::new(None);
    let failed = AtomicBool::new(false);
    let claimed = AtomicUsize::new(0);
    let limit = opts.max_points.unwrap_or(usize::MAX);
    if let Some(known) = &known {
        todo.par_iter().with_max_len(1).for_each(|&i| {
            if failed.load(Ordering::Relaxed) || claimed.load(Ordering::Relaxed) >= limit {
                return;
            }
            let record = classify(&sim, known, &header, i);
            if claimed.fetch_add(1, Ordering::Relaxed) >= limit {
                return;
            }
            if let Some(file) = &file {
                let line = record.to_line();
                let mut f = file.lock().unwrap_or_else(|e| e.into_inner());
                if let Err(e) = f.write_all(line.as_bytes()).and_then(|()| f.flush()) {
                    failed.store(true, Ordering::Relaxed);
                    write_error
                        .lock()
                        .unwrap_or_else(|e| e.into_inner())
                        .get_or_insert(e);
                    return;
                }
            }
            new_starts
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .push(record);
            bar.inc();
        });
    }
    bar.finish();
    drop(file);
    if let (Some(e), Some(out)) = (
        write_error.into_inner().unwrap_or_else(|e| e.into_inner()),
        out,
    ) {
        return Err(io_err(out)(e));
    }
    let new_starts = new_starts.into_inner().unwrap_or_else(|e| e.into_inner());
    let computed = new_starts.len();
    for s in new_starts {
        done.insert(s.index, s);
    }
    let complete = done.len() == total;
    let starts: Vec<StartResult> = done.into_values().collect();
    if let (true, Some(out)) = (complete, out) {
        write_canonical(out, &header, &starts)?;
    }
    Ok(Basins {
        attractors: summarize(&header, &starts),
        starts,
        file: out.map(Path::to_path_buf),
        header,
        already_done,
        computed,
        complete,
        elapsed: start.elapsed(),
    })
}

fn progress_bar(show: bool, len: u64, done: u64) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{wide_bar} {pos}/{len} starts  {elapsed} elapsed  ETA {eta}")
    {
        bar.set_style(style);
    }
    bar.set_position(done);
    bar.reset_eta();
    bar
}
