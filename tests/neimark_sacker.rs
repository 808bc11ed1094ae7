//! A real Neimark–Sacker point (issue 11): the paper model with a falling
//! friction slope below the belt speed (`mu3 = 4.4`: effective damping
//! `d − mu3/2m = −0.34` in Ω3, against `d + mu4/2m = 0.15` in Ω4) and
//! `Q0 = 100`. The slip-only motion `P_{3_33 4_33}` (Ω3 and Ω4, passing Σ3
//! twice) has a complex pair of eigenvalues outside the unit circle at
//! `W = 10.46`; it enters the circle as a pair near `W = 10.486` and meets
//! on the negative real axis before the period doubling at `W = 10.7026`.
//! On the grid `W = 9.5:11.3:19` the continuation steps from the complex
//! pair outside the circle to the real pair inside it in one step, and the
//! sweep used to miss the point (it looked for `det DP = 1` only between
//! two complex pairs). Each claim is checked independently: the `orbit`
//! command on both sides and at the point, and event-driven simulation.

mod common;

use std::process::Command;

use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::orbit::structure::Structure;
use stickslip::output::sweep_table::runs;
use stickslip::study::sweep::{sweep, Sweep, SweepOptions, TransitionKind};

const SET: &str = "Q0=100,mu3=4.4";
const STRUCTURE: &str = "P_{3_33 4_33}";

fn params(w: f64) -> Params {
    Params {
        Q0: 100.0,
        mu3: 4.4,
        W: w,
        ..Params::default()
    }
}

fn ns_sweep() -> Sweep {
    sweep::<Paper>(params(3.0), "W", 9.5, 11.3, 19, SweepOptions::default()).expect("sweep runs")
}

/// `orbit --json` for `P_{3_33 4_33}` at `W = w` from the guess: the
/// switching points and the eigenvalues of `DP`.
fn orbit(w: f64, guess: (f64, f64)) -> (Vec<SwitchingPoint>, Vec<[f64; 2]>, bool) {
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "orbit",
            "--model",
            "paper",
            "--structure",
            STRUCTURE,
            "--set",
            &format!("{SET},W={w:.17}"),
            "--guess",
            &format!("{:.17},{:.17}", guess.0, guess.1),
            "--json",
        ])
        .output()
        .expect("runs");
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    assert_eq!(doc["admissible"], true, "{doc}");
    let points = doc["points"]
        .as_array()
        .expect("points")
        .iter()
        .map(|p| SwitchingPoint {
            phase: p["Wt"].as_f64().expect("Wt"),
            x: p["x"].as_f64().expect("x"),
        })
        .collect();
    let ev = doc["eigenvalues"]
        .as_array()
        .unwrap_or_else(|| panic!("no eigenvalues: {doc}"))
        .iter()
        .map(|e| [e[0].as_f64().expect("re"), e[1].as_f64().expect("im")])
        .collect();
    (points, ev, doc["stable"].as_bool().expect("stable"))
}

/// Simulate `periods` forcing periods from the first switching point of
/// the motion ([`common::resimulate`]).
fn simulate(p: Params, points: &[SwitchingPoint], periods: u32) -> (usize, f64, f64) {
    let st = Structure::parse(Paper::INFO, STRUCTURE, 1).expect("structure");
    common::resimulate::from_first_point(p, &st, points, periods)
}

fn modulus(e: &[f64; 2]) -> f64 {
    e[0].hypot(e[1])
}

#[test]
fn the_falling_slope_gives_a_neimark_sacker_point_checked_independently() {
    let s = ns_sweep();
    let ns: Vec<_> = s
        .bifurcations
        .iter()
        .filter(|b| b.kind == TransitionKind::NeimarkSacker)
        .collect();
    assert_eq!(ns.len(), 1, "{:#?}", s.bifurcations);
    let ns = ns[0];
    assert_eq!(ns.structure, STRUCTURE);
    assert_eq!(ns.n, 1);
    assert!(ns.born.is_empty());
    assert!(
        (ns.value - 10.486056746632).abs() < 1e-8,
        "located at W = {}",
        ns.value
    );
    // The sweep's critical eigenvalue: a complex pair on the circle.
    assert!((modulus(&ns.eigenvalue) - 1.0).abs() < 1e-7, "{ns:#?}");
    assert!(ns.eigenvalue[1] > 0.05, "{ns:#?}");
    // The periodic solver at the reported value, from the reported point.
    let guess = (ns.start_wt, ns.start_x);
    let (_, ev, _) = orbit(ns.value, guess);
    assert_eq!(ev.len(), 2);
    for e in &ev {
        assert!((modulus(e) - 1.0).abs() < 1e-7, "orbit gives {ev:?}");
        assert!(e[1].abs() > 0.05, "not a complex pair: {ev:?}");
    }
    assert!((ev[0][1] + ev[1][1]).abs() < 1e-12 && (ev[0][0] - ev[1][0]).abs() < 1e-12);
    // Stability flips there: a complex pair outside the circle just below,
    // inside just above.
    let h = 2e-3;
    let (_, below, stable_below) = orbit(ns.value - h, guess);
    let (above_pts, above, stable_above) = orbit(ns.value + h, guess);
    assert!(!stable_below && stable_above, "{below:?} / {above:?}");
    for (ev, out) in [(&below, true), (&above, false)] {
        for e in ev {
            assert!(e[1].abs() > 0.05, "{ev:?}");
            assert_eq!(modulus(e) > 1.0, out, "{ev:?}");
        }
    }
    // The sweep says the same at its grid values: the motion is reported
    // unstable below the point, stable above it (up to the period doubling
    // at W = 10.7026).
    let grid = |lo: f64, hi: f64| {
        s.points
            .iter()
            .filter(move |p| p.value > lo && p.value < hi)
            .map(|p| {
                let m = p.motions.iter().find(|m| m.structure == STRUCTURE);
                (
                    p.value,
                    m.unwrap_or_else(|| panic!("W = {}: {p:#?}", p.value))
                        .stable,
                )
            })
            .collect::<Vec<_>>()
    };
    let (before, after) = (grid(9.8, ns.value), grid(ns.value, 10.701));
    assert!(
        before.len() >= 3 && after.len() >= 2,
        "{before:?} {after:?}"
    );
    assert!(before.iter().all(|&(_, st)| !st), "{before:?}");
    assert!(after.iter().all(|&(_, st)| st), "{after:?}");
    // And its branch: unstable up to the point, stable from it to the
    // period doubling (both located on one continuation step here), then
    // unstable (text report's stretches).
    let br = &s.branches[ns.branch];
    assert_eq!(br.structure, STRUCTURE);
    let runs: Vec<_> = runs(br, &s.bifurcations)
        .iter()
        .map(|r| (r.stable, r.from_kind, r.to_kind))
        .collect();
    let want = [
        (false, None, Some("neimark_sacker")),
        (true, Some("neimark_sacker"), Some("period_doubling")),
        (false, Some("period_doubling"), Some("period_doubling")),
        (true, Some("period_doubling"), None),
    ];
    assert_eq!(runs, want, "{br:#?}");
    // Just on the stable side the motion is a motion by simulation: one
    // forcing period from its first switching point, two passes of Σ3,
    // back where it started.
    assert_eq!(above_pts.len(), 2);
    let (events, dt, x) = simulate(params(ns.value + h), &above_pts, 1);
    assert_eq!(events, 2);
    assert!(dt.abs() < 1e-8, "the cycle ends {dt} off");
    assert!(
        (x - above_pts[0].x).abs() < 1e-8,
        "{x} vs {}",
        above_pts[0].x
    );
}
