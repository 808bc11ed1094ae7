//! Pseudo-arclength continuation, eigenvalue bifurcations and branch
//! switching, each checked against an independent computation:
//!
//! * every point of an unstable part of a branch solves the mapping
//!   equations (max residual ≤ 1e-10 relative) and is re-simulated for one
//!   cycle from its first switching point by the event-driven simulator: the
//!   events follow the structure's mappings in order and the motion returns
//!   to its start within 1e-8;
//! * at every located bifurcation, `orbit::motion::solve` at that parameter
//!   from those points gives the critical eigenvalue within 1e-7 of +1, −1
//!   or the unit circle;
//! * the period doubling of `P_{3_33 4_33}` (paper model, Q0 = 100,
//!   mu3 = 3, W = 10.7…10.95): the doubled branch is a motion of two forcing
//!   periods by simulation, and not one of one period;
//! * a fold: the two branches meet there, one stable, one unstable;
//! * Shaw's pitchfork (Coulomb oscillator at V = 0, static above kinetic
//!   friction): both unsymmetric branches, mirror images of each other;
//! * a corrector step and a tangent allocate nothing.

mod common;

use common::counting::{allocations, Counting};
use common::reference::segment_for;
use stickslip::bifurcation::bordered::{Bordered, Correction, State, Vector};
use stickslip::bifurcation::{
    born, follow, Bifurcation, Branch, BranchPoint, ContinuationOptions, EndReason, Start,
    TransitionKind,
};
use stickslip::dynamics::simulate::{EventKind, SimOptions, Simulator};
use stickslip::orbit::attractor::{self, mapping_between, Attractor, AttractorOptions};
use stickslip::orbit::motion::{solve, Motion};
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::{Model, ParamSet};

#[global_allocator]
static GLOBAL: Counting = Counting;

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn with<P: ParamSet>(base: &P, index: usize, value: f64) -> P {
    let mut p = *base;
    p.set(index, value);
    p
}

/// The motion a simulation from rest settles on.
fn settle<M: Model>(p: M::Params) -> Motion {
    let sim = Simulator::<M>::new(p, SimOptions::default()).expect("valid parameters");
    let start = sim.start(0.0, 0.0, 0.0).expect("a start");
    let opts = AttractorOptions {
        max_periods: 2000,
        ..AttractorOptions::default()
    };
    match attractor::find(&sim, start, opts) {
        Ok(Attractor::Periodic(m)) => m,
        other => panic!("no periodic motion from rest: {other:?}"),
    }
}

/// The independent checks of one branch point: the mapping residual
/// (relative to the motion's scales) and one re-simulated cycle.
fn check_point<M: Model>(
    base: &M::Params,
    index: usize,
    structure: &Structure,
    q: &BranchPoint,
) -> Result<(), String> {
    let p = with(base, index, q.value);
    let solver = PeriodicSolver::<M>::new(structure.clone());
    let l = PeriodicSolver::<M>::length_scale(&p, &q.points);
    let w = M::oscillator(&p).frequency.abs();
    let r = solver.residual(&p, &q.points);
    if r.is_nan() || r > 1e-10 * l * w.max(1.0) {
        return Err(format!("residual {r:e} at {}", q.value));
    }
    // A touch closer than 1e-13 counts as a graze (the default 1e-10 would
    // call the stick ends of points within about 1e-7 of a stick-vanishing
    // transition, where |Fnf| barely reaches `as`, grazes).
    let sim_opts = SimOptions {
        graze_tol: 1e-13,
        ..SimOptions::default()
    };
    let sim = Simulator::<M>::new(p, sim_opts).map_err(|e| e.to_string())?;
    let (pts, steps) = (&q.points, structure.steps());
    let m = pts.len();
    let shift = TAU * structure.periods() as f64;
    let seg = segment_for(&sim, steps[0], pts[0]);
    let mut events = Vec::new();
    sim.run(seg, pts[0].phase + shift + 1e-6, |e| events.push(*e))
        .map_err(|e| e.to_string())?;
    if events.len() != m || events.iter().any(|e| e.kind == EventKind::Graze) {
        return Err(format!(
            "{} events (structure: {m} mappings) at {}: {events:?}",
            events.len(),
            q.value
        ));
    }
    let info = sim.info();
    let mut prev = stickslip::dynamics::simulate::Event {
        phase: seg.phase,
        x: seg.x,
        v: seg.v,
        boundary: info.mappings[steps[0]].from,
        kind: EventKind::Pass,
        before: seg.location,
        after: seg.location,
    };
    for (k, e) in events.iter().enumerate() {
        let got = mapping_between(sim.info(), &prev, e);
        if got != Some(steps[k]) {
            return Err(format!(
                "segment {k} follows {got:?}, the structure says {} at {}",
                steps[k], q.value
            ));
        }
        prev = *e;
    }
    let last = events[m - 1];
    let (dphi, dx) = (
        (last.phase - pts[0].phase - shift).abs(),
        (last.x - pts[0].x).abs(),
    );
    // Within 1e-8, or, for a strongly unstable motion, within the rounding
    // of its switching points (1e-14 relative) amplified by its largest
    // eigenvalue over the cycle.
    let tol = 1e-8f64.max(1e-14 * q.stability.largest_modulus);
    if dphi.is_nan() || dx.is_nan() || dphi >= tol || dx >= tol * l.max(1.0) {
        return Err(format!(
            "returns ({dphi:e}, {dx:e}) away from its start at {} (largest |eigenvalue| {:e})",
            q.value, q.stability.largest_modulus
        ));
    }
    Ok(())
}

