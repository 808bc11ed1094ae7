//! `stickslip check`: every file through the generator's one entry point
//! (that of `build.rs` and `model!(file = ...)`), all errors reported.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use super::error::CliError;

/// Arguments of `check`.
#[derive(Args)]
pub struct CheckArgs {
    /// Model files (`models/paper.ssm`).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Print the diagnostics as JSON on stdout (for editors).
    #[arg(long)]
    json: bool,
}

/// Check the files: each error on stderr as it is found (or all as JSON on
/// stdout), a count; exit status 1 on any error.
pub fn run(args: &CheckArgs) -> Result<ExitCode, CliError> {
    let mut errors = 0;
    let mut reports = Vec::new();
    for file in &args.files {
        let origin = file.display().to_string();
        match stickslip_codegen::check_file(file, &origin) {
            Ok(generated) => reports.push(serde_json::json!({
                "file": origin,
                "ok": true,
                "model": generated.name,
                "diagnostics": [],
            })),
            Err(report) => {
                errors += report.errors.len();
                if !args.json {
                    eprint!("{}", report.render());
                }
                let diagnostics: Vec<serde_json::Value> =
                    report.errors.iter().map(diagnostic_json).collect();
                reports.push(serde_json::json!({
                    "file": origin,
                    "ok": false,
                    "model": null,
                    "diagnostics": diagnostics,
                }));
            }
        }
    }
    let n = args.files.len();
    if args.json {
        let doc = serde_json::json!({
            "checked": n,
            "errors": errors,
            "files": reports,
        });
        println!("{}", serde_json::to_string_pretty(&doc)?);
    } else {
        eprintln!(
            "checked {n} file{}: {errors} error{}",
            if n == 1 { "" } else { "s" },
            if errors == 1 { "" } else { "s" }
        );
    }
    Ok(if errors == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// One diagnostic for `check --json`: lines and columns 1-based, columns in
/// characters, the end exclusive; `null` position for a file-wide error.
fn diagnostic_json(e: &stickslip_codegen::Located) -> serde_json::Value {
    let (line, column, end_line, end_column) = match e.position {
        Some(p) => (
            Some(p.line),
            Some(p.column),
            Some(p.end_line),
            Some(p.end_column),
        ),
        None => (None, None, None, None),
    };
    serde_json::json!({
        "severity": e.severity.as_str(),
        "message": e.message,
        "file": e.file,
        "line": line,
        "column": column,
        "end_line": end_line,
        "end_column": end_column,
        "rendered": e.rendered,
    })
}
