//! Parameter maps (SPEC §9, the paper's Fig. 11): which motions exist at
//! each point of a grid over two parameters.
//!
//! At every grid point the motion is simulated from two starts (rest, and a
//! state above the stick boundary half a forcing period later) until it
//! settles ([`attractor::find`]); the distinct results — periodic motions
//! named by structure and period, or `NM` — are the point's motions, so
//! coexisting motions (the flow barrier of SPEC §10) show up as a set.
//!
//! [`run_map`] computes a grid (or one shard of it, for a cluster job
//! array) on all cores and appends each point's line to the output file as
//! soon as it is known, so that a run killed at any moment resumes without
//! losing or repeating a point; at the end the file is rewritten sorted by
//! index. [`merge`] joins shard files into the file a single run would have
//! written, byte for byte.
//!
//! # File format
//!
//! ```text
//! # stickslip map model=paper x=W=3:5:6 y=Q0=50:80:3 base=m=5,d=0.1,... [shard=0/3]
//! index,W,Q0,status,motions
//! 0,3.0,50.0,"ok","P_{3_31 0_11 3_13 4_33}"
//! 1,3.4,50.0,"ok","NM;P_{3_33 4_33}^2"
//! ```
//!
//! Grid point `index = iy * nx + ix` lies at `x = x.value(ix)`,
//! `y = y.value(iy)`. `status` is `ok` when every start settled, `invalid: …`
//! for parameters the model rejects, and otherwise names the starts that did
//! not settle (`start 2: unsettled`). `motions` are sorted and joined by `;`:
//! a structure in the paper's notation with `^N` when its period is `N > 1`
//! forcing periods, or `NM`. Numbers are printed in Rust's shortest
//! round-trip form, so a parsed line prints back byte for byte. The shard
//! appears in the header of a shard's file only: a complete map does not
//! depend on how it was computed.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::param::{ParamError, ParamSet};
use crate::model::Model;
use crate::orbit::attractor::{self, Attractor, AttractorOptions};
use crate::orbit::motion::{Motion, OrbitError};
use crate::orbit::periodic::Termination;

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// Forcing periods simulated at most from each start.
pub const MAX_PERIODS: u32 = 600;

/// The label of "no motion touches a boundary".
pub const NO_MOTION: &str = "NM";

/// The label of a permanent stick in a map.
pub const STICK: &str = "stick";

/// Why an axis specification was rejected.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AxisError {
    /// Not `NAME=FROM:TO:COUNT`.
    #[error("axis `{text}`: expected NAME=FROM:TO:COUNT (e.g. W=3:5:21)")]
    Syntax {
        /// The text given.
        text: String,
    },
    /// A bound that is not a number, or not finite.
    #[error("axis `{text}`: `{value}` is not a finite number")]
    NotFinite {
        /// The text given.
        text: String,
        /// The offending bound.
        value: String,
    },
    /// A count that is zero or not an integer.
    #[error("axis `{text}`: the point count `{value}` must be a positive integer")]
    Count {
        /// The text given.
        text: String,
        /// The offending count.
        value: String,
    },
    /// Not a run-time parameter of the model.
    #[error("axis `{text}`: {source}")]
    Parameter {
        /// The text given.
        text: String,
        /// Unknown, or fixed in the scene.
        source: ParamError,
    },
    /// Both axes vary the same parameter.
    #[error("both axes vary `{0}`: choose two different parameters")]
    SameParameter(String),
    /// More grid points than can be counted.
    #[error("the grid has too many points ({0} × {1})")]
    TooLarge(usize, usize),
}

/// One axis of a map: `count` values of parameter `name` from `from` to `to`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridAxis {
    /// The parameter.
    pub name: String,
    /// First value.
    pub from: f64,
    /// Last value (may be below `from`).
    pub to: f64,
    /// Number of values (at least 1).
    pub count: usize,
}

