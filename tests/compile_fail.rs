//! Bad models must not compile, and the compiler error must point at the
//! offending token (inline models) or name `file:line:col` (model files).
//! The cases are sorted by error class, one folder each under `tests/ui/`
//! (the model files they read are in `tests/ui/models/`).
//! Regenerate the expected output with
//! `TRYBUILD=overwrite cargo test --test compile_fail`, then read every
//! `tests/ui/*/*.stderr`.

use std::path::Path;

/// The error classes: `(folder under tests/ui, what its cases get wrong)`.
const CLASSES: [(&str, &str); 8] = [
    ("syntax", "the grammar: tokens, items, attributes, nesting"),
    (
        "names",
        "names: duplicates, unknown or reserved names, twins, `v`",
    ),
    (
        "numbers",
        "numbers and values at the defaults: overflow, NaN, zero, sign",
    ),
    (
        "bands",
        "boundaries and domains: labels, bands, gaps, overlaps",
    ),
    (
        "laws",
        "friction laws: affinity, jumps, smooth laws, static bounds",
    ),
    ("scenes", "scene entries: what a scene frees and names"),
    ("structures", "the mapping structures a scene lists"),
    (
        "files",
        "model files: `model!(file = ..)`, encodings, file:line:col",
    ),
];

#[test]
fn bad_models_fail_to_compile_with_located_errors() {
    stage_model_files();
    let t = trybuild::TestCases::new();
    for (folder, _) in CLASSES {
        t.compile_fail(format!("tests/ui/{folder}/*.rs"));
    }
}

/// Every folder of cases is run: a new class must be listed in `CLASSES`,
/// and no case may sit outside a class folder.
#[test]
fn every_ui_folder_is_a_listed_class() {
    let ui = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ui");
    for entry in std::fs::read_dir(&ui).expect("tests/ui") {
        let path = entry.expect("directory entry").path();
        let name = path.file_name().expect("file name").to_string_lossy();
        if path.is_dir() {
            assert!(
                name == "models" || CLASSES.iter().any(|(c, _)| *c == name),
                "tests/ui/{name}/ is not in CLASSES: its cases would not run"
            );
        } else {
            panic!("tests/ui/{name}: a case belongs in a class folder");
        }
    }
}

/// `model!(file = "tests/ui/models/x.ssm")` resolves the path against the
/// `CARGO_MANIFEST_DIR` of the crate being compiled. trybuild compiles the
/// cases as a crate of its own, in `<target>/tests/trybuild/stickslip/`, so the
/// model files must also be there, at the same relative path. Copying them
/// keeps the paths in the cases (and in their messages) those of this crate.
fn stage_model_files() {
    let target = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("CARGO_TARGET_TMPDIR is <target>/tmp");
    let from = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ui/models");
    let to = target.join("tests/trybuild/stickslip/tests/ui/models");
    std::fs::create_dir_all(&to).expect("create the staged models directory");
    for entry in std::fs::read_dir(&from).expect("tests/ui/models") {
        let path = entry.expect("directory entry").path();
        if path.extension().is_some_and(|e| e == "ssm") {
            let dest = to.join(path.file_name().expect("file name"));
            std::fs::copy(&path, &dest).expect("copy a model file");
        }
    }
}