/// Every unstable point of a branch passes [`check_point`]; returns how
/// many. Points within 1e-6 in the parameter of an end at a non-smooth
/// transition are excluded: there a margin is zero to within the
/// admissibility check's own tolerance (`orbit::admissible` compares a
/// simulated stick end with a switching point to 1e-7 in phase), which a
/// simulation resolves either way (a stick of zero length, a tangency).
fn check_unstable<M: Model>(base: &M::Params, index: usize, b: &Branch) -> usize {
    let mut n = 0;
    let at_transition = |q: &BranchPoint| {
        b.ends.iter().any(|e| {
            matches!(e.reason, EndReason::Transition { .. }) && (e.at.value - q.value).abs() < 1e-6
        })
    };
    for q in b
        .points
        .iter()
        .filter(|q| !q.stability.is_stable() && !at_transition(q))
    {
        if let Err(e) = check_point::<M>(base, index, &b.structure, q) {
            panic!("{}: {e}", b.structure.notation(M::info(base)));
        }
        n += 1;
    }
    n
}

/// `orbit::motion::solve` at a bifurcation's parameter from its points: the
/// critical eigenvalue of the re-solved motion, as the distance to the
/// bifurcation's condition.
fn orbit_distance<M: Model>(base: &M::Params, index: usize, b: &Branch, f: &Bifurcation) -> f64 {
    let p = with(base, index, f.at.value);
    let sim = Simulator::<M>::new(p, SimOptions::default()).expect("valid");
    let m = solve(
        &sim,
        b.structure.clone(),
        f.at.points.clone(),
        NewtonOptions::default(),
    );
    assert!(m.termination.converged(), "{:?}", m.termination);
    let st = m.stability.expect("DP exists");
    st.eigenvalues
        .iter()
        .map(|e| match f.kind {
            TransitionKind::PeriodDoubling => (e[0] + 1.0).hypot(e[1]),
            TransitionKind::NeimarkSacker => (e[0].hypot(e[1]) - 1.0).abs(),
            _ => (e[0] - 1.0).hypot(e[1]),
        })
        .fold(f64::INFINITY, f64::min)
}

fn opts(bounds: (f64, f64)) -> ContinuationOptions {
    ContinuationOptions {
        bounds,
        // Denser than the default, so that the branches have enough
        // unstable points to re-simulate.
        max_step: 5e-2,
        ..ContinuationOptions::default()
    }
}

/// Follow the branch of the motion a simulation from rest settles on at
/// `value`.
fn branch_from_rest<M: Model>(
    base: &M::Params,
    index: usize,
    value: f64,
    o: &ContinuationOptions,
) -> Branch {
    let m = settle::<M>(with(base, index, value));
    let start = Start {
        structure: m.structure.clone(),
        value,
        points: m.points.clone(),
        direction: None,
    };
    follow::<M>(base, index, &start, o).expect("the branch")
}

/// Whether the motion at `q` returns to its start after `periods` forcing
/// periods (simulated from its first switching point; distance in phase-space units).
fn return_distance<M: Model>(
    base: &M::Params,
    index: usize,
    structure: &Structure,
    q: &BranchPoint,
    periods: u32,
) -> f64 {
    let sim =
        Simulator::<M>::new(with(base, index, q.value), SimOptions::default()).expect("valid");
    let seg = segment_for(&sim, structure.steps()[0], q.points[0]);
    let end = q.points[0].phase + TAU * periods as f64;
    let last = sim.run(seg, end, |_| {}).expect("simulates");
    let (x, v) = sim.state_at(&last, end);
    let w = sim.oscillator().frequency;
    (x - seg.x).hypot((v - seg.v) / w)
}

