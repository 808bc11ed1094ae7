//! `stickslip curves` run as a user runs it: the JSON's shape and keys
//! (ends and codim-2 points keyed by the parameters' names), the text
//! blocks, two runs giving identical JSON, and every bad input a clear
//! message naming the argument, a non-zero status, no panic.

use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");

/// A small box around the stick motions at W ≈ 3.7, Q0 ≈ 70, a short grid.
const SMALL: [&str; 12] = [
    "curves", "--model", "paper", "--x", "W=3:4.5", "--y", "Q0=60:80", "--count", "24", "--spread",
    "1", "--json",
];

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {BIN}: {e}"))
}

fn text(b: &[u8]) -> String {
    String::from_utf8(b.to_vec()).expect("UTF-8")
}

fn keys(v: &Value) -> Vec<&str> {
    v.as_object()
        .unwrap_or_else(|| panic!("{v} is not an object"))
        .keys()
        .map(String::as_str)
        .collect()
}

fn with(extra: &[&str]) -> Vec<String> {
    SMALL.iter().chain(extra).map(|s| s.to_string()).collect()
}

#[test]
fn json_has_the_documented_shape_and_is_deterministic() {
    let args = with(&["--at", "Q0=67,73", "--seed", "Q0=70"]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let first = run(&args);
    assert!(first.status.success(), "{}", text(&first.stderr));
    let v: Value = serde_json::from_slice(&first.stdout).expect("JSON");
    assert_eq!(keys(&v), ["x", "y", "curves", "codim2", "failed_starts"]);
    assert_eq!(v["x"], "W");
    assert_eq!(v["y"], "Q0");
    let curves = v["curves"].as_array().expect("curves");
    assert!(!curves.is_empty(), "no curve in the small box: {v}");
    for c in curves {
        assert_eq!(
            keys(c),
            [
                "kind",
                "boundary",
                "structure",
                "from",
                "to",
                "points",
                "at"
            ]
        );
        assert!(c["kind"].is_string());
        assert!(
            c["structure"].as_str().expect("structure").starts_with('P') || c["structure"] == "NM"
        );
        for p in c["points"].as_array().expect("points") {
            let p = p.as_array().expect("[x, y]");
            assert_eq!(p.len(), 2);
            let (w, q) = (p[0].as_f64().expect("W"), p[1].as_f64().expect("Q0"));
            assert!(
                (3.0 - 1e-9..=4.5 + 1e-9).contains(&w),
                "W = {w} outside the box"
            );
            assert!(
                (60.0 - 1e-9..=80.0 + 1e-9).contains(&q),
                "Q0 = {q} outside the box"
            );
        }
        for a in c["at"].as_array().expect("at") {
            let q = a[1].as_f64().expect("Q0");
            assert!(q == 67.0 || q == 73.0, "a crossing off the --at lines: {a}");
        }
        for end in [&c["from"], &c["to"]] {
            if end.is_null() {
                continue;
            }
            let k = keys(end);
            assert_eq!(&k[..3], ["end", "W", "Q0"], "{end}");
            let reason = end["end"].as_str().expect("end");
            assert!(
                ["box_edge", "codim2", "newton_failure", "max_points"].contains(&reason),
                "{reason}"
            );
            assert_eq!(end.get("codim2").is_some(), reason == "codim2", "{end}");
            assert_eq!(
                end.get("detail").is_some(),
                reason == "newton_failure",
                "{end}"
            );
        }
    }
    for q in v["codim2"].as_array().expect("codim2") {
        assert_eq!(keys(q), ["W", "Q0", "kinds", "curves"]);
    }
    for f in v["failed_starts"].as_array().expect("failed_starts") {
        assert_eq!(
            keys(f),
            ["kind", "boundary", "structure", "W", "Q0", "why"],
            "{f}"
        );
    }
    let second = run(&args);
    assert_eq!(text(&first.stdout), text(&second.stdout), "two runs differ");
}

#[test]
fn text_has_a_block_per_curve() {
    let args = with(&[]);
    let args: Vec<&str> = args
        .iter()
        .map(String::as_str)
        .filter(|a| *a != "--json")
        .collect();
    let o = run(&args);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    assert!(
        out.starts_with("Transition curves in W = 3..4.5, Q0 = 60..80"),
        "{out}"
    );
    assert!(out.contains("\ncurve 0: "), "{out}");
    assert!(
        out.contains("  from: ") && out.contains("  points: "),
        "{out}"
    );
}

/// Each bad input: status 1, `error:` naming the argument, no panic.
#[test]
fn bad_input_is_a_clear_error() {
    let cases: [(&[&str], &str); 13] = [
        (
            &["--x", "Foo=0:1", "--y", "Q0=0:180"],
            "`Foo` is not a free parameter",
        ),
        (
            &["--x", "W=0.2:8", "--y", "Bar=0:1"],
            "`Bar` is not a free parameter",
        ),
        (&["--x", "W=0.2:8", "--y", "W=1:2"], "both name `W`"),
        (&["--x", "W=3:3", "--y", "Q0=0:180"], "bad range of `W`"),
        (&["--x", "W=8:0.2", "--y", "Q0=0:180"], "bad range of `W`"),
        (
            &["--x", "W=0.2:8", "--y", "Q0=NaN:180"],
            "bad range of `Q0`",
        ),
        (&["--x", "W=0.2:8", "--y", "Q0=0:inf"], "bad range of `Q0`"),
        (&["--x", "W0.2:8", "--y", "Q0=0:180"], "--x `W0.2:8`"),
        (
            &["--x", "W=0.2:8", "--y", "Q0=0:180", "--seed", "Q0=500"],
            "--seed Q0=500",
        ),
        (
            &["--x", "W=0.2:8", "--y", "Q0=0:180", "--seed", "d=0.1"],
            "`d` is neither",
        ),
        (
            &["--x", "W=0.2:8", "--y", "Q0=0:180", "--at", "W=1,nine"],
            "--at `W=1,nine`",
        ),
        (
            &["--x", "W=0.2:8", "--y", "Q0=0:180", "--at", "W=9"],
            "--at W=9",
        ),
        (
            &["--x", "W=0.2:8", "--y", "Q0=0:180", "--max-mappings", "0"],
            "must have at least 1 mapping, not 0",
        ),
    ];
    for (args, message) in cases {
        let mut all = vec!["curves", "--model", "paper"];
        all.extend_from_slice(args);
        let o = run(&all);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{all:?}: {err}");
        assert!(err.starts_with("error: "), "{all:?}: {err}");
        assert!(err.contains(message), "{all:?}: `{err}` lacks `{message}`");
        assert!(!err.contains("panicked"), "{all:?}: {err}");
    }
}

#[test]
fn a_bad_plot_path_fails_before_any_work() {
    let o = run(&[
        "curves", "--x", "W=0.2:8", "--y", "Q0=0:180", "--plot", "map.txt",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(text(&o.stderr).contains("unknown figure format"));
}

/// `map --curves` draws curves over the map's figure, so it needs `--plot`:
/// without it clap refuses before any work, naming the missing argument.
#[test]
fn map_curves_needs_a_plot() {
    let dir = std::env::temp_dir().join(format!("stickslip-map-curves-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let out = dir.join("m.csv");
    let o = run(&[
        "map",
        "--model",
        "paper",
        "--x",
        "W=3.8:4.4:3",
        "--y",
        "Q0=65:75:2",
        "--out",
        out.to_str().unwrap(),
        "--curves",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o.stderr));
    assert!(text(&o.stderr).contains("--plot"), "{}", text(&o.stderr));
    assert!(!out.exists(), "nothing computed");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--max-mappings M` traces the curves of the motions of at most M
/// mappings: below the default it leaves out the longer motions' curves
/// and keeps the others.
#[test]
fn max_mappings_limits_the_motions_traced() {
    let structures = |v: &Value| -> Vec<String> {
        v["curves"]
            .as_array()
            .expect("curves")
            .iter()
            .filter_map(|c| c["structure"].as_str().map(str::to_string))
            .collect()
    };
    let mappings = |s: &str| s.split_whitespace().count();
    let all = run(&SMALL);
    assert!(all.status.success(), "{}", text(&all.stderr));
    let all: Value = serde_json::from_slice(&all.stdout).expect("JSON");
    let few = run(&with(&["--max-mappings", "4"])
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>());
    assert!(few.status.success(), "{}", text(&few.stderr));
    let few: Value = serde_json::from_slice(&few.stdout).expect("JSON");
    let (all, few) = (structures(&all), structures(&few));
    assert!(all.iter().any(|s| mappings(s) > 4), "{all:?}");
    assert!(few.iter().all(|s| mappings(s) <= 4), "{few:?}");
    let short = |v: &[String]| v.iter().filter(|s| mappings(s) <= 4).count();
    assert!(
        short(&few) > 0 && short(&few) >= short(&all),
        "{few:?} against {all:?}"
    );
}

/// `--probes K` sweeps across the lines' curves: every curve of the run
/// without probes is traced again (same kind, motion and ends), and the
/// probes add curves of bands no line crosses.
#[test]
fn probes_keep_the_lines_curves_and_add_more() {
    // Without the edges' sweeps, which on this box find every band the
    // probes find (19 curves either way).
    let args = [
        "curves",
        "--model",
        "paper",
        "--x",
        "W=3:4",
        "--y",
        "Q0=65:75",
        "--count",
        "10",
        "--spread",
        "0",
        "--no-edges",
        "--json",
    ];
    // The ends by place and reason (a codim-2 end's index into the list
    // changes as points are added).
    let key = |c: &Value| {
        let end = |e: &Value| format!("{} {} {}", e["end"], e["W"], e["Q0"]);
        format!(
            "{} {} {} {} {}",
            c["kind"],
            c["structure"],
            c["boundary"],
            end(&c["from"]),
            end(&c["to"])
        )
    };
    let curves = |o: &Output| -> Vec<String> {
        assert!(o.status.success(), "{}", text(&o.stderr));
        let v: Value = serde_json::from_slice(&o.stdout).expect("JSON");
        v["curves"]
            .as_array()
            .expect("curves")
            .iter()
            .map(key)
            .collect()
    };
    let plain = curves(&run(&args));
    let mut probed_args = args.to_vec();
    probed_args.extend(["--probes", "2"]);
    let probed = curves(&run(&probed_args));
    for c in &plain {
        assert!(probed.contains(c), "{c} is lost with probes");
    }
    assert!(
        probed.len() > plain.len(),
        "{} curves either way",
        plain.len()
    );
}

/// A scene's free parameters are the plane's axes (its parameter set holds
/// them alone, indexed by their place among them; until stop 22 `curves`
/// took those places for the model's and refused `W` of every scene). Its
/// curves are the model's
/// curves of the same motions: each scene curve has a curve of the full
/// model with the same kind, boundary and structure whose ends agree to
/// 1e-8. A fixed parameter of the scene is no axis.
#[test]
fn a_scene_traces_the_curves_of_its_motions() {
    let box_of = |model: &str| {
        let o = run(&[
            "curves", "--model", model, "--x", "W=3:4", "--y", "Q0=65:75", "--count", "10",
            "--spread", "0", "--json",
        ]);
        assert!(o.status.success(), "{model}: {}", text(&o.stderr));
        serde_json::from_slice::<Value>(&o.stdout).expect("JSON")
    };
    let (scene, full) = (box_of("paper::reference"), box_of("paper"));
    let curves = |v: &Value| v["curves"].as_array().expect("curves").clone();
    let (scene, full) = (curves(&scene), curves(&full));
    assert!(!scene.is_empty(), "no curve");
    let ends = |c: &Value| -> Vec<(f64, f64)> {
        let mut e: Vec<(f64, f64)> = ["from", "to"]
            .iter()
            .filter(|k| !c[**k].is_null())
            .map(|k| (c[*k]["W"].as_f64().unwrap(), c[*k]["Q0"].as_f64().unwrap()))
            .collect();
        e.sort_by(|a, b| a.0.total_cmp(&b.0));
        e
    };
    for c in &scene {
        let same = full.iter().any(|f| {
            f["kind"] == c["kind"]
                && f["boundary"] == c["boundary"]
                && f["structure"] == c["structure"]
                && ends(f).len() == ends(c).len()
                && ends(f)
                    .iter()
                    .zip(ends(c))
                    .all(|(a, b)| (a.0 - b.0).abs() <= 1e-8 && (a.1 - b.1).abs() <= 1e-8)
        });
        assert!(same, "the scene's {c} is no curve of the model");
    }
    let o = run(&[
        "curves",
        "--model",
        "paper::reference",
        "--x",
        "d=0.1:0.2",
        "--y",
        "Q0=65:75",
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("`d` is not a free parameter of paper::reference; free: Q0, W"),
        "{err}"
    );
}
