//! The sweep's bifurcation analysis (issue 11), each claim checked by an
//! independent computation: the `orbit` command at every reported
//! bifurcation, simulations of the branches' points, and the two defects of
//! the natural-parameter sweep as regression tests.

mod common;

use std::process::Command;

use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::{sweep, Sweep, SweepOptions, TransitionKind};

/// The period-doubling window of the issue: `W = 10.7…10.95`, `Q0 = 100`, `mu3 = 3`.
fn pd_params() -> Params {
    Params {
        Q0: 100.0,
        mu3: 3.0,
        ..Params::default()
    }
}

fn pd_sweep() -> Sweep {
    sweep::<Paper>(pd_params(), "W", 10.7, 10.95, 26, SweepOptions::default()).expect("sweep runs")
}

use common::resimulate::from_first_point as simulate;

#[test]
fn a_period_doubling_is_one_classified_event_and_the_doubled_branch_is_followed() {
    // Defect 1 of the issue: the natural-parameter sweep printed
    // `eigenvalue P_{3_33 4_33} -> P_{3_33 4_33}` nine times here.
    let s = pd_sweep();
    let pd: Vec<_> = s
        .bifurcations
        .iter()
        .filter(|b| b.kind == TransitionKind::PeriodDoubling && b.structure == "P_{3_33 4_33}")
        .collect();
    assert_eq!(pd.len(), 1, "{:#?}", s.bifurcations);
    let pd = pd[0];
    assert!(pd.value > 10.7 && pd.value < 10.95);
    assert!((pd.eigenvalue[0] + 1.0).abs() < 1e-7 && pd.eigenvalue[1] == 0.0);
    let same: Vec<_> = s
        .transitions
        .iter()
        .filter(|t| t.from == "P_{3_33 4_33}" && t.to == "P_{3_33 4_33}")
        .collect();
    assert!(same.is_empty(), "{same:#?}");
    // The doubled branch: the structure applied twice, N = 2.
    assert_eq!(pd.born.len(), 1, "{pd:#?}");
    let born = &s.branches[pd.born[0]];
    assert_eq!(born.n, 2);
    assert_eq!(born.structure, "(P_{3_33 4_33})^{×2}");
    // A point of it away from the bifurcation is a motion of two forcing
    // periods and not of one (simulation, not Newton).
    let q = born
        .points
        .iter()
        .max_by(|a, b| {
            (a.value - pd.value)
                .abs()
                .total_cmp(&(b.value - pd.value).abs())
        })
        .expect("points");
    assert!(
        (q.value - pd.value).abs() > 1e-4,
        "the doubled branch is too short: {born:#?}"
    );
    let p = Params {
        W: q.value,
        ..pd_params()
    };
    let st = Structure::parse(Paper::INFO, &born.structure, 2).expect("structure");
    let (events, _, x2) = simulate(p, &st, &q.points, 2);
    assert_eq!(events, 4);
    assert!(
        (x2 - q.points[0].x).abs() < 1e-7,
        "not 2-periodic: {x2} vs {}",
        q.points[0].x
    );
    let (_, _, x1) = simulate(p, &st, &q.points, 1);
    assert!((x1 - q.points[0].x).abs() > 1e-5, "1-periodic: {x1}");
}

/// The eigenvalues `orbit --json` gives for a motion at a parameter value.
fn orbit_eigenvalues(structure: &str, n: u32, set: &str, guess: (f64, f64)) -> Vec<[f64; 2]> {
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "orbit",
            "--structure",
            structure,
            "--periods",
            &n.to_string(),
            "--set",
            set,
            "--guess",
            &format!("{:.17},{:.17}", guess.0, guess.1),
            "--json",
        ])
        .output()
        .expect("runs");
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&out.stderr)));
    doc["eigenvalues"]
        .as_array()
        .unwrap_or_else(|| panic!("no eigenvalues: {doc}"))
        .iter()
        .map(|e| [e[0].as_f64().expect("re"), e[1].as_f64().expect("im")])
        .collect()
}