#[test]
fn period_doubling_of_p_3_33_4_33_and_its_doubled_branch() {
    use stickslip::models::paper::{Paper, Params};
    let base = Params {
        Q0: 100.0,
        mu3: 3.0,
        ..Params::default()
    };
    let index = Params::index_of("W").expect("W");
    let o = opts((10.7, 10.95));
    let b = branch_from_rest::<Paper>(&base, index, 10.7, &o);
    assert_eq!(b.structure.notation(Paper::INFO), "P_{3_33 4_33}");
    // Cost per point (predictor, corrector, tangent, DP, every margin;
    // the located points included).
    let start = Start {
        structure: b.structure.clone(),
        value: b.points[0].value,
        points: b.points[0].points.clone(),
        direction: None,
    };
    let t = std::time::Instant::now();
    let again = follow::<Paper>(&base, index, &start, &o).expect("the branch");
    eprintln!(
        "{} points in {:?}: {:.1} µs per point",
        again.points.len(),
        t.elapsed(),
        t.elapsed().as_secs_f64() * 1e6 / again.points.len() as f64
    );
    assert_eq!(b.ends.len(), 2);
    assert!(b.ends.iter().all(|e| e.reason == EndReason::ParameterBound));
    assert_eq!((b.ends[0].at.value, b.ends[1].at.value), (10.7, 10.95));
    let pds: Vec<&Bifurcation> = b
        .bifurcations
        .iter()
        .filter(|f| f.kind == TransitionKind::PeriodDoubling)
        .collect();
    assert_eq!(pds.len(), 1, "{:?}", b.bifurcations);
    let pd = pds[0];
    assert_eq!(b.points[pd.index], pd.at);
    assert!((pd.eigenvalue[0] + 1.0).abs() < 1e-9, "{:?}", pd.eigenvalue);
    // Stable before, unstable after (the sweep's grid saw the loss of stability past 10.8).
    assert!(b.points[pd.index - 1].stability.is_stable());
    assert!(!b.points[pd.index + 1].stability.is_stable());
    let d = orbit_distance::<Paper>(&base, index, &b, pd);
    assert!(d < 1e-7, "orbit at the PD: eigenvalue {d:e} from -1");
    // The unstable part is made of motions.
    assert!(check_unstable::<Paper>(&base, index, &b) >= 5);

    // The doubled branch.
    let starts = born::<Paper>(&base, index, &b, pd, &o);
    assert_eq!(starts.len(), 1);
    let db = follow::<Paper>(&base, index, &starts[0], &o).expect("the doubled branch");
    assert_eq!(db.structure.periods(), 2);
    assert_eq!(db.structure.len(), 2 * b.structure.len());
    assert!(db.points.len() >= 4, "{} points", db.points.len());
    assert_eq!(db.ends.len(), 1);
    // The point farthest from the PD: periodic with two forcing periods, not one.
    let q = db
        .points
        .iter()
        .max_by(|a, c| {
            (a.value - pd.at.value)
                .abs()
                .total_cmp(&(c.value - pd.at.value).abs())
        })
        .expect("points");
    assert!((q.value - pd.at.value).abs() > 1e-3, "{}", q.value);
    check_point::<Paper>(&base, index, &db.structure, q).expect("a motion of two periods");
    let two = return_distance::<Paper>(&base, index, &db.structure, q, 2);
    let one = return_distance::<Paper>(&base, index, &db.structure, q, 1);
    assert!(two < 1e-8, "{two:e}");
    assert!(one > 1e-4, "also a motion of one period: {one:e}");
    for p in db
        .points
        .iter()
        .filter(|p| db.ends.iter().all(|e| e.at != **p))
    {
        check_point::<Paper>(&base, index, &db.structure, p).expect("a motion");
    }
}

