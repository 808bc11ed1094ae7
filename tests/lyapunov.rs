//! The Lyapunov spectrum of the stroboscopic map (issue 13), each against an
//! independent computation:
//!
//! * the exact tangent map against central finite differences of the
//!   stroboscopic map computed by simulation (passes, sticks, several domains);
//! * periodic motions: the exponents against `ln|λ_i| / T` of the reference
//!   eigenvalues of `DP` (`../shared/reference`, computed outside stickslip) and
//!   of the motion's own `DP` from the mapping Jacobians;
//! * the sum of the exponents against the phase-space contraction.

mod common;

use common::events::PiecewiseOde;
use common::reference::references;
use nalgebra::Matrix2;
use stickslip::dynamics::simulate::{EventKind, Location, SimOptions, Simulator};
use stickslip::dynamics::tangent::{advance, Tangent};
use stickslip::model::Model;
use stickslip::models::paper::{Paper, Params};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::attractor::Attractor;
use stickslip::orbit::lyapunov::{spectrum, LyapunovOptions, Verdict};

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn paper(w: f64, q0: f64) -> Simulator<Paper> {
    let p = Params {
        W: w,
        Q0: q0,
        ..Params::default()
    };
    Simulator::new(p, SimOptions::default()).expect("valid parameters")
}

/// The stroboscopic map from `(x, v)` at phase `phi` (one forcing period),
/// and the tangent computed along it; the kinds of events met.
fn strobe<M: Model>(
    sim: &Simulator<M>,
    x: f64,
    v: f64,
    phi: f64,
) -> ((f64, f64), Tangent, Vec<EventKind>, Vec<Location>) {
    let seg = sim.start(x, v, phi).expect("start");
    let mut t = Tangent::new(Matrix2::identity());
    let mut kinds = Vec::new();
    let mut locations = vec![seg.location];
    let end = advance(sim, seg, phi + TAU, &mut t, |e| {
        kinds.push(e.kind);
        locations.push(e.after);
    })
    .expect("simulation");
    ((end.x, end.v), t, kinds, locations)
}

#[test]
fn tangent_map_matches_finite_differences_of_the_stroboscopic_map() {
    let h = 1e-6;
    let mut seen = Vec::new();
    let mut cases = 0;
    for (w, q0) in [
        (5.0, 70.0),
        (3.7, 70.0),
        (3.0, 70.0),
        (2.0, 90.0),
        (4.2, 60.0),
    ] {
        let sim = paper(w, q0);
        // States along the motion after a short transient, at several phases.
        let mut seg = sim.start(0.3, 0.0, 0.0).expect("start");
        for k in 1..=40 {
            let phi = k as f64 * 1.37;
            seg = sim.run(seg, phi, |_| {}).expect("run");
            let (x, v) = sim.state_at(&seg, phi);
            if seg.location == Location::Stick || k < 10 {
                continue;
            }
            let (_, t, kinds, locations) = strobe(&sim, x, v, phi);
            let mut fd = Matrix2::zeros();
            for c in 0..2 {
                let dx = if c == 0 { h } else { 0.0 };
                let dv = if c == 1 { h } else { 0.0 };
                let (p, _, kp, _) = strobe(&sim, x + dx, v + dv, phi);
                let (m, _, km, _) = strobe(&sim, x - dx, v - dv, phi);
                // A perturbation that changes the sequence of events (near a
                // graze) has no derivative to compare with.
                if kp != kinds || km != kinds {
                    fd[(0, 0)] = f64::NAN;
                    break;
                }
                fd[(0, c)] = (p.0 - m.0) / (2.0 * h);
                fd[(1, c)] = (p.1 - m.1) / (2.0 * h);
            }
            if fd[(0, 0)].is_nan() {
                continue;
            }
            let scale = t.matrix.abs().max().max(1.0);
            let err = (t.matrix - fd).abs().max();
            assert!(
                err <= 2e-6 * scale,
                "W = {w}, Q0 = {q0}, from ({x}, {v}, {phi}): tangent {} vs finite differences {} ({kinds:?})",
                t.matrix,
                fd
            );
            cases += 1;
            seen.extend(kinds);
            seen.extend(locations.iter().map(|l| match l {
                Location::Stick => EventKind::StickOnset,
                Location::Domain(_) => EventKind::Pass,
            }));
            let _ = locations;
        }
    }
    assert!(cases >= 60, "only {cases} states compared");
    for kind in [EventKind::Pass, EventKind::StickOnset, EventKind::StickEnd] {
        assert!(seen.contains(&kind), "no {kind:?} in the compared periods");
    }
}

/// `ln|μ|` of eigenvalues `[re, im]`, largest first.
fn log_moduli(eigs: &[[f64; 2]]) -> [f64; 2] {
    let mut l: Vec<f64> = eigs.iter().map(|e| e[0].hypot(e[1]).ln()).collect();
    l.sort_by(|a, b| b.partial_cmp(a).expect("ordered"));
    [l[0], l[1]]
}

