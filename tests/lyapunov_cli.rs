//! `stickslip lyapunov`: the JSON keys and the `-inf` representation, the
//! text form, and typed errors for bad input (exit status 1, a clear message).

use std::process::Command;

use serde_json::Value;

fn stickslip(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .output()
        .expect("run stickslip");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn json_of_a_motion_with_stick_has_minus_inf_as_a_string() {
    let (ok, out, err) = stickslip(&[
        "lyapunov",
        "--set",
        "W=3.7,Q0=70",
        "--transient",
        "200",
        "--periods",
        "300",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: Value = serde_json::from_str(&out).expect("JSON");
    for key in ["exponents", "per_period", "error", "attractor", "structure"] {
        assert!(v.get(key).is_some(), "no `{key}` in {out}");
    }
    assert_eq!(v["attractor"], "periodic");
    assert_eq!(v["structure"], "P_{3_31 0_11 3_13 4_33}");
    assert_eq!(v["exponents"][1], "-inf");
    assert_eq!(v["per_period"][1], "-inf");
    // The largest: ln|λ| / T of the reference eigenvalue -0.5208312097085976
    // (../shared/reference), T = 2π/3.7.
    let want = 0.5208312097085976f64.ln() * 3.7 / (2.0 * std::f64::consts::PI);
    let got = v["exponents"][0].as_f64().expect("number");
    assert!((got - want).abs() < 1e-8, "{got} vs {want}");
    let pp = v["per_period"][0].as_f64().expect("number");
    assert!((pp - 0.5208312097085976f64.ln()).abs() < 1e-8, "{pp}");
    assert!(v["error"].as_f64().is_some_and(|e| e >= 0.0), "{out}");
}

#[test]
fn text_names_the_verdict() {
    let (ok, out, err) = stickslip(&[
        "lyapunov",
        "--model",
        "stribeck8",
        "--set",
        "W=2.38,Q0=3",
        "--transient",
        "200",
        "--periods",
        "2000",
    ]);
    assert!(ok, "{err}");
    assert!(out.contains("attractor: chaotic"), "{out}");
    assert!(out.contains("-inf"), "{out}");
    let (ok, out, err) = stickslip(&["lyapunov", "--set", "W=5,Q0=70", "--periods", "100"]);
    assert!(ok, "{err}");
    assert!(
        out.contains("attractor: periodic P_{3_31 1_12 2_22 1_21 3_13 4_33}, N = 1"),
        "{out}"
    );
}

#[test]
fn bad_input_is_a_clear_error() {
    for (args, message) in [
        (
            vec!["lyapunov", "--set", "Z=1"],
            "`Z` is not a parameter of `paper`",
        ),
        (
            vec!["lyapunov", "--from", "1,2"],
            "`1,2`: expected x,v,W t (3 comma-separated numbers)",
        ),
        (
            vec!["lyapunov", "--from", "1,x,0"],
            "`1,x,0`: `x` is not a number",
        ),
        (vec!["lyapunov", "--from", "1,inf,0"], "`inf` is not finite"),
        (
            vec!["lyapunov", "--periods", "0"],
            "--periods must be at least 1",
        ),
        (vec!["lyapunov", "--model", "nope"], "unknown model `nope`"),
        (vec!["lyapunov", "--set", "W=-1"], "W"),
    ] {
        let (ok, out, err) = stickslip(&args);
        assert!(!ok, "{args:?} succeeded: {out}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// `map` says what it found where the starts do not settle (issue 13 item 4):
/// the chaotic point of tests/lyapunov.rs, with both methods, twice
/// (byte-identical files).
#[test]
fn map_names_chaos_instead_of_unsettled() {
    let dir = std::env::temp_dir().join(format!("lyapunov_cli_map_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut files = Vec::new();
    for (k, method) in ["simulation", "continuation", "simulation"]
        .iter()
        .enumerate()
    {
        let out = dir.join(format!("map{k}.csv"));
        let (ok, stdout, err) = stickslip(&[
            "map",
            "--model",
            "stribeck8",
            "--x",
            "W=2.38:2.38:1",
            "--y",
            "Q0=3:3:1",
            "--method",
            method,
            "--out",
            out.to_str().expect("utf-8 path"),
        ]);
        assert!(ok, "{err}");
        let text = std::fs::read_to_string(&out).expect("map file");
        assert!(
            text.contains("start 1: chaotic (lambda1 = ") && !text.contains("unsettled"),
            "{method}: {text}"
        );
        assert!(
            stdout.contains("chaotic") || err.contains("chaotic"),
            "{stdout}{err}"
        );
        files.push(text);
    }
    assert_eq!(files[0], files[2], "a map is deterministic");
    std::fs::remove_dir_all(&dir).ok();
}

/// A continuation map over a chaotic window: a cell next to a chaotic one
/// has no motion to continue, so it must simulate its own starts and say
/// what it found. The default method used to write `"ok"` with no motions
/// at every such point (a silent wrong answer); every point must now be a
/// motion, NM, or a status that names what the starts did.
#[test]
fn a_continuation_map_of_a_chaotic_window_says_what_every_point_is() {
    let dir = std::env::temp_dir().join(format!("lyapunov_cli_window_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let out = dir.join("window.csv");
    let (ok, _, err) = stickslip(&[
        "map",
        "--model",
        "stribeck8",
        "--x",
        "W=2.34:2.46:4",
        "--y",
        "Q0=2.8:3.2:2",
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(&out).expect("map file");
    let points: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with(['#', 'i']))
        .collect();
    assert_eq!(points.len(), 8, "{text}");
    for line in points {
        assert!(
            !line.ends_with(",\"ok\",\"\""),
            "a point with nothing found: {line}"
        );
        assert!(line.contains("chaotic"), "{line}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
