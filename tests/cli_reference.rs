//! The guide's command-line reference (`docs/guide/src/reference/cli.md`)
//! is what the code generates (`stickslip reference`, from the parser's
//! definitions), so it cannot drift from the options the tool takes.
//! `STICKSLIP_BLESS=1 cargo test --test cli_reference` rewrites it.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");

#[test]
fn the_committed_cli_reference_is_what_the_code_generates() {
    let out = Command::new(BIN).arg("reference").output().expect("runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let generated = String::from_utf8(out.stdout).expect("UTF-8");
    // Every visible subcommand has its section, with its options.
    for sub in ["check", "sweep", "map", "curves", "basins", "orbit-diagram"] {
        assert!(
            generated.contains(&format!("## `stickslip {sub}`")),
            "no section for {sub}"
        );
    }
    assert!(
        generated.contains("--view <VIEW>"),
        "sweep's --view is missing"
    );
    assert!(!generated.contains("## `stickslip reference`"));
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/guide/src/reference/cli.md");
    if std::env::var_os("STICKSLIP_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write the reference");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "{} differs from what `stickslip reference` prints (the command line \
         changed); regenerate it with `STICKSLIP_BLESS=1 cargo test --test \
         cli_reference` and commit it",
        path.display()
    );
}
