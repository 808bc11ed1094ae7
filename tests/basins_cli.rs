//! `stickslip basins` and `stickslip orbit-diagram` run as a user runs
//! them: the JSON's keys and its fractions against the file it wrote, and
//! every bad input a clear message naming the argument, status 1, no panic.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {BIN}: {e}"))
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("basins-cli-{name}"));
    let _ = fs::remove_dir_all(&d);
    fs::create_dir_all(&d).unwrap();
    d
}

/// The run fails with status 1, a message containing every one of `needles`, and no panic.
fn fails(args: &[&str], needles: &[&str]) {
    let out = run(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in {err}");
    }
}

fn basins<'a>(out: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut a = vec![
        "basins",
        "--set",
        "W=3.94826,Q0=70",
        "--x",
        "x=0.98:1.02:6",
        "--y",
        "v=1.3:1.4:5",
        "--samples",
        "20",
        "--lyapunov",
        "0",
        "--out",
        out,
    ];
    a.extend_from_slice(extra);
    a
}

#[test]
fn json_agrees_with_the_file() {
    let d = dir("json");
    let out = d.join("b.csv");
    let out = out.to_str().unwrap();
    let o = run(&basins(out, &["--json"]));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let attractors = v["attractors"].as_array().unwrap();
    let text = fs::read_to_string(out).unwrap();
    let lines: Vec<&str> = text.lines().skip(2).collect();
    assert_eq!(lines.len(), 30 + 20);
    let mut sum = 0.0;
    for a in attractors {
        let name = a["name"].as_str().unwrap();
        let on_grid = lines
            .iter()
            .filter(|l| l.contains(&format!(",\"{name}\",")))
            .filter(|l| l.split(',').next().unwrap().parse::<usize>().unwrap() < 30)
            .count();
        assert_eq!(a["points"].as_u64().unwrap() as usize, on_grid);
        assert!((a["fraction"].as_f64().unwrap() - on_grid as f64 / 30.0).abs() < 1e-15);
        sum += a["fraction"].as_f64().unwrap();
        assert_eq!(a["interval"].as_array().unwrap().len(), 2);
    }
    assert!((sum - 1.0).abs() < 1e-12);
}

/// Without `--out` no file is written: the same summary goes to stdout,
/// twice in a row from the same folder, and a plot is drawn from memory;
/// `--resume` then asks for the file.
#[test]
fn without_out_no_file_is_written() {
    let d = dir("memory");
    let args: Vec<&str> = basins("unused", &["--json"])
        .into_iter()
        .filter(|a| *a != "--out" && *a != "unused")
        .collect();
    let plot = d.join("b.svg");
    let mut with_plot = args.clone();
    with_plot.extend(["--plot", plot.to_str().unwrap()]);
    let first = Command::new(BIN)
        .args(&with_plot)
        .current_dir(&d)
        .output()
        .unwrap();
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let second = Command::new(BIN)
        .args(&args)
        .current_dir(&d)
        .output()
        .unwrap();
    assert!(
        second.status.success(),
        "{}",
        String::from_utf8_lossy(&second.stderr)
    );
    let files: Vec<_> = fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(files, vec![std::ffi::OsString::from("b.svg")], "{files:?}");
    let (a, b): (Value, Value) = (
        serde_json::from_slice(&first.stdout).unwrap(),
        serde_json::from_slice(&second.stdout).unwrap(),
    );
    assert_eq!(a["attractors"], b["attractors"]);
    assert_eq!(a["file"], Value::Null);
    let points: u64 = a["attractors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["points"].as_u64().unwrap())
        .sum();
    assert_eq!(points, 30);
    let mut resume = args.clone();
    resume.push("--resume");
    fails(&resume, &["--resume needs", "--out FILE"]);
}

#[test]
fn bad_input_is_a_clear_error() {
    let d = dir("bad");
    let out = d.join("b.csv");
    let out = out.to_str().unwrap();
    let with = |opt: &str, val: &'static str| -> Vec<String> {
        let mut a: Vec<String> = basins(out, &[]).iter().map(|s| s.to_string()).collect();
        let i = a.iter().position(|s| s == opt).unwrap();
        a[i + 1] = val.to_string();
        a
    };
    let fails_with = |args: Vec<String>, needles: &[&str]| {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&a, needles);
    };
    fails_with(with("--x", "x=0:1"), &["x=0:1", "NAME=FROM:TO:COUNT"]);
    fails_with(with("--x", "x=0:1:0"), &["x=0:1:0", "positive integer"]);
    fails_with(with("--y", "v=0:nan:4"), &["not a finite number"]);
    fails_with(with("--x", "W=3:4:5"), &["--x", "must vary `x`"]);
    fails_with(with("--y", "x=0:1:5"), &["--y", "must vary `v`"]);
    fails_with(with("--set", "Wq=3"), &["`Wq` is not a parameter"]);
    fails(
        &[
            "basins", "--model", "nope", "--x", "x=0:1:2", "--y", "v=0:1:2",
        ],
        &["unknown model `nope`"],
    );
    fails_with(with("--set", "W=-1"), &["W"]);

    // A resume of a file written with other settings.
    let ok = run(&basins(out, &[]));
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    fails(&basins(out, &[]), &["already exists", "--resume"]);
    let mut other = basins(out, &["--resume"]);
    let i = other.iter().position(|s| *s == "--samples").unwrap();
    other[i + 1] = "21";
    fails(&other, &["different basin run", "samples=21"]);
    let mut other = basins(out, &["--resume"]);
    let i = other.iter().position(|s| *s == "--set").unwrap();
    other[i + 1] = "W=3.9483,Q0=70";
    fails(&other, &["different basin run", "W=3.9483"]);
    fs::write(out, "hello\n").unwrap();
    fails(&basins(out, &["--resume"]), &["not a stickslip basin file"]);
    fails(
        &basins(out, &["--plot", "b.txt"]),
        &["unknown figure format"],
    );
}

#[test]
fn orbit_diagram_bad_input_is_a_clear_error() {
    let base = [
        "orbit-diagram",
        "--set",
        "Q0=70",
        "--lyapunov",
        "0",
        "--no-branches",
    ];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        base.iter().copied().chain(extra.iter().copied()).collect()
    };
    fails(
        &with(&["--param", "W=3:4"]),
        &["W=3:4", "NAME=from:to:count"],
    );
    fails(&with(&["--param", "W=3:4:0"]), &["point count"]);
    fails(
        &with(&["--param", "Wx=3:4:3"]),
        &["`Wx` is not a parameter"],
    );
    fails(&with(&["--param", "W=3:inf:3"]), &["finite"]);
    fails(
        &with(&["--param", "W=3:4:3", "--periods", "0"]),
        &["--periods"],
    );
}
