//! Periodic motions: how long a Newton solve, a simulation and a cold-start
//! attractor search take on the paper model at Q0 = 70.
//!
//! `cargo bench --bench periodic`; results in benches/README.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::{self, AttractorOptions};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};
use stickslip::orbit::structure::Structure;

/// The reference six-mapping motion at W = 5, Q0 = 70 (../shared/reference).
const W5: [(f64, f64); 6] = [
    (0.44978275444676297, 2.3444143268199222),
    (3.845154388424461, -2.3096270701834074),
    (3.966288968452073, -2.255080621936518),
    (4.108275319339592, -2.148470024813479),
    (6.462410323345743, 2.183586772560424),
    (6.591544731401805, 2.280615346848513),
];

fn guess() -> Vec<SwitchingPoint> {
    W5.iter()
        .enumerate()
        .map(|(k, &(phase, x))| {
            let s = if k % 2 == 0 { 1.0 } else { -1.0 };
            SwitchingPoint {
                phase: phase + s * 1e-2,
                x: x - s * 1e-2,
            }
        })
        .collect()
}

fn benches(c: &mut Criterion) {
    let p = Params {
        W: 5.0,
        Q0: 70.0,
        ..Params::default()
    };
    let structure =
        Structure::parse(Paper::INFO, "P_{3_31 1_12 2_22 1_21 3_13 4_33}", 1).expect("structure");
    let mut solver = PeriodicSolver::<Paper>::new(structure.clone());
    // Sanity outside timing: the solve converges to the reference.
    let mut pts = guess();
    assert!(solver
        .solve(&p, &mut pts, NewtonOptions::default())
        .converged());
    assert!((pts[0].x - W5[0].1).abs() < 1e-9);

    let mut g = c.benchmark_group("periodic");
    g.measurement_time(Duration::from_secs(3));
    g.bench_function("newton_solve_w5_six_mappings", |b| {
        b.iter_batched_ref(
            guess,
            |pts| black_box(solver.solve(black_box(&p), pts, NewtonOptions::default())),
            criterion::BatchSize::SmallInput,
        )
    });
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("params");
    g.bench_function("newton_solve_checked_w5", |b| {
        b.iter(|| {
            black_box(solve(
                &sim,
                structure.clone(),
                guess(),
                NewtonOptions::default(),
            ))
        })
    });
    let start = sim.start(0.0, 0.0, 0.0).expect("start");
    let end = 100.0 * 2.0 * std::f64::consts::PI;
    g.bench_function("simulate_100_periods_w5", |b| {
        b.iter(|| {
            let mut n = 0usize;
            let seg = sim.run(black_box(start), end, |_| n += 1).expect("runs");
            black_box((seg, n))
        })
    });
    for w in [3.0, 3.7, 5.0] {
        let p = Params {
            W: w,
            Q0: 70.0,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("params");
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        g.bench_function(format!("cold_start_attractor_w{w}"), |b| {
            b.iter(|| {
                black_box(
                    attractor::find(&sim, start, AttractorOptions::default()).expect("settles"),
                )
            })
        });
    }
    g.finish();
}

criterion_group!(periodic, benches);
criterion_main!(periodic);
