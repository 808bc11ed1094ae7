//! The Rust side of the Python package's overhead: exactly the work of
//! `stickslip._native.simulate("paper", [("W", 5), ("Q0", 70)], (0, 0, 0))`
//! — the model chosen by name, the parameters checked from pairs,
//! `output::settled::settle` from rest, the title and the JSON report — and
//! of `Motion.history()` (400 samples per forcing period, as columns), with
//! no Python around them. `benches/python-overhead.sh` times the same calls
//! from Python and prints the ratio.
//!
//! `cargo bench --bench python_call`; results in benches/README.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models;
use stickslip::orbit::attractor::AttractorOptions;
use stickslip::output::history::History;
use stickslip::output::settled::{settle, Settled, Window};
use stickslip::{Model, ModelVisitor, ParamSet};

/// `(json, failure, title)`: what `_native.simulate` hands to Python, but
/// its trajectory object.
type Answer = (String, Option<String>, String);

/// `_native.simulate`'s work with model `M`.
fn simulate<M: Model>(base: M::Params, pairs: &[(&str, f64)], start: (f64, f64, f64)) -> Answer {
    let p = base
        .with_pairs(M::identity(&base), pairs)
        .expect("valid parameters");
    let sim = Simulator::<M>::new(p, SimOptions::default()).expect("a simulator");
    let settled = settle(&sim, start, AttractorOptions::default()).expect("settles");
    let settings: Vec<String> = pairs.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    let title = settled.title(sim.info().name, &settings.join(", "));
    (settled.report.to_json(), settled.report.failure(), title)
}

/// The columns `t, Wt, x, v, a, F, domain` of one cycle, as
/// `Motion.history(periods=1, samples=400)` builds them.
type Columns = (
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<f64>,
    Vec<i64>,
);

fn columns<M: Model>(sim: &Simulator<M>, settled: &Settled, per_period: usize) -> Columns {
    let Window::Motion(m) = &settled.window else {
        panic!("W = 5 settles to a periodic motion");
    };
    let history = History::of_motion(sim, m, per_period);
    let w = sim.oscillator().frequency;
    let n = history.samples().count();
    let mut c: Columns = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    // The first (and, for one period, only) repeat of the cycle.
    let dphase = black_box(0.0);
    for s in history.samples() {
        c.0.push(s.t + dphase / w);
        c.1.push(s.phase + dphase);
        c.2.push(s.x);
        c.3.push(s.v);
        c.4.push(s.a);
        c.5.push(s.friction);
        c.6.push(i64::from(s.domain));
    }
    c
}

/// The model by name, as `_native`'s `with_model` picks it.
struct Simulate<'a> {
    pairs: &'a [(&'a str, f64)],
    start: (f64, f64, f64),
}

impl ModelVisitor for Simulate<'_> {
    type Output = Answer;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Answer> {
        Some(simulate::<M>(base, self.pairs, self.start))
    }
}

fn benches(c: &mut Criterion) {
    let pairs = [("W", 5.0), ("Q0", 70.0)];
    let run = |name: &str| {
        let visitor = Simulate {
            pairs: black_box(&pairs),
            start: black_box((0.0, 0.0, 0.0)),
        };
        models::visit(black_box(name), visitor).expect("paper is compiled in")
    };
    // Outside timing: it settles to the reference six-mapping motion.
    let (json, failure, _) = run("paper");
    assert!(failure.is_none(), "{failure:?}");
    assert!(json.contains("P_{3_31 1_12 2_22 1_21 3_13 4_33}"), "{json}");

    let p = models::paper::Params {
        W: 5.0,
        Q0: 70.0,
        ..models::paper::Params::default()
    };
    let sim = Simulator::<models::paper::Paper>::new(p, SimOptions::default()).expect("sim");
    let settled = settle(&sim, (0.0, 0.0, 0.0), AttractorOptions::default()).expect("settles");
    assert!(columns(&sim, &settled, 400).0.len() >= 400);

    let mut g = c.benchmark_group("python_call");
    // Timed as Python's timeit is in python-overhead.sh: 15 batches of equal
    // size, about 0.2 s each.
    g.sampling_mode(SamplingMode::Flat);
    g.sample_size(15);
    g.warm_up_time(Duration::from_secs(1));
    g.measurement_time(Duration::from_secs(3));
    g.bench_function("simulate_w5", |b| b.iter(|| run("paper")));
    g.bench_function("history_w5", |b| {
        b.iter(|| columns(black_box(&sim), black_box(&settled), black_box(400)))
    });
    g.finish();
}

criterion_group!(group, benches);
criterion_main!(group);
