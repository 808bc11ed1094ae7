//! The event-driven simulation against an independent numerical integration
//! of the same ODE.
//!
//! The integrator (`tests/common/events.rs`, `PiecewiseOde`) knows nothing of
//! the closed forms: in domain `j` it integrates
//! `x'' = A0 cos(W t) − b_j − 2d_j x' − c_j x` (coefficients from
//! `Model::coefficients`) with an adaptive Dormand–Prince 5(4) at a relative
//! tolerance of 1e-13; a boundary crossing is located by bisection on steps
//! re-taken from the step's start with a shorter length; on the stick
//! boundary it applies the force criteria of SPEC §3 to the input forces
//! `F_j(x, V, t)` of the domains above and below, and a stick
//! (`x = x_i + V (t − t_i)`) ends at the first root of `|Fnf| = as`, found by
//! scanning and bisection.
//!
//! Compared from rest over 30 forcing periods: the same sequence of
//! (boundary, kind) events, phases within 1e-8 and displacements within 1e-8.

mod common;

use common::events::PiecewiseOde;
use stickslip::dynamics::simulate::{EventKind, SimOptions, Simulator};
use stickslip::models::coulomb::{self, Coulomb};
use stickslip::models::paper::{self, Paper};
use stickslip::Model;

const TAU: f64 = 2.0 * std::f64::consts::PI;
const PERIODS: f64 = 30.0;

/// Simulate `M` at `p` from rest with both methods and compare; returns the
/// worst phase and x deviations, the number of events and how many of them
/// are stick onsets or ends.
fn compare<M: Model>(label: &str, p: M::Params) -> (f64, f64, usize, usize) {
    let sim = Simulator::<M>::new(p, SimOptions::default()).expect("valid parameters");
    let end = PERIODS * TAU;
    let start = sim.start(0.0, 0.0, 0.0).expect("start");
    let mut simulated = Vec::new();
    let mut grazes = 0;
    sim.run(start, end, |e| {
        if e.kind == EventKind::Graze {
            grazes += 1;
        } else {
            simulated.push(*e);
        }
    })
    .unwrap_or_else(|e| panic!("{label}: simulation failed: {e}"));
    assert_eq!(
        grazes, 0,
        "{label}: grazes are not expected at these parameters"
    );
    let sys = PiecewiseOde::of::<M>(&p);
    let reference = sys.integrate(0.0, 0.0, 0.0, Some(sys.domain_of(0.0)), end / sys.w, 1e-13);
    // Ignore events within 1e-6 of the end (one side may place them just past it).
    let keep = |phase: f64| phase < end - 1e-6;
    let simulated: Vec<_> = simulated.into_iter().filter(|e| keep(e.phase)).collect();
    let reference: Vec<_> = reference.into_iter().filter(|e| keep(e.phase)).collect();
    let (mut dphi, mut dx) = (0.0f64, 0.0f64);
    for (n, (a, b)) in simulated.iter().zip(&reference).enumerate() {
        assert!(
            a.boundary == b.boundary && a.kind == b.kind,
            "{label}: event {n}: simulation {:?} on boundary {} at {}, integration {:?} on boundary {} at {}",
            a.kind,
            a.boundary,
            a.phase,
            b.kind,
            b.boundary,
            b.phase
        );
        dphi = dphi.max((a.phase - b.phase).abs());
        dx = dx.max((a.x - b.x).abs());
        assert!(
            (a.phase - b.phase).abs() < 1e-8 && (a.x - b.x).abs() < 1e-8,
            "{label}: event {n} ({:?} on {}): simulation ({}, {}), integration ({}, {})",
            a.kind,
            a.boundary,
            a.phase,
            a.x,
            b.phase,
            b.x
        );
    }
    assert_eq!(
        simulated.len(),
        reference.len(),
        "{label}: {} simulated events, {} integrated; first extra: {:?} / {:?}",
        simulated.len(),
        reference.len(),
        simulated.get(reference.len()),
        reference.get(simulated.len())
    );
    let sticks = simulated
        .iter()
        .filter(|e| matches!(e.kind, EventKind::StickOnset | EventKind::StickEnd))
        .count();
    eprintln!(
        "{label}: {} events ({sticks} stick onsets/ends), worst deviation: phase {dphi:.2e}, x {dx:.2e}",
        simulated.len()
    );
    (dphi, dx, simulated.len(), sticks)
}

fn paper_at(w: f64, q0: f64) -> paper::Params {
    paper::Params {
        W: w,
        Q0: q0,
        ..paper::Params::default()
    }
}

#[test]
fn paper_model_matches_the_integrator() {
    let cases = [
        (3.0, 70.0),
        (3.7, 70.0),
        (5.0, 70.0),
        (1.0, 70.0),
        (2.2, 70.0),
        (4.5, 70.0),
        (3.7, 40.0),
        (5.0, 40.0),
        (0.7, 120.0),
    ];
    let (mut total, mut sticks) = (0, 0);
    let (mut wp, mut wx) = (0.0f64, 0.0f64);
    for (w, q0) in cases {
        let (dp, dx, n, s) = compare::<Paper>(&format!("paper W={w} Q0={q0}"), paper_at(w, q0));
        total += n;
        sticks += s;
        wp = wp.max(dp);
        wx = wx.max(dx);
    }
    eprintln!("paper: {total} events in all; worst phase {wp:.2e}, worst x {wx:.2e}");
    // (At W = 1 only the transient from rest reaches the boundaries.)
    assert!(
        total > 100,
        "only {total} events: the comparison is vacuous"
    );
    assert!(sticks > 20, "only {sticks} stick onsets and ends");
}

