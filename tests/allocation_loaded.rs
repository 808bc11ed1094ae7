//! A model loaded at run time allocates nothing on the hot paths either,
//! counted by a global allocator: every mapping's residual and Jacobian,
//! flows, vector fields, coefficients, stick forces and the parameter check
//! of `models/paper.ssm` compiled to machine code; a converging Newton solve
//! of the reference six-mapping motion; event-driven simulation through
//! domains and stick. The load itself allocates (once, outside the counts).
//!
//! The count is kept per thread, so tests running in parallel (the test
//! harness's own threads) cannot disturb each other's counts.

mod common;

use std::path::Path;

use common::counting::{allocations, Counting};
use stickslip::dynamics::simulate::{Location, SimOptions, Simulator};
use stickslip::model::loaded::{load_file, Loaded, LoadedModel, LoadedParams};
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::{FrictionOscillator, Model, ParamSet};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// `models/paper.ssm`, loaded, at `W` and `Q0 = 70`.
fn paper(w: f64) -> LoadedParams {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/paper.ssm");
    let LoadedModel::Piecewise(base) = load_file(&path, None).expect("paper loads") else {
        panic!("paper is piecewise")
    };
    base.with_pairs(Loaded::identity(&base), &[("W", w), ("Q0", 70.0)])
        .expect("valid")
}

#[test]
fn every_function_of_a_loaded_model_allocates_nothing() {
    let p = paper(3.7);
    let info = Loaded::info(&p);
    let (n, sink) = allocations(|| {
        let mut sink = 0.0;
        for k in 0..100 {
            let phi1 = 5.0 + 0.01 * k as f64;
            for idx in 0..info.mappings.len() {
                let e = Loaded::mapping(&p, idx, 0.3, 4.9, 0.8, phi1);
                sink += e.residual[0] + e.d_prev[(1, 1)] + e.d_next[(0, 1)];
                sink += Loaded::residual(&p, idx, 0.3, 4.9, 0.8, phi1)[1];
            }
            for j in 0..info.domains.len() {
                sink += Loaded::flow(&p, j, 0.3, 2.0, 4.9, phi1)[0];
                sink += Loaded::normal_field(&p, j, 0.3, 2.0, phi1)[1];
                sink += Loaded::coefficients(&p, j).b;
            }
            for b in 0..info.boundaries.len() {
                sink += Loaded::boundary_velocity(&p, b);
            }
            sink += Loaded::stick_forces(&p, 0.3, phi1).map_or(0.0, |f| f.input_above);
            sink += Loaded::oscillator(&p).amplitude;
            sink += f64::from(u8::from(p.check().is_ok()));
        }
        sink
    });
    assert!(sink.is_finite());
    assert_eq!(n, 0, "{n} allocations in the loaded model's functions");
}

#[test]
fn a_newton_solve_and_a_simulation_with_a_loaded_model_allocate_nothing() {
    let p = paper(5.0);
    let structure = Structure::parse(Loaded::info(&p), "P_{3_31 1_12 2_22 1_21 3_13 4_33}", 1)
        .expect("structure");
    let mut solver = PeriodicSolver::<Loaded>::new(structure);
    let mut points: Vec<SwitchingPoint> = [
        (0.46, 2.33),
        (3.83, -2.30),
        (3.98, -2.26),
        (4.10, -2.14),
        (6.47, 2.17),
        (6.58, 2.29),
    ]
    .iter()
    .map(|&(phase, x)| SwitchingPoint { phase, x })
    .collect();
    let (n, t) = allocations(|| solver.solve(&p, &mut points, NewtonOptions::default()));
    assert!(t.converged(), "{t:?}");
    assert_eq!(n, 0, "the Newton solve allocated {n} times");

    for w in [3.7, 5.0] {
        let sim = Simulator::<Loaded>::new(paper(w), SimOptions::default()).expect("valid");
        let mut seg = sim.start(0.0, 0.0, 0.0).expect("start");
        let limit = 40.0 * std::f64::consts::TAU;
        let mut stick_steps = 0;
        loop {
            let location = seg.location;
            let (n, next) = allocations(|| sim.next_event(&seg, limit));
            assert_eq!(n, 0, "W = {w}: next_event from {seg:?} allocated {n} times");
            if location == Location::Stick {
                stick_steps += 1;
            }
            match next.expect("no simulation error") {
                Some((_, s)) => seg = s,
                None => break,
            }
        }
        if w == 3.7 {
            assert!(stick_steps > 10, "W = {w}: {stick_steps} stick steps");
        }
    }
}

#[test]
fn the_counter_counts() {
    // The checks above can fail: an allocation on this thread is seen.
    let (n, v) = allocations(|| vec![1.0f64; 16]);
    assert!(n > 0);
    drop(v);
}
