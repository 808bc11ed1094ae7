//! `DP` of a motion with a stick, against the reference case's (SPEC
//! reference `P_{3_31 0_11 3_13 4_33}` at W = 3.7, Q0 = 70, computed by an
//! independent closed-form event simulation): `monodromy` takes the flow
//! arriving at the stick together with the stick, free of its arrival time
//! (`MappingEval::local_jacobian_into_stick`), and must still give the
//! reference's `DP`. `monodromy_spectral` starts the cycle at its first
//! mapping that is not a stick, so that the flow before the cycle's first
//! stick is never split from it: for every rotation of the cycle (the
//! stick first, second, ...) its trace and determinant must be `DP`'s,
//! and its nonzero eigenvalue the reference's.

mod common;

use common::reference::references;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::periodic::{monodromy, monodromy_spectral, SwitchingPoint};
use stickslip::orbit::structure::Structure;

#[test]
fn dp_of_a_stick_motion_is_the_reference_in_every_rotation() {
    let mut checked = 0;
    for case in references() {
        if !case.mappings.iter().any(|m| m == "0_11") {
            continue;
        }
        let p = Params {
            W: case.w,
            Q0: case.q0,
            ..Params::default()
        };
        let shift = std::f64::consts::TAU * f64::from(case.periods);
        let reference =
            nalgebra::Matrix2::new(case.dp[0][0], case.dp[0][1], case.dp[1][0], case.dp[1][1]);
        let scale = reference.abs().max();
        let steps = case.structure().steps().to_vec();
        let dp = monodromy::<Paper>(&p, &steps, shift, &case.points).expect("DP");
        assert!(
            (dp - reference).abs().max() <= 1e-9 * scale,
            "{}: {dp} against {reference}",
            case.structure
        );
        let m = steps.len();
        for r in 0..m {
            // The cycle from its mapping `r`: points `r..`, then `..r` one
            // cycle later.
            let names: Vec<&str> = (0..m)
                .map(|i| case.mappings[(r + i) % m].as_str())
                .rev()
                .collect();
            let rotated =
                Structure::parse(Paper::INFO, &names.join(" "), case.periods).expect("a structure");
            let points: Vec<SwitchingPoint> = (0..m)
                .map(|i| {
                    let q = case.points[(r + i) % m];
                    let wrap = if r + i >= m { shift } else { 0.0 };
                    SwitchingPoint {
                        phase: q.phase + wrap,
                        x: q.x,
                    }
                })
                .collect();
            let sp = monodromy_spectral::<Paper>(&p, rotated.steps(), shift, &points).expect("DP");
            let what = format!("{} from mapping {}", case.structure, case.mappings[r]);
            assert!(
                (sp.trace() - reference.trace()).abs() <= 1e-9 * scale,
                "{what}: trace {} against {}",
                sp.trace(),
                reference.trace()
            );
            assert!(
                sp.determinant().abs() <= 1e-9 * scale * scale,
                "{what}: a stick's DP is singular, det {}",
                sp.determinant()
            );
            let nonzero = case.eigenvalues.iter().map(|e| e[0]).fold(0.0f64, |a, e| {
                if e.abs() > a.abs() {
                    e
                } else {
                    a
                }
            });
            assert!(
                (sp.trace() - nonzero).abs() <= 1e-9,
                "{what}: eigenvalue {} against {nonzero}",
                sp.trace()
            );
            checked += 1;
        }
    }
    assert!(checked >= 4, "{checked} rotations of stick motions checked");
}
