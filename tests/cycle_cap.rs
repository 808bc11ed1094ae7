//! The cycle cap of `attractor::find` never turns a long cycle into "no
//! periodic motion".
//!
//! * `stribeck::pl64` (64 pieces, 252 mapping functions) at low forcing
//!   frequencies crosses about a hundred boundaries per oscillation: cycles
//!   of 250 mappings (1 period), 460 (4 periods) and 1014 (5 periods, beyond
//!   the model's cap of 4 × 252, found by its period). With the default
//!   options each cycle is found (admissible, stable), and the search by
//!   cycle length alone with a cap just above the cycle finds the same.
//! * With a cap below the cycle's length (160 for pl64, 3 for a 4-mapping
//!   motion of the paper model), the outcome is `OrbitError::CycleTooLong`
//!   whose message is exactly "the cycle is longer than N mappings", with
//!   the number of mappings and periods of the cycle seen; never
//!   `Unsettled` ("no periodic motion ...").

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params as PaperParams};
use stickslip::models::stribeck::pl64::{Params, Pl64};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::OrbitError;
use stickslip::Model;

fn find<M: Model>(sim: &Simulator<M>, max_cycle: Option<usize>) -> Result<Attractor, OrbitError> {
    let opts = AttractorOptions {
        max_cycle,
        ..AttractorOptions::default()
    };
    attractor::find(sim, sim.start(0.0, 0.0, 0.0).expect("start"), opts)
}

#[test]
fn long_cycles_of_a_64_piece_model_are_found_or_named_too_long() {
    let mut longest = 0;
    for (w, q0) in [(0.4, 6.0), (0.5, 10.0), (0.4, 10.0)] {
        let what = format!("stribeck::pl64 at W = {w}, Q0 = {q0}");
        let sim = Simulator::<Pl64>::new(Params { W: w, Q0: q0 }, SimOptions::default())
            .expect("valid parameters");
        let motion = match find(&sim, None) {
            Ok(Attractor::Periodic(motion)) => motion,
            other => panic!("{what}: {other:?}"),
        };
        let m = motion.structure.len();
        assert!(
            m > 160,
            "{what}: a cycle of {m} mappings does not exercise the cap"
        );
        assert!(motion.is_admissible(), "{what}: {:?}", motion.violations);
        assert!(
            motion.stability.is_some_and(|s| s.is_stable()),
            "{what}: {:?}",
            motion.stability
        );
        // Independently: the search by cycle length alone, with a cap above
        // the cycle, finds the same motion.
        match find(&sim, Some(m + 16)) {
            Ok(Attractor::Periodic(by_length)) => {
                assert_eq!(by_length.structure, motion.structure, "{what}");
                let dev = by_length
                    .points
                    .iter()
                    .zip(&motion.points)
                    .map(|(a, b)| {
                        (a.phase - b.phase)
                            .abs()
                            .max((a.x - b.x).abs() / (1.0 + b.x.abs()))
                    })
                    .fold(0.0, f64::max);
                assert!(dev < 1e-9, "{what}: the two searches differ by {dev:e}");
            }
            other => panic!("{what}, cap {}: {other:?}", m + 16),
        }
        eprintln!(
            "[cycle_cap] {what}: {m} mappings in {} period(s) (the model's cap: {})",
            motion.structure.periods(),
            AttractorOptions::default().cycle_cap(Pl64::INFO)
        );
        longest = longest.max(m);
        // A cap below the cycle: the message, with the cycle seen.
        match find(&sim, Some(160)) {
            Err(e @ OrbitError::CycleTooLong { .. }) => {
                assert_eq!(e.to_string(), "the cycle is longer than 160 mappings");
                let OrbitError::CycleTooLong {
                    cap,
                    mappings,
                    periods,
                } = e
                else {
                    unreachable!()
                };
                assert_eq!(cap, 160);
                assert_eq!(
                    (mappings, periods),
                    (m, motion.structure.periods()),
                    "{what}: the cycle seen"
                );
            }
            other => panic!("{what}, cap 160: {other:?}"),
        }
    }
    assert!(longest > 160);
}

#[test]
fn a_small_cap_names_the_cycle_too_long() {
    // The paper model at W = 3.7, Q0 = 70: P_{3_31 0_11 3_13 4_33}, 4 mappings.
    let sim = Simulator::<Paper>::new(
        PaperParams {
            W: 3.7,
            Q0: 70.0,
            ..PaperParams::default()
        },
        SimOptions::default(),
    )
    .expect("valid parameters");
    let motion = match find(&sim, Some(4)) {
        Ok(Attractor::Periodic(motion)) => motion,
        other => panic!("cap 4: {other:?}"),
    };
    assert_eq!(motion.structure.len(), 4);
    assert_eq!(find(&sim, None), Ok(Attractor::Periodic(motion.clone())));
    for cap in [1, 2, 3] {
        match find(&sim, Some(cap)) {
            Err(e @ OrbitError::CycleTooLong { .. }) => {
                assert_eq!(
                    e.to_string(),
                    format!("the cycle is longer than {cap} mappings")
                );
                assert!(
                    matches!(e, OrbitError::CycleTooLong { cap: c, mappings: 4, periods }
                        if c == cap && periods == motion.structure.periods()),
                    "{e:?}"
                );
            }
            other => panic!("cap {cap}: {other:?}"),
        }
    }
}
