//! The speed/accuracy trade (issue 5): the N-piece models built at build time
//! converge to the smooth law at second order, as interpolating a smooth law
//! predicts; the integrator's own tolerance ladder converges too.

use stickslip::study::trade::{Measure, Trade};

fn measure() -> Trade {
    let set = vec![("W".to_string(), 1.5), ("Q0".to_string(), 6.0)];
    let model = stickslip::models::ModelRef::Name("stribeck".into());
    let m = Measure {
        model: &model,
        set: &set,
        pieces: &[4, 8, 16, 32, 64],
        tols: &[1e-5, 1e-7, 1e-9],
        reference_tol: 1e-12,
    };
    stickslip::models::visit("stribeck", m)
        .expect("compiled in")
        .expect("trade measured")
}

#[test]
fn piecewise_predictions_converge_at_second_order() {
    let t = measure();
    let pieces: Vec<(u32, f64)> = t
        .rows
        .iter()
        .filter_map(|r| r.pieces.map(|n| (n, r.error)))
        .collect();
    for w in pieces.windows(2) {
        assert!(w[1].1 < w[0].1, "error must fall with N: {pieces:?}");
    }
    let order = t.order.expect("an observed order");
    assert!(
        (1.7..2.5).contains(&order),
        "observed order {order}, expected about 2 ({pieces:?})"
    );
    let fine = pieces.last().expect("N = 64").1;
    assert!(fine < 1e-3, "64 pieces: error {fine}");
}

#[test]
fn the_integrators_tolerance_ladder_converges_to_the_reference() {
    let t = measure();
    let ladder: Vec<(f64, f64)> = t
        .rows
        .iter()
        .filter_map(|r| r.tol.map(|tol| (tol, r.error)))
        .collect();
    for w in ladder.windows(2) {
        assert!(
            w[1].1 < w[0].1,
            "error must fall with the tolerance: {ladder:?}"
        );
    }
    let (tol, err) = *ladder.last().expect("a tolerance");
    assert!(err < 1e3 * tol, "tolerance {tol}: error {err}");
    // The reference has the stick-slip cycle's events at the belt speed.
    assert!(t.reference.belt_events.len() >= 2);
}
