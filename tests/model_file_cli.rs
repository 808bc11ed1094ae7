//! `--model-file PATH [--scene S]`, run as a user runs it: every analysis
//! on a model file loaded at run time gives what it gives on the same model
//! compiled in (the main job's structures and transitions to 1e-10, the
//! other subcommands' JSON likewise); a rejected file fails with
//! `stickslip check`'s report; a map records the file's content hash and
//! refuses to resume or merge with another file's.

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

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("UTF-8 stdout")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("UTF-8 stderr")
}

fn ok(args: &[&str]) -> String {
    let o = run(args);
    assert!(o.status.success(), "{args:?} failed: {}", stderr(&o));
    stdout(&o)
}

fn json(args: &[&str]) -> Value {
    let out = ok(args);
    serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}):\n{out}"))
}

fn paper_file() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models/paper.ssm")
        .display()
        .to_string()
}

/// `name` in this test's own temporary folder (`test`: tests run at once).
fn tmp_in(test: &str, name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("model_file_cli")
        .join(test);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// `a` and `b` agree: the same keys and strings, numbers within `rel`
/// relative (of the larger); keys in `skip` (wall times) are not compared.
fn agree(a: &Value, b: &Value, rel: f64, skip: &[&str], at: &str) {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let (kx, ky): (Vec<_>, Vec<_>) = (x.keys().collect(), y.keys().collect());
            assert_eq!(kx, ky, "{at}: keys");
            for (k, v) in x {
                if !skip.contains(&k.as_str()) {
                    agree(v, &y[k], rel, skip, &format!("{at}.{k}"));
                }
            }
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: lengths");
            for (i, (u, v)) in x.iter().zip(y).enumerate() {
                agree(u, v, rel, skip, &format!("{at}[{i}]"));
            }
        }
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().expect("f64"), y.as_f64().expect("f64"));
            assert!(
                x == y || (x - y).abs() <= rel * x.abs().max(y.abs()),
                "{at}: {x:e} against {y:e}"
            );
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

#[test]
fn the_main_job_with_a_model_file_gives_the_same_structures_and_transitions() {
    let file = paper_file();
    let sweep = [
        "sweep",
        "--param",
        "W=0.2:9:200",
        "--set",
        "Q0=70",
        "--json",
    ];
    let compiled = json(&[&sweep[..], &["--model", "paper"]].concat());
    let loaded = json(&[&sweep[..], &["--model-file", &file]].concat());
    // The test can fail: the sweep found transitions and motions.
    assert!(compiled["transitions"]
        .as_array()
        .is_some_and(|t| t.len() > 5));
    agree(&compiled, &loaded, 1e-10, &[], "sweep");
}

#[test]
fn every_analysis_runs_on_a_model_file_as_on_the_compiled_model() {
    let file = paper_file();
    let dir = tmp_in("all", "maps");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    let out = |name: &str| dir.join(name).display().to_string();
    let (map_a, map_b) = (out("a.csv"), out("b.csv"));
    let (basins_a, basins_b) = (out("a.basins"), out("b.basins"));
    let cases: Vec<(Vec<String>, Vec<String>, &[&str])> = vec![
        (vec!["describe".into(), "--json".into()], vec![], &[]),
        (
            vec![
                "simulate".into(),
                "--set".into(),
                "W=3.7,Q0=70".into(),
                "--json".into(),
            ],
            vec![],
            &[],
        ),
        (
            vec![
                "orbit".into(),
                "--structure".into(),
                "P_{3_31 0_11 3_13 4_33}".into(),
                "--set".into(),
                "W=3.7,Q0=70".into(),
                "--json".into(),
            ],
            vec![],
            &[],
        ),
        (
            vec![
                "lyapunov".into(),
                "--set".into(),
                "W=5,Q0=70".into(),
                "--transient".into(),
                "50".into(),
                "--periods".into(),
                "100".into(),
                "--json".into(),
            ],
            vec![],
            &[],
        ),
        (
            vec![
                "orbit-diagram".into(),
                "--param".into(),
                "W=3.6:3.8:3".into(),
                "--set".into(),
                "Q0=70".into(),
                "--transient".into(),
                "30".into(),
                "--periods".into(),
                "10".into(),
                "--lyapunov".into(),
                "0".into(),
                "--json".into(),
            ],
            vec![],
            &[],
        ),
        (
            vec![
                "curves".into(),
                "--x".into(),
                "W=3.5:4".into(),
                "--y".into(),
                "Q0=65:75".into(),
                "--count".into(),
                "8".into(),
                "--spread".into(),
                "0".into(),
                "--no-edges".into(),
                "--json".into(),
            ],
            vec![],
            &[],
        ),
        (
            vec![
                "map".into(),
                "--x".into(),
                "W=3:4:3".into(),
                "--y".into(),
                "Q0=60:70:2".into(),
                "--out".into(),
            ],
            vec![map_a.clone(), map_b.clone()],
            &[],
        ),
        (
            vec![
                "basins".into(),
                "--set".into(),
                "W=3.94826,Q0=70".into(),
                "--x".into(),
                "x=0.98:1.02:3".into(),
                "--y".into(),
                "v=1.3:1.4:2".into(),
                "--samples".into(),
                "4".into(),
                "--lyapunov".into(),
                "0".into(),
                "--json".into(),
                "--out".into(),
            ],
            vec![basins_a.clone(), basins_b.clone()],
            &["seconds", "file"],
        ),
    ];
    for (args, outs, skip) in cases {
        let with = |model: &[&str], out: Option<&String>| -> Vec<String> {
            let mut v = args.clone();
            if let Some(o) = out {
                v.push(o.clone());
            }
            v.extend(model.iter().map(|s| s.to_string()));
            v
        };
        let a = with(&["--model", "paper"], outs.first());
        let b = with(&["--model-file", &file], outs.get(1));
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        let b: Vec<&str> = b.iter().map(String::as_str).collect();
        let (ta, tb) = (ok(&a), ok(&b));
        match (
            serde_json::from_str::<Value>(&ta),
            serde_json::from_str::<Value>(&tb),
        ) {
            (Ok(x), Ok(y)) => agree(&x, &y, 1e-10, skip, &args[0]),
            _ => {
                // A map prints a summary naming its file: compare the files.
                let read = |p: &str| std::fs::read_to_string(p).expect("map file");
                let (fa, fb) = (read(&outs[0]), read(&outs[1]));
                let body = |s: &str| s.lines().skip(1).map(str::to_string).collect::<Vec<_>>();
                assert_eq!(body(&fa), body(&fb), "{}: the points", args[0]);
                assert!(
                    fb.lines().next().is_some_and(|h| h.contains(" source=")),
                    "{fb}"
                );
                assert!(
                    !fa.lines().next().is_some_and(|h| h.contains(" source=")),
                    "{fa}"
                );
            }
        }
    }
}

