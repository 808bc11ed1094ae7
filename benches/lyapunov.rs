//! Lyapunov exponents: 10^5 forcing periods of the exact tangent map with
//! QR re-orthonormalisation (target under a second).
//!
//! `cargo bench --bench lyapunov`; results in benches/README.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{self, Paper};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::lyapunov::{spectrum, LyapunovOptions};

const OPTS: LyapunovOptions = LyapunovOptions {
    transient: 0,
    periods: 100_000,
};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("lyapunov_1e5_periods");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    // The chaotic case of tests/lyapunov.rs: eight domains, a stick every period.
    let p = stribeck8::Params {
        W: 2.38,
        Q0: 3.0,
        ..stribeck8::Params::default()
    };
    let sim = Simulator::<Stribeck8>::new(p, SimOptions::default()).expect("valid");
    g.bench_function("stribeck8_chaotic", |b| {
        b.iter(|| spectrum(&sim, black_box((0.1, 0.0, 0.0)), OPTS).expect("spectrum"))
    });
    // The paper's slip-only motion at W = 5 (six switchings per period).
    let p = paper::Params {
        W: 5.0,
        Q0: 70.0,
        ..paper::Params::default()
    };
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid");
    g.bench_function("paper_periodic_w5", |b| {
        b.iter(|| spectrum(&sim, black_box((0.1, 0.0, 0.0)), OPTS).expect("spectrum"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
