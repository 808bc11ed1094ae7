//! The global search for coexisting stable motions (issue 11, item 3), on the
//! bistable window of the paper model at W = 3.9482584517, Q0 = 70: two
//! stable period-1 motions, and a stable period-2 motion that a simulation
//! from rest lands on.

use std::time::Instant;

use stickslip::dynamics::simulate::{EventKind, Location, Segment, SimOptions, Simulator};
use stickslip::model::Model;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::known::{settle, stroboscopic_states, KnownMotions, Settled};
use stickslip::orbit::motion::{solve, Motion};
use stickslip::orbit::periodic::NewtonOptions;
use stickslip::orbit::structure::Structure;
use stickslip::study::search::{coexisting, same_motion, search, SearchOptions};

const TAU: f64 = 2.0 * std::f64::consts::PI;
const W_BISTABLE: f64 = 3.9482584517;
const STICKY: &str = "P_{3_31 0_11 1_11 3_13 4_33}";
const PASSING: &str = "P_{3_31 1_11 3_13 4_33}";
const DOUBLED: &str = "P_{3_31 0_11 1_11 3_13 4_33 3_31 1_11 3_13 4_33}";

fn sim_at(w: f64) -> Simulator<Paper> {
    let p = Params {
        W: w,
        Q0: 70.0,
        ..Params::default()
    };
    Simulator::new(p, SimOptions::default()).expect("valid parameters")
}

/// A motion of `structure` seeded by simulation and solved by Newton (as
/// `stickslip orbit --structure` does), checked stable and admissible.
fn motion(sim: &Simulator<Paper>, structure: &str, periods: u32) -> Motion {
    let s = Structure::parse(Paper::INFO, structure, periods).expect("structure");
    let guess = attractor::seed(sim, &s).expect("a simulation follows the structure");
    let m = solve(sim, s, guess, NewtonOptions::default());
    assert!(m.is_admissible(), "{structure}: {:?}", m.termination);
    assert!(m.stability.is_some_and(|s| s.is_stable()), "{structure}");
    m
}

/// The segment that starts the motion's first mapping.
fn first_segment(sim: &Simulator<Paper>, m: &Motion) -> Segment {
    let map = Paper::INFO.mappings[m.structure.steps()[0]];
    let p = m.points[0];
    Segment {
        x: p.x,
        v: sim.velocity(map.from),
        phase: p.phase,
        location: map.domain.map_or(Location::Stick, Location::Domain),
        search_from: p.phase,
    }
}

/// `(x, v)` after simulating `periods` forcing periods from the motion's
/// first switching point.
fn after(sim: &Simulator<Paper>, m: &Motion, periods: u32) -> (f64, f64) {
    let start = first_segment(sim, m);
    let end = start.phase + TAU * periods as f64;
    let seg = sim.run(start, end, |_| {}).expect("simulates");
    sim.state_at(&seg, end)
}

#[test]
fn stroboscopic_states_agree_with_simulation() {
    let sim = sim_at(W_BISTABLE);
    let doubled = motion(&sim, DOUBLED, 2);
    let states = stroboscopic_states(&sim, &doubled, 0.0);
    assert_eq!(states.len(), 2);
    // Simulate from the first switching point to each stroboscopic phase.
    let start = first_segment(&sim, &doubled);
    let base = TAU * (start.phase / TAU).ceil();
    for (i, s) in states.iter().enumerate() {
        let phi = base + TAU * i as f64;
        let seg = sim.run(start, phi, |_| {}).expect("simulates");
        let (x, v) = sim.state_at(&seg, phi);
        assert_eq!(seg.location, s.location, "state {i}");
        assert!((x - s.x).abs() < 1e-9 && (v - s.v).abs() < 1e-9, "state {i}: ({x}, {v}) vs {s:?}");
    }
    // The two states of a period-2 motion differ.
    assert!((states[0].x - states[1].x).abs() > 1e-5);
}