impl GridAxis {
    /// Parse `NAME=FROM:TO:COUNT` without knowing the model (see [`parse_for`](Self::parse_for)).
    pub fn parse(text: &str) -> Result<Self, AxisError> {
        let syntax = || AxisError::Syntax {
            text: text.to_string(),
        };
        let (name, range) = text.split_once('=').ok_or_else(syntax)?;
        let name = name.trim();
        let valid_name = !name.is_empty()
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !name.starts_with(|c: char| c.is_ascii_digit());
        if !valid_name {
            return Err(syntax());
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [from, to, count] = parts[..] else {
            return Err(syntax());
        };
        let number = |s: &str| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(AxisError::NotFinite {
                text: text.to_string(),
                value: s.to_string(),
            }),
        };
        let (from, to) = (number(from)?, number(to)?);
        let count = match count.parse::<usize>() {
            Ok(n) if n > 0 => n,
            _ => {
                return Err(AxisError::Count {
                    text: text.to_string(),
                    value: count.to_string(),
                })
            }
        };
        Ok(Self {
            name: name.to_string(),
            from,
            to,
            count,
        })
    }

    /// Parse `NAME=FROM:TO:COUNT` for model `M`: `NAME` must be one of its
    /// run-time parameters ([`ParamSet::NAMES`]).
    pub fn parse_for<M: Model>(text: &str) -> Result<Self, AxisError> {
        let axis = Self::parse(text)?;
        axis.check_for::<M>()
            .map_err(|source| AxisError::Parameter {
                text: text.to_string(),
                source,
            })?;
        Ok(axis)
    }

    /// Whether the axis's parameter is a run-time parameter of `M`.
    pub fn check_for<M: Model>(&self) -> Result<(), ParamError> {
        if M::Params::index_of(&self.name).is_some() {
            return Ok(());
        }
        let info = M::INFO;
        let free = M::Params::NAMES.join(", ");
        Err(match info.params.iter().find(|p| p.name == self.name) {
            Some(p) => ParamError::Fixed {
                name: self.name.clone(),
                model: info.name.to_string(),
                value: p.default,
                free,
            },
            None => ParamError::Unknown {
                name: self.name.clone(),
                model: info.name.to_string(),
                known: free,
            },
        })
    }

    /// Value `i` (`0 ≤ i < count`): `from + (to - from) i / (count - 1)`, exactly `to` at the end.
    pub fn value(&self, i: usize) -> f64 {
        if self.count <= 1 || i == 0 {
            self.from
        } else if i + 1 == self.count {
            self.to
        } else {
            self.from + (self.to - self.from) * i as f64 / (self.count - 1) as f64
        }
    }

    /// All values, in order.
    pub fn values(&self) -> Vec<f64> {
        (0..self.count).map(|i| self.value(i)).collect()
    }

    /// `NAME=FROM:TO:COUNT`, which [`parse`](Self::parse) reads back exactly.
    pub fn spec(&self) -> String {
        format!("{}={}:{}:{}", self.name, self.from, self.to, self.count)
    }
}

impl std::fmt::Display for GridAxis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.spec())
    }
}

/// Number of points of the grid `x × y`.
pub fn grid_len(x: &GridAxis, y: &GridAxis) -> Result<usize, AxisError> {
    x.count
        .checked_mul(y.count)
        .ok_or(AxisError::TooLarge(x.count, y.count))
}

/// Part `index` of `count` disjoint parts of a grid: the points whose index is `index` mod `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which part (`0 ≤ index < count`).
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

