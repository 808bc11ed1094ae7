//! The parallel driver: [`run_map`] computes a grid (or a shard) on all
//! cores, appending each point as soon as it is known, and resumes a killed
//! run; [`merge`] joins shard files into the file one run would write.

use std::collections::BTreeMap;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::model::Model;
use crate::study::progress::Progress;
use crate::study::record;

use super::classify::classify_point;
use super::continuation::classify_tile;
use super::error::{io_err, AxisError, MapError};
use super::file::{insert_all, write_canonical, MapFile, MapHeader, PointResult};
use super::grid::{grid_len, tile_of, GridAxis, Shard};

/// How the points of a map are classified.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MapMethod {
    /// Continue the motions of a point's neighbours by Newton, and simulate
    /// the starts only until they near a motion known there (see
    /// [`classify_tile`]): about ten times faster, and every motion the
    /// simulation method finds is listed, with the coexisting motions
    /// continued from the neighbours.
    #[default]
    Continuation,
    /// Simulate every point from its two starts until it settles
    /// ([`classify_point`]), independently of the other points.
    Simulation,
}

impl MapMethod {
    /// Parse `continuation` or `simulation`.
    pub fn parse(text: &str) -> Option<Self> {
        match text {
            "continuation" => Some(Self::Continuation),
            "simulation" => Some(Self::Simulation),
            _ => None,
        }
    }

    /// `continuation` or `simulation`: the name `--method` takes and the
    /// map file's header records.
    pub fn name(self) -> &'static str {
        match self {
            Self::Continuation => "continuation",
            Self::Simulation => "simulation",
        }
    }
}

/// Options of [`run_map`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MapOptions {
    /// Continue the run whose (possibly partial) output is already in the file.
    pub resume: bool,
    /// Compute only this part of the grid.
    pub shard: Option<Shard>,
    /// Show a progress bar on stderr (only when stderr is a terminal).
    pub progress: bool,
    /// Stop after computing this many points, leaving the file as a killed
    /// run would (unsorted, resumable). For tests and for time-boxed jobs.
    pub max_points: Option<usize>,
    /// How the points are classified.
    pub method: MapMethod,
}

/// What a run or merge did.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Points of the whole grid.
    pub grid_points: usize,
    /// Points of the part computed (the whole grid without a shard).
    pub shard_points: usize,
    /// Points found already computed in the file (resume) or in the inputs (merge).
    pub already_done: usize,
    /// Points computed by this call.
    pub computed: usize,
    /// Whether every point of the part is in the file, which is then sorted and final.
    pub complete: bool,
    /// How many points of each label ([`PointResult::label`]), most frequent first.
    pub labels: Vec<(String, usize)>,
    /// Wall time of the computation.
    pub elapsed: Duration,
}

fn label_counts(points: &[PointResult]) -> Vec<(String, usize)> {
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    for p in points {
        *counts.entry(p.label()).or_default() += 1;
    }
    let mut v: Vec<(String, usize)> = counts.into_iter().collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    v
}

/// Compute the map of `M` at `base` over `x_axis × y_axis` (or one shard of
/// it) on all cores into `out`, one line per point as soon as it is known.
///
/// Without `resume`, an existing `out` is an error ([`MapError::OutputExists`]).
/// With it, the points already in `out` are kept (a partial last line is
/// dropped), checked to belong to the same map, and only the rest are
/// computed. When every point of the part is in the file, it is rewritten
/// sorted by index (atomically), identical to an uninterrupted run.
pub fn run_map<M: Model>(
    base: &M::Params,
    x_axis: &GridAxis,
    y_axis: &GridAxis,
    out: &Path,
    opts: &MapOptions,
) -> Result<Summary, MapError> {
    run_map_counting::<M>(base, x_axis, y_axis, out, opts, None)
}

