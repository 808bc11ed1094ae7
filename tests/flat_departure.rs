//! A departure from a stick whose static bound is the kinetic limit
//! (`as = ak`: the smooth laws' N-piece models, here `stribeck8`) has no
//! acceleration: the force balance at the stick's end cancels, to a few
//! ulps of its terms. Until stop 22 the admissibility walk read the sign of
//! that rounding (±3e-13) as the departure's, and counted the zero of the
//! acceleration at the departure as an interior extremum on the boundary it
//! leaves: along a sweep the motion flickered between admissible and not,
//! and the sweep reported 19 transitions from the motion to itself
//! (grazing and stick vanishing "on Sigma1") between W = 1.6 and 1.9 at
//! Q0 = 3; the curves run of that box traced each as a curve that failed
//! within a few steps. Now the rate of the acceleration decides such a
//! departure, as SPEC §6 states for a tangential one.
//!
//! Checked independently: where the walk refused the motion, a simulation
//! from rest settles on it.

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::admissible::violations;
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::study::sweep::{sweep, SweepOptions};

const MOTION: &str = "7_76 6_65 5_51 0_11 5_15 6_56 7_67 8_77";

fn params(w: f64) -> stribeck8::Params {
    stribeck8::Params {
        W: w,
        Q0: 3.0,
        ..stribeck8::Params::default()
    }
}

#[test]
fn a_sweep_reports_no_transition_of_a_motion_to_itself() {
    let s =
        sweep::<Stribeck8>(params(1.6), "W", 1.6, 1.9, 20, SweepOptions::default()).expect("sweep");
    let to_itself: Vec<_> = s.transitions.iter().filter(|t| t.from == t.to).collect();
    assert!(to_itself.is_empty(), "{to_itself:#?}");
    assert!(
        s.branches
            .iter()
            .any(|b| b.structure == format!("P_{{{MOTION}}}")),
        "the motion's branch: {:?}",
        s.branches.iter().map(|b| &b.structure).collect::<Vec<_>>()
    );
}

/// At the two values where the walk said "the flow must leave Sigma1 into
/// domain 5 (margin -3.0e-13)" and "-4.4e-13", a simulation from rest
/// settles on the motion, and the walk finds it admissible.
#[test]
fn the_motion_is_admissible_where_rounding_said_otherwise() {
    for w in [1.6054, 1.62] {
        let sim = Simulator::<Stribeck8>::new(params(w), SimOptions::default()).expect("params");
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        let m = match attractor::find(&sim, start, AttractorOptions::default()) {
            Ok(Attractor::Periodic(m)) => m,
            other => panic!("W = {w}: a simulation from rest settles on {other:?}"),
        };
        assert_eq!(
            m.structure.notation(Stribeck8::INFO),
            format!("P_{{{MOTION}}}"),
            "W = {w}"
        );
        let v = violations(&sim, &m.structure, &m.points);
        assert!(v.is_empty(), "W = {w}: {v:#?}");
    }
}