/// Random parameters (fixed seed): forcing, damping, stiffness and friction.
#[test]
fn paper_model_matches_the_integrator_at_random_parameters() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(99);
    let mut total = 0;
    for n in 0..16 {
        let p = paper::Params {
            W: rng.gen_range(1.0..8.0),
            Q0: rng.gen_range(20.0..150.0),
            d: rng.gen_range(0.0..0.4),
            c: rng.gen_range(5.0..50.0),
            mus: rng.gen_range(0.41..0.9),
            ..paper::Params::default()
        };
        let (_, _, k, _) = compare::<Paper>(&format!("random case {n}: {p:?}"), p);
        total += k;
    }
    assert!(total > 300, "only {total} events");
}

#[test]
fn coulomb_model_matches_the_integrator() {
    let (_, _, n, sticks) = compare::<Coulomb>("coulomb defaults", coulomb::Params::default());
    assert!(n > 10, "only {n} events");
    assert!(
        sticks > 4,
        "only {sticks} stick events: stick-slip is what this model is for"
    );
}

/// The comparison can fail: a slightly different forcing frequency moves the
/// events by far more than the tolerance.
#[test]
fn the_comparison_detects_a_perturbed_model() {
    let p = paper_at(3.7, 70.0);
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid");
    let mut simulated = Vec::new();
    sim.run(sim.start(0.0, 0.0, 0.0).unwrap(), 5.0 * TAU, |e| {
        simulated.push(*e)
    })
    .unwrap();
    let mut q = p;
    q.W *= 1.0 + 1e-7;
    let sys = PiecewiseOde::of::<Paper>(&q);
    // Same phases, slightly different physics.
    let reference = sys.integrate(
        0.0,
        0.0,
        0.0,
        Some(sys.domain_of(0.0)),
        5.0 * TAU / q.W,
        1e-13,
    );
    let worst = simulated
        .iter()
        .zip(&reference)
        .map(|(a, b)| (a.phase - b.phase).abs())
        .fold(0.0f64, f64::max);
    assert!(worst > 1e-8, "a 1e-7 change of W went unnoticed: {worst:e}");
}

/// Issue 9's undamped case that does not settle (`d = 0`, `W = 0.3`,
/// `muk = 0.1`, `mus = 0.15`): the reference integration over 400 forcing
/// periods drifts like the simulation (no cycle in either), event by event
/// for the first 200 stick onsets.
/// Run with `--ignored --nocapture` to see the stick-onset drift.
#[test]
#[ignore = "slow: 400 forcing periods of Dormand–Prince"]
fn the_undamped_w03_case_drifts_in_the_integrator_too() {
    let p = coulomb::Params {
        m: 1.0,
        d: 0.0,
        c: 1.0,
        V: 0.0,
        mus: 0.15,
        muk: 0.1,
        g: 1.0,
        Q0: 1.0,
        W: 0.3,
    };
    let periods = 400.0;
    let sys = PiecewiseOde::of::<Coulomb>(&p);
    // Off the belt speed (the integrator starts inside a domain).
    let reference = sys.integrate(
        0.0,
        0.0,
        0.5,
        Some(sys.domain_of(0.5)),
        periods * TAU / sys.w,
        1e-13,
    );
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
    let mut simulated = Vec::new();
    sim.run(sim.start(0.0, 0.5, 0.0).unwrap(), periods * TAU, |e| {
        if e.kind != EventKind::Graze {
            simulated.push(*e)
        }
    })
    .unwrap();
    let r: Vec<(f64, f64)> = reference
        .iter()
        .filter(|e| e.kind == EventKind::StickOnset)
        .map(|e| (e.phase, e.x))
        .collect();
    let s: Vec<(f64, f64)> = simulated
        .iter()
        .filter(|e| e.kind == EventKind::StickOnset)
        .map(|e| (e.phase, e.x))
        .collect();
    for k in [10, 100, 300, 600, r.len().min(s.len()) - 1] {
        eprintln!(
            "onset {k}: integrator W t = {:.9} x = {:.12}; simulation W t = {:.9} x = {:.12}",
            r[k].0, r[k].1, s[k].0, s[k].1
        );
    }
    // Event by event within 1e-8 over the first 200 onsets; later the
    // neutral (undamped) drift amplifies round-off and the two part.
    let worst = (0..200)
        .map(|k| (r[k].1 - s[k].1).abs())
        .fold(0.0, f64::max);
    // No cycle of up to 16 onsets at the end of the integration: the onset
    // positions still move by more than 1e-6.
    let last = r.len() - 1;
    let closest = (1..=16)
        .map(|j| (r[last].1 - r[last - j].1).abs())
        .fold(f64::INFINITY, f64::min);
    eprintln!(
        "{} / {} onsets, worst |dx| over 200 onsets = {worst:.2e}, closest return = {closest:.2e}",
        r.len(),
        s.len()
    );
    assert!(worst < 1e-8);
    assert!(closest > 1e-6);
}