#[test]
fn finds_the_period_two_motion_beside_the_two_known_period_one_motions() {
    let sim = sim_at(W_BISTABLE);
    let known = vec![(7, motion(&sim, STICKY, 1)), (9, motion(&sim, PASSING, 1))];
    let opts = SearchOptions::default();
    let found = search(&sim, &known, &opts);
    eprintln!("{:?}", found.stats);
    assert_eq!(found.motions.len(), 1, "{:#?}", found.motions);
    let m = &found.motions[0];
    assert_eq!(m.structure.notation(Paper::INFO), DOUBLED);
    assert_eq!(m.structure.periods(), 2);
    assert!(m.is_admissible());
    // The simulation from rest lands on the same motion, in the same rotation.
    let start = sim.start(0.0, 0.0, 0.0).expect("rest");
    match attractor::find(&sim, start, AttractorOptions::default()) {
        Ok(Attractor::Periodic(rest)) => {
            assert_eq!(rest.structure, m.structure);
            assert!(same_motion(&rest, m, 1e-6));
        }
        other => panic!("from rest: {other:?}"),
    }
    // By simulation from its switching point: 2-periodic, not 1-periodic.
    let x0 = first_segment(&sim, m);
    let (x1, v1) = after(&sim, m, 1);
    let (x2, v2) = after(&sim, m, 2);
    assert!((x2 - x0.x).abs() < 1e-8 && (v2 - x0.v).abs() < 1e-8, "({x2}, {v2}) vs {x0:?}");
    assert!((x1 - x0.x).abs().max((v1 - x0.v).abs()) > 1e-4, "({x1}, {v1}) vs {x0:?}");
    // Eigenvalues of DP, by nalgebra, inside the unit circle.
    let dp = m.dp.expect("DP");
    for e in dp.complex_eigenvalues().iter() {
        assert!(e.norm() < 1.0, "eigenvalue {e}");
    }
    // Every start was accounted for.
    let s = found.stats;
    assert_eq!(s.starts, opts.starts);
    assert_eq!(
        s.stopped_known + s.stopped_found + s.matched + s.new + s.other + s.failed,
        s.starts
    );
    assert_eq!(s.new, 1);
    // The same through the plain API.
    assert_eq!(coexisting(&sim, &known, &opts).len(), 1);
}

#[test]
fn with_everything_known_nothing_is_new_and_starts_stop_early() {
    let sim = sim_at(W_BISTABLE);
    let all = vec![
        (0, motion(&sim, STICKY, 1)),
        (1, motion(&sim, PASSING, 1)),
        (2, motion(&sim, DOUBLED, 2)),
    ];
    let opts = SearchOptions::default();
    let known = search(&sim, &all, &opts);
    let none = search(&sim, &[], &opts);
    eprintln!("all known: {:?}\nnone known: {:?}", known.stats, none.stats);
    assert!(known.motions.is_empty(), "{:#?}", known.motions);
    assert!(known.stats.stopped_known * 4 >= 3 * opts.starts, "{:?}", known.stats);
    assert!(
        known.stats.periods * 3 < none.stats.periods,
        "{:?} vs {:?}",
        known.stats,
        none.stats
    );
    // With nothing known the search finds the period-2 motion itself.
    assert!(none
        .motions
        .iter()
        .any(|m| same_motion(m, &all[2].1, 1e-6)));
}

#[test]
fn a_start_on_a_known_motion_stops_at_once() {
    let sim = sim_at(W_BISTABLE);
    for (structure, n) in [(STICKY, 1), (PASSING, 1), (DOUBLED, 2)] {
        let m = motion(&sim, structure, n);
        let known = KnownMotions::from_motions(&sim, &[(3, m.clone())], 0.0);
        let states = known.states(3).expect("known");
        assert_eq!(states.len(), n as usize);
        assert!(known.radius(3).is_some_and(|r| r > 0.0));
        let phase = TAU * (m.points[0].phase / TAU).ceil();
        for (i, s) in states.iter().enumerate() {
            let phi = phase + TAU * i as f64;
            let start = sim.start(s.x, s.v, phi).expect("start");
            assert_eq!(known.near(&sim, &start, phi), Some(3));
            let out = settle(&sim, &known, start, AttractorOptions::default());
            assert_eq!(out.outcome, Ok(Settled::Known(3)), "{structure} state {i}");
            assert_eq!(out.periods, 0);
        }
        // A start far away is not near.
        let far = sim.start(5.0, -3.0, 0.0).expect("start");
        assert_eq!(known.near(&sim, &far, 0.0), None);
    }
}