impl Shard {
    /// Parse `k/n` (`0 ≤ k < n`).
    pub fn parse(text: &str) -> Result<Self, MapError> {
        let bad = || MapError::BadShard(text.to_string());
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = k.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether grid point `i` belongs to this part.
    pub fn contains(&self, i: usize) -> bool {
        i % self.count == self.index
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// What a map run or a merge can fail with.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// A bad axis.
    #[error(transparent)]
    Axis(#[from] AxisError),
    /// Not `k/n` with `0 ≤ k < n`.
    #[error("shard `{0}`: expected k/n with 0 <= k < n (e.g. 0/4)")]
    BadShard(String),
    /// The output exists and `resume` was not asked for.
    #[error("`{0}` already exists: use --resume to continue that run, or remove the file")]
    OutputExists(PathBuf),
    /// Reading or writing a file failed.
    #[error("`{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: io::Error,
    },
    /// A file that is not a map (no or a bad header).
    #[error("`{path}` is not a stickslip map file: {reason}")]
    Header {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// The file describes another map than the one asked for (resume) or than the other inputs (merge).
    #[error("`{path}` describes a different map: {what}")]
    Mismatch {
        /// The file.
        path: PathBuf,
        /// What differs.
        what: String,
    },
    /// A line that is not a point of the map.
    #[error("`{path}`, line {line}: {reason}")]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// The same grid point with different contents.
    #[error("grid points computed twice with different results: {}", list(.0))]
    Conflict(Vec<usize>),
    /// Grid points no input has.
    #[error("{} grid point(s) missing: {}", .0.len(), list(.0))]
    Missing(Vec<usize>),
    /// No input file given.
    #[error("nothing to merge: no input file")]
    NoInput,
    /// Drawing the figure failed.
    #[error("{0}")]
    Plot(String),
}

/// At most 20 indices, then how many more.
fn list(indices: &[usize]) -> String {
    let mut s = indices
        .iter()
        .take(20)
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    if indices.len() > 20 {
        let _ = write!(s, ", … ({} more)", indices.len() - 20);
    }
    s
}

fn io_err(path: &Path) -> impl FnOnce(io::Error) -> MapError + '_ {
    move |source| MapError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// What is known at one grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct PointResult {
    /// Grid index `iy * nx + ix`.
    pub index: usize,
    /// The x-axis parameter's value.
    pub x: f64,
    /// The y-axis parameter's value.
    pub y: f64,
    /// `ok`, `invalid: …`, or the starts that did not settle.
    pub status: String,
    /// The distinct motions found, sorted: `P_{…}` (with `^N` for `N > 1`) or `NM`.
    pub motions: Vec<String>,
}

impl PointResult {
    /// The point's class on the map: its motions joined by ` + `, or, when
    /// none was found, the status's first word (`invalid`, `unsettled`, …).
    pub fn label(&self) -> String {
        if !self.motions.is_empty() {
            return self.motions.join(" + ");
        }
        let s = self.status.as_str();
        let s = s
            .strip_prefix("start ")
            .and_then(|r| r.split_once(": ").map(|(_, rest)| rest))
            .unwrap_or(s);
        s.split([':', ' ', ';'])
            .next()
            .filter(|w| !w.is_empty())
            .unwrap_or("unknown")
            .to_string()
    }

    /// The CSV line, with its newline: `index,x,y,"status","motions"`.
    pub fn to_line(&self) -> String {
        format!(
            "{},{:?},{:?},{},{}\n",
            self.index,
            self.x,
            self.y,
            quote(&self.status),
            quote(&self.motions.join(";"))
        )
    }

    /// Parse a line written by [`to_line`](Self::to_line) (with or without its newline).
    pub fn parse_line(line: &str) -> Result<Self, String> {
        let line = line.strip_suffix('\n').unwrap_or(line);
        let line = line.strip_suffix('\r').unwrap_or(line);
        let fields = split_csv(line)?;
        let [index, x, y, status, motions] = &fields[..] else {
            return Err(format!(
                "expected 5 fields (index,x,y,status,motions), found {}",
                fields.len()
            ));
        };
        let index = index
            .parse::<usize>()
            .map_err(|_| format!("`{index}` is not a grid index"))?;
        let number = |s: &str| {
            s.parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))
        };
        Ok(Self {
            index,
            x: number(x)?,
            y: number(y)?,
            status: status.clone(),
            motions: if motions.is_empty() {
                Vec::new()
            } else {
                motions.split(';').map(str::to_string).collect()
            },
        })
    }
}

