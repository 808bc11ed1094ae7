//! Generates Rust for every model file in `models/` and in the folders of
//! `STICKSLIP_MODELS` (a thin driver over `stickslip-codegen`'s
//! `model_files`): `OUT_DIR/models/NAME.rs` per model and
//! `OUT_DIR/models.rs`, the catalogue `src/models.rs` includes.

use std::fs;
use std::path::{Path, PathBuf};

use stickslip_codegen::emit::registry;
use stickslip_codegen::model_files::{self, USER_MODELS};

fn write_if_changed(path: &Path, content: &str) {
    if fs::read_to_string(path).ok().as_deref() != Some(content) {
        fs::write(path, content).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    }
}

fn main() {
    let manifest =
        PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    println!("cargo:rerun-if-env-changed={USER_MODELS}");
    let user = std::env::var_os(USER_MODELS);
    // The one entry point of build.rs, `model!(file = ...)` and `stickslip
    // check` is `check_file`: the same file gets the same report from all three.
    let files = model_files::list(
        &manifest.join("models"),
        "models",
        user.as_deref(),
        &manifest,
    );
    for path in files.watched() {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    let generated = model_files::generate(&files).unwrap_or_else(|errors| {
        eprint!("{}", model_files::render(&errors, &files));
        std::process::exit(1)
    });
    fs::create_dir_all(out.join("models")).expect("create OUT_DIR/models");
    for g in &generated {
        write_if_changed(&out.join(registry::generated_path(g)), &g.code);
    }
    write_if_changed(&out.join("models.rs"), &registry::catalogue(&generated));
}
