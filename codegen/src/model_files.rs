//! The model files a build compiles in: every `models/*.ssm` of the
//! checkout, then every `*.ssm` of the folders listed in the environment
//! variable [`USER_MODELS`] (`STICKSLIP_MODELS=dir cargo build`, or
//! `pip install ./python`), separated as `PATH` is (`:`, `;` on Windows).
//!
//! `build.rs` is a thin driver over this module: [`list`] the files, print a
//! `rerun-if-changed` for each [`ModelFiles::watched`] path, [`generate`]
//! them, write what comes back. Every file gets the checks of
//! [`check_file`], named in messages as its folder was given
//! (`models/paper.ssm`, `/home/me/mine/spring.ssm:12:5`), never as a copy.
//! On top of them, for a user's folders:
//!
//! * a folder that does not exist, is not a folder or cannot be read is an
//!   error, and so is a folder with no `.ssm` file (nothing is silently
//!   built);
//! * two models may not share a name, not even one differing only in case
//!   (their generated files would overwrite each other on a case-insensitive
//!   file system): the error is at the later file's `model NAME` and names
//!   the other file. A built-in model always comes first, so a user's model
//!   named like it is the one reported.
//!
//! A relative folder is read from `base` (cargo runs a build script in the
//! checkout); the same folder listed twice, or the built-in folder listed
//! again, is read once. Hidden files (`.#paper.ssm`, an editor's lock) are
//! skipped.

use std::collections::HashMap;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};

use crate::diagnostic::Diagnostics;
use crate::report::{check_file, Report};
use crate::GeneratedFile;

/// The environment variable listing the folders of a user's model files.
pub const USER_MODELS: &str = "STICKSLIP_MODELS";

/// One model file to compile.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelFile {
    /// Where it is read.
    pub path: PathBuf,
    /// The file as named in messages: its folder as given, then its name.
    pub origin: String,
    /// Its name without `.ssm`: the name its model must have.
    pub stem: String,
    /// Whether it is one of the checkout's own models (not a user's).
    pub built_in: bool,
}

/// What [`list`] found: the files in build order (the built-in folder
/// first, then each user folder in the order given; by name within a
/// folder), the folders read, and what was wrong with them.
#[derive(Clone, Debug, Default)]
pub struct ModelFiles {
    /// The files, in build order.
    pub files: Vec<ModelFile>,
    /// Every folder named (read or not), for `rerun-if-changed`.
    pub folders: Vec<PathBuf>,
    /// A folder that is missing, unreadable or empty of models; a file whose
    /// name is not UTF-8.
    pub errors: Vec<Report>,
}

impl ModelFiles {
    /// The paths whose change must run the build again: each folder (a file
    /// added or removed) and each file.
    pub fn watched(&self) -> impl Iterator<Item = &Path> {
        let folders = self.folders.iter().map(PathBuf::as_path);
        folders.chain(self.files.iter().map(|f| f.path.as_path()))
    }
}

/// The model files of the build: every `*.ssm` of `built_in` (named
/// `built_in_origin/NAME.ssm` in messages), then of each folder of `user`
/// (the value of [`USER_MODELS`], folders separated as in `PATH`; empty
/// entries are ignored), a relative one read from `base`.
pub fn list(
    built_in: &Path,
    built_in_origin: &str,
    user: Option<&OsStr>,
    base: &Path,
) -> ModelFiles {
    let mut out = ModelFiles::default();
    let mut seen: Vec<PathBuf> = Vec::new();
    read_folder(built_in, built_in_origin, true, &mut seen, &mut out);
    for given in user.into_iter().flat_map(std::env::split_paths) {
        if given.as_os_str().is_empty() {
            continue;
        }
        let origin = given.display().to_string();
        read_folder(&base.join(&given), &origin, false, &mut seen, &mut out);
    }
    out
}