/// A CSV field in double quotes, inner quotes doubled; line breaks become spaces.
fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\"\""),
            '\n' | '\r' => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Split one CSV line (RFC 4180 quoting).
fn split_csv(line: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        let mut field = String::new();
        if chars.peek() == Some(&'"') {
            chars.next();
            loop {
                match chars.next() {
                    None => return Err("an unterminated quoted field".to_string()),
                    Some('"') if chars.peek() == Some(&'"') => {
                        chars.next();
                        field.push('"');
                    }
                    Some('"') => break,
                    Some(c) => field.push(c),
                }
            }
            match chars.next() {
                None => {
                    fields.push(field);
                    return Ok(fields);
                }
                Some(',') => fields.push(field),
                Some(c) => return Err(format!("`{c}` after a quoted field")),
            }
        } else {
            loop {
                match chars.next() {
                    None => {
                        fields.push(field);
                        return Ok(fields);
                    }
                    Some(',') => break,
                    Some('"') => return Err("a quote inside an unquoted field".to_string()),
                    Some(c) => field.push(c),
                }
            }
            fields.push(field);
        }
    }
}

/// The motion's name on the map: its structure, with `^N` for `N > 1`.
pub fn motion_label<M: Model>(motion: &Motion) -> String {
    let n = motion.structure.periods();
    let s = motion.structure.notation(M::INFO);
    if n > 1 {
        format!("{s}^{n}")
    } else {
        s
    }
}

/// Whether two motions are the same orbit: same structure and period, and
/// the first switching point of one is (modulo 2π in phase) a switching point of the other.
fn same_motion(a: &Motion, b: &Motion) -> bool {
    if a.structure != b.structure {
        // A cycle started elsewhere is the same cycle only if one is a rotation of the other;
        // both come canonical from `attractor::find`, so a difference means different motions.
        return false;
    }
    let Some(p) = a.points.first() else {
        return false;
    };
    b.points.iter().any(|q| {
        let d = (p.phase - q.phase).rem_euclid(TAU);
        let d = d.min(TAU - d);
        d < 1e-6 && (p.x - q.x).abs() < 1e-6 * (1.0 + p.x.abs())
    })
}

/// Short text for a start that did not settle.
fn failure<M: Model>(e: &OrbitError) -> String {
    match e {
        OrbitError::Unsettled { periods, .. } => format!("unsettled ({periods} periods)"),
        OrbitError::NotConverged(Termination::NotConverged { reason, .. }) => {
            format!("not_converged ({reason})")
        }
        OrbitError::NotConverged(Termination::Singular { reason, .. }) => {
            format!("not_converged (singular: {reason})")
        }
        OrbitError::Inadmissible(m) => {
            format!("inadmissible ({})", motion_label::<M>(m))
        }
        OrbitError::Simulation(e) => format!("simulation_error ({e})"),
        other => format!("error ({other})"),
    }
}

/// The two starts of every grid point: rest, and `v` one above the stick
/// boundary (or the highest boundary) half a forcing period later.
fn starts<M: Model>(sim: &Simulator<M>) -> [(f64, f64, f64); 2] {
    let info = M::INFO;
    let k = info
        .stick_boundary()
        .unwrap_or(info.boundaries.len().saturating_sub(1));
    let v = if info.boundaries.is_empty() {
        1.0
    } else {
        sim.velocity(k) + 1.0
    };
    [(0.0, 0.0, 0.0), (0.0, v, std::f64::consts::PI)]
}

