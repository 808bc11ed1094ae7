//! The reference periodic motions of `../shared/reference/` (computed
//! independently from SPEC §1) reproduced by the runtime: by Newton from a
//! guess perturbed by 1e-2, and by simulation from rest; switching points
//! within 1e-9, eigenvalues within 1e-8. And the NM case.

use serde_json::Value;
use stickslip::attractor::{self, Attractor, AttractorOptions};
use stickslip::models::paper::{Paper, Params};
use stickslip::motion::{solve, Motion};
use stickslip::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::simulate::{SimOptions, Simulator};
use stickslip::structure::Structure;
use stickslip::Model;

struct Reference {
    structure: String,
    w: f64,
    q0: f64,
    periods: u32,
    points: Vec<SwitchingPoint>,
    eigenvalues: Vec<[f64; 2]>,
}

fn references() -> Vec<Reference> {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference/orbits.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let v: Value = serde_json::from_str(&text).expect("valid JSON");
    let f = |v: &Value| v.as_f64().expect("number");
    v["orbits"]
        .as_array()
        .expect("orbits")
        .iter()
        .map(|o| Reference {
            structure: o["structure"].as_str().expect("structure").to_string(),
            w: f(&o["W"]),
            q0: f(&o["Q0"]),
            periods: f(&o["N_periods"]) as u32,
            points: o["switching_points"]
                .as_array()
                .expect("points")
                .iter()
                .map(|p| SwitchingPoint {
                    phase: f(&p["Wt"]),
                    x: f(&p["x"]),
                })
                .collect(),
            eigenvalues: o["eigenvalues"]
                .as_array()
                .expect("ev")
                .iter()
                .map(|e| [f(&e[0]), f(&e[1])])
                .collect(),
        })
        .collect()
}

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
        let p = Params {
            W: r.w,
            Q0: r.q0,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
        let structure = Structure::parse(Paper::INFO, &r.structure, r.periods).expect("structure");
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
        let p = Params {
            W: r.w,
            Q0: r.q0,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        match attractor::find(&sim, start, AttractorOptions::default()).expect("settles") {
            Attractor::Periodic(motion) => assert_matches(&r, &motion, "simulate"),
            Attractor::NoMotion(nm) => panic!("{}: found NM {nm:?}", r.structure),
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
    }
}
