//! A simulation started on a Newton solution returns to it after one cycle.
//!
//! For every reference motion of `../shared/reference/orbits.json`, the
//! structure is solved by `motion::solve` from the reference points; the
//! event-driven simulator is then started at switching point 0 (on the first
//! mapping's start boundary, in the first mapping's domain) and run for
//! `2πN`. Checked: (a) the events follow the structure's mappings in order
//! (`attractor::mapping_between`), no graze; (b) every event lies on the
//! corresponding switching point within 1e-10 in phase and in x; (c) the
//! return point is point 0 shifted by `2πN`, within 1e-10.

mod common;

use common::reference::{references, segment_for};
use stickslip::dynamics::simulate::{Event, EventKind, Segment};
use stickslip::models::paper::Paper;
use stickslip::orbit::attractor::mapping_between;
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};

const TAU: f64 = 2.0 * std::f64::consts::PI;
const TOL: f64 = 1e-10;

/// A pseudo-event standing for the start of mapping `idx` at `seg`, so that
/// `mapping_between(start, first event)` names the first mapping.
fn start_event(idx: usize, seg: &Segment) -> Event {
    let mi = Paper::INFO.mappings[idx];
    Event {
        phase: seg.phase,
        x: seg.x,
        v: seg.v,
        boundary: mi.from,
        kind: EventKind::Pass,
        before: seg.location,
        after: seg.location,
    }
}

#[test]
fn simulation_from_a_newton_solution_returns_to_it() {
    let info = Paper::INFO;
    let refs = references();
    assert!(
        refs.len() >= 3,
        "the reference file lists the three motions"
    );
    let mut worst = 0.0f64;
    for r in &refs {
        let sim = r.simulator();
        let structure = r.structure();
        let names: Vec<&str> = structure
            .steps()
            .iter()
            .map(|&i| info.mappings[i].name)
            .collect();
        assert_eq!(names, r.mappings, "{}: application order", r.structure);
        let motion = solve(
            &sim,
            structure.clone(),
            r.points.clone(),
            NewtonOptions::default(),
        );
        assert!(
            motion.is_admissible(),
            "{}: {:?} {:?}",
            r.structure,
            motion.termination,
            motion.violations
        );
        let pts = &motion.points;
        let m = pts.len();
        let shift = TAU * r.periods as f64;
        let steps = structure.steps();

        let seg = segment_for(&sim, steps[0], pts[0]);
        let mut events = Vec::new();
        let end = pts[0].phase + shift + 1e-6;
        sim.run(seg, end, |e| events.push(*e))
            .unwrap_or_else(|e| panic!("{}: simulation failed: {e}", r.structure));
        assert!(
            events.iter().all(|e| e.kind != EventKind::Graze),
            "{}: a graze on a reference motion: {events:?}",
            r.structure
        );
        assert_eq!(
            events.len(),
            m,
            "{}: {} events in one cycle, the structure has {m} mappings: {events:?}",
            r.structure,
            events.len()
        );
        let mut prev = start_event(steps[0], &seg);
        for (k, e) in events.iter().enumerate() {
            // (a) the segment that ends at event k follows mapping k.
            let got = mapping_between(Paper::INFO, &prev, e);
            assert_eq!(
                got,
                Some(steps[k]),
                "{}: segment {k} follows {:?}, the structure says {}",
                r.structure,
                got.map(|i| info.mappings[i].name),
                info.mappings[steps[k]].name
            );
            // (b) event k is switching point k + 1 (point m = point 0 + 2πN).
            let want = if k + 1 < m {
                pts[k + 1]
            } else {
                SwitchingPoint {
                    phase: pts[0].phase + shift,
                    x: pts[0].x,
                }
            };
            let (dphi, dx) = ((e.phase - want.phase).abs(), (e.x - want.x).abs());
            worst = worst.max(dphi).max(dx);
            assert!(
                dphi < TOL && dx < TOL,
                "{}: event {k} at ({}, {}), switching point ({}, {}): deviation ({dphi:e}, {dx:e})",
                r.structure,
                e.phase,
                e.x,
                want.phase,
                want.x
            );
            assert_eq!(
                e.boundary, info.mappings[steps[k]].to,
                "{}: event {k} boundary",
                r.structure
            );
            prev = *e;
        }
        // (c) the return point.
        let last = events.last().expect("m >= 1 events");
        assert!(
            (last.phase - (pts[0].phase + shift)).abs() < TOL && (last.x - pts[0].x).abs() < TOL,
            "{}: returns to ({}, {}) instead of ({}, {})",
            r.structure,
            last.phase,
            last.x,
            pts[0].phase + shift,
            pts[0].x
        );
        // The Newton solution is the reference one (else the test proves little).
        for (a, b) in pts.iter().zip(&r.points) {
            assert!((a.phase - b.phase).abs() < 1e-9 && (a.x - b.x).abs() < 1e-9);
        }
    }
    eprintln!("worst deviation of a re-simulated switching point: {worst:e}");
}

/// The same check keeps holding over several cycles: each cycle starts from
/// the simulated return point, so deviations would accumulate if the
/// simulation drifted off the solution (the motions are stable, so they stay
/// bounded by the first cycle's).
#[test]
fn ten_cycles_stay_on_the_solution() {
    for r in references() {
        let sim = r.simulator();
        let structure = r.structure();
        let motion = solve(
            &sim,
            structure.clone(),
            r.points.clone(),
            NewtonOptions::default(),
        );
        let pts = &motion.points;
        let m = pts.len();
        let shift = TAU * r.periods as f64;
        let seg = segment_for(&sim, structure.steps()[0], pts[0]);
        let mut events = Vec::new();
        sim.run(seg, pts[0].phase + 10.0 * shift + 1e-6, |e| events.push(*e))
            .expect("simulation");
        assert_eq!(events.len(), 10 * m, "{}: {events:?}", r.structure);
        for (n, e) in events.iter().enumerate() {
            let (cycle, k) = ((n / m) as f64, (n + 1) % m);
            let want = pts[k].phase + shift * (cycle + if k == 0 { 1.0 } else { 0.0 });
            assert!(
                (e.phase - want).abs() < TOL * 10.0 && (e.x - pts[k].x).abs() < TOL * 10.0,
                "{}: event {n} at ({}, {}) vs ({want}, {})",
                r.structure,
                e.phase,
                e.x,
                pts[k].x
            );
        }
    }
}
