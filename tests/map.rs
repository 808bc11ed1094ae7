//! Parameter maps: a run's file parses back and agrees with independent
//! simulations; a run killed (by a point limit, by a line cut short, by a
//! real SIGKILL of a child process) and resumed gives the uninterrupted
//! run's file byte for byte; shards merged give it too; merge and axis
//! errors are typed; the figure is drawn.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::param::ParamError;
use stickslip::models::paper::{sweep_w::SweepW, Paper, Params};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::output::figure::map::plot_map;
use stickslip::study::map::{
    self, classify_point, merge, motion_label, run_map, AxisError, GridAxis, MapError, MapFile,
    MapMethod, MapOptions, PointResult, Shard,
};

/// W = 2.5, 3, …, 5 and Q0 = 70, 80, 90: (W, Q0) = (5, 70) is a reference motion.
const X: &str = "W=2.5:5:6";
const Y: &str = "Q0=70:90:3";
const REFERENCE_W5: &str = "P_{3_31 1_12 2_22 1_21 3_13 4_33}";

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("map-{name}"));
    let _ = fs::remove_dir_all(&d);
    fs::create_dir_all(&d).unwrap();
    d
}

/// The paper model's map over the axes `x` and `y` (`NAME=FROM:TO:COUNT`) into `out`.
fn run_on(x: &str, y: &str, out: &Path, opts: MapOptions) -> Result<map::Summary, MapError> {
    let x = GridAxis::parse_for::<Paper>(&Default::default(), x).unwrap();
    let y = GridAxis::parse_for::<Paper>(&Default::default(), y).unwrap();
    run_map::<Paper>(&Params::default(), &x, &y, out, &opts)
}

/// Options: continue the file at the output path.
fn resume() -> MapOptions {
    MapOptions {
        resume: true,
        ..MapOptions::default()
    }
}

/// Options: stop after `n` points.
fn at_most(n: usize) -> MapOptions {
    MapOptions {
        max_points: Some(n),
        ..MapOptions::default()
    }
}

fn run(out: &Path, opts: MapOptions) -> Result<map::Summary, MapError> {
    run_on(X, Y, out, opts)
}

/// The uninterrupted single run's file, computed once.
fn reference() -> &'static str {
    static TEXT: OnceLock<String> = OnceLock::new();
    TEXT.get_or_init(|| {
        let out = dir("reference").join("map.csv");
        let t = Instant::now();
        let s = run(&out, MapOptions::default()).unwrap();
        eprintln!("18-point map in {:?}", t.elapsed());
        assert!(s.complete);
        assert_eq!((s.grid_points, s.shard_points, s.computed), (18, 18, 18));
        fs::read_to_string(&out).unwrap()
    })
}

fn data_lines(text: &str) -> Vec<&str> {
    text.lines().skip(2).collect()
}

