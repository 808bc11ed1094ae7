//! The hot path of the continuation map (issue 12): continuing a
//! neighbour's motion to a point's parameters — Newton, the smallest
//! admissibility margin and the stability, on a prepared
//! [`Continuer`] — allocates nothing, counted by a global allocator (per
//! thread, see tests/common/counting.rs).

mod common;

use common::counting::{allocations, Counting};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::seed;
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver};
use stickslip::orbit::structure::Structure;
use stickslip::study::map::Continuer;

#[global_allocator]
static GLOBAL: Counting = Counting;

fn sim(w: f64, q0: f64) -> Simulator<Paper> {
    let p = Params {
        W: w,
        Q0: q0,
        ..Params::default()
    };
    Simulator::new(p, SimOptions::default()).unwrap()
}

#[test]
fn continuing_a_motion_to_a_neighbouring_point_allocates_nothing() {
    // Two motions of the map's range, each continued one grid step (of the
    // 400 x 400 map) in W and in Q0, and a step where it is lost.
    for (w, q0, text) in [
        (3.7, 70.0, "P_{3_31 0_11 3_13 4_33}"),
        (5.0, 70.0, "P_{3_31 1_12 2_22 1_21 3_13 4_33}"),
    ] {
        let here = sim(w, q0);
        let structure = Structure::parse(Paper::INFO, text, 1).unwrap();
        let guess = seed(&here, &structure).expect("seeded");
        let motion = solve(&here, structure.clone(), guess, NewtonOptions::default());
        assert!(motion.is_admissible(), "{text}");
        let mut continuer = Continuer::<Paper>::new();
        continuer.prepare(&structure);
        for (dw, dq) in [(7.8 / 399.0, 0.0), (0.0, 180.0 / 399.0)] {
            let there = sim(w + dw, q0 + dq);
            let (n, out) = allocations(|| {
                continuer
                    .continue_motion(&there, &structure, &motion.points)
                    .map(|(pts, st)| (pts[0], st.largest_modulus))
            });
            assert_eq!(n, 0, "{text} at W+{dw}, Q0+{dq}: {n} allocations");
            let (p0, rho) = out.expect("continued");
            // The continued motion solves the mapping equations at the new
            // point (an independent residual evaluation), and is stable.
            let pts = continuer
                .continue_motion(&there, &structure, &motion.points)
                .map(|(pts, _)| pts.to_vec())
                .unwrap();
            assert_eq!(pts[0], p0);
            let r = PeriodicSolver::<Paper>::new(structure.clone()).residual(there.params(), &pts);
            assert!(r < 1e-9, "{text}: residual {r:e}");
            assert!(rho < 1.0, "{text}");
            let moved =
                (p0.x - motion.points[0].x).abs() + (p0.phase - motion.points[0].phase).abs();
            assert!(moved > 0.0 && moved < 0.1, "{text}: moved {moved}");
        }
    }
}
