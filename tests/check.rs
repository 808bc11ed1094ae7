//! `stickslip check`, run as a user runs it: exit status 0 for every shipped
//! model and 1 for every bad one; its report is word for word that of the
//! build path (`check_file`, which `build.rs` calls) and the message inside
//! the `model!(file = ...)` compile error (`tests/ui/files/*.stderr`); `--json`
//! locates each error at the line and column (in characters) of the
//! offending text, found here independently by searching the source.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");
const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Run `stickslip check ARGS` from the crate's root (so that relative paths
/// name files as `build.rs` and the macro name them).
fn check(args: &[&str]) -> Output {
    Command::new(BIN)
        .current_dir(ROOT)
        .arg("check")
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {BIN}: {e}"))
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8(bytes.to_vec()).expect("UTF-8 output")
}

/// The `.ssm` files of a directory, relative to the crate root, sorted.
fn ssm_files(dir: &str) -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(Path::new(ROOT).join(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ssm"))
        .map(|p| format!("{dir}/{}", p.file_name().expect("name").to_string_lossy()))
        .collect();
    out.sort();
    out
}

/// The stderr of `check` on one bad file without its summary line.
fn report_of(file: &str) -> String {
    let o = check(&[file]);
    assert_eq!(o.status.code(), Some(1), "{file}: {}", text(&o.stderr));
    let err = text(&o.stderr);
    let (report, summary) = err
        .trim_end_matches('\n')
        .rsplit_once('\n')
        .unwrap_or_else(|| panic!("{file}: no summary line in\n{err}"));
    assert!(summary.starts_with("checked 1 file: "), "{summary}");
    format!("{report}\n")
}

#[test]
fn every_shipped_model_checks_clean() {
    let models = ssm_files("models");
    assert!(models.len() >= 4);
    for file in &models {
        let o = check(&[file]);
        assert_eq!(o.status.code(), Some(0), "{file}: {}", text(&o.stderr));
        assert_eq!(text(&o.stderr), "checked 1 file: 0 errors\n");
    }
    // All at once.
    let args: Vec<&str> = models.iter().map(String::as_str).collect();
    let o = check(&args);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        text(&o.stderr),
        format!("checked {} files: 0 errors\n", models.len())
    );
}

#[test]
fn every_bad_model_fails_with_the_build_paths_report() {
    let bad = ssm_files("tests/ui/models");
    assert!(bad.len() >= 9);
    for file in &bad {
        let printed = report_of(file);
        // The build path: what build.rs prints for this file.
        let built = stickslip_codegen::check_file(&Path::new(ROOT).join(file), file)
            .expect_err("a bad model")
            .render();
        assert_eq!(printed, built, "{file}");
        // Every error is `error: ...` then `--> FILE:LINE:COL`, as rustc.
        let lines: Vec<&str> = printed.lines().collect();
        let mut errors = 0;
        for (i, l) in lines.iter().enumerate() {
            if l.starts_with("error: ") {
                errors += 1;
                let next = lines[i + 1].trim_start();
                assert!(next.starts_with(&format!("--> {file}:")), "{next}");
            }
        }
        assert!(
            printed.ends_with(&format!(
                "{errors} error{} in {file}\n",
                if errors == 1 { "" } else { "s" }
            )),
            "{printed}"
        );
    }
}

/// The message of the `model!(file = ...)` compile error in a trybuild
/// `.stderr`: the lines between `error: invalid model file` and the
/// compiler's own ` --> tests/ui/...rs` line, without rustc's indentation
/// of a multi-line message.
fn macro_message(stderr: &str) -> Option<String> {
    let mut lines = stderr.lines();
    lines.find(|l| *l == "error: invalid model file")?;
    let mut out = String::new();
    for l in lines {
        if l.starts_with(" --> tests/ui/") {
            break;
        }
        out.push_str(l.strip_prefix("       ").unwrap_or(l));
        out.push('\n');
    }
    Some(out.trim_end_matches('\n').to_string() + "\n")
}

#[test]
fn the_macro_reports_the_same_text_for_each_model_file() {
    let mut compared = 0;
    let files = Path::new(ROOT).join("tests/ui/files");
    for case in std::fs::read_dir(files).expect("tests/ui/files") {
        let path = case.expect("entry").path();
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let source = std::fs::read_to_string(&path).expect("read a case");
        let Some(file) = source
            .split("file = \"")
            .nth(1)
            .and_then(|rest| rest.split('"').next())
        else {
            continue;
        };
        if !Path::new(ROOT).join(file).exists() {
            continue; // files/missing: the macro's path is absolute, see below
        }
        let stderr = std::fs::read_to_string(path.with_extension("stderr")).expect("a .stderr");
        let message = macro_message(&stderr)
            .unwrap_or_else(|| panic!("{}: no `invalid model file` error", path.display()));
        // rustc shows a tab of the quoted source line (and of the caret
        // line's padding) as four spaces; `check` keeps the tab.
        let report = report_of(file).replace('\t', "    ");
        assert_eq!(message, report, "{}", path.display());
        compared += 1;
    }
    assert!(compared >= 9, "only {compared} model-file cases");
}