#[test]
fn at_every_bifurcation_the_orbit_command_gives_the_critical_eigenvalue() {
    let s = pd_sweep();
    assert!(!s.bifurcations.is_empty());
    for b in &s.bifurcations {
        let set = format!("Q0=100,mu3=3,W={:.17}", b.value);
        let ev = orbit_eigenvalues(&b.structure, b.n, &set, (b.start_wt, b.start_x));
        let hit = ev.iter().any(|e| match b.kind {
            TransitionKind::Fold | TransitionKind::BranchPoint => {
                (e[0] - 1.0).abs() < 1e-7 && e[1].abs() < 1e-7
            }
            TransitionKind::PeriodDoubling => (e[0] + 1.0).abs() < 1e-7 && e[1].abs() < 1e-7,
            TransitionKind::NeimarkSacker => (e[0].hypot(e[1]) - 1.0).abs() < 1e-7,
            _ => false,
        });
        assert!(hit, "{:?} at W = {}: orbit gives {ev:?}", b.kind, b.value);
    }
}

#[test]
fn every_unstable_branch_point_is_a_motion_by_simulation() {
    let s = pd_sweep();
    let mut unstable = 0;
    for b in &s.branches {
        let st = Structure::parse(Paper::INFO, &b.structure, b.n).expect("structure");
        let (first, last) = (b.points[0].value, b.points[b.points.len() - 1].value);
        for q in &b.points {
            // The ends at a non-smooth transition are tangencies: a
            // simulation cannot tell on which side it is.
            if (q.value - first).abs() < 1e-6 || (q.value - last).abs() < 1e-6 {
                continue;
            }
            let p = Params {
                W: q.value,
                ..pd_params()
            };
            let (events, dt, x) = simulate(p, &st, &q.points, b.n);
            // One cycle from the first switching point: the structure's
            // events, back at the start (an unstable motion leaves only
            // slowly: rounding grows by |λ| per cycle).
            let modulus = q.eigenvalues[0][0].hypot(q.eigenvalues[0][1]);
            let tol = 1e-8 * modulus.max(1.0);
            assert_eq!(events, st.len(), "W = {}: {}", q.value, b.structure);
            assert!(dt.abs() < tol, "W = {}: the cycle ends {dt} off", q.value);
            assert!(
                (x - q.points[0].x).abs() < tol,
                "W = {}: {x} vs {}",
                q.value,
                q.points[0].x
            );
            if !q.stable {
                unstable += 1;
            }
        }
    }
    assert!(unstable >= 3, "only {unstable} unstable points");
}

#[test]
fn the_period_two_motion_of_the_bistable_window_is_found() {
    // Defect 2 of the issue: at W = 3.9482584517, Q0 = 70 the sweep reported
    // two stable period-1 motions, while a simulation from rest lands on a
    // third, a stable period-2 motion that attracts almost every start.
    let base = Params {
        Q0: 70.0,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 3.9475, 3.949, 7, SweepOptions::default()).expect("sweep");
    let want = Structure::parse(
        Paper::INFO,
        "P_{3_31 0_11 1_11 3_13 4_33 3_31 1_11 3_13 4_33}",
        2,
    )
    .expect("structure");
    let rotations = |a: &Structure, b: &Structure| {
        let (x, y) = (a.steps(), b.steps());
        x.len() == y.len()
            && (0..x.len()).any(|r| (0..x.len()).all(|k| x[(r + k) % x.len()] == y[k]))
    };
    let found: Vec<_> = s
        .points
        .iter()
        .filter(|p| {
            p.motions.iter().any(|m| {
                m.n == 2
                    && m.stable
                    && Structure::parse(Paper::INFO, &m.structure, 2)
                        .is_ok_and(|st| rotations(&st, &want))
            })
        })
        .map(|p| p.value)
        .collect();
    assert!(!found.is_empty(), "{:#?}", s.points);
    // And the period-1 motions stay reported beside it.
    let w = found[0];
    let at = s.points.iter().find(|p| p.value == w).expect("point");
    assert!(
        at.motions.iter().filter(|m| m.n == 1 && m.stable).count() >= 1,
        "{at:#?}"
    );
}

