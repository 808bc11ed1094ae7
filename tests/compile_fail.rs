//! Bad models must not compile, and the compiler error must point at the
//! offending token (inline models) or name `file:line:col` (model files).
//! Regenerate the expected output with
//! `TRYBUILD=overwrite cargo test --test compile_fail`, then read every
//! `tests/ui/*.stderr`.

use std::path::Path;

#[test]
fn bad_models_fail_to_compile_with_located_errors() {
    stage_model_files();
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
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