#[test]
fn an_unreadable_file_is_an_error_naming_it() {
    let o = check(&["models/paper.ssm", "tests/ui/models/no_such_model.ssm"]);
    assert_eq!(o.status.code(), Some(1));
    let err = text(&o.stderr);
    assert!(
        err.starts_with("error: cannot read tests/ui/models/no_such_model.ssm: "),
        "{err}"
    );
    assert!(err.ends_with("checked 2 files: 1 error\n"), "{err}");

    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("check");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let binary = dir.join("latin1.ssm");
    std::fs::write(&binary, b"model m { param \xe9 = 1.0; }").expect("write");
    let o = check(&[binary.to_str().expect("UTF-8 path")]);
    assert_eq!(o.status.code(), Some(1));
    // The bad byte is located: line 1, column 17 (the 17th character).
    let err = text(&o.stderr);
    assert!(
        err.starts_with("error: the file is not valid UTF-8 at byte 0xE9"),
        "{err}"
    );
    assert!(err.contains("latin1.ssm:1:17\n"), "{err}");

    // A directory is not a model file either.
    let o = check(&["models"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(text(&o.stderr).starts_with("error: cannot read models: "));
}

#[test]
fn several_files_are_all_checked_and_all_errors_reported() {
    let files = [
        "tests/ui/models/bad_names.ssm",
        "models/coulomb.ssm",
        "tests/ui/models/syntax_errors.ssm",
    ];
    let o = check(&files);
    assert_eq!(o.status.code(), Some(1));
    let expected = format!(
        "{}{}checked 3 files: 5 errors\n",
        report_of(files[0]),
        report_of(files[2])
    );
    assert_eq!(text(&o.stderr), expected);
}

/// Line (1-based) and column (1-based, in characters) of the first
/// occurrence of `needle` at or after `after` on a line containing `context`.
fn locate(source: &str, context: &str, needle: &str) -> (u64, u64) {
    let (i, line) = source
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains(context))
        .unwrap_or_else(|| panic!("no line with `{context}`"));
    let start = line.find(context).expect("context") + context.find(needle).expect("needle");
    (i as u64 + 1, line[..start].chars().count() as u64 + 1)
}

#[test]
fn json_locates_each_error_by_line_and_character_column() {
    let o = check(&[
        "--json",
        "tests/ui/models/bad_names.ssm",
        "models/paper.ssm",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stderr.is_empty(), "{}", text(&o.stderr));
    let doc: Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    assert_eq!(doc["checked"], 2);
    assert_eq!(doc["errors"], 2);
    let bad = &doc["files"][0];
    assert_eq!(bad["file"], "tests/ui/models/bad_names.ssm");
    assert_eq!(bad["ok"], false);
    let good = &doc["files"][1];
    assert_eq!(good["ok"], true);
    assert_eq!(good["model"], "paper");
    assert_eq!(good["diagnostics"].as_array().map(Vec::len), Some(0));

    let source = std::fs::read_to_string(Path::new(ROOT).join("tests/ui/models/bad_names.ssm"))
        .expect("read");
    let d = bad["diagnostics"].as_array().expect("diagnostics");
    assert_eq!(d.len(), 2);
    let rendered = report_of("tests/ui/models/bad_names.ssm");
    for (diag, (context, needle)) in d.iter().zip([("d * v", "v"), ("-muu", "muu")]) {
        let (line, col) = locate(&source, context, needle);
        assert_eq!(diag["severity"], "error");
        assert_eq!(diag["file"], "tests/ui/models/bad_names.ssm");
        assert_eq!(diag["line"], line, "{diag}");
        assert_eq!(diag["column"], col, "{diag}");
        assert_eq!(diag["end_line"], line, "{diag}");
        assert_eq!(diag["end_column"], col + needle.chars().count() as u64);
        let message = diag["message"].as_str().expect("message");
        let text = diag["rendered"].as_str().expect("rendered");
        assert!(text.starts_with(&format!("error: {message}\n")), "{text}");
        assert!(rendered.contains(text), "{text}");
    }

    // An unreadable file: an error without a position.
    let o = check(&["--json", "no/such.ssm"]);
    assert_eq!(o.status.code(), Some(1));
    let doc: Value = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    let d = &doc["files"][0]["diagnostics"][0];
    assert!(d["line"].is_null() && d["column"].is_null(), "{d}");
    assert!(d["message"]
        .as_str()
        .is_some_and(|m| m.starts_with("cannot read no/such.ssm: ")));
}

#[test]
fn columns_count_characters_not_bytes() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("check");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("accents.ssm");
    // `ééé` is 3 characters, 6 bytes: a byte column would be 3 too far.
    let source = "model accents {\n    param ééé = 1.0, > zzz;\n}\n";
    std::fs::write(&path, source).expect("write");
    let file = path.to_str().expect("UTF-8 path");
    let o = check(&["--json", file]);
    assert_eq!(o.status.code(), Some(1));
    let doc: Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let d = &doc["files"][0]["diagnostics"][0];
    let (line, col) = locate(source, "> zzz", "zzz");
    assert_eq!(
        (d["line"].clone(), d["column"].clone()),
        (line.into(), col.into()),
        "{d}"
    );
    assert_eq!(col, 24);
    // The caret sits under `zzz` in the rendered text.
    let rendered = d["rendered"].as_str().expect("rendered");
    let caret = rendered.lines().last().expect("caret line");
    let gutter = caret.find('|').expect("gutter") + 2;
    assert_eq!(
        caret[gutter..].chars().count() as u64,
        col - 1 + 3,
        "{rendered}"
    );
    assert!(caret.ends_with("^^^"), "{rendered}");
}
