//! What can go wrong on the command line, and where: one variant per kind of
//! mistake, the library's typed errors wrapped as they are. `main` prints
//! each as `error: {message}` and exits with status 1.

use std::io;
use std::path::PathBuf;

use stickslip::orbit::motion::OrbitError;
use stickslip::orbit::structure::StructureError;
use stickslip::study::basins::BasinsError;
use stickslip::study::curves::CurvesError;
use stickslip::study::diagram::DiagramError;
use stickslip::study::map::{AxisError, MapError};
use stickslip::study::sweep::SweepError;
use stickslip::study::trade::TradeError;
use stickslip::{dynamics::simulate::SimError, models, ParamError};

/// Why a subcommand failed.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// `--model` names no compiled-in model.
    #[error(transparent)]
    UnknownModel(#[from] models::UnknownModel),
    /// `--model-file`: a file the generator rejects (`stickslip check`'s report).
    #[error("{0}")]
    Load(#[from] stickslip::model::loaded::LoadError),
    /// `--model-file` of a model with a smooth law, for a command that
    /// takes a piecewise-linear one.
    #[error(
        "`{model}` has a smooth law: give one of its piecewise-linear scenes with `--scene` \
         (a `pieces: N` scene), or use the law itself with `simulate` (unforced), \
         `equilibria` or `trade`"
    )]
    SmoothFile {
        /// The file.
        model: String,
    },
    /// `trade --model-file` of a piecewise-linear model.
    #[error("`{model}` is piecewise-linear: `trade` takes a model with a smooth `law`")]
    NotSmoothFile {
        /// The file.
        model: String,
    },
    /// `trade --model` names no compiled-in model with a smooth law.
    #[error(
        "`{name}` is not a model with a smooth law; compiled-in: {}",
        names(models::ALL.iter().filter_map(models::Entry::smooth).map(|i| i.name))
    )]
    NotSmooth {
        /// The name given.
        name: String,
    },
    /// A `--set` item without `=`.
    #[error("`{item}`: expected NAME=VALUE")]
    Assignment {
        /// The item given.
        item: String,
    },
    /// A `--set` item whose value is not a number.
    #[error("`{item}`: `{value}` is not a number")]
    AssignmentValue {
        /// The item given.
        item: String,
        /// Its value part.
        value: String,
    },
    /// A `--set` item naming the parameter that `--param`, `--x` or `--y`
    /// varies (its value would be overwritten without a word).
    #[error("`--set {name}=...`: `{name}` is varied by {by}; drop it from --set")]
    SetVaried {
        /// The parameter.
        name: String,
        /// The option that varies it.
        by: &'static str,
    },
    /// A list of numbers (`--guess W t,x`, `--from x,v,W t`) of the wrong length.
    #[error("`{text}`: expected {what} ({count} comma-separated numbers)")]
    NumberCount {
        /// The text given.
        text: String,
        /// What the numbers are.
        what: &'static str,
        /// How many are expected.
        count: usize,
    },
    /// A member of such a list that is not a number.
    #[error("`{text}`: `{part}` is not a number (expected {what})")]
    NotANumber {
        /// The text given.
        text: String,
        /// The member.
        part: String,
        /// What the numbers are.
        what: &'static str,
    },
    /// A member of such a list that is NaN or infinite.
    #[error("`{text}`: `{part}` is not finite (expected {what})")]
    NotFinite {
        /// The text given.
        text: String,
        /// The member.
        part: String,
        /// What the numbers are.
        what: &'static str,
    },
    /// `sweep --param` not of the form `NAME=from:to:count`.
    #[error("`{text}`: expected NAME=from:to:count, e.g. W=0.2:9:200")]
    Range {
        /// The text given.
        text: String,
    },
    /// A grid of no points, or more than a million.
    #[error("`{text}`: the count must be between 1 and 1000000 (got {count}), e.g. vd=0.2:3:15")]
    GridCount {
        /// The option's text.
        text: String,
        /// The count given.
        count: usize,
    },
    /// `curves --x`/`--y` not of the form `NAME=from:to`.
    #[error("{option} `{text}`: expected NAME=from:to, e.g. W=0.2:8")]
    BoxRange {
        /// The option.
        option: &'static str,
        /// The text given.
        text: String,
    },
    /// `curves --seed`/`--at` not of the form `NAME=v1,v2,...`.
    #[error("{option} `{text}`: expected NAME=VALUE or NAME=v1,v2,..., e.g. Q0=70")]
    LineValues {
        /// The option.
        option: &'static str,
        /// The text given.
        text: String,
    },
    /// `simulate --periods 0`.
    #[error("--periods must be at least 1")]
    ZeroPeriods,
    /// A parameter the model rejects (unknown, not finite, out of its bounds).
    #[error(transparent)]
    Params(#[from] ParamError),
    /// `orbit --structure` that is not a structure of the model.
    #[error("structure `{text}`: {source}")]
    Structure {
        /// The text given.
        text: String,
        /// What is wrong with it.
        source: StructureError,
    },
    /// `orbit` without `--guess` (or with one the flow does not follow),
    /// and no simulated motion follows the structure.
    #[error(
        "no simulated motion follows {structure}; give the first switching point with --guess W t,x"
    )]
    NoSeed {
        /// The structure, in the model's notation.
        structure: String,
    },
    /// `--plot` whose extension names no figure format.
    #[error(
        "`{}`: unknown figure format; use a file name ending in .svg or .png",
        path.display()
    )]
    PlotFormat {
        /// The path given.
        path: PathBuf,
    },
    /// `--plot` into a directory that does not exist.
    #[error("`{}`: there is no directory `{}`", path.display(), directory.display())]
    PlotDirectory {
        /// The path given.
        path: PathBuf,
        /// Its parent.
        directory: PathBuf,
    },
    /// `--plot` naming a directory.
    #[error("`{}` is a directory; give a file name ending in .svg or .png", path.display())]
    PlotIsDirectory {
        /// The path given.
        path: PathBuf,
    },
    /// Drawing a figure failed.
    #[error("{0}")]
    Figure(String),
    /// Writing an output file failed.
    #[error("cannot write `{}`: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: io::Error,
    },
    /// A figure or CSV was asked of a result that is not a motion.
    #[error("there is no motion")]
    NoMotion,
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] SimError),
    /// No periodic motion was found.
    #[error(transparent)]
    Orbit(#[from] OrbitError),
    /// A smooth law's simulation.
    #[error(transparent)]
    Smooth(#[from] stickslip::orbit::smooth::SmoothError),
    /// A sweep of a smooth law.
    #[error(transparent)]
    Law(#[from] stickslip::study::law::LawError),
    /// `--plot` or `--csv` of a smooth law's motion.
    #[error("`{option}` is written for a piecewise model: for the smooth law `{model}`, print the text or `--json`, or give one of its scenes with `--scene`")]
    SmoothOutput {
        /// The option given.
        option: &'static str,
        /// The model.
        model: String,
    },
    /// The sweep could not run.
    #[error(transparent)]
    Sweep(#[from] SweepError),
    /// The curves run could not run.
    #[error(transparent)]
    Curves(#[from] CurvesError),
    /// A bad map axis.
    #[error(transparent)]
    Axis(#[from] AxisError),
    /// The map or merge failed.
    #[error(transparent)]
    Map(#[from] MapError),
    /// The trade could not be measured.
    #[error(transparent)]
    Trade(#[from] TradeError),
    /// The basin run failed.
    #[error(transparent)]
    Basins(#[from] BasinsError),
    /// The orbit diagram could not run.
    #[error(transparent)]
    Diagram(#[from] DiagramError),
    /// Serializing the JSON output failed.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
}

/// `a, b, c`.
fn names<'a>(names: impl Iterator<Item = &'a str>) -> String {
    names.collect::<Vec<_>>().join(", ")
}

/// A model that cannot be found: a name not compiled in, or a file the
/// generator rejects.
impl From<stickslip::models::LookupError> for CliError {
    fn from(e: stickslip::models::LookupError) -> Self {
        match e {
            stickslip::models::LookupError::Unknown(e) => CliError::UnknownModel(e),
            stickslip::models::LookupError::Load(e) => CliError::Load(e),
        }
    }
}

impl CliError {
    /// Whether this is a model file's report (each error headed `error:`).
    pub fn is_report(&self) -> bool {
        matches!(self, CliError::Load(_))
    }
}
