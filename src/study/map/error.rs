//! What a map run or a merge can fail with ([`MapError`]).

use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

use crate::model::param::ParamError;

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
pub(super) fn list(indices: &[usize]) -> String {
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

pub(super) fn io_err(path: &Path) -> impl FnOnce(io::Error) -> MapError + '_ {
    move |source| MapError::Io {
        path: path.to_path_buf(),
        source,
    }
}