fn assert_exponents(got: [f64; 2], want: [f64; 2], what: &str) {
    for i in 0..2 {
        if want[i] == f64::NEG_INFINITY {
            assert_eq!(got[i], f64::NEG_INFINITY, "{what}: exponent {i}: {got:?}");
        } else {
            assert!(
                (got[i] - want[i]).abs() <= 1e-8 * want[i].abs().max(1.0),
                "{what}: exponent {i}: {got:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn periodic_exponents_are_the_logs_of_the_dp_eigenvalues() {
    let mut with_stick = false;
    let mut slip_only = false;
    for case in references() {
        let sim = case.simulator();
        let period = TAU / case.w;
        let start = case.points[0];
        let opts = LyapunovOptions {
            transient: 200,
            periods: 400,
        };
        let s = spectrum(&sim, (start.x + 1e-3, 1.0, start.phase), opts).expect("spectrum");
        let Verdict::Periodic { structure, n } = &s.verdict else {
            panic!("{}: verdict {:?}", case.structure, s.verdict);
        };
        assert_eq!(*n, case.periods, "{}", case.structure);
        let t = period * case.periods as f64;
        // The reference eigenvalues (computed outside stickslip); a stick
        // makes one exactly zero: -inf.
        let mut want = log_moduli(&case.eigenvalues).map(|l| l / t);
        let stick = case.mappings.iter().any(|m| m == "0_11");
        if stick {
            want[1] = f64::NEG_INFINITY;
            with_stick = true;
        } else {
            slip_only = true;
        }
        assert_exponents(s.exponents, want, structure);
        // And the motion's own DP (mapping Jacobians), computed otherwise.
        let Some(Attractor::Periodic(motion)) = &s.attractor else {
            panic!("{structure}: no motion");
        };
        let stab = motion.stability.as_ref().expect("DP");
        let mut own = log_moduli(&stab.eigenvalues).map(|l| l / t);
        if stab.has_zero_eigenvalue {
            own[1] = f64::NEG_INFINITY;
        }
        assert_exponents(s.exponents, own, structure);
        for i in 0..2 {
            if s.exponents[i].is_finite() {
                assert!((s.per_period[i] - s.exponents[i] * period).abs() <= 1e-14);
            }
        }
    }
    assert!(with_stick && slip_only);
}

/// The chaotic case found by the search (README, "Lyapunov exponents"): the
/// eight-piece Stribeck model at `Q0 = 3`, `W = 2.38`.
fn chaotic() -> Simulator<Stribeck8> {
    let p = stribeck8::Params {
        W: 2.38,
        Q0: 3.0,
        ..stribeck8::Params::default()
    };
    Simulator::new(p, SimOptions::default()).expect("valid parameters")
}

#[test]
fn tangent_map_matches_finite_differences_in_eight_domains() {
    let sim = chaotic();
    let mut seg = sim.start(0.1, 0.0, 0.0).expect("start");
    let mut cases = 0;
    let mut domains = Vec::new();
    for k in 1..=80 {
        let phi = k as f64 * 2.11;
        seg = sim.run(seg, phi, |_| {}).expect("run");
        let (x, v) = sim.state_at(&seg, phi);
        if seg.location == Location::Stick || k < 10 {
            continue;
        }
        let (_, t, kinds, locations) = strobe(&sim, x, v, phi);
        let h = 1e-6;
        let mut fd = Matrix2::zeros();
        let mut same = true;
        for c in 0..2 {
            let (dx, dv) = if c == 0 { (h, 0.0) } else { (0.0, h) };
            let (p, _, kp, _) = strobe(&sim, x + dx, v + dv, phi);
            let (m, _, km, _) = strobe(&sim, x - dx, v - dv, phi);
            same &= kp == kinds && km == kinds;
            fd[(0, c)] = (p.0 - m.0) / (2.0 * h);
            fd[(1, c)] = (p.1 - m.1) / (2.0 * h);
        }
        if !same {
            continue;
        }
        let scale = t.matrix.abs().max().max(1.0);
        let err = (t.matrix - fd).abs().max();
        assert!(
            err <= 2e-6 * scale,
            "from ({x}, {v}, {phi}): tangent {} vs finite differences {} ({kinds:?})",
            t.matrix,
            fd
        );
        cases += 1;
        domains.extend(locations);
    }
    assert!(cases >= 40, "only {cases} states compared");
    domains.sort_by_key(|l| match l {
        Location::Stick => 0,
        Location::Domain(j) => j + 1,
    });
    domains.dedup();
    assert!(domains.len() >= 5, "visited only {domains:?}");
}

/// The largest exponent by two nearby trajectories (Benettin, renormalised
/// every forcing period), integrated by the independent Dormand–Prince
/// reference with events (`tests/common/events`): the mean and the standard
/// error over 10 blocks.
fn benettin<M: Model>(
    p: &M::Params,
    start: (f64, f64),
    transient: u32,
    periods: u32,
) -> (f64, f64) {
    let ode = PiecewiseOde::of::<M>(p);
    let w = ode.w;
    let period = TAU / w;
    let rtol = 1e-13;
    let (mut y, mut dom) = ([start.0, start.1], Some(ode.domain_of(start.1)));
    let mut t = 0.0;
    for _ in 0..transient {
        let (_, y1, d1) = ode.integrate_to(t, y[0], y[1], dom, t + period, rtol);
        (y, dom, t) = (y1, d1, t + period);
    }
    let d0 = 1e-7;
    // The neighbour: displaced off the velocity direction (a stuck state
    // keeps v on the belt).
    let mut dir = [1.0, 0.0];
    let mut logs = Vec::new();
    for _ in 0..periods {
        let z = [y[0] + d0 * dir[0], y[1] + d0 * dir[1]];
        let dz = if z[1] == y[1] && dom.is_none() {
            None
        } else {
            Some(ode.domain_of(z[1]))
        };
        let (_, y1, d1) = ode.integrate_to(t, y[0], y[1], dom, t + period, rtol);
        let (_, z1, _) = ode.integrate_to(t, z[0], z[1], dz, t + period, rtol);
        let sep = [z1[0] - y1[0], z1[1] - y1[1]];
        let dist = sep[0].hypot(sep[1]);
        logs.push((dist / d0).ln());
        dir = [sep[0] / dist, sep[1] / dist];
        (y, dom, t) = (y1, d1, t + period);
    }
    let blocks = 10;
    let len = periods as usize / blocks;
    let means: Vec<f64> = (0..blocks)
        .map(|b| logs[b * len..(b + 1) * len].iter().sum::<f64>() / (len as f64 * period))
        .collect();
    let mean = means.iter().sum::<f64>() / blocks as f64;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (blocks - 1) as f64;
    (mean, (var / blocks as f64).sqrt())
}

#[test]
fn chaotic_largest_exponent_agrees_with_two_trajectories() {
    let sim = chaotic();
    let s = spectrum(
        &sim,
        (0.1, 0.0, 0.0),
        LyapunovOptions {
            transient: 1000,
            periods: 20_000,
        },
    )
    .expect("spectrum");
    assert_eq!(s.verdict, Verdict::Chaotic, "{s:?}");
    assert_eq!(s.exponents[1], f64::NEG_INFINITY, "a stick every period");
    let (lambda, err) = benettin::<Stribeck8>(sim.params(), (0.1, 0.0), 200, 3000);
    let bar = 3.0 * s.error.hypot(err);
    eprintln!(
        "spectrum {:.5} ± {:.1e}, two trajectories {lambda:.5} ± {err:.1e}",
        s.exponents[0], s.error
    );
    assert!(
        (s.exponents[0] - lambda).abs() <= bar,
        "spectrum {} ± {}, two trajectories {lambda} ± {err}",
        s.exponents[0],
        s.error
    );
    // The bar is tight enough to tell the exponent from zero.
    assert!(bar < 0.3 * lambda, "bar {bar} vs {lambda}");
}

#[test]
fn sum_of_exponents_is_the_phase_space_contraction_without_stick() {
    // The slip-only motion at W = 5 (a short run from a perturbed point: no
    // repeat, so the exponents are the QR averages).
    let sim = paper(5.0, 70.0);
    let start = (2.0, 1.0, 0.3);
    let periods = 6;
    let s = spectrum(
        &sim,
        start,
        LyapunovOptions {
            transient: 0,
            periods,
        },
    )
    .expect("spectrum");
    // Liouville: d/dt ln det = trace = -2 d_j in domain j; at a pass the
    // determinant jumps by a+/a- (the accelerations on both sides).
    let end = start.2 + periods as f64 * TAU;
    let w = sim.oscillator().frequency;
    let seg = sim.start(start.0, start.1, start.2).expect("start");
    let mut log_det = 0.0;
    let mut last = (start.2, seg.location);
    let p = *sim.params();
    let mut stuck = false;
    let flow = |from: f64, to: f64, loc: Location| match loc {
        Location::Domain(j) => -Paper::coefficients(&p, j).two_d * (to - from) / w,
        Location::Stick => f64::NEG_INFINITY,
    };
    let mut jumps = 0.0;
    sim.run(seg, end, |e| {
        log_det += flow(last.0, e.phase, last.1);
        if e.kind == EventKind::Pass {
            let [Location::Domain(a), Location::Domain(b)] = [e.before, e.after] else {
                unreachable!()
            };
            let am = Paper::normal_field(&p, a, e.x, e.v, e.phase)[0];
            let ap = Paper::normal_field(&p, b, e.x, e.v, e.phase)[0];
            jumps += (ap / am).abs().ln();
        }
        stuck |= e.kind == EventKind::StickOnset;
        if e.kind != EventKind::Graze {
            last = (e.phase, e.after);
        }
    })
    .expect("run");
    log_det += flow(last.0, end, last.1);
    assert!(!stuck, "the run sticks");
    let want = (log_det + jumps) / (end - start.2) * w;
    let got = s.exponents[0] + s.exponents[1];
    assert!(jumps.abs() > 0.1, "jumps {jumps}");
    assert!(
        (got - want).abs() <= 1e-9 * want.abs().max(1.0),
        "sum {got} vs contraction {want} ({s:?})"
    );
}
