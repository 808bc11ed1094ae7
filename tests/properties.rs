//! Properties over random parameters of the paper model (proptest, a fixed
//! seed and a fixed number of cases so that CI time stays bounded).
//!
//! * `attractor::find` from rest (400 forcing periods at most) never panics:
//!   it returns a steady state or a typed error. Every periodic motion it
//!   reports is admissible and survives an independent re-simulation: started
//!   at its point 0, the event simulation follows its mappings and lands on
//!   point 0 shifted by `2πN` within 1e-7. Every NM has its velocity range
//!   strictly inside its domain's band.
//! * Invalid parameters (NaN, ±inf, negative or zero where a bound forbids
//!   it, boundaries out of order, static below kinetic friction) are typed
//!   errors of `Params::from_pairs`, `ParamSet::check` and `Simulator::new`,
//!   never panics; non-finite states are typed errors of `Simulator::start`.
//!
//! `PROPERTIES_VERBOSE=1` prints what `find` answered for every case.

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use stickslip::dynamics::simulate::{
    Event, EventKind, Location, Segment, SimError, SimOptions, Simulator,
};
use stickslip::model::param::{ParamError, ParamSet};
use stickslip::models::paper::{self, Paper, Params};
use stickslip::orbit::attractor::{self, mapping_between, Attractor, AttractorOptions};
use stickslip::orbit::motion::{Motion, OrbitError};

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x5717_c4a1),
        max_shrink_iters: 200,
        ..ProptestConfig::default()
    }
}

/// Re-simulate one cycle of `motion` from its point 0; returns the distance
/// of the return point to point 0 (+2πN) in (phase, x).
fn resimulate(sim: &Simulator<Paper>, motion: &Motion) -> Result<(f64, f64), String> {
    let info = Paper::INFO;
    let steps = motion.structure.steps();
    let pts = &motion.points;
    let m = pts.len();
    let shift = TAU * motion.structure.periods() as f64;
    let first = info.mappings[steps[0]];
    let seg = Segment {
        x: pts[0].x,
        v: sim.velocity(first.from),
        phase: pts[0].phase,
        location: first.domain.map_or(Location::Stick, Location::Domain),
        search_from: pts[0].phase,
    };
    let mut events = Vec::new();
    sim.run(seg, pts[0].phase + shift + 1e-6, |e| {
        if e.kind != EventKind::Graze {
            events.push(*e)
        }
    })
    .map_err(|e| format!("re-simulation failed: {e}"))?;
    if events.len() != m {
        return Err(format!(
            "{} events in one cycle of {} ({m} mappings): {events:?}",
            events.len(),
            motion.structure.notation(info)
        ));
    }
    let mut prev = Event {
        phase: seg.phase,
        x: seg.x,
        v: seg.v,
        boundary: first.from,
        kind: EventKind::Pass,
        before: seg.location,
        after: seg.location,
    };
    for (k, e) in events.iter().enumerate() {
        let got = mapping_between(Paper::INFO, &prev, e);
        if got != Some(steps[k]) {
            return Err(format!(
                "segment {k} follows {:?}, the structure says {}",
                got.map(|i| info.mappings[i].name),
                info.mappings[steps[k]].name
            ));
        }
        prev = *e;
    }
    let last = events[m - 1];
    Ok((
        (last.phase - (pts[0].phase + shift)).abs(),
        (last.x - pts[0].x).abs(),
    ))
}

