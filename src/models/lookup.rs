//! The model lookup: the one place where the compiled-in models and the
//! models loaded at run time meet. The command line (`--model NAME`,
//! `--model-file PATH --scene S`) and the Python package (`Model(name)`,
//! `Model.from_file`, `Model.from_source`) both name a model with a
//! [`ModelRef`] and run their work with [`ModelRef::visit`]: a
//! [`ModelVisitor`] handed the model's type and its base parameter set,
//! whichever back end made it.

use std::fmt;
use std::path::PathBuf;

use super::UnknownModel;
use crate::model::loaded::{load_file, load_source, LoadError, Loaded, LoadedModel, LoadedSmooth};
use crate::model::registry::ModelVisitor;

/// A model, as a user names it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ModelRef {
    /// A compiled-in model or scene (`paper`, `paper::sweep_w`, `stribeck`).
    Name(String),
    /// A model file, loaded and compiled to machine code at run time; with
    /// a scene, that scene of its model.
    File {
        /// The file.
        path: PathBuf,
        /// The scene.
        scene: Option<String>,
    },
    /// A model's text, loaded like a file; `origin` names it in messages.
    Source {
        /// The model file's text.
        text: String,
        /// How messages name it (`<source>`).
        origin: String,
        /// The scene.
        scene: Option<String>,
    },
}

/// Why a model could not be found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LookupError {
    /// A name that is no compiled-in model.
    #[error(transparent)]
    Unknown(#[from] UnknownModel),
    /// A file or text the generator rejects (`stickslip check`'s report).
    #[error(transparent)]
    Load(#[from] LoadError),
}

impl ModelRef {
    /// Run `visitor` with the model; `Ok(None)` when the visitor does not
    /// take a model of its kind (and for a name that is not compiled in).
    /// A file is read, checked and compiled on its first use in the process
    /// only (`model::loaded`).
    pub fn visit<V: ModelVisitor>(&self, visitor: V) -> Result<Option<V::Output>, LookupError> {
        let loaded = match self {
            ModelRef::Name(name) => return Ok(super::visit(name, visitor)),
            ModelRef::File { path, scene } => load_file(path, scene.as_deref())?,
            ModelRef::Source {
                text,
                origin,
                scene,
            } => load_source(text, origin, scene.as_deref())?,
        };
        Ok(match loaded {
            LoadedModel::Piecewise(base) => visitor.piecewise::<Loaded>(base),
            LoadedModel::Smooth(base) => visitor.smooth::<LoadedSmooth>(base),
        })
    }

    /// The scene `scene` of the same model (`stribeck` → `stribeck::pl8`).
    pub fn scene(&self, scene: &str) -> ModelRef {
        match self {
            ModelRef::Name(name) => {
                let model = name.split("::").next().unwrap_or(name);
                ModelRef::Name(format!("{model}::{scene}"))
            }
            ModelRef::File { path, .. } => ModelRef::File {
                path: path.clone(),
                scene: Some(scene.to_string()),
            },
            ModelRef::Source { text, origin, .. } => ModelRef::Source {
                text: text.clone(),
                origin: origin.clone(),
                scene: Some(scene.to_string()),
            },
        }
    }

    /// Whether it is loaded at run time (a file or a text).
    pub fn is_loaded(&self) -> bool {
        !matches!(self, ModelRef::Name(_))
    }
}

/// As a reader names it: `paper`, `models/paper.ssm`,
/// `models/paper.ssm --scene sweep_w`.
impl fmt::Display for ModelRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (what, scene) = match self {
            ModelRef::Name(name) => return f.write_str(name),
            ModelRef::File { path, scene } => (path.display().to_string(), scene),
            ModelRef::Source { origin, scene, .. } => (origin.clone(), scene),
        };
        match scene {
            Some(s) => write!(f, "{what} --scene {s}"),
            None => f.write_str(&what),
        }
    }
}
