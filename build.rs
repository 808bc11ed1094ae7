//! Generates Rust for every model file in `models/` (a thin driver over
//! `stickslip-codegen`): `OUT_DIR/models/NAME.rs` per model and
//! `OUT_DIR/models.rs`, the catalogue `src/models.rs` includes.

use std::fs;
use std::path::{Path, PathBuf};

use stickslip_codegen::emit::registry;

fn write_if_changed(path: &Path, content: &str) {
    if fs::read_to_string(path).ok().as_deref() != Some(content) {
        fs::write(path, content).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    }
}

fn main() {
    let manifest =
        PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    let models_dir = manifest.join("models");
    println!("cargo:rerun-if-changed=models");
    let mut files: Vec<PathBuf> = fs::read_dir(&models_dir)
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    files.retain(|p| p.extension().is_some_and(|e| e == "ssm"));
    files.sort();
    fs::create_dir_all(out.join("models")).expect("create OUT_DIR/models");

    let mut failed = false;
    let mut generated = Vec::new();
    for file in &files {
        println!("cargo:rerun-if-changed={}", file.display());
        let origin = format!(
            "models/{}",
            file.file_name().expect("file").to_string_lossy()
        );
        // The one entry point of build.rs, `model!(file = ...)` and
        // `stickslip check`: the same file gets the same report from all three.
        match stickslip_codegen::check_file(file, &origin) {
            Err(report) => {
                eprint!("{}", report.render());
                failed = true;
            }
            Ok(g) => {
                write_if_changed(&out.join(registry::generated_path(&g)), &g.code);
                generated.push(g);
            }
        }
    }
    if failed {
        eprintln!(
            "stickslip: invalid model file(s) in {}",
            models_dir.display()
        );
        std::process::exit(1);
    }
    write_if_changed(&out.join("models.rs"), &registry::catalogue(&generated));
}
