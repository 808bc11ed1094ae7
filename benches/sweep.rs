//! Bifurcation sweeps: the 200-point W sweep of the paper model at Q0 = 70,
//! including the location of every transition and the simulations beyond
//! them, both directions. `cargo bench --bench sweep`; results in
//! benches/README.md (the 100 × 100 map is timed with the CLI, see there).

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use stickslip::models::paper::{Paper, Params};
use stickslip::study::sweep::{sweep, SweepOptions};

fn benches(c: &mut Criterion) {
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10).measurement_time(Duration::from_secs(10));
    g.bench_function("paper_w_0.2_9_200_points_q70", |b| {
        b.iter(|| {
            black_box(
                sweep::<Paper>(black_box(base), "W", 0.2, 9.0, 200, SweepOptions::default())
                    .expect("sweep"),
            )
        })
    });
    g.bench_function("paper_w_3.6_4.3_15_points_q70", |b| {
        b.iter(|| {
            black_box(
                sweep::<Paper>(black_box(base), "W", 3.6, 4.3, 15, SweepOptions::default())
                    .expect("sweep"),
            )
        })
    });
    g.finish();
}

criterion_group!(sweeps, benches);
criterion_main!(sweeps);
