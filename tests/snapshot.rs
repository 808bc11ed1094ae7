//! Snapshots of the generated code: `tests/snapshots/NAME.rs` is the
//! reviewable, checked-in output of the generator for the paper model and
//! the small Coulomb model. When the generator changes on purpose, re-bless
//! them with `STICKSLIP_BLESS=1 cargo test --test snapshot` and review the
//! diff. `tests/snapshot_compiles.rs` compiles the snapshots themselves.

/// Compare the compiled-in source of model `name` with its snapshot (or
/// write the snapshot, with `STICKSLIP_BLESS` set).
fn matches_snapshot(name: &str) {
    let file = format!("tests/snapshots/{name}.rs");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(&file);
    let generated = stickslip::models::generated_source(name)
        .unwrap_or_else(|| panic!("{name} is not compiled in"));
    if std::env::var_os("STICKSLIP_BLESS").is_some() {
        std::fs::write(&path, generated).expect("write snapshot");
        return;
    }
    let snapshot = std::fs::read_to_string(&path).unwrap_or_default();
    if snapshot != generated {
        let first = snapshot
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(snapshot.lines().count().min(generated.lines().count()));
        panic!(
            "generated code differs from {file} from line {}:\n  snapshot:  {:?}\n  generated: {:?}\n\
             review the change, then re-bless with STICKSLIP_BLESS=1 cargo test --test snapshot",
            first + 1,
            snapshot.lines().nth(first),
            generated.lines().nth(first)
        );
    }
}

#[test]
fn generated_code_for_the_paper_model_matches_the_snapshot() {
    matches_snapshot("paper");
}

#[test]
fn generated_code_for_the_coulomb_model_matches_the_snapshot() {
    matches_snapshot("coulomb");
}
