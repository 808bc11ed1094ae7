//! Sweeps along W at Q0 = 70 (SPEC §9): the two transitions listed in
//! `../shared/reference/README.md` located within 1e-8, and every reported
//! motion confirmed by an independent simulation.

use stickslip::models::paper::{Paper, Params};
use stickslip::study::sweep::{sweep, SweepOptions, TransitionKind};

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

use stickslip::dynamics::simulate::{EventKind, Location, Segment, SimOptions, Simulator};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::MotionSummary;

/// Start a simulation on the motion's first switching point and follow one
/// cycle: it must come back to the same point (the motion is a real,
/// periodic solution of the dynamics, checked independently of Newton).
fn resimulate(w: f64, m: &MotionSummary) -> Result<(), String> {
    let info = Paper::INFO;
    let p = Params {
        W: w,
        Q0: 70.0,
        ..Params::default()
    };
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).map_err(|e| e.to_string())?;
    if m.structure == "NM" {
        let start = sim.start(0.0, 0.0, 0.0).map_err(|e| e.to_string())?;
        return match attractor::find(&sim, start, AttractorOptions::default()) {
            Ok(Attractor::NoMotion(_)) => Ok(()),
            other => Err(format!("W = {w}: NM reported, simulation finds {other:?}")),
        };
    }
    let s = Structure::parse(info, &m.structure, m.n).map_err(|e| e.to_string())?;
    let first = info.mappings[s.steps()[0]];
    let location = first.domain.map_or(Location::Stick, Location::Domain);
    let p0 = m.points[0];
    let seg = Segment {
        x: p0.x,
        v: sim.velocity(first.from),
        phase: p0.phase,
        location,
        search_from: p0.phase,
    };
    let end = p0.phase + 2.0 * std::f64::consts::PI * m.n as f64;
    let mut events = Vec::new();
    sim.run(seg, end + 1e-6, |e| {
        if e.kind != EventKind::Graze {
            events.push(*e)
        }
    })
    .map_err(|e| e.to_string())?;
    let last = events.last().ok_or(format!("W = {w}: no event"))?;
    if events.len() != s.len() || (last.phase - end).abs() > 1e-7 || (last.x - p0.x).abs() > 1e-7 {
        return Err(format!(
            "W = {w}, {}: one cycle of simulation has {} events (expected {}) and ends at ({}, {}) instead of ({end}, {})",
            m.structure,
            events.len(),
            s.len(),
            last.phase,
            last.x,
            p0.x
        ));
    }
    Ok(())
}

#[test]
fn every_reported_motion_survives_an_independent_simulation() {
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 0.2, 9.0, 45, SweepOptions::default()).expect("sweep runs");
    let mut checked = 0;
    for p in &s.points {
        assert!(!p.motions.is_empty(), "W = {}: no motion reported", p.value);
        for m in &p.motions {
            resimulate(p.value, m).unwrap_or_else(|e| panic!("{e}"));
            checked += 1;
        }
    }
    assert!(checked >= 45);
}

#[test]
fn a_narrow_bistable_window_reports_both_motions() {
    // Between the stick onset and the stick vanishing near W = 3.948 both the
    // motion with stick and the one without coexist (SPEC §10: flow barrier).
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s =
        sweep::<Paper>(base, "W", 3.94, 3.955, 16, SweepOptions::default()).expect("sweep runs");
    let both: Vec<_> = s
        .points
        .iter()
        .filter(|p| {
            p.motions
                .iter()
                .any(|m| m.structure == "P_{3_31 1_11 3_13 4_33}")
                && p.motions
                    .iter()
                    .any(|m| m.structure == "P_{3_31 0_11 1_11 3_13 4_33}")
        })
        .collect();
    assert!(!both.is_empty(), "no bistable point in {:#?}", s.points);
    for p in both {
        assert!(
            p.value > 3.9478 && p.value < 3.9487,
            "bistable at W = {}",
            p.value
        );
        for m in &p.motions {
            assert!(m.stable, "W = {}: {} unstable", p.value, m.structure);
            resimulate(p.value, m).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}