#[test]
fn a_scene_of_a_model_file_is_the_compiled_scene() {
    let file = paper_file();
    let a = json(&["describe", "--model", "paper::sweep_w", "--json"]);
    let b = json(&[
        "describe",
        "--model-file",
        &file,
        "--scene",
        "sweep_w",
        "--json",
    ]);
    agree(&a, &b, 0.0, &[], "describe");
    let o = run(&["describe", "--model-file", &file, "--scene", "nope"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("has no scene `nope`"), "{err}");
    // `--scene` without `--model-file` is refused by the parser.
    let o = run(&["describe", "--scene", "sweep_w"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--model-file"), "{}", stderr(&o));
}

#[test]
fn trade_runs_on_a_smooth_law_file() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models/stribeck.ssm")
        .display()
        .to_string();
    let args = ["trade", "--pieces", "4,8", "--tol", "1e-6", "--json"];
    let a = json(&[&args[..], &["--model", "stribeck"]].concat());
    let b = json(&[&args[..], &["--model-file", &file]].concat());
    agree(&a, &b, 1e-10, &["seconds"], "trade");
    // A smooth law is no piecewise-linear model: a command that needs one
    // says how to pick a scene.
    let o = run(&["describe", "--model-file", &file]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--scene"), "{}", stderr(&o));
}

#[test]
fn a_rejected_model_file_fails_with_the_report_check_gives() {
    let path = tmp_in("rejected", "paper.ssm");
    let text = std::fs::read_to_string(paper_file())
        .expect("paper.ssm")
        .replace("param mus = 0.5, >= 0;", "param mus = 0.5, >= zero;");
    std::fs::write(&path, text).expect("write");
    let path = path.display().to_string();
    let check = run(&["check", &path]);
    assert_eq!(check.status.code(), Some(1));
    let report = stderr(&check);
    let report = report
        .split_once("\nchecked ")
        .map_or(report.as_str(), |(r, _)| r);
    assert!(report.contains(&format!("--> {path}:")), "{report}");
    for command in [
        vec!["describe", "--model-file", &path],
        vec!["sweep", "--model-file", &path, "--param", "W=1:2:3"],
    ] {
        let o = run(&command);
        assert_eq!(o.status.code(), Some(1), "{command:?}");
        let err = stderr(&o);
        assert!(
            err.contains(report.trim_end()),
            "{command:?}:\n{err}\nnot\n{report}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn a_map_records_the_file_it_was_made_with_and_refuses_another() {
    let model = tmp_in("map", "paper.ssm");
    std::fs::copy(paper_file(), &model).expect("copy");
    let model = model.display().to_string();
    let (one, two) = (tmp_in("map", "one.csv"), tmp_in("map", "two.csv"));
    let (one, two) = (one.display().to_string(), two.display().to_string());
    let map = |model: &[&str], out: &str, extra: &[&str]| {
        let mut a = vec!["map", "--x", "W=3:4:3", "--y", "Q0=60:70:2", "--out", out];
        a.extend_from_slice(model);
        a.extend_from_slice(extra);
        run(&a)
    };
    let o = map(&["--model-file", &model], &one, &["--shard", "0/2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let header = std::fs::read_to_string(&one).expect("shard");
    let first = header.lines().next().expect("header");
    let text = std::fs::read_to_string(&model).expect("model");
    let hash = stickslip::model::loaded::content_hash(&text);
    assert!(first.contains(&format!(" source={hash:016x} ")), "{first}");
    // Resumed with the same file: fine.
    let o = map(
        &["--model-file", &model],
        &one,
        &["--shard", "0/2", "--resume"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // With the compiled-in model, or the file changed: refused.
    let o = map(&["--model", "paper"], &one, &["--shard", "0/2", "--resume"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("a different model file"),
        "{}",
        stderr(&o)
    );
    std::fs::write(
        &model,
        format!("{text}\n// a comment changes the content\n"),
    )
    .expect("edit");
    let o = map(
        &["--model-file", &model],
        &one,
        &["--shard", "0/2", "--resume"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("a different model file"),
        "{}",
        stderr(&o)
    );
    // Merged with a shard of the other file: refused.
    let o = map(&["--model-file", &model], &two, &["--shard", "1/2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let merged = tmp_in("map", "merged.csv").display().to_string();
    let o = run(&["merge", &one, &two, "--out", &merged]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("a different model file"),
        "{}",
        stderr(&o)
    );
}
