//! The `orbit` and `simulate` commands, run as a user runs them: the JSON
//! schema and the reference motion at W = 3.7, Q0 = 70 (switching points
//! within 1e-9, eigenvalues within 1e-8), NM at W = 1, the figure's six
//! panels, the CSV, and bad input (a clear message, a non-zero status, no
//! panic).

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");
const STICK: &str = "P_{3_31 0_11 3_13 4_33}";

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {BIN}: {e}"))
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("UTF-8 stdout")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("UTF-8 stderr")
}

/// Run, expect success, parse stdout as JSON.
fn json(args: &[&str]) -> Value {
    let o = run(args);
    assert!(
        o.status.success(),
        "{args:?} failed: {}\n{}",
        stderr(&o),
        stdout(&o)
    );
    serde_json::from_str(&stdout(&o)).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e})"))
}

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// The reference stick motion at W = 3.7, Q0 = 70.
fn reference() -> Value {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference/orbits.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let v: Value = serde_json::from_str(&text).expect("valid JSON");
    v["orbits"]
        .as_array()
        .expect("orbits")
        .iter()
        .find(|o| o["structure"] == STICK)
        .expect("the W = 3.7 reference motion")
        .clone()
}

fn keys(v: &Value) -> Vec<&str> {
    v.as_object()
        .expect("an object")
        .keys()
        .map(String::as_str)
        .collect()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

/// The report is exactly the documented periodic motion and matches the reference.
fn assert_reference_motion(report: &Value, how: &str) {
    let r = reference();
    assert_eq!(
        keys(report),
        [
            "kind",
            "structure",
            "N",
            "params",
            "points",
            "eigenvalues",
            "stable",
            "admissible",
            "violations",
            "newton"
        ],
        "{how}"
    );
    assert_eq!(report["kind"], "periodic", "{how}");
    assert_eq!(report["structure"], STICK, "{how}");
    assert_eq!(report["N"], 1, "{how}");
    assert_eq!(report["stable"], true, "{how}");
    assert_eq!(report["admissible"], true, "{how}");
    assert_eq!(report["violations"].as_array().map(Vec::len), Some(0));
    let params = &report["params"];
    assert_eq!(
        keys(params),
        [
            "m", "d", "c", "V", "V1", "V2", "mus", "muk", "mu1", "mu2", "mu3", "mu4", "g", "Q0",
            "W"
        ]
    );
    assert_eq!(f(&params["W"]), 3.7);
    assert_eq!(f(&params["Q0"]), 70.0);
    assert_eq!(f(&params["m"]), 5.0);
    assert_eq!(keys(&report["newton"]), ["iterations", "residual"]);
    assert!(f(&report["newton"]["residual"]) <= 1e-9, "{how}");

    let points = report["points"].as_array().expect("points");
    let want = r["switching_points"].as_array().expect("reference points");
    assert_eq!(points.len(), want.len(), "{how}");
    for (k, (p, w)) in points.iter().zip(want).enumerate() {
        assert_eq!(
            keys(p),
            ["k", "Wt", "Wt_mod_2pi", "x", "v", "boundary", "mapping"],
            "{how}"
        );
        assert_eq!(p["k"], k);
        for (key, wkey) in [
            ("Wt", "Wt"),
            ("Wt_mod_2pi", "Wt_mod_2pi"),
            ("x", "x"),
            ("v", "v"),
        ] {
            let (a, b) = (f(&p[key]), f(&w[wkey]));
            assert!(
                (a - b).abs() < 1e-9,
                "{how}: point {k} {key} = {a}, reference {b}"
            );
        }
        assert_eq!(p["boundary"], w["boundary"], "{how}: point {k}");
        assert_eq!(p["mapping"], w["starts_mapping"], "{how}: point {k}");
    }

    let ev = report["eigenvalues"].as_array().expect("eigenvalues");
    assert_eq!(ev.len(), 2);
    for w in r["eigenvalues"].as_array().expect("reference eigenvalues") {
        let (re, im) = (f(&w[0]), f(&w[1]));
        assert!(
            ev.iter()
                .any(|e| (f(&e[0]) - re).abs() < 1e-8 && (f(&e[1]) - im).abs() < 1e-8),
            "{how}: eigenvalue ({re}, {im}) not in {ev:?}"
        );
    }
}

#[test]
fn orbit_json_reproduces_the_reference_motion() {
    let report = json(&[
        "orbit",
        "--model",
        "paper",
        "--structure",
        STICK,
        "--set",
        "W=3.7,Q0=70",
        "--json",
    ]);
    assert_reference_motion(&report, "orbit (seeded by simulation)");
}

#[test]
fn orbit_from_a_perturbed_guess_reproduces_the_reference_motion() {
    let r = reference();
    let p0 = &r["switching_points"][0];
    let guess = format!("{},{}", f(&p0["Wt"]) + 1e-2, f(&p0["x"]) - 1e-2);
    let o = run(&[
        "orbit",
        "--structure",
        STICK,
        "--set",
        "W=3.7,Q0=70",
        "--guess",
        &guess,
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The guess is followed through the structure: no fallback note.
    assert!(
        !stderr(&o).contains("seeding by simulation"),
        "{}",
        stderr(&o)
    );
    let report: Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert_reference_motion(&report, "orbit --guess");
}

#[test]
fn orbit_falls_back_to_simulation_when_the_guess_does_not_follow_the_structure() {
    // From (W t, x) = (1, 2) on Sigma3 the flow of 4_33 does not go on as the structure says.
    let o = run(&[
        "orbit",
        "--structure",
        STICK,
        "--set",
        "W=3.7,Q0=70",
        "--guess",
        "1,2",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("seeding by simulation instead"),
        "{}",
        stderr(&o)
    );
    let report: Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert_reference_motion(&report, "orbit --guess (fallback)");
}

#[test]
fn simulate_json_from_rest_finds_the_reference_motion() {
    let report = json(&[
        "simulate",
        "--model",
        "paper",
        "--set",
        "W=3.7,Q0=70",
        "--json",
    ]);
    assert_reference_motion(&report, "simulate");
    // And from another start, with a period limit.
    let report = json(&[
        "simulate",
        "--set",
        "W=3.7,Q0=70",
        "--from",
        "-0.5,2,1",
        "--periods",
        "500",
        "--json",
    ]);
    assert_reference_motion(&report, "simulate --from");
}

#[test]
fn simulate_certifies_no_motion_at_w_1() {
    let report = json(&["simulate", "--set", "W=1,Q0=70", "--json"]);
    assert_eq!(keys(&report), ["kind", "max_v"]);
    assert_eq!(report["kind"], "NM");
    assert!((f(&report["max_v"]) - 0.483).abs() < 1e-3, "{report}");
}

#[test]
fn text_output_has_the_table_the_eigenvalues_and_the_classification() {
    let o = run(&["orbit", "--structure", STICK, "--set", "W=3.7,Q0=70"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    for want in [
        "periodic motion: P_{3_31 0_11 3_13 4_33}",
        "W t mod 2π",
        "4_33     Sigma3",
        "0_11     Sigma1",
        "|λ1| = 0.520831209709",
        "stability: stable",
        "admissible: yes",
    ] {
        assert!(text.contains(want), "missing `{want}` in\n{text}");
    }
}

#[test]
fn plot_writes_an_svg_with_the_six_panels() {
    let path = tmp("orbit.svg");
    let o = run(&[
        "orbit",
        "--structure",
        STICK,
        "--set",
        "W=3.7,Q0=70",
        "--json",
        "--plot",
        path.to_str().expect("UTF-8 path"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // stdout stays pure JSON.
    let _: Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    let svg = std::fs::read_to_string(&path).expect("the SVG is written");
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(100)]);
    assert!(svg.trim_end().ends_with("</svg>"));
    for title in stickslip::output::figure::orbit::PANEL_TITLES {
        let escaped = title.replace('\'', "&apos;");
        assert_eq!(
            svg.matches(escaped.as_str()).count(),
            1,
            "panel `{title}` should appear once"
        );
    }
    assert!(
        svg.contains(STICK),
        "the figure's title names the structure"
    );
    // The boundaries the motion touches are labelled; the stick is drawn in black.
    assert!(svg.contains("Σ1") && svg.contains("Σ3"));
    assert!(svg.contains("#000000"));
}

#[test]
fn plot_writes_a_png_and_simulate_plots_nm() {
    let path = tmp("nm.png");
    let o = run(&[
        "simulate",
        "--set",
        "W=1,Q0=70",
        "--plot",
        path.to_str().expect("UTF-8 path"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let png = std::fs::read(&path).expect("the PNG is written");
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
}

#[test]
fn csv_writes_one_period_with_every_switching_point() {
    let path = tmp("orbit.csv");
    let o = run(&[
        "simulate",
        "--set",
        "W=3.7,Q0=70",
        "--csv",
        path.to_str().expect("UTF-8 path"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(&path).expect("the CSV is written");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("t,Wt,x,v,a,domain,F"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            let cells: Vec<f64> = l
                .split(',')
                .map(|c| c.parse().unwrap_or_else(|_| panic!("`{c}` in `{l}`")))
                .collect();
            assert_eq!(cells.len(), 7, "{l}");
            cells
        })
        .collect();
    assert!(rows.len() >= 400, "{} rows", rows.len());
    let r = reference();
    let w = 3.7;
    let first = &rows[0];
    let p0 = &r["switching_points"][0];
    assert!((first[1] - f(&p0["Wt"])).abs() < 1e-9);
    assert!((first[0] - first[1] / w).abs() < 1e-12);
    assert!((first[2] - f(&p0["x"])).abs() < 1e-9);
    // One forcing period, in time order.
    let last = rows.last().expect("rows");
    assert!((last[1] - first[1] - 2.0 * std::f64::consts::PI).abs() < 1e-9);
    assert!(rows.windows(2).all(|p| p[1][1] >= p[0][1]));
    // Every switching point is a sample; the stick (domain 0) has v = 3, a = 0, |F| <= as.
    for p in r["switching_points"].as_array().expect("points") {
        assert!(
            rows.iter().any(
                |row| (row[1] - f(&p["Wt"])).abs() < 1e-9 && (row[2] - f(&p["x"])).abs() < 1e-9
            ),
            "switching point {p} is not a row"
        );
    }
    let domains: Vec<f64> = rows.iter().map(|r| r[5]).collect();
    for d in [0.0, 3.0, 4.0] {
        assert!(domains.contains(&d), "domain {d} missing");
    }
    for row in rows.iter().filter(|r| r[5] == 0.0) {
        assert_eq!(row[3], 3.0);
        assert_eq!(row[4], 0.0);
        assert!(row[6].abs() <= 4.9 + 1e-9, "Fnf {} beyond as", row[6]);
    }
    // In a domain, F is the kinetic law: domain 4 at v gives (0.5 (v - 1.5) + 0.15 - 19.6) / 5.
    for row in rows.iter().filter(|r| r[5] == 4.0) {
        let law = (0.5 * (row[3] - 1.5) + 0.15 - 19.6) / 5.0;
        assert!((row[6] - law).abs() < 1e-9, "F {} vs law {law}", row[6]);
    }
}

/// Bad input: non-zero status, one clear `error:` line, nothing on stdout, no panic.
fn assert_rejected(args: &[&str], message: &str) {
    let o = run(args);
    let err = stderr(&o);
    assert!(!o.status.success(), "{args:?} succeeded");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    assert!(
        err.contains(message),
        "{args:?}: expected `{message}` in stderr:\n{err}"
    );
    assert!(
        stdout(&o).trim().is_empty(),
        "{args:?} printed {}",
        stdout(&o)
    );
}

#[test]
fn bad_input_is_rejected_with_a_clear_message() {
    assert_rejected(
        &["orbit", "--structure", STICK, "--set", "W=nan,Q0=70"],
        "error: parameter `W` is NaN: it must be a finite number",
    );
    assert_rejected(
        &["simulate", "--set", "W=nan"],
        "error: parameter `W` is NaN",
    );
    assert_rejected(
        &["orbit", "--structure", "P_{3_31 9_99}", "--set", "W=3.7"],
        "`9_99` is not a mapping of model `paper`",
    );
    assert_rejected(
        &[
            "orbit",
            "--structure",
            "P_{1_22 3_13 4_33}",
            "--set",
            "W=3.7",
        ],
        "3_13 ends on Sigma1, but 1_22 starts on Sigma2",
    );
    assert_rejected(
        &["orbit", "--model", "nope", "--structure", STICK],
        "error: unknown model `nope`; compiled-in: coulomb, paper",
    );
    assert_rejected(
        &["simulate", "--model", "nope"],
        "error: unknown model `nope`",
    );
    assert_rejected(
        &["orbit", "--structure", STICK, "--set", "Z=1"],
        "`Z` is not a parameter of `paper`",
    );
    assert_rejected(
        &["orbit", "--structure", STICK, "--guess", "a,b"],
        "`a` is not a number",
    );
    assert_rejected(
        &["simulate", "--from", "1,2"],
        "expected x,v,W t (3 comma-separated numbers)",
    );
    assert_rejected(
        &["orbit", "--structure", STICK, "--plot", "figure.jpg"],
        "unknown figure format; use a file name ending in .svg or .png",
    );
    assert_rejected(
        &["simulate", "--set", "W=3.7", "--periods", "5"],
        "no periodic motion and no certified NM within 5 forcing periods",
    );
    // A parameter the model does not have: the free ones are listed.
    assert_rejected(
        &["sweep", "--param", "omega=1:2:3"],
        "`omega` is not a parameter of `paper` (its parameters: m, d, c, V, V1, V2, mus, muk, mu1, mu2, mu3, mu4, g, Q0, W)",
    );
    // One a scene fixes: say how to free it.
    assert_rejected(
        &["sweep", "--model", "stribeck::pl16", "--param", "W=1:2:3", "--set", "vs=0.3"],
        "`vs` is fixed to 0.4 in `stribeck::pl16` (free: Q0, W); to vary it, add `vs` to the scene's `free:` list in the model file",
    );
    assert_rejected(
        &["sweep", "--model", "paper::sweep_w", "--param", "Q0=1:2:3"],
        "`Q0` is fixed to 70 in `paper::sweep_w` (free: W)",
    );
}

/// A `--set` of the parameter a command varies would be overwritten
/// silently: every command that varies one refuses it.
#[test]
fn a_set_of_the_varied_parameter_is_refused() {
    let out = tmp("set-varied.csv");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (
            &["sweep", "--param", "W=1:2:3", "--set", "W=5"],
            "`--set W=...`: `W` is varied by --param",
        ),
        (
            &["orbit-diagram", "--param", "W=1:2:3", "--set", "Q0=70,W=5"],
            "`W` is varied by --param",
        ),
        (
            &[
                "map", "--x", "W=1:2:3", "--y", "Q0=1:3:3", "--set", "Q0=5", "--out", out,
            ],
            "`Q0` is varied by --y",
        ),
        (
            &["curves", "--x", "W=1:2", "--y", "Q0=1:3", "--set", "W=5"],
            "`W` is varied by --x",
        ),
        (
            &[
                "curves",
                "--x",
                "W=1:2",
                "--y",
                "Q0=1:3",
                "--set",
                "d=0.1,Q0=5",
            ],
            "`Q0` is varied by --y",
        ),
    ];
    for (args, message) in cases {
        assert_rejected(args, message);
    }
    assert!(!std::path::Path::new(out).exists(), "map wrote {out}");
}

#[test]
fn an_inadmissible_solution_is_not_reported_as_a_motion() {
    // At W = 3.7 the motion sticks: Newton on P_{3_33 4_33} converges to a
    // solution whose flows cross their boundaries early.
    let o = run(&[
        "orbit",
        "--structure",
        "P_{3_33 4_33}",
        "--set",
        "W=3.7,Q0=70",
        "--json",
    ]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "{err}");
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].contains("the Newton solution of P_{3_33 4_33} is not a motion"),
        "{err}"
    );
    let report: Value = serde_json::from_str(&stdout(&o)).expect("JSON");
    assert_eq!(report["kind"], "inadmissible");
    assert_eq!(report["admissible"], false);
    let violations = report["violations"].as_array().expect("violations");
    assert!(!violations.is_empty());
    for v in violations {
        assert_eq!(keys(v), ["segment", "condition", "margin"]);
    }
    // No figure or CSV of a non-motion.
    let path = tmp("inadmissible.svg");
    let o = run(&[
        "orbit",
        "--structure",
        "P_{3_33 4_33}",
        "--set",
        "W=3.7,Q0=70",
        "--plot",
        path.to_str().expect("UTF-8 path"),
    ]);
    assert!(!o.status.success());
    assert!(stdout(&o).contains("NOT A MOTION"));
    assert!(!path.exists());
}
