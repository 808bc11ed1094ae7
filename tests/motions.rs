//! The reference periodic motions of `../shared/reference/` (computed
//! independently from SPEC §1) reproduced by the runtime: by Newton from a
//! guess perturbed by 1e-2, and by simulation from rest; switching points
//! within 1e-9, eigenvalues within 1e-8. And the NM case.

mod common;

use common::reference::{references, Reference};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::{solve, Motion};
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};

fn assert_matches(r: &Reference, motion: &Motion, how: &str) {
    let info = Paper::INFO;
    assert_eq!(motion.structure.notation(info), r.structure, "{how}");
    assert!(
        motion.is_admissible(),
        "{how}: {:?} {:?}",
        motion.termination,
        motion.violations
    );
    assert_eq!(motion.points.len(), r.points.len());
    for (k, (a, b)) in motion.points.iter().zip(&r.points).enumerate() {
        assert!(
            (a.phase - b.phase).abs() < 1e-9 && (a.x - b.x).abs() < 1e-9,
            "{how} {}: point {k}: ({}, {}) vs reference ({}, {})",
            r.structure,
            a.phase,
            a.x,
            b.phase,
            b.x
        );
    }
    let st = motion.stability.expect("stability");
    for want in &r.eigenvalues {
        assert!(
            st.eigenvalues
                .iter()
                .any(|e| (e[0] - want[0]).abs() < 1e-8 && (e[1] - want[1]).abs() < 1e-8),
            "{how} {}: eigenvalue {want:?} not in {:?}",
            r.structure,
            st.eigenvalues
        );
    }
    assert!(st.is_stable());
}

#[test]
fn newton_from_a_perturbed_guess_reproduces_the_reference_motions() {
    for r in references() {
        let sim = r.simulator();
        let structure = r.structure();
        let guess: Vec<SwitchingPoint> = r
            .points
            .iter()
            .enumerate()
            .map(|(k, pt)| {
                let s = if k % 2 == 0 { 1.0 } else { -1.0 };
                SwitchingPoint {
                    phase: pt.phase + s * 1e-2,
                    x: pt.x - s * 1e-2,
                }
            })
            .collect();
        let motion = solve(&sim, structure, guess, NewtonOptions::default());
        assert_matches(&r, &motion, "newton");
    }
}

#[test]
fn simulation_from_rest_finds_the_reference_motions() {
    for r in references() {
        let sim = r.simulator();
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        match attractor::find(&sim, start, AttractorOptions::default()).expect("settles") {
            Attractor::Periodic(motion) => assert_matches(&r, &motion, "simulate"),
            Attractor::NoMotion(nm) => panic!("{}: found NM {nm:?}", r.structure),
            Attractor::Stick(s) => panic!("{}: found a stick {s:?}", r.structure),
            Attractor::Autonomous(a) => panic!("{}: found an autonomous cycle {a:?}", r.structure),
        }
    }
}

#[test]
fn no_motion_at_w_1_is_certified() {
    let p = Params {
        W: 1.0,
        Q0: 70.0,
        ..Params::default()
    };
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
    let start = sim.start(0.0, 0.0, 0.0).expect("start");
    match attractor::find(&sim, start, AttractorOptions::default()).expect("settles") {
        Attractor::NoMotion(nm) => {
            assert_eq!(Paper::INFO.domains[nm.domain].label, 4);
            assert!((nm.max_v - 0.483).abs() < 1e-3, "max v {}", nm.max_v);
        }
        Attractor::Periodic(m) => {
            panic!("expected NM, found {}", m.structure.notation(Paper::INFO))
        }
        Attractor::Stick(s) => panic!("expected NM, found a stick {s:?}"),
        Attractor::Autonomous(a) => panic!("expected NM, found an autonomous cycle {a:?}"),
    }
}
