//! The checked-in snapshot of the generated code compiles as it is and
//! computes what the built-in model computes.

#[allow(
    non_snake_case,
    clippy::excessive_precision,
    clippy::approx_constant,
    clippy::redundant_field_names,
    clippy::single_match,
    dead_code
)]
mod snapshot {
    include!("snapshots/paper.rs");
}

use stickslip::Model;

#[test]
fn snapshot_compiles_and_agrees_with_the_built_model() {
    let p = stickslip::models::paper::Params::default();
    let q = snapshot::Params::default();
    for idx in 0..stickslip::models::paper::Paper::INFO.mappings.len() {
        let a = stickslip::models::paper::Paper::mapping(&p, idx, 0.1, 0.2, 0.3, 1.9);
        let b = snapshot::Paper::mapping(&q, idx, 0.1, 0.2, 0.3, 1.9);
        assert_eq!(a, b);
    }
}
