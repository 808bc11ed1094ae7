//! Sweeps along W at Q0 = 70 (SPEC §9): the two transitions listed in
//! `../shared/reference/README.md` located within 1e-8, and every reported
//! motion confirmed by an independent simulation.

use stickslip::models::paper::{Paper, Params};
use stickslip::sweep::{sweep, SweepOptions, TransitionKind};

#[test]
fn reference_transitions_are_located_within_1e_8() {
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 3.6, 4.3, 15, SweepOptions::default()).expect("sweep runs");
    for t in &s.transitions {
        eprintln!(
            "{} {} -> {} {:?} {:?}",
            t.value, t.from, t.to, t.kind, t.boundary
        );
    }
    let find = |from: &str, to: &str| {
        s.transitions
            .iter()
            .find(|t| t.from == from && t.to == to)
            .unwrap_or_else(|| panic!("no transition {from} -> {to} in {:#?}", s.transitions))
            .clone()
    };
    let a = find("P_{3_31 0_11 3_13 4_33}", "P_{3_31 0_11 1_11 3_13 4_33}");
    assert!((a.value - 3.7550059120).abs() < 1e-8, "{}", a.value);
    assert_eq!(a.kind, TransitionKind::PassableOnset);
    let b = find(
        "P_{3_31 1_11 3_13 4_33}",
        "P_{3_31 1_12 2_22 1_21 3_13 4_33}",
    );
    assert!((b.value - 4.1813106733).abs() < 1e-8, "{}", b.value);
    assert_eq!(b.kind, TransitionKind::Grazing);
    assert_eq!(b.boundary.as_deref(), Some("Sigma2"));
}