/// Which motions exist at grid point `index` (see the module doc). Never
/// panics on bad parameters: they give the status `invalid: …`.
pub fn classify_point<M: Model>(
    base: &M::Params,
    x_axis: &GridAxis,
    y_axis: &GridAxis,
    index: usize,
) -> PointResult {
    let nx = x_axis.count.max(1);
    let (ix, iy) = (index % nx, index / nx);
    let (x, y) = (x_axis.value(ix), y_axis.value(iy));
    let mut result = PointResult {
        index,
        x,
        y,
        status: String::new(),
        motions: Vec::new(),
    };
    let mut p = *base;
    for (axis, value) in [(x_axis, x), (y_axis, y)] {
        match M::Params::index_of(&axis.name) {
            Some(i) => p.set(i, value),
            None => {
                let e = axis.check_for::<M>().expect_err("not a run-time parameter");
                result.status = format!("invalid: {e}");
                return result;
            }
        }
    }
    if let Err(e) = p.check() {
        result.status = format!("invalid: {e}");
        return result;
    }
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| settle::<M>(p)));
    match outcome {
        Ok((status, motions)) => {
            result.status = status;
            result.motions = motions;
        }
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".to_string());
            result.status = format!("panic: {what}");
        }
    }
    result
}

/// Simulate from both starts at checked parameters `p`: `(status, motions)`.
fn settle<M: Model>(p: M::Params) -> (String, Vec<String>) {
    let sim = match Simulator::<M>::new(p, SimOptions::default()) {
        Ok(sim) => sim,
        Err(e) => return (format!("invalid: {e}"), Vec::new()),
    };
    let opts = AttractorOptions {
        max_periods: MAX_PERIODS,
        ..AttractorOptions::default()
    };
    let mut found: Vec<Motion> = Vec::new();
    let mut no_motion = false;
    let mut stick = false;
    let mut autonomous = false;
    let mut problems: Vec<String> = Vec::new();
    for (k, (x0, v0, phase0)) in starts(&sim).into_iter().enumerate() {
        let outcome = sim
            .start(x0, v0, phase0)
            .map_err(OrbitError::from)
            .and_then(|seg| attractor::find(&sim, seg, opts));
        match outcome {
            Ok(Attractor::Periodic(m)) => {
                if !found.iter().any(|f| same_motion(f, &m)) {
                    found.push(m);
                }
            }
            Ok(Attractor::NoMotion(_)) => no_motion = true,
            Ok(Attractor::Stick(_)) => stick = true,
            Ok(Attractor::Autonomous(_)) => autonomous = true,
            Err(e) => problems.push(format!("start {}: {}", k + 1, failure::<M>(&e))),
        }
    }
    let mut motions: Vec<String> = found.iter().map(motion_label::<M>).collect();
    if no_motion {
        motions.push(NO_MOTION.to_string());
    }
    if stick {
        motions.push(STICK.to_string());
    }
    if autonomous {
        motions.push("autonomous".to_string());
    }
    motions.sort();
    let status = if problems.is_empty() {
        "ok".to_string()
    } else {
        problems.join("; ")
    };
    (status, motions)
}

/// The first line of a map file: what was computed.
#[derive(Clone, Debug, PartialEq)]
pub struct MapHeader {
    /// Model (or scene) name.
    pub model: String,
    /// The x axis.
    pub x: GridAxis,
    /// The y axis.
    pub y: GridAxis,
    /// The other run-time parameters, in declaration order.
    pub base: Vec<(String, f64)>,
    /// The part computed, in a shard's file only.
    pub shard: Option<Shard>,
}

const MAGIC: &str = "# stickslip map";

impl MapHeader {
    /// The header of a map of `M` at `base` over `x × y`.
    pub fn new<M: Model>(
        base: &M::Params,
        x: &GridAxis,
        y: &GridAxis,
        shard: Option<Shard>,
    ) -> Self {
        let base = M::Params::NAMES
            .iter()
            .enumerate()
            .filter(|(_, n)| **n != x.name && **n != y.name)
            .map(|(i, n)| (n.to_string(), base.get(i)))
            .collect();
        Self {
            model: M::INFO.name.to_string(),
            x: x.clone(),
            y: y.clone(),
            base,
            shard: shard.filter(|s| s.count > 1),
        }
    }

    /// Grid points.
    pub fn len(&self) -> usize {
        self.x.count.saturating_mul(self.y.count)
    }

