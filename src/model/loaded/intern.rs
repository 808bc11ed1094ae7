//! Loading: a model file's text through the generator's run-time back end,
//! once per distinct text. A loaded model is leaked (its code, its
//! description) and kept in a table keyed by the text, the file's name and
//! the scene: loading the same text again compiles nothing, and the memory
//! a process spends on loaded models grows only with the number of distinct
//! sources it loads (a few hundred kilobytes each).

use std::collections::HashMap;
use std::path::Path;
use std::sync::Mutex;

use stickslip_codegen::jit::{self, Compiled};
use stickslip_codegen::report::read_file;
use stickslip_codegen::Report;

use super::describe;
use super::routines::ROUTINES;
use super::{LoadedParams, LoadedSmoothParams, PiecewiseHandle, SmoothHandle, CAPACITY};

/// A model loaded at run time, as its base parameter set (the declared
/// defaults), which carries the model: hand it to the analyses as a
/// compiled-in model's `Params::default()` is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LoadedModel {
    /// A piecewise-linear model or scene ([`super::Loaded`]).
    Piecewise(LoadedParams),
    /// A model with a smooth law ([`super::LoadedSmooth`]).
    Smooth(LoadedSmoothParams),
}

/// Why a model could not be loaded: the report `stickslip check` gives for
/// the file (`file:line:col`, the source line, a caret), or a scene it does
/// not have.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}", report.render().trim_end())]
pub struct LoadError {
    /// Every error, located.
    pub report: Report,
}

/// The content hash of a model file's text, as map headers record it:
/// FNV-1a over its bytes (64 bits; stable across builds and platforms,
/// unlike the standard library's hasher).
pub fn content_hash(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

type Key = (String, Option<String>, Option<String>);

/// Every model this process has loaded, by `(text, file stem, scene)`.
static LOADED: Mutex<Option<HashMap<Key, LoadedModel>>> = Mutex::new(None);

/// Load the model file at `path` (its scene `scene`, if given): checked as
/// `stickslip check` checks it (the model must be named like the file),
/// compiled to machine code.
pub fn load_file(path: &Path, scene: Option<&str>) -> Result<LoadedModel, LoadError> {
    let origin = path.display().to_string();
    let (text, stem) = read_file(path, &origin).map_err(|report| LoadError { report })?;
    load(&text, &origin, stem, scene)
}

/// Load a model from its text (its scene `scene`, if given); `origin` names
/// it in messages.
pub fn load_source(
    text: &str,
    origin: &str,
    scene: Option<&str>,
) -> Result<LoadedModel, LoadError> {
    load(text, origin, None, scene)
}

fn load(
    text: &str,
    origin: &str,
    stem: Option<String>,
    scene: Option<&str>,
) -> Result<LoadedModel, LoadError> {
    let key: Key = (text.to_string(), stem, scene.map(str::to_string));
    // A poisoned table (a panic elsewhere while it was held) still holds
    // only complete entries.
    let mut table = LOADED.lock().unwrap_or_else(|e| e.into_inner());
    let table = table.get_or_insert_with(HashMap::new);
    if let Some(&model) = table.get(&key) {
        return Ok(model);
    }
    let compiled = jit::compile_text(text, origin, key.1.as_deref(), scene, &ROUTINES)
        .map_err(|report| LoadError { report })?;
    let hash = content_hash(text);
    let model = match compiled {
        Compiled::Piecewise {
            instance,
            regimes,
            code,
        } => {
            let info = describe::piecewise(&instance, &regimes, hash);
            let handle: &'static PiecewiseHandle = Box::leak(Box::new(PiecewiseHandle {
                info,
                names: describe::names(&info.identity),
                code: *code,
            }));
            LoadedModel::Piecewise(LoadedParams::defaults(handle, &info.identity))
        }
        Compiled::Smooth { smooth, code } => {
            let info = describe::smooth(&smooth, hash);
            let handle: &'static SmoothHandle = Box::leak(Box::new(SmoothHandle {
                info,
                names: describe::names(&info.identity),
                code: *code,
            }));
            LoadedModel::Smooth(LoadedSmoothParams::defaults(handle, &info.identity))
        }
    };
    debug_assert!(match model {
        LoadedModel::Piecewise(p) => p.len() <= CAPACITY,
        LoadedModel::Smooth(p) => p.len() <= CAPACITY,
    });
    table.insert(key, model);
    Ok(model)
}