#[test]
fn a_single_run_parses_back_and_agrees_with_simulation() {
    let text = reference();
    let (x, y) = (
        GridAxis::parse_for::<Paper>(&Default::default(), X).unwrap(),
        GridAxis::parse_for::<Paper>(&Default::default(), Y).unwrap(),
    );
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "# stickslip map model=paper x=W=2.5:5:6 y=Q0=70:90:3 \
         base=m=5,d=0.1,c=30,V=3,V1=4.5,V2=1.5,mus=0.5,muk=0.4,mu1=0.1,mu2=0.5,mu3=0.1,mu4=0.5,g=9.8 \
         method=continuation"
    );
    assert_eq!(lines[1], "index,W,Q0,status,motions");
    assert_eq!(lines.len(), 2 + 18);

    let dir = dir("parse");
    let path = dir.join("map.csv");
    fs::write(&path, text).unwrap();
    let file = MapFile::read(&path).unwrap();
    assert_eq!(file.header.x, x);
    assert_eq!(file.header.y, y);
    assert_eq!(file.header.shard, None);
    assert_eq!(file.header.method, Some(MapMethod::Continuation));
    assert!(!file.dropped_partial);
    // Re-serialized byte for byte.
    let mut again = file.header.to_lines();
    for p in &file.points {
        again.push_str(&p.to_line());
    }
    assert_eq!(again, text);

    for (k, p) in file.points.iter().enumerate() {
        assert_eq!(p.index, k);
        assert_eq!((p.x, p.y), (x.value(k % 6), y.value(k / 6)));
        // An independent simulation from rest finds one of the point's motions.
        let params = Params {
            W: p.x,
            Q0: p.y,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(params, SimOptions::default()).unwrap();
        let start = sim.start(0.0, 0.0, 0.0).unwrap();
        let opts = AttractorOptions {
            max_periods: map::MAX_PERIODS,
            ..AttractorOptions::default()
        };
        match attractor::find(&sim, start, opts) {
            Ok(Attractor::Periodic(m)) => {
                let label = motion_label(Paper::INFO, &m);
                assert!(p.motions.contains(&label), "{label} not in {p:?}");
            }
            Ok(Attractor::NoMotion(_)) => assert!(p.motions.iter().any(|m| m == "NM"), "{p:?}"),
            Ok(Attractor::Stick(_)) => assert!(p.motions.iter().any(|m| m == "stick"), "{p:?}"),
            Ok(Attractor::Autonomous(_)) => {
                assert!(p.motions.iter().any(|m| m == "autonomous"), "{p:?}")
            }
            Err(e) => assert!(p.status.contains("start 1"), "{e} but {p:?}"),
        }
    }
    // (W, Q0) = (5, 70): the reference motion of ../shared/reference.
    let at = file
        .points
        .iter()
        .find(|p| p.x == 5.0 && p.y == 70.0)
        .unwrap();
    assert!(at.motions.iter().any(|m| m == REFERENCE_W5), "{at:?}");
    assert_eq!(at.status, "ok");
}

#[test]
fn classify_point_names_reference_motions_no_motion_and_invalid_parameters() {
    let one = |w: f64, q0: f64| {
        let x = GridAxis::parse_for::<Paper>(&Default::default(), &format!("W={w}:{w}:1")).unwrap();
        let y =
            GridAxis::parse_for::<Paper>(&Default::default(), &format!("Q0={q0}:{q0}:1")).unwrap();
        classify_point::<Paper>(&Params::default(), &x, &y, 0)
    };
    let p = one(3.7, 70.0);
    assert!(
        p.motions.iter().any(|m| m == "P_{3_31 0_11 3_13 4_33}"),
        "{p:?}"
    );
    let p = one(1.0, 70.0);
    assert_eq!(p.motions, ["NM"]);
    assert_eq!(p.status, "ok");
    assert_eq!(p.label(), "NM");
    // W = 0 is rejected by the model (W > 0): a status, not a panic.
    let x = GridAxis::parse_for::<Paper>(&Default::default(), "W=0:1:2").unwrap();
    let y = GridAxis::parse_for::<Paper>(&Default::default(), "Q0=70:70:1").unwrap();
    let p = classify_point::<Paper>(&Params::default(), &x, &y, 0);
    assert!(p.status.starts_with("invalid: "), "{p:?}");
    assert!(p.motions.is_empty());
    assert_eq!(p.label(), "invalid");
    assert_eq!(PointResult::parse_line(&p.to_line()).unwrap(), p);
}

