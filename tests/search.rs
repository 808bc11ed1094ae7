//! The global search for coexisting stable motions (issue 11, item 3), on the
//! bistable window of the paper model at W = 3.9482584517, Q0 = 70: two
//! stable period-1 motions, and a stable period-2 motion that a simulation
//! from rest lands on.

use stickslip::dynamics::simulate::{EventKind, Location, Segment, SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::known::{settle, stroboscopic_states, KnownMotions, Settled};
use stickslip::orbit::motion::{solve, Motion, OrbitError};
use stickslip::orbit::periodic::NewtonOptions;
use stickslip::orbit::structure::Structure;
use stickslip::study::search::{coexisting, same_motion, search, starts, SearchOptions};

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
        assert!(
            (x - s.x).abs() < 1e-9 && (v - s.v).abs() < 1e-9,
            "state {i}: ({x}, {v}) vs {s:?}"
        );
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
    assert!(
        (x2 - x0.x).abs() < 1e-8 && (v2 - x0.v).abs() < 1e-8,
        "({x2}, {v2}) vs {x0:?}"
    );
    assert!(
        (x1 - x0.x).abs().max((v1 - x0.v).abs()) > 1e-4,
        "({x1}, {v1}) vs {x0:?}"
    );
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

/// The stable motions at the bistable point.
fn bistable_three(sim: &Simulator<Paper>) -> Vec<(usize, Motion)> {
    vec![
        (0, motion(sim, STICKY, 1)),
        (1, motion(sim, PASSING, 1)),
        (2, motion(sim, DOUBLED, 2)),
    ]
}

#[test]
fn with_everything_known_nothing_is_new_and_starts_stop_early() {
    // At W = 3.7 one stable motion, isolated: starts stop at least 2.5
    // times sooner than plain settling (a certificate needs a whole cycle
    // followed in the motion's linear regime, where plain settling needs the
    // cycle repeated to 1e-4 and then Newton). At the bistable point three
    // motions lie within 3e-4 of their size of one another and near
    // transitions, so their reaches are small and starts stop only 1.5 times
    // sooner (but skip Newton and the checks).
    let at_37 = sim_at(3.7);
    let rest = attractor::find(
        &at_37,
        at_37.start(0.0, 0.0, 0.0).expect("rest"),
        AttractorOptions::default(),
    );
    let Ok(Attractor::Periodic(only)) = rest else {
        panic!("W = 3.7 from rest: {rest:?}");
    };
    let bistable = sim_at(W_BISTABLE);
    let cases = [
        (at_37, vec![(0, only)], 2.5),
        (bistable.clone(), bistable_three(&bistable), 1.5),
    ];
    let opts = SearchOptions::default();
    for (sim, all, ratio) in cases {
        let known = search(&sim, &all, &opts);
        let none = search(&sim, &[], &opts);
        // The same starts settled one by one with nothing known (no stop, no
        // learning): the periods `attractor::find` needs.
        let (plain, _) = plain_settling(&sim, &all, &opts);
        let w = sim.oscillator().frequency;
        eprintln!(
            "W = {w}: all known {:?}\n  none known {:?}\n  plain settling {plain} periods",
            known.stats, none.stats
        );
        assert!(known.motions.is_empty(), "{:#?}", known.motions);
        assert!(
            known.stats.stopped_known * 4 >= 3 * opts.starts,
            "{:?}",
            known.stats
        );
        assert!(
            known.stats.periods as f64 * ratio < plain as f64,
            "W = {w}: {:?} vs {plain}",
            known.stats
        );
        // With nothing known the search finds a stable motion from rest and
        // the other starts stop on it: the last one known here among them.
        let last = &all[all.len() - 1].1;
        assert!(
            none.motions.iter().any(|m| same_motion(m, last, 1e-6)),
            "{:#?}",
            none.motions
        );
        assert!(
            none.stats.stopped_found * 4 >= 3 * opts.starts,
            "{:?}",
            none.stats
        );
    }
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

/// The three stable motions of the bistable window lie within `3e-4` of
/// their length scale of one another, and the period-2 motion alternates
/// between the two period-1 motions' structures: a start a short way off
/// each motion's stroboscopic state, towards another motion's, is
/// certified to go where a plain simulation (no stop) goes, never to a
/// neighbour because it passes close to it.
#[test]
fn close_motions_certify_only_their_own_starts() {
    let sim = sim_at(W_BISTABLE);
    let all = bistable_three(&sim);
    let known = KnownMotions::from_motions(&sim, &all, 0.0);
    let empty = KnownMotions::new(&sim, 0.0);
    let mut certified = 0;
    for (a, ma) in &all {
        assert!(known.certifies(*a), "{a}");
        for (b, _) in &all {
            if a == b {
                continue;
            }
            for sa in known.states(*a).unwrap() {
                for sb in known.states(*b).unwrap() {
                    for t in [1e-3, 0.1, 0.5] {
                        let (x, v) = (sa.x + t * (sb.x - sa.x), sa.v + t * (sb.v - sa.v));
                        let start = sim.start(x, v, 0.0).expect("start");
                        let stop = settle(&sim, &known, start, AttractorOptions::default());
                        let plain = settle(&sim, &empty, start, AttractorOptions::default());
                        let Ok(Settled::Attractor(found)) = plain.outcome else {
                            panic!("{:?}", plain.outcome);
                        };
                        let Attractor::Periodic(truth) = *found else {
                            panic!("{found:?}");
                        };
                        match stop.outcome {
                            Ok(Settled::Known(id)) => {
                                certified += 1;
                                let (_, m) = all.iter().find(|(i, _)| *i == id).unwrap();
                                assert!(
                                    same_motion(m, &truth, 1e-6),
                                    "from {a} towards {b} ({t}): certified {id}, goes to {}",
                                    truth.structure.notation(Paper::INFO)
                                );
                            }
                            Ok(Settled::Attractor(other)) => {
                                let Attractor::Periodic(o) = *other else {
                                    panic!("{other:?}");
                                };
                                assert!(same_motion(&o, &truth, 1e-6));
                            }
                            Err(e) => panic!("{e}"),
                        }
                        if t == 1e-3 && same_motion(ma, &truth, 1e-6) {
                            assert!(
                                stop.periods < plain.periods,
                                "{a}: {} vs {}",
                                stop.periods,
                                plain.periods
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(certified > 0);
}

/// Stable motions at `w`: everything a no-known search and rest reach.
fn stable_motions(sim: &Simulator<Paper>) -> Vec<(usize, Motion)> {
    let mut all = search(sim, &[], &SearchOptions::default()).motions;
    if let Ok(Attractor::Periodic(m)) = attractor::find(
        sim,
        sim.start(0.0, 0.0, 0.0).expect("rest"),
        AttractorOptions::default(),
    ) {
        if m.stability.is_some_and(|s| s.is_stable())
            && !all.iter().any(|a| same_motion(a, &m, 1e-6))
        {
            all.push(m);
        }
    }
    all.into_iter().enumerate().collect()
}

/// Periods that settling each start with nothing known (plain
/// `attractor::find`, no stop, no learning) takes, and the time.
fn plain_settling(
    sim: &Simulator<Paper>,
    all: &[(usize, Motion)],
    opts: &SearchOptions,
) -> (u64, f64) {
    let empty = KnownMotions::new(sim, 0.0);
    let table = KnownMotions::from_motions(sim, all, 0.0);
    let t = cpu_seconds();
    let mut plain = 0u64;
    for (x, v) in starts(sim, &table, opts.starts, opts.margin) {
        let start = sim.start(x, v, 0.0).expect("start");
        plain += u64::from(settle(sim, &empty, start, opts.attractor).periods);
    }
    (plain, cpu_seconds() - t)
}

/// CPU time of this thread, in seconds (the machine may be shared: wall
/// time would count the other processes' turns).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// The mean CPU time of `f`, in seconds, over enough repetitions to fill a
/// fifth of a second (the kernel's accounting has a coarse tick).
fn best_of<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let t = cpu_seconds();
    let mut reps = 0u32;
    loop {
        let out = f();
        reps += 1;
        let spent = cpu_seconds() - t;
        if spent >= 0.2 || reps >= 10_000 {
            return (spent / f64::from(reps), out);
        }
    }
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
            .map(|(_, m)| {
                format!(
                    "{}^{}",
                    m.structure.notation(Paper::INFO),
                    m.structure.periods()
                )
            })
            .collect();
        // The raw simulation: 200 periods from rest.
        let (dt, events) = best_of(|| {
            let mut events = 0usize;
            let start = sim.start(0.0, 0.0, 0.0).expect("rest");
            sim.run(start, 200.0 * TAU, |e| {
                if e.kind != EventKind::Graze {
                    events += 1
                }
            })
            .expect("runs");
            events
        });
        eprintln!(
            "W = {w}: stable {}; simulation {:.1} events/period, {:.2} us/period, {:.2} us/event",
            names.join(", "),
            events as f64 / 200.0,
            dt * 1e6 / 200.0,
            dt * 1e6 / events as f64
        );
        for k in [4, 8, 16, 32] {
            let opts = SearchOptions {
                starts: k,
                ..SearchOptions::default()
            };
            let (tp, plain) = best_of(|| plain_settling(&sim, &known, &opts));
            eprintln!(
                "  K = {k:<3} plain find per start: {:8.1} us, periods {:5}",
                tp * 1e6,
                plain.0
            );
            for (label, given) in [("known", &known[..]), ("none", &[][..])] {
                let (dt, found) = best_of(|| search(&sim, given, &opts));
                let s = found.stats;
                eprintln!(
                    "  K = {k:<3} {label:<5}: {:8.1} us  periods {:5}  (stopped {} + {}, matched {}, new {}, other {}, failed {})",
                    dt * 1e6,
                    s.periods,
                    s.stopped_known,
                    s.stopped_found,
                    s.matched,
                    s.new,
                    s.other,
                    s.failed,
                );
            }
        }
    }
}

/// Where the period-2 motion lives (run with `--ignored --nocapture`).
#[test]
#[ignore]
fn period_two_window() {
    for i in 0..=30 {
        let w = 3.9475 + 1.5e-3 * f64::from(i) / 30.0;
        let sim = sim_at(w);
        let opts = SearchOptions {
            starts: 32,
            ..SearchOptions::default()
        };
        let found = search(&sim, &[], &opts);
        let names: Vec<String> = found
            .motions
            .iter()
            .map(|m| m.structure.notation(Paper::INFO))
            .collect();
        eprintln!("W = {w:.5}: {}  {:?}", names.join(" + "), found.stats);
    }
}

/// Per start: where plain settling lands, and where the stop says.
#[test]
#[ignore]
fn stops_agree_with_plain_settling() {
    for w in [3.948, W_BISTABLE, 3.9485] {
        let sim = sim_at(w);
        let opts = SearchOptions {
            starts: 32,
            ..SearchOptions::default()
        };
        let all = stable_motions_plain(&sim, &opts);
        let table = KnownMotions::from_motions(&sim, &all, 0.0);
        let empty = KnownMotions::new(&sim, 0.0);
        let mut wrong = 0;
        for (x, v) in starts(&sim, &table, opts.starts, opts.margin) {
            let start = sim.start(x, v, 0.0).expect("start");
            let plain = settle(&sim, &empty, start, opts.attractor);
            let Some(p) = periodic(plain.outcome) else {
                continue;
            };
            let truth = all
                .iter()
                .find(|(_, m)| same_motion(m, &p, 1e-6))
                .map(|(i, _)| *i);
            let stop = settle(&sim, &table, start, opts.attractor);
            let said = match stop.outcome {
                Ok(Settled::Known(i)) => Some(i),
                _ => None,
            };
            if truth != said {
                wrong += 1;
            }
            eprintln!(
                "W = {w}: ({x:.3}, {v:.3}) plain {truth:?} in {} / stop {said:?} in {}",
                plain.periods, stop.periods
            );
        }
        eprintln!("W = {w}: {} motions, {wrong} wrong", all.len());
    }
}

/// Every stable motion plain settling reaches from the starts.
fn stable_motions_plain(sim: &Simulator<Paper>, opts: &SearchOptions) -> Vec<(usize, Motion)> {
    let empty = KnownMotions::new(sim, 0.0);
    let mut all: Vec<Motion> = Vec::new();
    for (x, v) in starts(sim, &empty, opts.starts, opts.margin) {
        let start = sim.start(x, v, 0.0).expect("start");
        if let Some(m) = periodic(settle(sim, &empty, start, opts.attractor).outcome) {
            if !all.iter().any(|a| same_motion(a, &m, 1e-6)) {
                all.push(m);
            }
        }
    }
    all.into_iter().enumerate().collect()
}

/// The periodic motion a settling found, if that is what it found.
fn periodic(outcome: Result<Settled, OrbitError>) -> Option<Motion> {
    match outcome {
        Ok(Settled::Attractor(a)) => match *a {
            Attractor::Periodic(m) => Some(m),
            _ => None,
        },
        _ => None,
    }
}
