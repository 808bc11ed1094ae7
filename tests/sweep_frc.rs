//! The frequency-response view of a sweep: the amplitudes in the CSV (as in
//! the JSON), the `--view frc` figure (its tags apart and inside the image,
//! NM drawn), and the amplitudes against an independent evaluation of each
//! motion: dense sampling of the closed-form time history.

use std::path::PathBuf;
use std::process::Command;

use serde_json::Value;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::output::figure::layout::Rect;
use stickslip::output::figure::sweep::{SweepFigure, View};
use stickslip::output::figure::{register, Figure};
use stickslip::output::history::History;
use stickslip::output::sweep_table;
use stickslip::study::sweep::{sweep, SweepOptions};

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sweep_frc");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Every motion's amplitude equals the largest `|x|`, `|v|` of its time
/// history sampled densely (every segment from its own start with the
/// closed form), to the sampling's resolution, and is never below it.
#[test]
fn amplitudes_bound_and_match_the_sampled_history() {
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 2.0, 6.0, 21, SweepOptions::default()).expect("sweep");
    let mut checked = 0;
    for p in &s.points {
        for m in p.motions.iter().filter(|m| m.structure.starts_with("P_")) {
            let params = Params { W: p.value, ..base };
            let sim = Simulator::<Paper>::new(params, SimOptions::default()).unwrap();
            let structure = Structure::parse(Paper::INFO, &m.structure, m.n).unwrap();
            // The summary's points are mod 2π: unwrap them in order, and
            // solve the motion there (it holds already; Newton polishes).
            let mut points: Vec<SwitchingPoint> = Vec::new();
            for q in &m.points {
                let mut phase = q.phase;
                if let Some(last) = points.last() {
                    while phase < last.phase {
                        phase += std::f64::consts::TAU;
                    }
                }
                points.push(SwitchingPoint { phase, x: q.x });
            }
            let motion = solve(&sim, structure, points, NewtonOptions::default());
            assert!(motion.is_admissible(), "W = {}: {}", p.value, m.structure);
            let h = History::of_motion(&sim, &motion, 20_000);
            let (mut hx, mut hv) = (0.0f64, 0.0f64);
            for q in h.samples() {
                hx = hx.max(q.x.abs());
                hv = hv.max(q.v.abs());
            }
            let scale_x = m.max_abs_x.max(1.0);
            let scale_v = m.max_abs_v.max(1.0);
            // Never below a sampled value; above it by at most the sampling's
            // quadratic error at an extremum.
            assert!(
                m.max_abs_x >= hx - 1e-12 * scale_x && m.max_abs_x - hx < 1e-6 * scale_x,
                "W = {}: {} max|x| {} vs sampled {hx}",
                p.value,
                m.structure,
                m.max_abs_x
            );
            assert!(
                m.max_abs_v >= hv - 1e-12 * scale_v && m.max_abs_v - hv < 1e-5 * scale_v,
                "W = {}: {} max|v| {} vs sampled {hv}",
                p.value,
                m.structure,
                m.max_abs_v
            );
            checked += 1;
        }
    }
    assert!(checked >= 15, "{checked} motions checked");
}

#[test]
fn the_csv_has_one_row_per_motion_with_the_jsons_amplitudes() {
    let path = tmp("s.csv");
    let out = Command::new(BIN)
        .args([
            "sweep", "--param", "W=2:5:13", "--set", "Q0=70", "--json", "--csv",
        ])
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    let csv = std::fs::read_to_string(&path).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("W,structure,N,start_Wt,start_x,stable,lambda_max,max_abs_x,max_abs_v")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let motions: Vec<(f64, &Value)> = json["points"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|p| {
            let w = p["W"].as_f64().unwrap();
            p["motions"].as_array().unwrap().iter().map(move |m| (w, m))
        })
        .collect();
    assert_eq!(rows.len(), motions.len());
    assert!(rows.iter().any(|r| r[1] == "\"NM\""), "an NM row");
    for (r, (w, m)) in rows.iter().zip(&motions) {
        assert_eq!(r[0].parse::<f64>().unwrap(), *w);
        assert_eq!(r[1], format!("\"{}\"", m["structure"].as_str().unwrap()));
        for (col, key) in [(7, "max_abs_x"), (8, "max_abs_v")] {
            let want = m[key].as_f64().expect("an amplitude");
            assert!(want > 0.0);
            // serde_json's parser may be an ulp off the shortest decimal.
            let got: f64 = r[col].parse().unwrap();
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want,
                "{key} at W = {w}: {got} vs {want}"
            );
        }
    }
    // The library's writer, on the stable-only view, too.
    let s = sweep::<Paper>(
        Params {
            Q0: 70.0,
            ..Params::default()
        },
        "W",
        2.0,
        5.0,
        13,
        SweepOptions::default(),
    )
    .unwrap();
    assert_eq!(sweep_table::csv(&s), csv);
}

#[test]
fn the_frc_figure_draws_every_motion_with_tags_apart_and_inside() {
    register().unwrap();
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 0.2, 9.0, 200, SweepOptions::default()).expect("sweep");
    let figure = SweepFigure::view(&s, "frc", true, View::Frc);
    let (w, h) = figure.size();
    let frame = Rect::at(0, 0, (w as i32, h as i32));
    // Two panels side by side, and no long key: a compact image.
    assert!(h < 900, "{w} x {h}");
    let (panels, key) = figure.placed().unwrap();
    assert_eq!(panels.len(), 2, "tags over both panels");
    let mut boxes: Vec<Rect> = key.into_iter().filter(|r| r.x1 > r.x0).collect();
    for tags in &panels {
        let n: usize = tags.iter().map(|t| t.numbers.1 - t.numbers.0 + 1).sum();
        assert_eq!(n, s.transitions.len(), "every transition numbered once");
        boxes.extend(tags.iter().map(|t| t.rect));
    }
    for (i, a) in boxes.iter().enumerate() {
        assert!(a.inside(&frame), "{a:?} leaves the image");
        for b in &boxes[i + 1..] {
            assert!(!a.overlaps(b), "{a:?} overlaps {b:?}");
        }
    }
    // The no-motion regime has an amplitude, so it is drawn (and keyed).
    let svg = tmp("frc.svg");
    stickslip::output::figure::sweep::plot_sweep(&s, "frc", &svg, true, View::Frc).unwrap();
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("amplitude max |x| over the cycle"));
    assert!(text.contains(">\nNM\n</text>"), "NM is in the key");
}