#[test]
fn b_killed_and_resumed_runs_equal_a_single_run() {
    let want = reference();
    let dir = dir("resume");

    // Stopped after 5 points: an unsorted, resumable file.
    let out = dir.join("limit.csv");
    let s = run(&out, at_most(5)).unwrap();
    assert!(!s.complete);
    assert_eq!(s.computed, 5);
    let partial = fs::read_to_string(&out).unwrap();
    assert_eq!(data_lines(&partial).len(), 5);
    // Without --resume an existing file is an error, and is left alone.
    let e = run(&out, MapOptions::default()).unwrap_err();
    assert!(matches!(e, MapError::OutputExists(_)), "{e}");
    assert!(e.to_string().contains("--resume"), "{e}");
    assert_eq!(fs::read_to_string(&out).unwrap(), partial);

    // The last line cut in the middle of a write, as by a kill.
    let cut = partial.len() - partial.lines().last().unwrap().len() / 2 - 1;
    fs::write(&out, &partial[..cut]).unwrap();
    let s = run(
        &out,
        MapOptions {
            resume: true,
            max_points: Some(4),
            ..MapOptions::default()
        },
    )
    .unwrap();
    assert_eq!((s.already_done, s.computed, s.complete), (4, 4, false));
    // And garbage without a newline at the end.
    let mut f = fs::OpenOptions::new().append(true).open(&out).unwrap();
    std::io::Write::write_all(&mut f, b"17,5.0,9").unwrap();
    drop(f);
    let s = run(&out, resume()).unwrap();
    assert_eq!((s.already_done, s.computed, s.complete), (8, 10, true));
    assert_eq!(fs::read_to_string(&out).unwrap(), want);
    // Resuming a complete map computes nothing and changes nothing.
    let s = run(&out, resume()).unwrap();
    assert_eq!((s.already_done, s.computed, s.complete), (18, 0, true));
    assert_eq!(fs::read_to_string(&out).unwrap(), want);

    // Killed before the header was complete.
    let out = dir.join("header.csv");
    fs::write(&out, "# stickslip map mod").unwrap();
    run(&out, resume()).unwrap();
    assert_eq!(fs::read_to_string(&out).unwrap(), want);

    // Resuming a file of another map is refused.
    let other = dir.join("other.csv");
    run_on("W=2.5:5:5", Y, &other, at_most(1)).unwrap();
    let e = run(&other, resume()).unwrap_err();
    assert!(matches!(e, MapError::Mismatch { .. }), "{e}");
    assert!(e.to_string().contains("x axis W=2.5:5:5"), "{e}");
}

/// The grid of the SIGKILL test: large enough (861 points) that the child
/// is still computing when it is killed.
const BIG_X: &str = "W=2.5:5:41";
const BIG_Y: &str = "Q0=70:90:21";

fn run_big(out: &Path, opts: MapOptions) -> Result<map::Summary, MapError> {
    run_on(BIG_X, BIG_Y, out, opts)
}

/// Run by `a_sigkilled_run_resumes` in a child process (the test binary
/// itself): computes the big map into `STICKSLIP_MAP_CHILD_OUT`. Does nothing otherwise.
#[test]
fn child_process_map_run() {
    let Ok(out) = std::env::var("STICKSLIP_MAP_CHILD_OUT") else {
        return;
    };
    run_big(&PathBuf::from(out), MapOptions::default()).unwrap();
}

