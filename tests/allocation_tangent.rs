//! Carrying the exact tangent map along the simulation
//! (`dynamics::tangent::advance`) allocates nothing: over forcing periods
//! with passes, sticks and eight domains, counted by a global allocator.

mod common;

use common::counting::{allocations, Counting};
use nalgebra::Matrix2;
use stickslip::dynamics::simulate::{EventKind, SimOptions, Simulator};
use stickslip::dynamics::tangent::{advance, Tangent};
use stickslip::models::paper::{self, Paper};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::Model;

#[global_allocator]
static GLOBAL: Counting = Counting;

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn check<M: Model>(sim: &Simulator<M>, what: &str) -> Vec<EventKind> {
    let mut seg = sim.start(0.1, 0.0, 0.0).expect("start");
    let mut kinds = [0usize; 4];
    for k in 1..=50 {
        let mut t = Tangent::new(Matrix2::identity());
        let (n, next) = allocations(|| {
            advance(sim, seg, k as f64 * TAU, &mut t, |e| {
                kinds[e.kind as usize] += 1;
            })
        });
        assert_eq!(n, 0, "{what}: a tangent period allocated {n} times");
        seg = next.expect("simulation");
    }
    [
        EventKind::Pass,
        EventKind::StickOnset,
        EventKind::StickEnd,
        EventKind::Graze,
    ]
    .into_iter()
    .zip(kinds)
    .filter(|&(_, n)| n > 0)
    .map(|(k, _)| k)
    .collect()
}

#[test]
fn tangent_periods_allocate_nothing() {
    let p = paper::Params {
        W: 3.7,
        Q0: 70.0,
        ..paper::Params::default()
    };
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid");
    let seen = check(&sim, "paper W = 3.7");
    assert!(seen.contains(&EventKind::StickOnset), "{seen:?}");
    let p = stribeck8::Params {
        W: 2.38,
        Q0: 3.0,
        ..stribeck8::Params::default()
    };
    let sim = Simulator::<Stribeck8>::new(p, SimOptions::default()).expect("valid");
    let seen = check(&sim, "stribeck8 W = 2.38");
    assert!(
        seen.contains(&EventKind::Pass) && seen.contains(&EventKind::StickEnd),
        "{seen:?}"
    );
}
