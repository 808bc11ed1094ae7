//! `admissible::worst_margin` allocates nothing (counted by a global
//! allocator, per thread), on every reference motion and on perturbations
//! of them that violate conditions, while `conditions` of the same points
//! allocates (its list, and the text of each violated condition).

mod common;

use common::counting::{allocations, Counting};
use common::reference::references;
use stickslip::orbit::admissible::{conditions, worst_margin};
use stickslip::orbit::periodic::SwitchingPoint;

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn worst_margin_allocates_nothing() {
    let mut violated = 0;
    for r in references() {
        let sim = r.simulator();
        let structure = r.structure();
        for shift in [0.0, 1e-3, 3e-2] {
            let points: Vec<SwitchingPoint> = r
                .points
                .iter()
                .enumerate()
                .map(|(k, p)| SwitchingPoint {
                    phase: p.phase + shift * (k as f64 - 1.5),
                    x: p.x - shift,
                })
                .collect();
            let (n, worst) = allocations(|| worst_margin(&sim, &structure, &points));
            assert_eq!(n, 0, "{} shifted by {shift}: {n} allocations", r.structure);
            let worst = worst.expect("points");
            if worst.margin.is_nan() || worst.margin <= 0.0 {
                violated += 1;
            }
            let (n, all) = allocations(|| conditions(&sim, &structure, &points));
            assert!(n >= 1, "the counter counts");
            assert!(all
                .iter()
                .any(|c| c.margin.to_bits() == worst.margin.to_bits()));
        }
    }
    assert!(violated > 0, "no perturbation violated a condition");
}
