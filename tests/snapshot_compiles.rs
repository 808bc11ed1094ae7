//! The checked-in snapshots of the generated code compile as they are and
//! compute what the built-in models compute.

/// A snapshot as a module, under the lints a generated module is allowed
/// (the generator's list, `emit::registry::module_lints`, plus `dead_code`:
/// nothing calls the snapshot's free functions).
macro_rules! snapshot {
    ($module:ident, $file:literal) => {
        #[allow(
            non_snake_case,
            clippy::excessive_precision,
            clippy::approx_constant,
            clippy::redundant_field_names,
            clippy::single_match,
            dead_code
        )]
        mod $module {
            include!($file);
        }
    };
}

snapshot!(snapshot, "snapshots/paper.rs");
snapshot!(coulomb_snapshot, "snapshots/coulomb.rs");

use stickslip::Model;

/// Every mapping of `A` (built in) and `B` (its snapshot) at a few points,
/// bit for bit, and the same description.
fn agree<A: Model, B: Model>(p: &A::Params, q: &B::Params) {
    assert_eq!(A::info(p).name, B::info(q).name);
    assert_eq!(A::info(p).mappings.len(), B::info(q).mappings.len());
    assert_eq!(A::identity(p).params.len(), B::identity(q).params.len());
    assert_eq!(A::oscillator(p).frequency, B::oscillator(q).frequency);
    for idx in 0..A::info(p).mappings.len() {
        for (x0, phi0, x1, phi1) in [(0.1, 0.2, 0.3, 1.9), (-0.4, 1.0, 0.7, 4.0)] {
            let a = A::mapping(p, idx, x0, phi0, x1, phi1);
            let b = B::mapping(q, idx, x0, phi0, x1, phi1);
            // Debug prints every digit, and NaN equal to NaN.
            assert_eq!(
                format!("{a:?}"),
                format!("{b:?}"),
                "{} mapping {idx}",
                A::info(p).name
            );
        }
    }
}

#[test]
fn snapshot_compiles_and_agrees_with_the_built_model() {
    agree::<stickslip::models::paper::Paper, snapshot::Paper>(
        &Default::default(),
        &Default::default(),
    );
}

#[test]
fn coulomb_snapshot_compiles_and_agrees_with_the_built_model() {
    agree::<stickslip::models::coulomb::Coulomb, coulomb_snapshot::Coulomb>(
        &Default::default(),
        &Default::default(),
    );
}
