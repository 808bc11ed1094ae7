//! What a basin run can fail with ([`BasinsError`]).

use std::io;
use std::path::{Path, PathBuf};

use crate::dynamics::simulate::SimError;
use crate::model::param::ParamError;
use crate::study::map::AxisError;

/// Why a basin run failed.
#[derive(Debug, thiserror::Error)]
pub enum BasinsError {
    /// A bad axis (syntax, count, bounds).
    #[error(transparent)]
    Axis(#[from] AxisError),
    /// An axis of another state variable than the option's.
    #[error("{option} `{text}`: the axis must vary `{expected}` (e.g. {expected}=-1:1:100)")]
    AxisVariable {
        /// `--x` or `--y`.
        option: &'static str,
        /// The text given.
        text: String,
        /// `x` or `v`.
        expected: &'static str,
    },
    /// A phase that is not finite.
    #[error("--phase `{0}` is not a finite number")]
    Phase(f64),
    /// The parameters are invalid.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// The simulator rejects the parameters.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// The output exists and `resume` was not asked for.
    #[error("`{0}` already exists: use --resume to continue that run, or remove the file")]
    OutputExists(PathBuf),
    /// `resume` without a file to resume from.
    #[error("--resume needs the run's file: give it with --out FILE")]
    ResumeWithoutFile,
    /// Reading or writing a file failed.
    #[error("`{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: io::Error,
    },
    /// A file that is not a basin file.
    #[error("`{path}` is not a stickslip basin file: {reason}")]
    Header {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// The file describes another run than the one asked for.
    #[error(
        "`{path}` describes a different basin run: {what}; remove it or run with its settings"
    )]
    Mismatch {
        /// The file.
        path: PathBuf,
        /// The first difference.
        what: String,
    },
    /// A line that cannot be read or does not belong to the run.
    #[error("`{path}` line {line}: {reason}")]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// The same start twice with different results.
    #[error("`{path}` gives start {index} twice, differently")]
    Conflict {
        /// The file.
        path: PathBuf,
        /// The start.
        index: usize,
    },
    /// Drawing the figure failed.
    #[error("cannot draw the basins: {0}")]
    Plot(String),
}

/// The I/O error at `path`.
pub(super) fn io_err(path: &Path) -> impl Fn(io::Error) -> BasinsError + '_ {
    move |source| BasinsError::Io {
        path: path.to_path_buf(),
        source,
    }
}