/// The property: whatever `find` answers at `p` is real or a typed error.
fn check_attractor(p: Params) -> Result<(), TestCaseError> {
    // A rejection is a typed error (and must then also stop the simulator).
    if let Err(e) = p.check() {
        let sim = Simulator::<Paper>::new(p, SimOptions::default());
        prop_assert!(matches!(sim, Err(SimError::Params(ref s)) if s.to_string() == e.to_string()));
        return Ok(());
    }
    let opts = SimOptions {
        max_events: 200_000,
        ..SimOptions::default()
    };
    let sim = Simulator::<Paper>::new(p, opts).expect("checked parameters");
    let start = sim.start(0.0, 0.0, 0.0).expect("a finite start");
    let found = attractor::find(
        &sim,
        start,
        AttractorOptions {
            max_periods: 400,
            ..AttractorOptions::default()
        },
    );
    if std::env::var_os("PROPERTIES_VERBOSE").is_some() {
        eprintln!(
            "W {:.3} Q0 {:.1} d {:.3} mus {:.3} c {:.1}: {}",
            p.W,
            p.Q0,
            p.d,
            p.mus,
            p.c,
            match &found {
                Ok(Attractor::Periodic(m)) => format!(
                    "{} N={}",
                    m.structure.notation(Paper::INFO),
                    m.structure.periods()
                ),
                Ok(Attractor::NoMotion(nm)) => format!("NM in domain {}", nm.domain),
                Ok(Attractor::Stick(s)) => format!("stick at x = {}", s.x),
                Ok(Attractor::Autonomous(a)) => format!("autonomous cycle {a:?}"),
                Err(e) => format!("error: {e}"),
            }
        );
    }
    match found {
        Ok(Attractor::Periodic(motion)) => {
            prop_assert!(
                motion.is_admissible(),
                "{}: {:?} {:?}",
                motion.structure.notation(Paper::INFO),
                motion.termination,
                motion.violations
            );
            let (dphi, dx) = resimulate(&sim, &motion).map_err(|e| {
                TestCaseError::fail(format!("{}: {e}", motion.structure.notation(Paper::INFO)))
            })?;
            if std::env::var_os("PROPERTIES_VERBOSE").is_some() {
                eprintln!("re-simulation: {dphi:e} (phase), {dx:e} (x)");
            }
            prop_assert!(
                dphi < 1e-7 && dx < 1e-7,
                "{}: the re-simulation returns {dphi:e} (phase), {dx:e} (x) away from point 0",
                motion.structure.notation(Paper::INFO)
            );
        }
        Ok(Attractor::Stick(s)) => {
            prop_assert!(false, "a permanent stick on a moving belt: {s:?}");
        }
        Ok(Attractor::Autonomous(a)) => {
            prop_assert!(false, "an autonomous cycle with forcing: {a:?}");
        }
        Ok(Attractor::NoMotion(nm)) => {
            let dom = Paper::INFO.domains[nm.domain];
            prop_assert!(nm.max_v.is_finite() && nm.min_v.is_finite() && nm.min_v <= nm.max_v);
            if let Some(k) = dom.upper {
                prop_assert!(
                    nm.max_v < sim.velocity(k),
                    "NM {nm:?} reaches {}",
                    sim.velocity(k)
                );
            }
            if let Some(k) = dom.lower {
                prop_assert!(
                    nm.min_v > sim.velocity(k),
                    "NM {nm:?} reaches {}",
                    sim.velocity(k)
                );
            }
        }
        // Typed: every variant says what happened (and formats).
        Err(e) => {
            prop_assert!(!e.to_string().is_empty());
            prop_assert!(
                matches!(
                    e,
                    OrbitError::Unsettled { .. }
                        | OrbitError::NotConverged(_)
                        | OrbitError::Inadmissible(_)
                        | OrbitError::Simulation(
                            SimError::TooManyEvents { .. } | SimError::NotFinite { .. }
                        )
                        | OrbitError::Guess(_)
                        | OrbitError::Structure(_)
                ),
                "unexpected error kind: {e:?}"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(128))]

    #[test]
    fn attractors_at_random_parameters_are_real_motions(
        w in 0.3f64..9.0,
        q0 in 0.0f64..150.0,
        d in 0.0f64..1.0,
        mus in 0.41f64..1.0,
        c in 5.0f64..50.0,
    ) {
        check_attractor(Params { W: w, Q0: q0, d, mus, c, ..Params::default() })?;
    }

    /// Light damping: long transients, stick, multi-period motions.
    #[test]
    fn attractors_at_light_damping_are_real_motions(
        w in 1.5f64..7.0,
        q0 in 20.0f64..150.0,
        d in 0.0f64..0.15,
        mus in 0.41f64..1.0,
        c in 5.0f64..50.0,
    ) {
        check_attractor(Params { W: w, Q0: q0, d, mus, c, ..Params::default() })?;
    }

    /// Any value, finite or not, for any parameter: `from_pairs` answers
    /// `Ok` exactly when `check` accepts, and never panics.
    #[test]
    fn any_value_of_any_parameter_is_accepted_or_a_typed_error(
        index in 0usize..Params::NAMES.len(),
        value in prop_oneof![
            Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY),
            Just(0.0), Just(-0.0), Just(-1.0), Just(f64::MIN_POSITIVE), Just(f64::MAX),
            any::<f64>(), -100.0f64..100.0,
        ],
    ) {
        let name = Params::NAMES[index];
        let mut q = Params::default();
        q.set(index, value);
        let checked = q.check();
        match Params::from_pairs(Paper::INFO, &[(name, value)]) {
            Ok(p) => {
                prop_assert!(checked.is_ok());
                prop_assert!(value.is_finite());
                prop_assert!(Simulator::<Paper>::new(p, SimOptions::default()).is_ok());
            }
            Err(e) => {
                // (NaN inside the errors: compare what they say.)
                prop_assert_eq!(Some(e.to_string()), checked.err().map(|c| c.to_string()));
                if !value.is_finite() {
                    let is_not_finite = matches!(e, ParamError::NotFinite { .. });
                    prop_assert!(is_not_finite, "{name} = {value}: {e:?}");
                }
                prop_assert!(matches!(
                    Simulator::<Paper>::new(q, SimOptions::default()),
                    Err(SimError::Params(_))
                ));
            }
        }
    }

    /// Any start state: `Ok` exactly when all three values are finite.
    #[test]
    fn any_start_state_is_accepted_or_a_typed_error(
        x in prop_oneof![any::<f64>(), -10.0f64..10.0, Just(f64::NAN)],
        v in prop_oneof![any::<f64>(), -10.0f64..10.0, Just(3.0), Just(1.5), Just(4.5), Just(f64::INFINITY)],
        phase in prop_oneof![any::<f64>(), -100.0f64..100.0, Just(f64::NEG_INFINITY)],
    ) {
        let sim = Simulator::<Paper>::new(Params::default(), SimOptions::default()).expect("defaults");
        match sim.start(x, v, phase) {
            Ok(seg) => {
                prop_assert!(x.is_finite() && v.is_finite() && phase.is_finite());
                prop_assert_eq!((seg.x, seg.v, seg.phase), (x, v, phase));
            }
            Err(e) => {
                prop_assert!(!(x.is_finite() && v.is_finite() && phase.is_finite()));
                let bad_start = matches!(e, SimError::BadStart { .. });
                prop_assert!(bad_start, "{e:?}");
            }
        }
    }
}

