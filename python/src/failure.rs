//! What can go wrong, as the Python exception that says it: the library's
//! typed errors keep their messages (the CLI's, without `error: `), and each
//! kind of mistake has its class in `stickslip.errors`.

use pyo3::prelude::*;
use stickslip::dynamics::simulate::SimError;
use stickslip::models::{LookupError, UnknownModel};
use stickslip::orbit::lyapunov::LyapunovError;
use stickslip::orbit::motion::OrbitError;
use stickslip::study::basins::BasinsError;
use stickslip::study::curves::CurvesError;
use stickslip::study::map::{AxisError, MapError};
use stickslip::study::sweep::SweepError;
use stickslip::ParamError;

/// Which exception of `stickslip.errors` a failure raises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `ModelError`: no such model, or a model file that does not check.
    Model,
    /// `ParamError`: a parameter the model rejects.
    Param,
    /// `StructureError`: a structure that is not one of the model.
    Structure,
    /// `NewtonError`: Newton did not converge.
    Newton,
    /// `InadmissibleError`: the solution is not a motion.
    Inadmissible,
    /// `SeedError`: no start for Newton (no simulated motion follows the structure).
    Seed,
    /// `SimulationError`: the simulation could not go on.
    Simulation,
    /// `UnsettledError`: the simulation did not settle on a motion the
    /// search recognises within the periods given.
    Unsettled,
    /// `InputError`: another bad argument (a range, a count, a file).
    Input,
}

impl Kind {
    fn class(self) -> &'static str {
        match self {
            Kind::Model => "ModelError",
            Kind::Param => "ParamError",
            Kind::Structure => "StructureError",
            Kind::Newton => "NewtonError",
            Kind::Inadmissible => "InadmissibleError",
            Kind::Seed => "SeedError",
            Kind::Simulation => "SimulationError",
            Kind::Unsettled => "UnsettledError",
            Kind::Input => "InputError",
        }
    }
}

/// A failure on its way to Python.
#[derive(Debug)]
pub struct Failure {
    /// Its class.
    pub kind: Kind,
    /// Its message.
    pub message: String,
}

impl Failure {
    /// A failure of `kind` saying `message`.
    pub fn new(kind: Kind, message: impl ToString) -> Self {
        Self {
            kind,
            message: message.to_string(),
        }
    }
}

impl From<UnknownModel> for Failure {
    fn from(e: UnknownModel) -> Self {
        Self::new(Kind::Model, e)
    }
}

/// A name not compiled in, or a model file or text the generator rejects:
/// `ModelError` with `stickslip check`'s report.
impl From<LookupError> for Failure {
    fn from(e: LookupError) -> Self {
        Self::new(Kind::Model, e)
    }
}

impl From<ParamError> for Failure {
    fn from(e: ParamError) -> Self {
        Self::new(Kind::Param, e)
    }
}

impl From<SimError> for Failure {
    fn from(e: SimError) -> Self {
        Self::new(Kind::Simulation, e)
    }
}

impl From<stickslip::orbit::smooth::SmoothError> for Failure {
    fn from(e: stickslip::orbit::smooth::SmoothError) -> Self {
        use stickslip::orbit::smooth::SmoothError;
        let kind = match &e {
            SmoothError::Integrate(_) => Kind::Simulation,
            SmoothError::Equilibrium(_) => Kind::Param,
            SmoothError::NoReturn { .. }
            | SmoothError::NotSettled { .. }
            | SmoothError::NoPeriodic { .. } => Kind::Unsettled,
        };
        Self::new(kind, e)
    }
}

impl From<stickslip::study::law::LawError> for Failure {
    fn from(e: stickslip::study::law::LawError) -> Self {
        use stickslip::study::law::LawError;
        match e {
            LawError::Params(e) => e.into(),
            LawError::At { .. } => Self::new(Kind::Simulation, e),
            LawError::Forced(_) | LawError::Empty => Self::new(Kind::Input, e),
        }
    }
}

impl From<OrbitError> for Failure {
    fn from(e: OrbitError) -> Self {
        let kind = match &e {
            OrbitError::Params(_) => Kind::Param,
            OrbitError::Structure(_) => Kind::Structure,
            OrbitError::Simulation(_) => Kind::Simulation,
            OrbitError::Guess(_) => Kind::Input,
            OrbitError::NotConverged(_) => Kind::Newton,
            OrbitError::Inadmissible(_) => Kind::Inadmissible,
            OrbitError::Unsettled { .. } | OrbitError::CycleTooLong { .. } => Kind::Unsettled,
            OrbitError::NoSeed(_) => Kind::Seed,
        };
        Self::new(kind, e)
    }
}

impl From<SweepError> for Failure {
    fn from(e: SweepError) -> Self {
        match e {
            SweepError::Orbit(e) => e.into(),
            SweepError::Params(_) => Self::new(Kind::Param, e),
            SweepError::Range(_) | SweepError::Options(_) => Self::new(Kind::Input, e),
        }
    }
}

impl From<AxisError> for Failure {
    fn from(e: AxisError) -> Self {
        let kind = match e {
            AxisError::Parameter { .. } => Kind::Param,
            _ => Kind::Input,
        };
        Self::new(kind, e)
    }
}

/// An output file that exists, without `resume=True`: the CLI's message
/// names its option, this one the keyword.
fn output_exists(path: &std::path::Path) -> Failure {
    Failure::new(
        Kind::Input,
        format!(
            "`{}` already exists: use resume=True to continue that run, or remove the file",
            path.display()
        ),
    )
}

impl From<MapError> for Failure {
    fn from(e: MapError) -> Self {
        match e {
            MapError::Axis(e) => e.into(),
            MapError::OutputExists(path) => output_exists(&path),
            _ => Self::new(Kind::Input, e),
        }
    }
}

impl From<BasinsError> for Failure {
    fn from(e: BasinsError) -> Self {
        match e {
            BasinsError::Axis(e) => e.into(),
            BasinsError::Params(e) => e.into(),
            BasinsError::Sim(e) => e.into(),
            BasinsError::OutputExists(path) => output_exists(&path),
            _ => Self::new(Kind::Input, e),
        }
    }
}

impl From<CurvesError> for Failure {
    fn from(e: CurvesError) -> Self {
        let kind = match &e {
            CurvesError::UnknownParam { .. } | CurvesError::Corner { .. } => Kind::Param,
            // The sweep's failure, with the message saying where it happened.
            CurvesError::Sweep(inner) => Failure::from(inner.clone()).kind,
            _ => Kind::Input,
        };
        Self::new(kind, e)
    }
}

impl From<LyapunovError> for Failure {
    fn from(e: LyapunovError) -> Self {
        match e {
            LyapunovError::Sim(e) => e.into(),
            LyapunovError::NoPeriods => Self::new(Kind::Input, e),
        }
    }
}

impl From<serde_json::Error> for Failure {
    fn from(e: serde_json::Error) -> Self {
        Self::new(Kind::Input, e)
    }
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        Python::attach(|py| {
            let raised = py
                .import("stickslip.errors")
                .and_then(|errors| errors.getattr(f.kind.class()))
                .and_then(|class| class.call1((f.message.clone(),)));
            match raised {
                Ok(exception) => PyErr::from_value(exception),
                // The package is broken (errors.py missing): still no panic.
                Err(e) => e,
            }
        })
    }
}
