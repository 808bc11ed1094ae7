//! The documented allocation-free hot paths allocate nothing, counted by a
//! global allocator: after constructing a `PeriodicSolver` and a
//! `Simulator`, one Newton direction, one damped Newton step, a whole
//! converging Newton solve (and the residual and Poincaré-map Jacobian), and `Simulator::next_event` for
//! domain segments and for stick segments.
//!
//! The count is kept per thread, so tests running in parallel (the test
//! harness's own threads) cannot disturb each other's counts.

mod common;

use common::counting::{allocations, Counting};
use common::reference::references;
use stickslip::dynamics::simulate::{Location, SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::periodic::{
    monodromy_spectral, NewtonOptions, PeriodicSolver, SwitchingPoint,
};
use stickslip::orbit::structure::Structure;

#[global_allocator]
static GLOBAL: Counting = Counting;

fn params(w: f64) -> Params {
    Params {
        W: w,
        Q0: 70.0,
        ..Params::default()
    }
}

#[test]
fn newton_direction_and_step_allocate_nothing() {
    // The reference motions (SPEC reference cases, ../shared/reference).
    for case in references() {
        let (text, reference) = (&case.structure, &case.points);
        let p = params(case.w);
        assert_eq!(case.q0, p.Q0, "{text}");
        let structure = Structure::parse(Paper::INFO, text, case.periods).expect("structure");
        let mut solver = PeriodicSolver::<Paper>::new(structure);
        // A perturbed guess, so that the steps do real work (and backtrack).
        let mut points: Vec<SwitchingPoint> = reference
            .iter()
            .enumerate()
            .map(|(k, pt)| SwitchingPoint {
                phase: pt.phase + if k % 2 == 0 { 2e-2 } else { -2e-2 },
                x: pt.x - 1e-2,
            })
            .collect();
        let (n, dir) = allocations(|| solver.direction(&p, &points));
        assert!(dir.is_ok(), "{text}: {dir:?}");
        assert_eq!(
            n, 0,
            "{text}: PeriodicSolver::direction allocated {n} times"
        );
        let (n, r0) = allocations(|| solver.residual(&p, &points));
        assert_eq!(n, 0, "{text}: PeriodicSolver::residual allocated {n} times");
        let mut r = r0;
        for it in 0..8 {
            let (n, next) = allocations(|| solver.step(&p, &mut points, r));
            assert_eq!(
                n, 0,
                "{text}: PeriodicSolver::step (iteration {it}) allocated {n} times"
            );
            r = next.expect("a regular step");
        }
        assert!(
            r < 1e-10 && r < r0,
            "{text}: Newton converges ({r0:e} -> {r:e})"
        );
        // The whole solve, from a perturbed guess to convergence (the
        // scale-invariant stopping test included), allocates nothing.
        let mut guess: Vec<SwitchingPoint> = points
            .iter()
            .map(|q| SwitchingPoint {
                phase: q.phase + 1e-3,
                x: q.x * (1.0 + 1e-3),
            })
            .collect();
        let (n, t) = allocations(|| solver.solve(&p, &mut guess, NewtonOptions::default()));
        assert!(t.converged(), "{text}: {t:?}");
        assert_eq!(n, 0, "{text}: PeriodicSolver::solve allocated {n} times");
        let (n, dp) = allocations(|| solver.poincare_jacobian(&p, &points));
        assert!(dp.is_ok());
        assert_eq!(n, 0, "{text}: poincare_jacobian allocated {n} times");
        let shift = std::f64::consts::TAU * f64::from(case.periods);
        let steps = solver.structure().steps();
        let (n, dp) = allocations(|| monodromy_spectral::<Paper>(&p, steps, shift, &points));
        assert!(dp.is_ok());
        assert_eq!(n, 0, "{text}: monodromy_spectral allocated {n} times");
        // The error path too: a degenerate guess (all points equal) is singular
        // or not finite, and says so without allocating.
        let flat = vec![points[0]; points.len()];
        let (n, _) = allocations(|| solver.direction(&p, &flat));
        assert_eq!(
            n, 0,
            "{text}: direction on a degenerate guess allocated {n} times"
        );
    }
}

#[test]
fn next_event_allocates_nothing_in_domains_and_in_stick() {
    // W = 3.7: the steady motion sticks once per period; W = 5: every domain.
    for w in [3.7, 5.0, 3.0] {
        let sim = Simulator::<Paper>::new(params(w), SimOptions::default()).expect("valid");
        let mut seg = sim.start(0.0, 0.0, 0.0).expect("start");
        let limit = 60.0 * std::f64::consts::TAU;
        let (mut domain_steps, mut stick_steps) = (0usize, 0usize);
        loop {
            let location = seg.location;
            let (n, next) = allocations(|| sim.next_event(&seg, limit));
            assert_eq!(n, 0, "W = {w}: next_event from {seg:?} allocated {n} times");
            match location {
                Location::Domain(_) => domain_steps += 1,
                Location::Stick => stick_steps += 1,
            }
            match next.expect("no simulation error") {
                Some((_, s)) => seg = s,
                None => break,
            }
        }
        assert!(domain_steps > 20, "W = {w}: {domain_steps} domain steps");
        if w == 3.7 {
            assert!(stick_steps > 20, "W = {w}: {stick_steps} stick steps");
        }
        // A whole run through `run` with a non-allocating callback, too.
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        let mut events = 0usize;
        let (n, end) = allocations(|| sim.run(start, limit, |_| events += 1));
        assert!(end.is_ok());
        assert_eq!(n, 0, "W = {w}: Simulator::run allocated {n} times");
        assert!(events > 20);
    }
}

/// Newton on an autonomous structure (the undamped Coulomb belt
/// oscillator's stick-slip cycle, period unknown): the direction, a step
/// and a whole solve from a perturbed guess allocate nothing.
#[test]
fn newton_on_an_autonomous_cycle_allocates_nothing() {
    use stickslip::models::coulomb::{self, Coulomb};
    use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
    let p = coulomb::Params {
        Q0: 0.0,
        d: 0.0,
        V: 0.5,
        ..coulomb::Params::default()
    };
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("params");
    let start = sim.start(0.0, 0.5, 0.0).expect("start");
    let Ok(Attractor::Autonomous(cycle)) =
        attractor::find(&sim, start, AttractorOptions::default())
    else {
        panic!("the stick-slip cycle")
    };
    let structure = Structure::autonomous(sim.info(), &cycle.steps).expect("structure");
    assert!(structure.is_autonomous());
    let mut solver = PeriodicSolver::<Coulomb>::new(structure);
    let mut guess: Vec<SwitchingPoint> = cycle
        .points
        .iter()
        .map(|q| SwitchingPoint {
            phase: q.phase * 1.01,
            x: q.x * 1.01,
        })
        .collect();
    let (n, dir) = allocations(|| solver.direction(&p, &guess));
    assert!(dir.is_ok(), "{dir:?}");
    assert_eq!(n, 0, "direction allocated {n} times");
    let (n, t) = allocations(|| solver.solve(&p, &mut guess, NewtonOptions::default()));
    assert!(t.converged(), "{t:?}");
    assert_eq!(n, 0, "solve allocated {n} times");
    for (a, b) in guess.iter().zip(&cycle.points) {
        assert!((a.x - b.x).abs() <= 1e-12 && (a.phase - b.phase).abs() <= 1e-12);
    }
}

#[test]
fn the_counter_counts() {
    // The checks above can fail: an allocation on this thread is seen.
    let (n, v) = allocations(|| vec![1.0f64; 16]);
    assert!(n >= 1);
    drop(v);
    let sim = Simulator::<Paper>::new(params(3.7), SimOptions::default());
    let (n, _) = allocations(|| Simulator::<Paper>::new(params(3.7), SimOptions::default()));
    assert!(n >= 1, "constructing a simulator allocates its tables");
    drop(sim);
}