    /// Whether the grid is empty (never, for a parsed header).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The two header lines (comment and column names), with newlines.
    pub fn to_lines(&self) -> String {
        let base = self
            .base
            .iter()
            .map(|(n, v)| format!("{n}={v}"))
            .collect::<Vec<_>>()
            .join(",");
        let mut s = format!(
            "{MAGIC} model={} x={} y={} base={base}",
            self.model, self.x, self.y
        );
        if let Some(shard) = self.shard {
            let _ = write!(s, " shard={shard}");
        }
        let _ = write!(
            s,
            "\nindex,{},{},status,motions\n",
            self.x.name, self.y.name
        );
        s
    }

    /// Parse the first header line (the comment).
    pub fn parse(line: &str) -> Result<Self, String> {
        let rest = line
            .trim_end()
            .strip_prefix(MAGIC)
            .ok_or_else(|| format!("the first line does not start with `{MAGIC}`"))?;
        let (mut model, mut x, mut y, mut base, mut shard) = (None, None, None, None, None);
        for token in rest.split_whitespace() {
            let (key, value) = token
                .split_once('=')
                .ok_or_else(|| format!("`{token}` in the header is not KEY=VALUE"))?;
            match key {
                "model" => model = Some(value.to_string()),
                "x" => x = Some(GridAxis::parse(value).map_err(|e| e.to_string())?),
                "y" => y = Some(GridAxis::parse(value).map_err(|e| e.to_string())?),
                "base" => {
                    let mut pairs = Vec::new();
                    for pair in value.split(',').filter(|p| !p.is_empty()) {
                        let (n, v) = pair
                            .split_once('=')
                            .ok_or_else(|| format!("`{pair}` in base is not NAME=VALUE"))?;
                        let v: f64 = v
                            .parse()
                            .map_err(|_| format!("`{v}` in base is not a number"))?;
                        pairs.push((n.to_string(), v));
                    }
                    base = Some(pairs);
                }
                "shard" => shard = Some(Shard::parse(value).map_err(|e| e.to_string())?),
                other => return Err(format!("unknown header key `{other}`")),
            }
        }
        let missing = |what: &str| format!("the header lacks `{what}=`");
        Ok(Self {
            model: model.ok_or_else(|| missing("model"))?,
            x: x.ok_or_else(|| missing("x"))?,
            y: y.ok_or_else(|| missing("y"))?,
            base: base.ok_or_else(|| missing("base"))?,
            shard,
        })
    }

    /// How `other` describes a different grid (shards aside), if it does.
    fn grid_difference(&self, other: &Self) -> Option<String> {
        if self.model != other.model {
            return Some(format!("model `{}`, not `{}`", other.model, self.model));
        }
        if self.x != other.x {
            return Some(format!("x axis {}, not {}", other.x, self.x));
        }
        if self.y != other.y {
            return Some(format!("y axis {}, not {}", other.y, self.y));
        }
        if self.base != other.base {
            let show = |b: &[(String, f64)]| {
                b.iter()
                    .map(|(n, v)| format!("{n}={v}"))
                    .collect::<Vec<_>>()
                    .join(",")
            };
            return Some(format!(
                "parameters {}, not {}",
                show(&other.base),
                show(&self.base)
            ));
        }
        None
    }

    /// Check that `record` is grid point `record.index` of this map (and of its shard).
    fn check_record(&self, record: &PointResult) -> Result<(), String> {
        if record.index >= self.len() {
            return Err(format!(
                "index {} is outside the {}-point grid",
                record.index,
                self.len()
            ));
        }
        if let Some(shard) = self.shard {
            if !shard.contains(record.index) {
                return Err(format!(
                    "index {} does not belong to shard {shard}",
                    record.index
                ));
            }
        }
        let nx = self.x.count;
        let (x, y) = (
            self.x.value(record.index % nx),
            self.y.value(record.index / nx),
        );
        if record.x.to_bits() != x.to_bits() || record.y.to_bits() != y.to_bits() {
            return Err(format!(
                "point {} is at ({:?}, {:?}), but the grid puts it at ({x:?}, {y:?})",
                record.index, record.x, record.y
            ));
        }
        Ok(())
    }
}