#[test]
fn corrector_step_and_tangent_allocate_nothing() {
    use stickslip::models::paper::{Paper, Params};
    let base = Params {
        Q0: 100.0,
        mu3: 3.0,
        ..Params::default()
    };
    let index = Params::index_of("W").expect("W");
    let m = settle::<Paper>(with(&base, index, 10.75));
    let n = m.points.len();
    let l = PeriodicSolver::<Paper>::length_scale(&with(&base, index, 10.75), &m.points);
    let mut sys = Bordered::<Paper>::new(m.structure.clone(), base, index, l, 0.25);
    let x0 = State {
        points: m.points.clone(),
        value: 10.75,
    };
    let border = Vector::parameter(n);
    let mut t = Vector::zeros(n);
    let (count, r) = allocations(|| sys.tangent(&x0, &border, &mut t));
    assert!(r.is_ok());
    assert_eq!(count, 0, "the tangent allocated {count} times");
    assert!(t.dl > 0.0);
    // A predictor step along the tangent, corrected on the hyperplane.
    let mut x = x0.clone();
    Bordered::<Paper>::advance(&x0, 1e-3, &t, &mut x);
    let anchor = x.clone();
    let (count, c) = allocations(|| sys.correct(&mut x, &t, &anchor, 1e-12, 12));
    assert!(matches!(c, Correction::Converged { .. }), "{c:?}");
    assert_eq!(count, 0, "the corrector allocated {count} times");
    // The corrected point solves the mapping equations and lies on the hyperplane.
    assert!(sys.residual(&x) < 1e-11);
    assert!(sys.dot_diff(&t, &x, &anchor).abs() < 1e-14);
    assert!((x.value - x0.value).abs() > 1e-5);
}

/// The real eigenvalue of `q`'s `DP` nearest +1.
fn near_one(q: &BranchPoint) -> f64 {
    let e = q.stability.eigenvalues;
    let pick = if (e[0][0] - 1.0).abs() + e[0][1].abs() <= (e[1][0] - 1.0).abs() + e[1][1].abs() {
        e[0]
    } else {
        e[1]
    };
    assert_eq!(pick[1], 0.0, "real near a fold: {e:?}");
    pick[0]
}

#[test]
fn fold_of_a_four_stop_motion_of_the_coulomb_oscillator() {
    use stickslip::models::coulomb::{Coulomb, Params};
    // Damped Coulomb oscillator on a fixed surface, static 1.5× kinetic friction.
    let base = Params {
        V: 0.0,
        d: 0.02,
        mus: 0.45,
        muk: 0.3,
        Q0: 1.0,
        ..Params::default()
    };
    let index = Params::index_of("W").expect("W");
    let o = opts((0.05, 0.5));
    let b = branch_from_rest::<Coulomb>(&base, index, 0.2, &o);
    let folds: Vec<&Bifurcation> = b
        .bifurcations
        .iter()
        .filter(|f| f.kind == TransitionKind::Fold)
        .collect();
    assert!(!folds.is_empty(), "{:?}", b.bifurcations);
    for f in folds {
        let (a, c) = (&b.points[f.index - 1], &b.points[f.index + 1]);
        // The branch turns back: both neighbours lie on one side of the fold.
        assert!(
            (a.value - f.at.value) * (c.value - f.at.value) > 0.0,
            "{} {} {}",
            a.value,
            f.at.value,
            c.value
        );
        // One side stable, the other unstable; the eigenvalue crosses +1.
        assert_ne!(a.stability.is_stable(), c.stability.is_stable());
        assert!((near_one(a) - 1.0) * (near_one(c) - 1.0) < 0.0);
        assert!((f.eigenvalue[0] - 1.0).abs() < 1e-9, "{:?}", f.eigenvalue);
        let d = orbit_distance::<Coulomb>(&base, index, &b, f);
        assert!(d < 1e-7, "orbit at the fold: eigenvalue {d:e} from 1");
        // Two motions coexist at the neighbour nearer the fold: Newton at
        // fixed parameter from the other neighbour's points finds a second,
        // distinct solution with the other stability.
        let (near, far) = if (a.value - f.at.value).abs() < (c.value - f.at.value).abs() {
            (a, c)
        } else {
            (c, a)
        };
        let sim = Simulator::<Coulomb>::new(with(&base, index, near.value), SimOptions::default())
            .expect("valid");
        let other = solve(
            &sim,
            b.structure.clone(),
            far.points.clone(),
            NewtonOptions::default(),
        );
        assert!(other.is_admissible(), "{:?}", other.termination);
        let gap = (other.points[0].x - near.points[0].x).abs();
        assert!(gap > 1e-6, "the same motion: {gap:e}");
        assert_eq!(
            other.stability.expect("DP").is_stable(),
            far.stability.is_stable()
        );
    }
    assert!(check_unstable::<Coulomb>(&base, index, &b) >= 3);
}