/// Add the `.ssm` files of `folder` to `out`, or the reason there are none.
fn read_folder(
    folder: &Path,
    origin: &str,
    built_in: bool,
    seen: &mut Vec<PathBuf>,
    out: &mut ModelFiles,
) {
    out.folders.push(folder.to_path_buf());
    let what = if built_in {
        "the built-in models".to_string()
    } else {
        format!("{USER_MODELS}: the folder `{origin}`")
    };
    // How the folder was read, when it was given relative to `base`.
    let read_as = if Path::new(origin).is_relative() && !built_in {
        format!(" (read as {})", folder.display())
    } else {
        String::new()
    };
    let fail = |out: &mut ModelFiles, message: String| {
        out.errors.push(Report::whole_file(origin, message));
    };
    match std::fs::metadata(folder) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return fail(out, format!("{what}{read_as} does not exist"));
        }
        Err(e) => return fail(out, format!("{what}{read_as} cannot be read: {e}")),
        Ok(m) if !m.is_dir() => {
            return fail(
                out,
                format!(
                    "{what}{read_as} is a file, not a folder: {USER_MODELS} lists folders \
                     of `.ssm` files, separated by `{}`",
                    if cfg!(windows) { ';' } else { ':' }
                ),
            );
        }
        Ok(_) => {}
    }
    // The same folder twice is one set of models, not a clash with itself.
    let canonical = std::fs::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
    if seen.contains(&canonical) {
        return;
    }
    seen.push(canonical);
    let entries = match std::fs::read_dir(folder) {
        Ok(rd) => rd,
        Err(e) => return fail(out, format!("{what}{read_as} cannot be read: {e}")),
    };
    let mut names = Vec::new();
    let mut others = Vec::new();
    for entry in entries {
        let entry = match entry {
            Ok(entry) => entry,
            Err(e) => return fail(out, format!("{what}{read_as} cannot be read: {e}")),
        };
        let name = entry.file_name();
        let path = entry.path();
        if name.to_string_lossy().starts_with('.') {
            continue;
        }
        if path.extension() == Some(OsStr::new("ssm")) {
            names.push(name);
        } else {
            others.push(name.to_string_lossy().into_owned());
        }
    }
    names.sort();
    if names.is_empty() {
        others.sort();
        let found = match others.len() {
            0 => "it is empty".to_string(),
            n => format!(
                "it holds {n} other entr{} ({}{})",
                if n == 1 { "y" } else { "ies" },
                others
                    .iter()
                    .take(3)
                    .map(|o| format!("`{o}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                if n > 3 { ", ..." } else { "" }
            ),
        };
        return fail(
            out,
            format!("{what}{read_as} holds no model file `*.ssm`: {found}"),
        );
    }
    for name in names {
        let path = folder.join(&name);
        // The checkout's own models are named alike on every platform.
        let shown = if built_in {
            format!("{origin}/{}", name.to_string_lossy())
        } else {
            Path::new(origin).join(&name).display().to_string()
        };
        match Path::new(&name).file_stem().and_then(OsStr::to_str) {
            Some(stem) => out.files.push(ModelFile {
                stem: stem.to_string(),
                path,
                origin: shown,
                built_in,
            }),
            None => fail(
                out,
                format!(
                    "the file name `{shown}` is not UTF-8: a model file is named after \
                     its model, `NAME.ssm`"
                ),
            ),
        }
    }
}

/// Check and generate every file of `files`, in order: the generated
/// models, or every error found (the folders' errors, each file's own,
/// and each name clash), one [`Report`] per file.
pub fn generate(files: &ModelFiles) -> Result<Vec<GeneratedFile>, Vec<Report>> {
    let mut errors = files.errors.clone();
    let mut generated = Vec::new();
    // The first file of each name, by its name in lower case.
    let mut first: HashMap<String, &ModelFile> = HashMap::new();
    for file in &files.files {
        let mut report = match check_file(&file.path, &file.origin) {
            Ok(g) => {
                generated.push(g);
                None
            }
            Err(report) => Some(report),
        };
        match first.get(&file.stem.to_lowercase()) {
            None => {
                first.insert(file.stem.to_lowercase(), file);
            }
            Some(other) => {
                let clash = clash(file, other);
                match &mut report {
                    Some(r) => r.errors.extend(clash.errors),
                    None => report = Some(clash),
                }
            }
        }
        errors.extend(report);
    }
    if errors.is_empty() {
        Ok(generated)
    } else {
        Err(errors)
    }
}

/// Every report rendered, then a line naming the folders.
pub fn render(errors: &[Report], files: &ModelFiles) -> String {
    let mut out: String = errors.iter().map(Report::render).collect();
    let folders: Vec<String> = files
        .folders
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    out.push_str(&format!(
        "stickslip: invalid model file(s) in {}\n",
        folders.join(", ")
    ));
    out
}

/// The error of `file`, whose model is named like the earlier `other`'s: at
/// its `model NAME` when the file parses that far, else about the file.
fn clash(file: &ModelFile, other: &ModelFile) -> Report {
    let whose = if other.built_in {
        "a built-in model"
    } else {
        "another model"
    };
    let message = if file.stem == other.stem {
        format!(
            "a model named `{}` is already compiled in: {whose}, in {}; rename this \
             model and its file",
            file.stem, other.origin
        )
    } else {
        format!(
            "the model `{}` differs only in case from `{}`, {whose}, in {}: their \
             generated files would overwrite each other on a case-insensitive file \
             system; rename this model and its file",
            file.stem, other.stem, other.origin
        )
    };
    match name_location(&file.path) {
        Some((span, source)) => {
            let mut located = Diagnostics::new();
            located.error(span, message);
            Report::from_diagnostics(&located, &file.origin, &source)
        }
        None => Report::whole_file(&file.origin, message),
    }
}

/// The span of `NAME` in `model NAME` of the file at `path`, and the file's
/// text; `None` when the file does not parse that far.
fn name_location(path: &Path) -> Option<(proc_macro2::Span, String)> {
    let bytes = std::fs::read(path).ok()?;
    let source = crate::source::decode(&bytes).ok()?;
    let source = crate::source::strip_bom(&source).to_string();
    let tokens = crate::tokenize(&source).ok()?;
    let mut diags = Diagnostics::new();
    let ast = crate::parse::parse_model(tokens, &mut diags)?;
    Some((ast.name.span(), source))
}

#[cfg(test)]
#[path = "model_files/tests.rs"]
mod tests;