/// [`run_map`], counting into `counter` the points of the part that are in
/// the file (set first to those already there, then one more as each
/// finishes; out of [`Summary::shard_points`]), for a caller that shows its
/// own progress while the run goes on (the Python package).
/// `opts.progress` still decides the terminal bar.
pub fn run_map_counting<M: Model>(
    base: &M::Params,
    x_axis: &GridAxis,
    y_axis: &GridAxis,
    out: &Path,
    opts: &MapOptions,
    counter: Option<&AtomicU64>,
) -> Result<Summary, MapError> {
    let start = Instant::now();
    for axis in [x_axis, y_axis] {
        axis.check_for::<M>(base)
            .map_err(|source| AxisError::Parameter {
                text: axis.spec(),
                source,
            })?;
        if axis.count == 0 {
            return Err(AxisError::Count {
                text: axis.spec(),
                value: "0".to_string(),
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
    }
    if x_axis.name == y_axis.name {
        return Err(AxisError::SameParameter(x_axis.name.clone()).into());
    }
    let total = grid_len(x_axis, y_axis)?;
    if let Some(s) = opts.shard {
        if s.count == 0 || s.index >= s.count {
            return Err(MapError::BadShard(s.to_string()));
        }
    }
    let header = MapHeader::new::<M>(base, x_axis, y_axis, opts.method, opts.shard);
    let nx = x_axis.count;
    let in_part = |i: usize| header.shard.is_none_or(|s| s.contains(i, nx));
    let shard_points = (0..total).filter(|&i| in_part(i)).count();

    // The points already computed, and the file to append to.
    let mut done: BTreeMap<usize, PointResult> = BTreeMap::new();
    let existing = match fs::read(out) {
        Ok(text) => Some(text),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(io_err(out)(e)),
    };
    let file = match existing {
        Some(_) if !opts.resume => return Err(MapError::OutputExists(out.to_path_buf())),
        Some(bytes) => match MapFile::parse(out, &bytes)? {
            Some(previous) => {
                if let Some(what) = header.grid_difference(&previous.header) {
                    return Err(MapError::Mismatch {
                        path: out.to_path_buf(),
                        what,
                    });
                }
                if previous.header.shard != header.shard {
                    let show = |s: Option<Shard>| s.map_or("none".to_string(), |s| s.to_string());
                    return Err(MapError::Mismatch {
                        path: out.to_path_buf(),
                        what: format!(
                            "shard {}, not {}",
                            show(previous.header.shard),
                            show(header.shard)
                        ),
                    });
                }
                let mut conflicts = Vec::new();
                insert_all(&mut done, previous.points, &mut conflicts);
                if !conflicts.is_empty() {
                    return Err(MapError::Conflict(conflicts));
                }
                record::reopen(out, previous.valid_len).map_err(io_err(out))?
            }
            // Killed before even the header was complete: start afresh.
            None => record::start(out, &header.to_lines(), false).map_err(io_err(out))?,
        },
        None => record::start(out, &header.to_lines(), true).map_err(io_err(out))?,
    };
    let already_done = done.len();
    let todo: Vec<usize> = (0..total)
        .filter(|&i| in_part(i) && !done.contains_key(&i))
        .collect();

    let bar = Progress::new(
        progress_bar(opts.progress, shard_points as u64, already_done as u64),
        counter,
        already_done as u64,
    );
    let file = Mutex::new(file);
    let new_points: Mutex<Vec<PointResult>> = Mutex::new(Vec::with_capacity(todo.len()));
    let write_error: Mutex<Option<io::Error>> = Mutex::new(None);
    let failed = AtomicBool::new(false);
    let claimed = AtomicUsize::new(0);
    let limit = opts.max_points.unwrap_or(usize::MAX);
    // The unfinished tiles, each with its missing points (in index order).
    let mut tiles: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &i in &todo {
        tiles.entry(tile_of(i, nx)).or_default().push(i);
    }
    let tiles: Vec<(usize, Vec<usize>)> = tiles.into_iter().collect();
    // Append `records` (the missing points of one tile), as far as the limit allows.
    let write = |records: Vec<PointResult>| {
        for record in records {
            if failed.load(Ordering::Relaxed) || claimed.fetch_add(1, Ordering::Relaxed) >= limit {
                return;
            }
            let line = record.to_line();
            {
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
            new_points
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .push(record);
            bar.inc();
        }
    };
    let stop = || failed.load(Ordering::Relaxed) || claimed.load(Ordering::Relaxed) >= limit;
    match opts.method {
        MapMethod::Simulation => todo.par_iter().with_max_len(1).for_each(|&i| {
            if !stop() {
                write(vec![classify_point::<M>(base, x_axis, y_axis, i)]);
            }
        }),
        MapMethod::Continuation => tiles.par_iter().with_max_len(1).for_each(|(t, missing)| {
            if stop() {
                return;
            }
            // The whole tile is recomputed (its result depends on it alone);
            // only its missing points are written.
            let records = classify_tile::<M>(base, x_axis, y_axis, *t)
                .into_iter()
                .filter(|r| missing.binary_search(&r.index).is_ok())
                .collect();
            write(records);
        }),
    }
    bar.finish();
    drop(file);
    if let Some(e) = write_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(io_err(out)(e));
    }
    let new_points = new_points.into_inner().unwrap_or_else(|e| e.into_inner());
    let computed = new_points.len();
    for p in new_points {
        done.insert(p.index, p);
    }
    let complete = done.len() == shard_points;
    let points: Vec<PointResult> = done.into_values().collect();
    if complete {
        write_canonical(out, &header, &points)?;
    }
    Ok(Summary {
        grid_points: total,
        shard_points,
        already_done,
        computed,
        complete,
        labels: label_counts(&points),
        elapsed: start.elapsed(),
    })
}

fn progress_bar(show: bool, len: u64, done: u64) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    if !show {
        return ProgressBar::hidden();
    }
    // The stderr target draws nothing when stderr is not a terminal.
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{wide_bar} {pos}/{len} points  {rate}  {elapsed} elapsed  ETA {eta}",
    ) {
        let rate = |state: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
            let _ = write!(w, "{:.0}/s", state.per_sec());
        };
        bar.set_style(style.with_key("rate", rate));
    }
    bar.set_position(done);
    bar.reset_eta();
    bar
}