#[test]
fn a_sigkilled_run_resumes() {
    let dir = dir("sigkill");
    let single = dir.join("single.csv");
    let t = Instant::now();
    let s = run_big(&single, MapOptions::default()).unwrap();
    eprintln!("{}-point map in {:?}", s.computed, t.elapsed());
    let want = fs::read_to_string(&single).unwrap();
    let total = s.grid_points;

    let out = dir.join("map.csv");
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args(["child_process_map_run", "--exact", "--test-threads=1"])
        .env("STICKSLIP_MAP_CHILD_OUT", &out)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Kill it (SIGKILL) as soon as it has written a few points.
    let t = Instant::now();
    loop {
        let n = fs::read_to_string(&out).map_or(0, |s| data_lines(&s).len());
        if n >= 3 || t.elapsed() > Duration::from_secs(60) {
            break;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    let at_kill = fs::read(&out).unwrap();
    let done = String::from_utf8_lossy(&at_kill)
        .lines()
        .skip(2)
        .filter(|l| PointResult::parse_line(l).is_ok())
        .count();
    eprintln!("child killed ({status}) with {done} of {total} points written");
    assert!(done < total, "the child finished before it was killed");
    let s = run_big(&out, resume()).unwrap();
    assert!(s.complete);
    assert_eq!(s.already_done + s.computed, total);
    assert_eq!(fs::read_to_string(&out).unwrap(), want);
}

/// The x axis of the shard test: 33 points, three tiles of 16, 16 and 1 columns.
const SHARD_X: &str = "W=2.5:5:33";

#[test]
fn c_shards_merged_equal_a_single_run() {
    // Three tiles (16, 16 and 1 points wide): one per shard.
    let dir = dir("shards");
    let single = dir.join("single.csv");
    run_on(SHARD_X, Y, &single, MapOptions::default()).unwrap();
    let want_text = fs::read_to_string(&single).unwrap();
    let want: &str = &want_text;
    let run = |out: &Path, opts: MapOptions| run_on(SHARD_X, Y, out, opts);
    let mut files = Vec::new();
    for k in 0..3 {
        let out = dir.join(format!("shard{k}.csv"));
        let s = run(
            &out,
            MapOptions {
                shard: Some(Shard { index: k, count: 3 }),
                ..MapOptions::default()
            },
        )
        .unwrap();
        let tile = [48, 48, 3][k];
        assert_eq!((s.shard_points, s.computed, s.complete), (tile, tile, true));
        let text = fs::read_to_string(&out).unwrap();
        assert!(text
            .lines()
            .next()
            .unwrap()
            .ends_with(&format!(" shard={k}/3")));
        files.push(out);
    }
    let merged = dir.join("merged.csv");
    let s = merge(&files, &merged).unwrap();
    assert_eq!((s.grid_points, s.complete), (99, true));
    assert_eq!(fs::read_to_string(&merged).unwrap(), want);

    // A shard killed and resumed, in another order, with an overlapping
    // complete map: identical duplicates are fine.
    let resumed = dir.join("shard1-resumed.csv");
    let shard = Some(Shard::parse("1/3").unwrap());
    run(
        &resumed,
        MapOptions {
            shard,
            max_points: Some(2),
            ..MapOptions::default()
        },
    )
    .unwrap();
    run(
        &resumed,
        MapOptions {
            shard,
            resume: true,
            ..MapOptions::default()
        },
    )
    .unwrap();
    let full = dir.join("full.csv");
    fs::write(&full, want).unwrap();
    let merged2 = dir.join("merged2.csv");
    merge(
        &[files[2].clone(), resumed, files[0].clone(), full],
        &merged2,
    )
    .unwrap();
    assert_eq!(fs::read_to_string(&merged2).unwrap(), want);

    // A partial shard file (a killed shard) merges too if others cover it.
    let partial = dir.join("shard0-partial.csv");
    run(
        &partial,
        MapOptions {
            shard: Some(Shard { index: 0, count: 3 }),
            max_points: Some(3),
            ..MapOptions::default()
        },
    )
    .unwrap();
    let merged3 = dir.join("merged3.csv");
    merge(
        &[
            partial,
            files[0].clone(),
            files[1].clone(),
            files[2].clone(),
        ],
        &merged3,
    )
    .unwrap();
    assert_eq!(fs::read_to_string(&merged3).unwrap(), want);
}

#[test]
fn d_merge_errors_name_the_points() {
    let want = reference();
    let dir = dir("merge-errors");
    let full = dir.join("full.csv");
    fs::write(&full, want).unwrap();
    let out = dir.join("out.csv");

    // Missing points: every third line removed.
    let holes = dir.join("holes.csv");
    let mut text = want.lines().take(2).collect::<Vec<_>>().join("\n") + "\n";
    for (k, l) in data_lines(want).iter().enumerate() {
        if k % 3 != 1 {
            text.push_str(l);
            text.push('\n');
        }
    }
    fs::write(&holes, &text).unwrap();
    match merge(std::slice::from_ref(&holes), &out) {
        Err(MapError::Missing(v)) => assert_eq!(v, [1, 4, 7, 10, 13, 16]),
        other => panic!("{other:?}"),
    }
    assert!(!out.exists());

    // The same point with another result.
    let changed = dir.join("changed.csv");
    let line = data_lines(want)[7];
    let mut p = PointResult::parse_line(line).unwrap();
    p.motions = vec!["NM".to_string()];
    fs::write(&changed, want.replace(line, p.to_line().trim_end())).unwrap();
    match merge(&[full.clone(), changed], &out) {
        Err(e @ MapError::Conflict(_)) => {
            assert!(matches!(&e, MapError::Conflict(v) if v == &[7]));
            assert!(e.to_string().contains('7'), "{e}");
        }
        other => panic!("{other:?}"),
    }

    // Another grid.
    let other = dir.join("other.csv");
    run_on("W=2.5:5:6", "Q0=70:91:3", &other, at_most(1)).unwrap();
    match merge(&[full.clone(), other.clone()], &out) {
        Err(e @ MapError::Mismatch { .. }) => {
            assert!(e.to_string().contains("y axis Q0=70:91:3"), "{e}")
        }
        other => panic!("{other:?}"),
    }
    // Other base parameters.
    let base = dir.join("base.csv");
    fs::write(&base, want.replace(",mus=0.5,", ",mus=0.6,")).unwrap();
    assert!(matches!(
        merge(&[full.clone(), base], &out),
        Err(MapError::Mismatch { .. })
    ));
    // A point off its grid position, and a line that is not a point.
    let off = dir.join("off.csv");
    fs::write(&off, want.replacen("\n3,4.0,70.0,", "\n3,4.5,70.0,", 1)).unwrap();
    assert!(matches!(
        merge(std::slice::from_ref(&off), &out),
        Err(MapError::Corrupt { line: 6, .. })
    ));
    let junk = dir.join("junk.csv");
    fs::write(&junk, format!("{want}hello\n")).unwrap();
    assert!(matches!(
        merge(std::slice::from_ref(&junk), &out),
        Err(MapError::Corrupt { line: 21, .. })
    ));
    let not_map = dir.join("not-map.csv");
    fs::write(&not_map, "a,b\n").unwrap();
    assert!(matches!(
        merge(std::slice::from_ref(&not_map), &out),
        Err(MapError::Header { .. })
    ));
    assert!(matches!(merge(&[], &out), Err(MapError::NoInput)));
    assert!(!out.exists());
}

#[test]
fn d_the_header_records_the_method_and_resume_and_merge_refuse_another() {
    let want = reference();
    let dir = dir("method");
    let simulation = |max_points: Option<usize>, resume: bool| MapOptions {
        method: MapMethod::Simulation,
        max_points,
        resume,
        ..MapOptions::default()
    };
    // A simulation run killed after 4 points, resumed by continuation:
    // refused, the file untouched.
    let out = dir.join("simulation.csv");
    run(&out, simulation(Some(4), false)).unwrap();
    let text = fs::read_to_string(&out).unwrap();
    assert!(
        text.lines().next().unwrap().ends_with(" method=simulation"),
        "{text}"
    );
    match run(&out, resume()) {
        Err(e @ MapError::Mismatch { .. }) => assert!(
            e.to_string()
                .contains("different map: method simulation, not continuation"),
            "{e}"
        ),
        other => panic!("{other:?}"),
    }
    assert_eq!(fs::read_to_string(&out).unwrap(), text);
    // Resumed by simulation, it is the single simulation run's file.
    let s = run(&out, simulation(None, true)).unwrap();
    assert_eq!((s.already_done, s.complete), (4, true));
    let single = dir.join("simulation-single.csv");
    run(&single, simulation(None, false)).unwrap();
    let sim_text = fs::read_to_string(&single).unwrap();
    assert_eq!(fs::read_to_string(&out).unwrap(), sim_text);
    assert_eq!(
        MapFile::read(&out).unwrap().header.method,
        Some(MapMethod::Simulation)
    );

    // Merge refuses files of two methods, in either order.
    let full = dir.join("full.csv");
    fs::write(&full, want).unwrap();
    let merged = dir.join("merged.csv");
    for (inputs, what) in [
        (
            [full.clone(), out.clone()],
            "method simulation, not continuation",
        ),
        (
            [out.clone(), full.clone()],
            "method continuation, not simulation",
        ),
    ] {
        match merge(&inputs, &merged) {
            Err(e @ MapError::Mismatch { .. }) => assert!(e.to_string().contains(what), "{e}"),
            other => panic!("{other:?}"),
        }
    }
    assert!(!merged.exists());

    // A file from before the header recorded the method parses (method
    // unknown), and is neither resumed nor merged with a recorded one.
    let older = dir.join("older.csv");
    fs::write(&older, want.replacen(" method=continuation", "", 1)).unwrap();
    assert_eq!(MapFile::read(&older).unwrap().header.method, None);
    for result in [
        run(&older, resume()),
        merge(&[full.clone(), older.clone()], &merged),
    ] {
        match result {
            Err(e @ MapError::Mismatch { .. }) => {
                assert!(e.to_string().contains("method unrecorded"), "{e}")
            }
            other => panic!("{other:?}"),
        }
    }
    // Files that all lack it still merge (as they did).
    merge(std::slice::from_ref(&older), &merged).unwrap();
    assert_eq!(
        fs::read_to_string(&merged).unwrap(),
        want.replacen(" method=continuation", "", 1)
    );
    // An unknown method is a bad header.
    let bad = dir.join("bad.csv");
    fs::write(
        &bad,
        want.replacen("method=continuation", "method=guess", 1),
    )
    .unwrap();
    match MapFile::read(&bad) {
        Err(e @ MapError::Header { .. }) => assert!(e.to_string().contains("`guess`"), "{e}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn e_bad_axes_and_shards_are_typed_errors() {
    use AxisError::*;
    for (text, want) in [
        ("W3:5:6", "Syntax"),
        ("W=3:5", "Syntax"),
        ("W=3:5:6:7", "Syntax"),
        ("=3:5:6", "Syntax"),
        ("W=3:5:0", "Count"),
        ("W=3:5:-2", "Count"),
        ("W=3:5:2.5", "Count"),
        ("W=NaN:5:3", "NotFinite"),
        ("W=3:inf:3", "NotFinite"),
        ("W=3:x:3", "NotFinite"),
    ] {
        let e = GridAxis::parse_for::<Paper>(&Default::default(), text).unwrap_err();
        let kind = match e {
            Syntax { .. } => "Syntax",
            Count { .. } => "Count",
            NotFinite { .. } => "NotFinite",
            _ => "other",
        };
        assert_eq!(kind, want, "{text}: {e}");
        assert!(e.to_string().contains(text), "{e}");
    }
    let e = GridAxis::parse_for::<Paper>(&Default::default(), "Z=3:5:6").unwrap_err();
    assert!(
        matches!(&e, Parameter { source: ParamError::Unknown { name, .. }, .. } if name == "Z"),
        "{e}"
    );
    assert!(e.to_string().contains("Q0"), "{e}");
    // The W sweep scene fixes Q0.
    let e = GridAxis::parse_for::<SweepW>(&Default::default(), "Q0=40:80:3").unwrap_err();
    assert!(
        matches!(
            &e,
            Parameter {
                source: ParamError::Fixed { .. },
                ..
            }
        ),
        "{e}"
    );
    let x = GridAxis::parse_for::<Paper>(&Default::default(), "W=3:5:2").unwrap();
    let dir = dir("bad-axes");
    let e = run_map::<Paper>(
        &Params::default(),
        &x,
        &x,
        &dir.join("m.csv"),
        &MapOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, MapError::Axis(SameParameter(_))), "{e}");
    let unknown = GridAxis {
        name: "Z".into(),
        from: 0.0,
        to: 1.0,
        count: 2,
    };
    let e = run_map::<Paper>(
        &Params::default(),
        &unknown,
        &x,
        &dir.join("m.csv"),
        &MapOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, MapError::Axis(Parameter { .. })), "{e}");
    assert!(!dir.join("m.csv").exists());
    for bad in ["3/3", "1", "a/2", "0/0", "-1/2"] {
        assert!(
            matches!(Shard::parse(bad), Err(MapError::BadShard(_))),
            "{bad}"
        );
    }
    assert_eq!(Shard::parse("2/5").unwrap(), Shard { index: 2, count: 5 });
}

#[test]
fn the_map_is_drawn_as_svg_and_png() {
    let want = reference();
    let dir = dir("plot");
    let file = dir.join("map.csv");
    fs::write(&file, want).unwrap();
    let svg = dir.join("map.svg");
    plot_map(&file, &svg).unwrap();
    let text = fs::read_to_string(&svg).unwrap();
    assert!(text.contains("<svg"));
    assert!(text.contains(REFERENCE_W5), "legend names the structures");
    let png = dir.join("map.png");
    plot_map(&file, &png).unwrap();
    assert!(fs::metadata(&png).unwrap().len() > 1000);
    // A partial map draws too (missing points hatched).
    let partial = dir.join("partial.csv");
    let text: String = want.lines().take(9).map(|l| format!("{l}\n")).collect();
    fs::write(&partial, text).unwrap();
    plot_map(&partial, &dir.join("partial.svg")).unwrap();
    assert!(matches!(
        plot_map(&file, &dir.join("map.gif")),
        Err(MapError::Plot(_))
    ));
}