/// A map file as read: its header and points (in file order).
#[derive(Clone, Debug, PartialEq)]
pub struct MapFile {
    /// The header.
    pub header: MapHeader,
    /// The points, in file order.
    pub points: Vec<PointResult>,
    /// Bytes of complete lines: a trailing line without newline (a write cut short) is not counted.
    pub valid_len: u64,
    /// Whether such a partial trailing line was dropped.
    pub dropped_partial: bool,
}

impl MapFile {
    /// Read and check a map file: its header, every complete line (a partial
    /// last line, left by a killed run, is dropped), each point on the grid.
    pub fn read(path: &Path) -> Result<Self, MapError> {
        let bytes = fs::read(path).map_err(io_err(path))?;
        Self::parse(path, &bytes)?.ok_or_else(|| MapError::Header {
            path: path.to_path_buf(),
            reason: "the file has no complete header line".to_string(),
        })
    }

    /// Parse `bytes` (the contents of `path`); `None` when not even the
    /// header line is complete. A partial last line may end inside a
    /// character: only complete lines must be UTF-8.
    fn parse(path: &Path, bytes: &[u8]) -> Result<Option<Self>, MapError> {
        let (complete, dropped_partial) = match bytes.iter().rposition(|&b| b == b'\n') {
            Some(end) => (&bytes[..=end], end + 1 < bytes.len()),
            None => (&bytes[..0], !bytes.is_empty()),
        };
        let complete = std::str::from_utf8(complete).map_err(|e| {
            let line = 1 + complete[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
            MapError::Corrupt {
                path: path.to_path_buf(),
                line,
                reason: "not UTF-8 text".to_string(),
            }
        })?;
        let mut lines = complete.split_inclusive('\n').enumerate();
        let Some((_, first)) = lines.next() else {
            return Ok(None);
        };
        let header = MapHeader::parse(first).map_err(|reason| MapError::Header {
            path: path.to_path_buf(),
            reason,
        })?;
        let columns = format!("index,{},{},status,motions", header.x.name, header.y.name);
        let mut points = Vec::new();
        for (k, line) in lines {
            let corrupt = |reason: String| MapError::Corrupt {
                path: path.to_path_buf(),
                line: k + 1,
                reason,
            };
            if k == 1 && line.trim_end() == columns {
                continue;
            }
            let record = PointResult::parse_line(line).map_err(corrupt)?;
            header.check_record(&record).map_err(corrupt)?;
            points.push(record);
        }
        Ok(Some(Self {
            header,
            points,
            valid_len: complete.len() as u64,
            dropped_partial,
        }))
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

/// Write `header` and `points` (sorted by index) to `out` atomically: a
/// temporary file beside it, synced, renamed over it.
fn write_canonical(out: &Path, header: &MapHeader, points: &[PointResult]) -> Result<(), MapError> {
    let mut text = header.to_lines();
    let mut sorted: Vec<&PointResult> = points.iter().collect();
    sorted.sort_by_key(|p| p.index);
    for p in sorted {
        text.push_str(&p.to_line());
    }
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "map".to_string());
    let tmp = out.with_file_name(format!(".{name}.tmp"));
    let mut f = File::create(&tmp).map_err(io_err(&tmp))?;
    f.write_all(text.as_bytes()).map_err(io_err(&tmp))?;
    f.sync_all().map_err(io_err(&tmp))?;
    drop(f);
    fs::rename(&tmp, out).map_err(io_err(out))?;
    Ok(())
}

/// Merge records into `by_index`; identical duplicates are kept once, different ones collected.
fn insert_all(
    by_index: &mut BTreeMap<usize, PointResult>,
    points: Vec<PointResult>,
    conflicts: &mut Vec<usize>,
) {
    for p in points {
        match by_index.get(&p.index) {
            Some(q) if q.to_line() != p.to_line() => conflicts.push(p.index),
            Some(_) => {}
            None => {
                by_index.insert(p.index, p);
            }
        }
    }
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
    let start = Instant::now();
    for axis in [x_axis, y_axis] {
        axis.check_for::<M>()
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
    let header = MapHeader::new::<M>(base, x_axis, y_axis, opts.shard);
    let in_part = |i: usize| header.shard.is_none_or(|s| s.contains(i));
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
                let f = OpenOptions::new()
                    .write(true)
                    .open(out)
                    .map_err(io_err(out))?;
                // Drop a line cut short by a kill before appending after it.
                f.set_len(previous.valid_len).map_err(io_err(out))?;
                drop(f);
                OpenOptions::new()
                    .append(true)
                    .open(out)
                    .map_err(io_err(out))?
            }
            None => {
                // Killed before even the header was complete: start afresh.
                let mut f = File::create(out).map_err(io_err(out))?;
                f.write_all(header.to_lines().as_bytes())
                    .map_err(io_err(out))?;
                f
            }
        },
        None => {
            let mut f = OpenOptions::new()
                .append(true)
                .create_new(true)
                .open(out)
                .map_err(io_err(out))?;
            f.write_all(header.to_lines().as_bytes())
                .map_err(io_err(out))?;
            f
        }
    };
    let already_done = done.len();
    let todo: Vec<usize> = (0..total)
        .filter(|&i| in_part(i) && !done.contains_key(&i))
        .collect();

