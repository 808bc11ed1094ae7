//! The two back ends side by side: what loading a model file costs (parse,
//! check, expand, equations, Cranelift), and the hot paths with the loaded
//! model against the same model compiled in, in one run.
//!
//! `cargo bench --bench loaded`; the numbers are in the guide's chapter
//! "Models without a Rust build".

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::loaded::{load_file, routines::ROUTINES, Loaded, LoadedModel};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::{FrictionOscillator, Model, ParamSet};

/// The reference six-mapping motion at W = 5, Q0 = 70 (as `periodic`).
const W5: [(f64, f64); 6] = [
    (0.44978275444676297, 2.3444143268199222),
    (3.845154388424461, -2.3096270701834074),
    (3.966288968452073, -2.255080621936518),
    (4.108275319339592, -2.148470024813479),
    (6.462410323345743, 2.183586772560424),
    (6.591544731401805, 2.280615346848513),
];

const STRUCTURE: &str = "P_{3_31 1_12 2_22 1_21 3_13 4_33}";

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

/// `newton/BACK_END` and `checked/BACK_END` for model `M` at `p`.
fn hot_paths<M: Model>(
    g: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    back_end: &str,
    p: M::Params,
) {
    let structure = Structure::parse(M::info(&p), STRUCTURE, 1).expect("structure");
    let mut solver = PeriodicSolver::<M>::new(structure.clone());
    // Outside timing: the solve converges to the reference.
    let mut pts = guess();
    assert!(solver
        .solve(&p, &mut pts, NewtonOptions::default())
        .converged());
    assert!((pts[0].x - W5[0].1).abs() < 1e-9);
    g.bench_function(format!("newton_solve_w5_six_mappings/{back_end}"), |b| {
        b.iter_batched_ref(
            guess,
            |pts| black_box(solver.solve(black_box(&p), pts, NewtonOptions::default())),
            criterion::BatchSize::SmallInput,
        )
    });
    let sim = Simulator::<M>::new(p, SimOptions::default()).expect("params");
    g.bench_function(format!("newton_solve_checked_w5/{back_end}"), |b| {
        b.iter(|| {
            black_box(solve(
                &sim,
                structure.clone(),
                guess(),
                NewtonOptions::default(),
            ))
        })
    });
}

fn benches(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/paper.ssm");
    let text = std::fs::read_to_string(&path).expect("models/paper.ssm");

    let mut g = c.benchmark_group("load");
    g.measurement_time(Duration::from_secs(5));
    // Everything a first load does but keep the result: read nothing, the
    // text in memory; parse, check, expand, equations, Cranelift. The
    // machine code is freed after each iteration.
    for scene in [None, Some("sweep_w")] {
        let name = format!("paper{}", scene.map_or(String::new(), |s| format!("::{s}")));
        g.bench_function(name, |b| {
            b.iter(|| {
                let compiled = stickslip_codegen::jit::compile_text(
                    black_box(&text),
                    "models/paper.ssm",
                    Some("paper"),
                    scene,
                    &ROUTINES,
                );
                black_box(compiled.is_ok())
            })
        });
    }
    g.finish();

    let mut g = c.benchmark_group("loaded");
    g.measurement_time(Duration::from_secs(3));
    let compiled = Params {
        W: 5.0,
        Q0: 70.0,
        ..Params::default()
    };
    hot_paths::<Paper>(&mut g, "compiled", compiled);
    let LoadedModel::Piecewise(base) = load_file(&path, None).expect("paper loads") else {
        panic!("paper is piecewise")
    };
    let loaded = base
        .with_pairs(Loaded::identity(&base), &[("W", 5.0), ("Q0", 70.0)])
        .expect("W = 5, Q0 = 70");
    hot_paths::<Loaded>(&mut g, "loaded", loaded);
    g.finish();
}

criterion_group!(loaded, benches);
criterion_main!(loaded);
