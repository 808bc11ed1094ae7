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
    let warnings = stage_warning_cases();
    let t = trybuild::TestCases::new();
    for (folder, _) in CLASSES {
        t.compile_fail(format!("tests/ui/{folder}/*.rs"));
    }
    // One trybuild run for both: its cases share one build of the crate.
    for case in warnings {
        t.pass(case);
    }
}

/// Every valid model generates code that compiles with `#![deny(warnings)]`
/// where `build.rs` includes it: the shipped models and the corner cases of
/// `tests/warnings/` (a belt that stands still, no forcing, every parameter
/// but one folded, a smooth law on a still belt, hostile names). The
/// `model!` macro cannot show this: lints in code a macro of another crate
/// expands are not reported. Each model's generated module is written to
/// `<target>/tmp/warnings/` and included by a case that denies warnings.
fn stage_warning_cases() -> Vec<std::path::PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("warnings");
    std::fs::create_dir_all(&dir).expect("create the warnings directory");
    let mut cases = Vec::new();
    for folder in ["models", "tests/warnings"] {
        let mut files: Vec<_> = std::fs::read_dir(root.join(folder))
            .expect("a models folder")
            .map(|e| e.expect("directory entry").path())
            .filter(|p| p.extension().is_some_and(|e| e == "ssm"))
            .collect();
        files.sort();
        for path in files {
            let origin = format!("{folder}/{}", path.file_name().unwrap().to_string_lossy());
            let generated = stickslip_codegen::check_file(&path, &origin)
                .unwrap_or_else(|r| panic!("{}", r.render()));
            let body: proc_macro2::TokenStream =
                generated.code.parse().expect("generated code tokenizes");
            let module = stickslip_codegen::emit::registry::module(&generated, body);
            let code = dir.join(format!("{}_module.rs", generated.name));
            std::fs::write(&code, module.to_string()).expect("write the module");
            let case = dir.join(format!("{}.rs", generated.name));
            let text = format!(
                "#![deny(warnings)]\ninclude!({:?});\nfn main() {{}}\n",
                code.display().to_string()
            );
            std::fs::write(&case, text).expect("write the case");
            cases.push(case);
        }
    }
    cases
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
