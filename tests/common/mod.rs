//! Shared by the integration tests: random parameter sets of the paper model
//! that put a chosen domain in a chosen damping regime, and the independent
//! references the tests compare with. Each reference is here once and is
//! written for the tests from the textbook, not copied from `src/` (a check
//! must not share the mistakes of the code it checks); `tests/references.rs`
//! tests them against closed-form solutions.
//!
//! * `dopri`: the Dormand–Prince 5(4) tableau as data, a generic stepper and
//!   its dense output.
//! * `events`: a reference simulation of a piecewise model with events and
//!   stick, on `dopri` and `roots`.
//! * `roots`: scanning and bisection.
//! * `taylor`: a Taylor-series integrator of one domain's ODE, its
//!   transition matrix, and the modal form for two real exponents.
//! * `graze`: near-grazing starts for the paper model (test inputs).
//! * `counting`: a counting global allocator for the allocation tests.
//! * `reference`: the reference periodic motions of `../shared/reference/`.
//! * `resimulate`: a periodic motion re-simulated by the library from its
//!   first switching point.
//! * `shaw`: Shaw's oscillator and the box the curves tests run on it.
//! * `cycle`: the mapping equations of a cycle of mappings at its switching
//!   points (a motion built by hand).
//! * `sweep_ends`: a sweep's branch ends as curve starts (phases unwrapped).
#![allow(dead_code)]

pub mod counting;
pub mod cycle;
pub mod dopri;
pub mod events;
pub mod graze;
pub mod reference;
pub mod resimulate;
pub mod roots;
pub mod shaw;
pub mod sweep_ends;
pub mod taylor;

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use stickslip::models::paper::{Paper, Params};
use stickslip::{Model, ParamSet};

/// The regimes the tests sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    Under,
    Over,
    Critical,
    NearCritical,
    Negative,
}

pub const TARGETS: [Target; 5] = [
    Target::Under,
    Target::Over,
    Target::Critical,
    Target::NearCritical,
    Target::Negative,
];

pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// Random paper parameters with domain `j` (index, lowest band first) in `target`.
pub fn params_for(rng: &mut StdRng, j: usize, target: Target) -> Params {
    let mut p = Params {
        m: rng.gen_range(1.0..10.0),
        c: rng.gen_range(0.5..40.0),
        mus: rng.gen_range(0.45..0.8),
        muk: rng.gen_range(0.1..0.4),
        mu1: rng.gen_range(0.0..0.5),
        mu2: rng.gen_range(0.0..0.5),
        mu3: rng.gen_range(0.0..0.5),
        mu4: rng.gen_range(0.0..0.5),
        Q0: rng.gen_range(5.0..100.0),
        W: rng.gen_range(0.5..8.0),
        d: 0.0,
        ..Params::default()
    };
    // d_j = d + s_j / 2; read s_j / 2 from the generated coefficients at d = 0.
    let half_slope = Paper::coefficients(&p, j).two_d / 2.0;
    let root = p.c.sqrt();
    let dj = match target {
        Target::Under => rng.gen_range(0.0..0.9) * root,
        Target::Over => rng.gen_range(1.1..3.0) * root,
        Target::Critical | Target::NearCritical => root,
        Target::Negative => -rng.gen_range(0.02..0.3) * root,
    };
    p.d = dj - half_slope;
    if target == Target::Critical {
        // Make d_j^2 - c exactly zero as the generated code computes it.
        let actual = Paper::coefficients(&p, j).two_d / 2.0;
        p.c = actual * actual;
    }
    if target == Target::NearCritical {
        let actual = Paper::coefficients(&p, j).two_d / 2.0;
        p.c = actual * actual * (1.0 + rng.gen_range(-1e-7..1e-7));
    }
    p
}

/// Central difference with one Richardson step: error O(h^4).
pub fn derivative(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    let d = |h: f64| (f(x + h) - f(x - h)) / (2.0 * h);
    (4.0 * d(h / 2.0) - d(h)) / 3.0
}

/// Parameter names of a model, for messages.
pub fn names<P: ParamSet>(p: &P) -> &'static [&'static str] {
    p.names()
}