/// Shaw's mirror image of a motion of a symmetric structure (m even, the
/// second half the mirror of the first): `x → −x`, `t → t + T/2`.
fn mirror(points: &[SwitchingPoint]) -> Vec<SwitchingPoint> {
    let m = points.len();
    let h = m / 2;
    (0..m)
        .map(|k| {
            let (q, wrap) = if k + h < m {
                (points[k + h], 0.0)
            } else {
                (points[k + h - m], TAU)
            };
            SwitchingPoint {
                x: -q.x,
                phase: q.phase + wrap - std::f64::consts::PI,
            }
        })
        .collect()
}

fn point_distance(a: &[SwitchingPoint], b: &[SwitchingPoint]) -> f64 {
    let turns = ((a[0].phase - b[0].phase) / TAU).round() * TAU;
    a.iter()
        .zip(b)
        .map(|(p, q)| (p.x - q.x).abs().max((p.phase - q.phase - turns).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn shaw_pitchfork_of_symmetric_two_stop_motions() {
    use stickslip::models::coulomb::{Coulomb, Params};
    // Shaw (J. Sound Vib. 108, 1986): Den Hartog's undamped oscillator with
    // Coulomb friction on a fixed surface (V = 0), static friction 1.5× kinetic.
    let base = Params {
        V: 0.0,
        d: 0.0,
        mus: 0.45,
        muk: 0.3,
        Q0: 1.5,
        ..Params::default()
    };
    let index = Params::index_of("W").expect("W");
    let o = opts((0.2, 0.6));
    let b = branch_from_rest::<Coulomb>(&base, index, 0.35, &o);
    assert_eq!(
        b.structure.notation(Coulomb::INFO),
        "P_{0_11 1_11 0_11 2_11}"
    );
    // The branch is symmetric: each point is its own mirror image (but the
    // branch point, where the solution is not locally unique: there the
    // corrector may slide along the kernel by about the square root of the rounding).
    let at_bp: Vec<usize> = b.bifurcations.iter().map(|f| f.index).collect();
    for (i, q) in b.points.iter().enumerate() {
        if at_bp.contains(&i) {
            continue;
        }
        let d = point_distance(&mirror(&q.points), &q.points);
        assert!(d < 1e-8, "not symmetric at {}: {d:e}", q.value);
    }
    let bps: Vec<&Bifurcation> = b
        .bifurcations
        .iter()
        .filter(|f| f.kind == TransitionKind::BranchPoint)
        .collect();
    assert_eq!(bps.len(), 1, "{:?}", b.bifurcations);
    let bp = bps[0];
    let d = orbit_distance::<Coulomb>(&base, index, &b, bp);
    assert!(
        d < 1e-7,
        "orbit at the branch point: eigenvalue {d:e} from 1"
    );
    // The symmetric motions lose stability there.
    assert_ne!(
        b.points[bp.index - 1].stability.is_stable(),
        b.points[bp.index + 1].stability.is_stable()
    );
    check_unstable::<Coulomb>(&base, index, &b);
    let starts = born::<Coulomb>(&base, index, &b, bp, &o);
    assert_eq!(starts.len(), 2);
    let halves: Vec<Branch> = starts
        .iter()
        .map(|s| follow::<Coulomb>(&base, index, s, &o).expect("a half"))
        .collect();
    for h in &halves {
        assert_eq!(h.structure, b.structure);
        assert!(h.points.len() >= 3, "{} points", h.points.len());
        for q in h
            .points
            .iter()
            .filter(|q| h.ends.iter().all(|e| e.at != **q))
        {
            check_point::<Coulomb>(&base, index, &h.structure, q).expect("a motion");
        }
        // Unsymmetric away from the branch point.
        let q = h.points.last().expect("points");
        assert!(point_distance(&mirror(&q.points), &q.points) > 1e-4);
    }
    // The halves are mirror images: at each point of one, Newton at that
    // parameter from the nearest point of the other converges to its mirror.
    for (a, c) in [(&halves[0], &halves[1]), (&halves[1], &halves[0])] {
        for q in a.points.iter().skip(1) {
            let near = c
                .points
                .iter()
                .min_by(|x, y| {
                    (x.value - q.value)
                        .abs()
                        .total_cmp(&(y.value - q.value).abs())
                })
                .expect("points");
            let sim = Simulator::<Coulomb>::new(with(&base, index, q.value), SimOptions::default())
                .expect("valid");
            let other = solve(
                &sim,
                c.structure.clone(),
                near.points.clone(),
                NewtonOptions::default(),
            );
            assert!(other.termination.converged(), "{:?}", other.termination);
            let d = point_distance(&mirror(&q.points), &other.points);
            assert!(d < 1e-8, "not mirror images at {}: {d:e}", q.value);
        }
    }
}