#[test]
fn neighbourhoods_of_close_motions_do_not_overlap() {
    let sim = sim_at(W_BISTABLE);
    let all = vec![
        (0, motion(&sim, STICKY, 1)),
        (1, motion(&sim, PASSING, 1)),
        (2, motion(&sim, DOUBLED, 2)),
    ];
    let known = KnownMotions::from_motions(&sim, &all, 0.0);
    let w = W_BISTABLE;
    for (a, _) in &all {
        for (b, _) in &all {
            if a == b {
                continue;
            }
            let (ra, rb) = (known.radius(*a).unwrap(), known.radius(*b).unwrap());
            for sa in known.states(*a).unwrap() {
                for sb in known.states(*b).unwrap() {
                    let d = (sa.x - sb.x).abs().max((sa.v - sb.v).abs() / w);
                    assert!(ra + rb < d, "{a} {b}: {ra} + {rb} vs {d}");
                }
            }
        }
    }
}

/// Stable motions at `w`: everything a no-known search and rest reach.
fn stable_motions(sim: &Simulator<Paper>) -> Vec<(usize, Motion)> {
    let mut all = search(sim, &[], &SearchOptions::default()).motions;
    if let Ok(Attractor::Periodic(m)) = attractor::find(
        sim,
        sim.start(0.0, 0.0, 0.0).expect("rest"),
        AttractorOptions::default(),
    ) {
        if m.stability.is_some_and(|s| s.is_stable()) && !all.iter().any(|a| same_motion(a, &m, 1e-6)) {
            all.push(m);
        }
    }
    all.into_iter().enumerate().collect()
}

/// The cost of one search (run with `--release -- --ignored --nocapture`).
#[test]
#[ignore]
fn cost_of_one_search() {
    for w in [3.7, W_BISTABLE, 5.0, 8.0] {
        let sim = sim_at(w);
        let known = stable_motions(&sim);
        let names: Vec<String> = known
            .iter()
            .map(|(_, m)| format!("{}^{}", m.structure.notation(Paper::INFO), m.structure.periods()))
            .collect();
        for k in [4, 8, 16, 32] {
            let opts = SearchOptions {
                starts: k,
                ..SearchOptions::default()
            };
            for (label, given) in [("known", &known[..]), ("none", &[][..])] {
                let reps = 20;
                let t = Instant::now();
                let mut last = None;
                for _ in 0..reps {
                    last = Some(search(&sim, given, &opts));
                }
                let dt = t.elapsed().as_secs_f64() / reps as f64;
                let s = last.expect("ran").stats;
                let mut events = 0usize;
                let start = sim.start(0.0, 0.0, 0.0).expect("rest");
                sim.run(start, 100.0 * TAU, |e| {
                    if e.kind != EventKind::Graze {
                        events += 1
                    }
                })
                .expect("runs");
                eprintln!(
                    "W = {w:<12} K = {k:<3} {label:<5}: {:8.1} us  periods {:5}  (stopped {} + {}, matched {}, new {}, other {}, failed {}); {:.1} events/period; stable: {}",
                    dt * 1e6,
                    s.periods,
                    s.stopped_known,
                    s.stopped_found,
                    s.matched,
                    s.new,
                    s.other,
                    s.failed,
                    events as f64 / 100.0,
                    names.join(", ")
                );
            }
        }
    }
}
