//! The hot paths allocate nothing: a counting global allocator around
//! residual + Jacobian evaluations of every mapping, flows, vector fields and
//! stick forces.

mod common;

use common::counting::{allocated, Counting};
use stickslip::models::paper::{Paper, Params};
use stickslip::Model;

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn residuals_jacobians_and_flows_allocate_nothing() {
    let p = Params {
        W: 3.7,
        ..Params::default()
    };
    let n_mappings = Paper::INFO.mappings.len();
    let n_domains = Paper::INFO.domains.len();
    let before = allocated();
    let mut sink = 0.0;
    for k in 0..100 {
        let phi1 = 5.0 + 0.01 * k as f64;
        for idx in 0..n_mappings {
            let e = Paper::mapping(&p, idx, 0.3, 4.9, 0.8, phi1);
            sink += e.residual[0] + e.d_prev[(1, 1)] + e.d_next[(0, 1)];
            sink += Paper::residual(&p, idx, 0.3, 4.9, 0.8, phi1)[1];
            sink += e.local_jacobian().map_or(0.0, |m| m[(0, 0)]);
        }
        for j in 0..n_domains {
            sink += Paper::flow(&p, j, 0.3, 2.0, 4.9, phi1)[0];
            sink += Paper::normal_field(&p, j, 0.3, 2.0, phi1)[1];
            sink += Paper::coefficients(&p, j).b;
        }
        sink += Paper::stick_forces(&p, 0.3, phi1).map_or(0.0, |f| f.input_above);
    }
    let after = allocated();
    assert!(sink.is_finite());
    assert_eq!(
        after - before,
        0,
        "{} allocations in the hot path",
        after - before
    );
}

#[test]
fn the_counter_counts() {
    // The check above can fail: an allocation is seen.
    let before = allocated();
    let v: Vec<f64> = std::hint::black_box(vec![1.0; 16]);
    assert!(allocated() > before);
    drop(v);
}
