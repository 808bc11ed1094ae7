//! Snapshot of the generated code for the paper model: `tests/snapshots/paper.rs`
//! is the reviewable, checked-in output of the generator. When the generator
//! changes on purpose, re-bless it with
//! `STICKSLIP_BLESS=1 cargo test --test snapshot` and review the diff.
//! `tests/snapshot_compiles.rs` compiles the snapshot itself.

#[test]
fn generated_code_for_the_paper_model_matches_the_snapshot() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/paper.rs");
    let generated = stickslip::models::generated_source("paper").expect("paper is compiled in");
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
            "generated code differs from tests/snapshots/paper.rs from line {}:\n  snapshot:  {:?}\n  generated: {:?}\n\
             review the change, then re-bless with STICKSLIP_BLESS=1 cargo test --test snapshot",
            first + 1,
            snapshot.lines().nth(first),
            generated.lines().nth(first)
        );
    }
}