#[test]
fn shaws_pitchfork_gives_two_mirror_image_branches() {
    // Shaw (J. Sound Vib. 108, 1986): the Coulomb oscillator on a fixed
    // surface, undamped, static friction 1.5 × kinetic. The symmetric
    // two-stop motion loses stability to a pair of unsymmetric ones.
    use stickslip::models::coulomb::{Coulomb, Params as C};
    let base = C {
        V: 0.0,
        d: 0.0,
        mus: 0.45,
        muk: 0.3,
        Q0: 1.5,
        ..C::default()
    };
    let s = sweep::<Coulomb>(base, "W", 0.33, 0.42, 10, SweepOptions::default()).expect("sweep");
    let bp: Vec<_> = s
        .bifurcations
        .iter()
        .filter(|b| b.kind == TransitionKind::BranchPoint)
        .collect();
    assert_eq!(bp.len(), 1, "{:#?}", s.bifurcations);
    let bp = bp[0];
    assert_eq!(bp.structure, "P_{0_11 1_11 0_11 2_11}");
    assert!((bp.eigenvalue[0] - 1.0).abs() < 1e-7);
    let set = format!("V=0,d=0,mus=0.45,muk=0.3,Q0=1.5,W={:.17}", bp.value);
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "orbit",
            "--model",
            "coulomb",
            "--structure",
            &bp.structure,
            "--set",
            &set,
            "--guess",
            &format!("{:.17},{:.17}", bp.start_wt, bp.start_x),
            "--json",
        ])
        .output()
        .expect("runs");
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let ev = doc["eigenvalues"].as_array().expect("eigenvalues");
    assert!(
        ev.iter()
            .any(|e| (e[0].as_f64().unwrap() - 1.0).abs() < 1e-7),
        "orbit gives {ev:?}"
    );
    // Two branches born, of the same structure, each with stable points.
    assert_eq!(bp.born.len(), 2, "{bp:#?}");
    let (a, b) = (&s.branches[bp.born[0]], &s.branches[bp.born[1]]);
    for br in [a, b] {
        assert_eq!(br.structure, bp.structure);
        assert!(br.points.iter().any(|q| q.stable));
    }
    // Mirror images: at the same parameter value, the switching
    // displacements of one are those of the other with the sign changed.
    let (qa, qb) = (a.points.last().unwrap(), b.points.last().unwrap());
    assert!(
        (qa.value - qb.value).abs() < 1e-9,
        "{} vs {}",
        qa.value,
        qb.value
    );
    let scale = qa.points.iter().fold(0.0f64, |m, p| m.max(p.x.abs()));
    assert!(scale > 1e-3);
    for p in &qa.points {
        assert!(
            qb.points
                .iter()
                .any(|q| (q.x + p.x).abs() < 1e-6 * scale.max(1.0)),
            "x = {} has no mirror in {:?}",
            p.x,
            qb.points
        );
    }
    // And they are not symmetric themselves (else they would be the old branch).
    let symmetric = qa.points.iter().all(|p| {
        qa.points
            .iter()
            .any(|q| (q.x + p.x).abs() < 1e-6 * scale.max(1.0))
    });
    assert!(!symmetric, "the born branch is symmetric: {:?}", qa.points);
}

#[test]
fn a_fold_next_to_a_grazing_is_a_fold_not_a_branch_point() {
    // The period-2 motion `P_{3_33 4_33}^2` (Q0 = 80, mu3 = 4.4) turns
    // back at W = 11.0522004, 1e-5 before it grazes Σ1. On this grid the
    // step across the fold was cut at the grazing, and the cut end kept the
    // step's tangent: the turn went unseen and the fold was reported as a
    // branch point whose born branch was the branch itself.
    let base = Params {
        Q0: 80.0,
        mu3: 4.4,
        ..Params::default()
    };
    let s = sweep::<Paper>(base, "W", 11.0, 11.1, 11, SweepOptions::default()).expect("sweep");
    assert!(
        s.bifurcations
            .iter()
            .all(|b| b.kind != TransitionKind::BranchPoint),
        "{:#?}",
        s.bifurcations
    );
    let folds: Vec<_> = s
        .bifurcations
        .iter()
        .filter(|b| b.kind == TransitionKind::Fold)
        .collect();
    assert_eq!(folds.len(), 1, "{:#?}", s.bifurcations);
    let f = folds[0];
    assert!((f.value - 11.0522004).abs() < 1e-6, "{f:#?}");
    assert!(f.born.is_empty());
    // The branch turns back there: its neighbours lie on one side.
    let br = &s.branches[f.branch];
    let k = br
        .points
        .iter()
        .position(|q| q.value == f.value)
        .expect("the fold is a point of its branch");
    assert!(k > 0 && k + 1 < br.points.len(), "{br:#?}");
    let (a, c) = (br.points[k - 1].value, br.points[k + 1].value);
    assert!((a - f.value) * (c - f.value) > 0.0, "{a} {} {c}", f.value);
}