/// Join map files of the same grid — shards, possibly partial, possibly
/// with duplicate points — into the complete map `out`, the same bytes as a
/// single run of the whole grid. Every grid point must be present, and a
/// point given twice must be given identically.
pub fn merge(inputs: &[PathBuf], out: &Path) -> Result<Summary, MapError> {
    let start = Instant::now();
    let mut header: Option<MapHeader> = None;
    let mut by_index: BTreeMap<usize, PointResult> = BTreeMap::new();
    let mut conflicts = Vec::new();
    let mut read_points = 0usize;
    for path in inputs {
        let file = MapFile::read(path)?;
        match &header {
            None => header = Some(file.header.clone()),
            Some(h) => {
                if let Some(what) = h.grid_difference(&file.header) {
                    return Err(MapError::Mismatch {
                        path: path.clone(),
                        what: format!("{what} (as in `{}`)", inputs[0].display()),
                    });
                }
            }
        }
        read_points += file.points.len();
        insert_all(&mut by_index, file.points, &mut conflicts);
    }
    let Some(mut header) = header else {
        return Err(MapError::NoInput);
    };
    if !conflicts.is_empty() {
        conflicts.sort_unstable();
        conflicts.dedup();
        return Err(MapError::Conflict(conflicts));
    }
    let total = header.len();
    let missing: Vec<usize> = (0..total).filter(|i| !by_index.contains_key(i)).collect();
    if !missing.is_empty() {
        return Err(MapError::Missing(missing));
    }
    header.shard = None;
    let points: Vec<PointResult> = by_index.into_values().collect();
    write_canonical(out, &header, &points)?;
    Ok(Summary {
        grid_points: total,
        shard_points: total,
        already_done: read_points,
        computed: 0,
        complete: true,
        labels: label_counts(&points),
        elapsed: start.elapsed(),
    })
}