#[test]
fn invalid_parameters_are_typed_errors() {
    let info = Paper::INFO;
    let not_finite = |name: &str, value: f64| {
        let e = Params::from_pairs(info, &[(name, value)]).unwrap_err();
        assert!(
            matches!(&e, ParamError::NotFinite { name: n, .. } if n == name),
            "{name} = {value}: {e:?}"
        );
    };
    for name in ["W", "Q0", "m", "c", "d", "V", "V1", "V2", "mus", "muk", "g"] {
        not_finite(name, f64::NAN);
        not_finite(name, f64::INFINITY);
        not_finite(name, f64::NEG_INFINITY);
    }
    // Declared bounds: W > 0, m > 0, c > 0, g > 0, d >= 0, mus >= 0, muk >= 0.
    for (name, value) in [
        ("W", 0.0),
        ("W", -3.0),
        ("m", -5.0),
        ("m", 0.0),
        ("c", -30.0),
        ("g", -9.8),
        ("d", -0.1),
        ("mus", -0.5),
        ("muk", -0.4),
    ] {
        let e = Params::from_pairs(info, &[(name, value)]).unwrap_err();
        assert!(
            matches!(&e, ParamError::OutOfRange { name: n, .. } if n == name),
            "{name} = {value}: {e:?}"
        );
        assert!(e.to_string().contains(name));
    }
    // Model conditions.
    assert!(matches!(
        Params::from_pairs(info, &[("V1", 2.0)]),
        Err(ParamError::BoundaryOrder { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("V2", 3.5)]),
        Err(ParamError::BoundaryOrder { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("mus", 0.1)]),
        Err(ParamError::StaticBelowKinetic { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("omega", 1.0)]),
        Err(ParamError::Unknown { .. })
    ));
    // A scene with W free only: Q0 is fixed there.
    assert!(matches!(
        paper::sweep_w::Params::from_pairs(paper::sweep_w::SweepW::INFO, &[("Q0", 1.0)]),
        Err(ParamError::Fixed { .. })
    ));
    // Negative forcing amplitude and negative velocities are a valid model.
    assert!(Params::from_pairs(info, &[("Q0", -70.0)]).is_ok());
    assert!(Params::from_pairs(info, &[("V", -1.0), ("V1", 0.5), ("V2", -3.0)]).is_ok());

    // Simulator::new checks what the struct holds.
    for bad in [
        Params {
            W: f64::NAN,
            ..Params::default()
        },
        Params {
            Q0: f64::INFINITY,
            ..Params::default()
        },
        Params {
            m: -1.0,
            ..Params::default()
        },
        Params {
            c: 0.0,
            ..Params::default()
        },
    ] {
        assert!(matches!(
            Simulator::<Paper>::new(bad, SimOptions::default()),
            Err(SimError::Params(_))
        ));
    }

    let sim = Simulator::<Paper>::new(Params::default(), SimOptions::default()).expect("defaults");
    for (x, v, phase) in [
        (f64::NAN, 0.0, 0.0),
        (0.0, f64::INFINITY, 0.0),
        (0.0, 0.0, f64::NEG_INFINITY),
        (f64::NEG_INFINITY, f64::NAN, f64::INFINITY),
    ] {
        assert!(matches!(
            sim.start(x, v, phase),
            Err(SimError::BadStart { .. })
        ));
    }
    assert!(sim.start(-2.0, -5.0, -10.0).is_ok());
}
