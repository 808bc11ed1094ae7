//! Shared by the generator's tests: edit a model's text, generate it, and
//! read a report's errors as `(message, "FILE:LINE:COL")`.
#![allow(dead_code)]

use stickslip_codegen::{generate_source, GeneratedFile};

/// `source` with each `(from, to)` applied; `from` must occur exactly once.
pub fn edit(source: &str, edits: &[(&str, &str)]) -> String {
    let mut s = source.to_string();
    for (from, to) in edits {
        assert_eq!(
            s.matches(from).count(),
            1,
            "`{from}` must occur exactly once in the model"
        );
        s = s.replacen(from, to, 1);
    }
    s
}

/// The model generated from `source` (named `test.ssm` in reports).
pub fn generate(source: &str) -> Result<GeneratedFile, String> {
    generate_source(source, "test.ssm")
}

/// The generated file of a model that must be accepted.
pub fn accepted(source: &str) -> GeneratedFile {
    match generate(source) {
        Ok(g) => g,
        Err(report) => panic!("the model should be accepted, got:\n{report}"),
    }
}

/// The errors of a rejected model, as `(message, "test.ssm:LINE:COL")`,
/// after checking the report's final count line.
pub fn errors(source: &str) -> Vec<(String, String)> {
    let report = match generate(source) {
        Ok(_) => panic!("the model should be rejected:\n{source}"),
        Err(r) => r,
    };
    let out = parse_report(&report);
    let count = match out.len() {
        1 => "1 error in test.ssm".to_string(),
        n => format!("{n} errors in test.ssm"),
    };
    assert_eq!(
        report.lines().last(),
        Some(count.as_str()),
        "count line of:\n{report}"
    );
    out
}

/// Every `error: MESSAGE` of a report with the location on the next line.
pub fn parse_report(report: &str) -> Vec<(String, String)> {
    let lines: Vec<&str> = report.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if let Some(message) = line.strip_prefix("error: ") {
            let location = lines
                .get(i + 1)
                .and_then(|l| l.trim_start().strip_prefix("--> "))
                .unwrap_or_else(|| panic!("no location after `{line}` in:\n{report}"));
            out.push((message.to_string(), location.to_string()));
        }
    }
    out
}