    let bar = progress_bar(opts.progress, shard_points as u64, already_done as u64);
    let file = Mutex::new(file);
    let new_points: Mutex<Vec<PointResult>> = Mutex::new(Vec::with_capacity(todo.len()));
    let write_error: Mutex<Option<io::Error>> = Mutex::new(None);
    let failed = AtomicBool::new(false);
    let claimed = AtomicUsize::new(0);
    let limit = opts.max_points.unwrap_or(usize::MAX);
    todo.par_iter().with_max_len(1).for_each(|&i| {
        if failed.load(Ordering::Relaxed) || claimed.fetch_add(1, Ordering::Relaxed) >= limit {
            return;
        }
        let record = classify_point::<M>(base, x_axis, y_axis, i);
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
        bar.inc(1);
    });
    bar.finish_and_clear();
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
/// with duplicate points — into the complete map `out`, byte-identical to a
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_values_hit_both_ends() {
        let a = GridAxis::parse("W=0.2:9:45").unwrap();
        assert_eq!(a.value(0), 0.2);
        assert_eq!(a.value(44), 9.0);
        assert_eq!(GridAxis::parse(&a.spec()).unwrap(), a);
        let one = GridAxis::parse("Q0=70:80:1").unwrap();
        assert_eq!(one.values(), vec![70.0]);
    }

    #[test]
    fn lines_round_trip() {
        let p = PointResult {
            index: 12,
            x: 3.4000000000000004,
            y: 1e-7,
            status: "start 2: error (say \"no\", twice)".to_string(),
            motions: vec!["NM".to_string(), "P_{3_33 4_33}^2".to_string()],
        };
        let line = p.to_line();
        let q = PointResult::parse_line(&line).unwrap();
        assert_eq!(p, q);
        assert_eq!(q.to_line(), line);
        let empty = PointResult {
            motions: Vec::new(),
            ..p
        };
        assert_eq!(PointResult::parse_line(&empty.to_line()).unwrap(), empty);
    }

    #[test]
    fn labels() {
        let mut p = PointResult {
            index: 0,
            x: 0.0,
            y: 0.0,
            status: "start 1: unsettled (600 periods); start 2: unsettled (600 periods)".into(),
            motions: Vec::new(),
        };
        assert_eq!(p.label(), "unsettled");
        p.status = "invalid: the forcing frequency is 0; it must be positive".into();
        assert_eq!(p.label(), "invalid");
        p.motions = vec!["NM".into(), "P_{3_33 4_33}".into()];
        assert_eq!(p.label(), "NM + P_{3_33 4_33}");
    }
}
