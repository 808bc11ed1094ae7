//! Den Hartog's friction oscillator (Phil. Mag. 9, 1930/31; restated by
//! Marino & Cicirello, Nonlinear Dyn. 2020): the `coulomb` model with the
//! belt at rest (V = 0),
//!
//!     x'' + 2 d x' + c x = A0 cos(W t) − ak sgn(x'),
//!
//! against its closed-form non-stop steady state, derived here without any of
//! the library's flows.
//!
//! **Closed form.** Den Hartog's ansatz: a symmetric motion, `x(t + π/W) =
//! −x(t)`, with two velocity reversals per period and `x' > 0` on the half
//! period from the minimum `−X0` (at local time 0, forcing `A0 cos(W t + φ)`)
//! to the maximum `X0` (at `π/W`). On that half `x = −e + xp + h` with
//! `e = ak / c`, the forced response `xp = R cos(W t + φ − θ)`,
//! `R = A0 / sqrt((c − W²)² + (2 d W)²)`, `θ = atan2(2 d W, c − W²)`, and `h`
//! homogeneous, carried over the half period by the transfer matrix `Φ` of
//! `h'' + 2 d h' + c h = 0`. With `p = xp(0)`, `q = xp'(0)` and `xp(π/W) = −p`,
//! the four boundary conditions `x(0) = −X0, x'(0) = 0, x(π/W) = X0,
//! x'(π/W) = 0` become `Φ (e − s, −q) = (e + s, q)` with `s = X0 + p`, i.e.
//!
//!     (Φ + I) (s, q)ᵀ = (Φ − I) (e, 0)ᵀ,
//!
//! a linear 2×2 system for `(s, q)`; then `p = −sqrt(R² − (q / W)²)` (the branch
//! continuous with the frictionless response), `X0 = s − p` and
//! `φ = θ + atan2(−q / W, p)`. For `d = 0` this is Den Hartog's
//! `X0 / (A0 / c) = sqrt(V0² − (r U)²)`, `V0 = 1 / (1 − β²)`,
//! `U = sin(π/β) / (β (1 + cos(π/β)))`, `β = W / sqrt(c)`, `r = ak / A0`
//! (checked below).
//!
//! **Non-stop boundary.** The ansatz is a motion only if the mass does not
//! stop at a reversal (the acceleration just after it, `A0 cos φ + c X0 − ak`,
//! is positive: spring and forcing overcome friction) and the velocity keeps
//! its sign in between. Where the first condition fails, the motion has stops.

mod common;

use common::dopri;
use common::roots::bracket;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::coulomb::{Coulomb, Params};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::{solve, Motion};
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::{sweep, SweepOptions};

const TAU: f64 = 2.0 * std::f64::consts::PI;
const PI: f64 = std::f64::consts::PI;

/// The oscillator per unit mass.
#[derive(Clone, Copy, Debug)]
struct Osc {
    a0: f64,
    d: f64,
    c: f64,
    ak: f64,
    w: f64,
}

/// Den Hartog's non-stop motion.
#[derive(Clone, Copy, Debug)]
struct NonStop {
    /// Amplitude.
    x0: f64,
    /// Phase `W t` of the minimum (start of the upward half), in [0, 2π).
    phi: f64,
    /// Acceleration just after the reversal (positive: the mass does not stop).
    kick: f64,
    /// Smallest `x' / (W X0)` inside the upward half period (sampled).
    min_v: f64,
    /// Largest velocity (on the upward half; the downward half mirrors it):
    /// the sampled maximum refined by golden-section search.
    max_v: f64,
}

/// `Φ(τ)` of `h'' + 2 d h' + c h = 0` on `(h, h')`.
fn transfer(d: f64, c: f64, tau: f64) -> [[f64; 2]; 2] {
    let w2 = c - d * d;
    let (cs, sn) = if w2 > 0.0 {
        let w = w2.sqrt();
        ((w * tau).cos(), (w * tau).sin() / w)
    } else if w2 < 0.0 {
        let w = (-w2).sqrt();
        ((w * tau).cosh(), (w * tau).sinh() / w)
    } else {
        (1.0, tau)
    };
    let e = (-d * tau).exp();
    [
        [e * (cs + d * sn), e * sn],
        [-e * c * sn, e * (cs - d * sn)],
    ]
}

fn den_hartog(o: Osc) -> Option<NonStop> {
    let half = PI / o.w;
    let f = transfer(o.d, o.c, half);
    let e = o.ak / o.c;
    // (Φ + I) (s, q) = (Φ − I) (e, 0).
    let (a11, a12, a21, a22) = (f[0][0] + 1.0, f[0][1], f[1][0], f[1][1] + 1.0);
    let (b1, b2) = ((f[0][0] - 1.0) * e, f[1][0] * e);
    let det = a11 * a22 - a12 * a21;
    let s = (b1 * a22 - a12 * b2) / det;
    let q = (a11 * b2 - a21 * b1) / det;
    let kw = o.c - o.w * o.w;
    let dw = 2.0 * o.d * o.w;
    let r = o.a0 / kw.hypot(dw);
    let theta = dw.atan2(kw);
    let p2 = r * r - (q / o.w).powi(2);
    if p2.is_nan() || p2 < 0.0 {
        return None;
    }
    let p = -p2.sqrt();
    let x0 = s - p;
    let phi = (theta + (-q / o.w).atan2(p)).rem_euclid(TAU);
    let kick = o.a0 * phi.cos() + o.c * x0 - o.ak;
    // The velocity on the upward half: h' + xp'.
    let (h0, dh0) = (-x0 + e - p, -q);
    let velocity = |t: f64| {
        let g = transfer(o.d, o.c, t);
        g[1][0] * h0 + g[1][1] * dh0 - r * o.w * (o.w * t + phi - theta).sin()
    };
    let mut min_v = f64::INFINITY;
    let (mut best, mut at) = (f64::NEG_INFINITY, 0);
    let n = 2000;
    for i in 1..n {
        let t = half * i as f64 / n as f64;
        let v = velocity(t);
        min_v = min_v.min(v / (o.w * x0.abs()));
        if v > best {
            (best, at) = (v, i);
        }
    }
    // Golden section on the samples either side of the largest.
    let (mut a, mut b) = (
        half * (at - 1) as f64 / n as f64,
        half * (at + 1) as f64 / n as f64,
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    while b - a > 1e-15 * half {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if velocity(c) > velocity(d) {
            b = d;
        } else {
            a = c;
        }
    }
    Some(NonStop {
        x0,
        phi,
        kick,
        min_v,
        max_v: velocity(0.5 * (a + b)),
    })
}

/// The friction level `ak` where the non-stop motion starts to stop at its
/// reversals (`kick = 0`), by bisection on the closed form.
fn boundary(o: Osc) -> f64 {
    let ok = |ak: f64| den_hartog(Osc { ak, ..o }).is_some_and(|n| n.kick > 0.0 && n.x0 > 0.0);
    assert!(ok(1e-9 * o.a0) && !ok(o.a0), "{o:?}");
    // The last friction level that is still non-stop, to 1e-15 relative.
    bracket(0.0, o.a0, |ak| !ok(ak), 1e-15 * o.a0).0
}

/// Parameters of `coulomb` with the given oscillator, `mus = ratio * muk`.
/// Non-unit mass, stiffness and gravity, so that a lost factor shows.
fn params(beta: f64, zeta: f64, r: f64, mus_ratio: f64) -> (Params, Osc) {
    let (m, c, g, q0) = (2.5, 30.0, 9.8, 70.0);
    let a0 = q0 / m;
    let w = beta * f64::sqrt(c);
    let d = zeta * f64::sqrt(c);
    let muk = r * a0 / g;
    let p = Params {
        m,
        d,
        c,
        V: 0.0,
        mus: muk * mus_ratio,
        muk,
        g,
        Q0: q0,
        W: w,
    };
    (
        p,
        Osc {
            a0,
            d,
            c,
            ak: muk * g,
            w,
        },
    )
}

/// The closed form's two switching points in the library's order for
/// `P_{1_11 2_11}` (`2_11`, the downward half, first): the maximum, then the
/// minimum one half period later.
fn closed_points(n: &NonStop) -> [SwitchingPoint; 2] {
    [
        SwitchingPoint {
            phase: n.phi + PI,
            x: n.x0,
        },
        SwitchingPoint {
            phase: n.phi + TAU,
            x: -n.x0,
        },
    ]
}

/// Every point of `motion` equals a closed-form point (phases mod 2π) within
/// `tol`; returns the largest deviation.
fn assert_same(motion: &Motion, n: &NonStop, tol: f64, how: &str) -> f64 {
    let mut worst = 0.0f64;
    assert_eq!(
        motion.structure.notation(Coulomb::INFO),
        "P_{1_11 2_11}",
        "{how}"
    );
    assert_eq!(motion.structure.periods(), 1, "{how}");
    assert!(motion.is_admissible(), "{how}: {:?}", motion.violations);
    for pt in &motion.points {
        let want = closed_points(n)
            .into_iter()
            .find(|c| (c.x > 0.0) == (pt.x > 0.0))
            .expect("a point of each sign");
        let dphi = (pt.phase - want.phase + PI).rem_euclid(TAU) - PI;
        assert!(
            dphi.abs() < tol && (pt.x - want.x).abs() < tol * want.x.abs().max(1.0),
            "{how}: ({}, {}) vs Den Hartog ({}, {}): Δφ = {dphi:e}, Δx = {:e}",
            pt.phase,
            pt.x,
            want.phase,
            want.x,
            pt.x - want.x
        );
        worst = worst.max(dphi.abs()).max((pt.x - want.x).abs());
    }
    worst
}

fn orbit(p: Params, n: &NonStop) -> Motion {
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("valid parameters");
    let structure = Structure::parse(Coulomb::INFO, "P_{1_11 2_11}", 1).expect("structure");
    let guess = closed_points(n)
        .into_iter()
        .map(|c| SwitchingPoint {
            phase: c.phase + 1e-3,
            x: c.x * (1.0 - 1e-3),
        })
        .collect();
    solve(&sim, structure, guess, NewtonOptions::default())
}

/// Simulate from rest; where the forcing cannot break the static friction
/// from rest (`A0 ≤ as`), check that this is reported as a permanent stick at
/// 0 and simulate from a moving start instead.
fn simulate(p: Params) -> Result<Attractor, String> {
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("valid parameters");
    let find = |x: f64, v: f64| {
        let start = sim.start(x, v, 0.0).expect("start");
        attractor::find(&sim, start, AttractorOptions::default()).map_err(|e| e.to_string())
    };
    let (a0, a_s) = (p.Q0 / p.m, p.mus * p.g);
    if a0 > a_s {
        return find(0.0, 0.0);
    }
    match find(0.0, 0.0) {
        Ok(Attractor::Stick(s)) => assert!(s.x == 0.0 && s.since == 0.0, "{s:?}"),
        other => panic!("A0 = {a0} <= as = {a_s}: from rest {other:?}"),
    }
    find(0.0, p.W * a0 / p.c)
}

const BETAS: [f64; 10] = [0.4, 0.6, 0.75, 0.9, 1.1, 1.3, 1.6, 2.0, 2.5, 3.0];
const ZETAS: [f64; 3] = [0.0, 0.05, 0.3];
/// Friction levels as fractions of the non-stop boundary.
const FRACTIONS: [f64; 3] = [0.1, 0.5, 0.9];

#[test]
fn the_closed_form_is_den_hartogs_undamped_formula() {
    for beta in BETAS {
        for r in [0.05, 0.2, 0.5] {
            let (_, o) = params(beta, 0.0, r, 1.0);
            let Some(n) = den_hartog(o) else { continue };
            let v0 = 1.0 / (1.0 - beta * beta);
            let u = (PI / beta).sin() / (beta * (1.0 + (PI / beta).cos()));
            let arg = v0 * v0 - (r * u).powi(2);
            if arg < 0.0 {
                continue;
            }
            let want = arg.sqrt() * o.a0 / o.c;
            assert!(
                (n.x0 - want).abs() < 1e-12 * want,
                "β = {beta}, r = {r}: {} vs {want}",
                n.x0
            );
        }
    }
}

#[test]
fn the_closed_form_solves_the_equation_of_motion() {
    // Independent of the derivation: integrate the ODE over one half period
    // from the closed form's minimum (Dormand–Prince, `tests/common/dopri.rs`,
    // fine fixed steps) and land on its maximum.
    for (beta, zeta) in [(0.75, 0.0), (1.6, 0.05), (2.5, 0.3)] {
        let (_, o0) = params(beta, zeta, 0.0, 1.0);
        let o = Osc {
            ak: 0.5 * boundary(o0),
            ..o0
        };
        let n = den_hartog(o).expect("non-stop motion");
        let f = |t: f64, y: &[f64; 2]| {
            [
                y[1],
                o.a0 * (o.w * t).cos() - o.ak - 2.0 * o.d * y[1] - o.c * y[0],
            ]
        };
        let steps = 2_000;
        let t0 = n.phi / o.w;
        let h = PI / o.w / steps as f64;
        let mut y = [-n.x0, 0.0];
        for i in 0..steps {
            y = dopri::step(f, t0 + h * i as f64, y, h).y;
        }
        let [x, v] = y;
        assert!(
            (x - n.x0).abs() < 1e-10 * n.x0 && v.abs() < 1e-9 * o.w * n.x0,
            "β = {beta}, ζ = {zeta}: ({x}, {v}) vs ({}, 0)",
            n.x0
        );
    }
}

#[test]
fn orbit_and_simulate_reproduce_den_hartog_inside_the_non_stop_boundary() {
    let (mut compared, mut worst) = (0, 0.0f64);
    for beta in BETAS {
        for zeta in ZETAS {
            let (_, o0) = params(beta, zeta, 0.0, 1.0);
            let rb = boundary(o0) / o0.a0;
            for frac in FRACTIONS {
                for mus_ratio in [1.0, 1.5] {
                    let (p, o) = params(beta, zeta, frac * rb, mus_ratio);
                    let n = den_hartog(o).expect("inside the boundary");
                    let how =
                        format!("β = {beta}, ζ = {zeta}, r = {frac} r*, mus/muk = {mus_ratio}");
                    if n.min_v < 0.0 {
                        // The velocity changes sign inside the half period: not
                        // Den Hartog's motion (low β), and no motion of this structure.
                        let m = orbit(p, &n);
                        assert!(!m.is_admissible(), "{how}: {:?}", m.points);
                        continue;
                    }
                    if n.min_v < 1e-3 {
                        // Sampled too coarsely to decide (a near-graze inside).
                        continue;
                    }
                    let a = assert_same(&orbit(p, &n), &n, 1e-9, &format!("orbit {how}"));
                    let b = match simulate(p) {
                        Ok(Attractor::Periodic(m)) => {
                            assert_same(&m, &n, 1e-9, &format!("simulate {how}"))
                        }
                        other => panic!("simulate {how}: {other:?}"),
                    };
                    worst = worst.max(a).max(b);
                    compared += 1;
                }
            }
        }
    }
    eprintln!("{compared} grid points compared; worst deviation {worst:.1e}");
    assert!(compared >= 100, "{compared} points compared");
}

/// The frequency response of a sweep along W (its amplitudes `max |x|`,
/// `max |v|` at the grid values and along the branches) is Den Hartog's
/// closed-form amplitude `X0` and the largest velocity of his motion.
#[test]
fn the_sweeps_amplitudes_are_den_hartogs() {
    let (mut compared, mut worst) = (0, 0.0f64);
    for (zeta, mus_ratio) in [(0.0, 1.0), (0.05, 1.5), (0.3, 1.0)] {
        let (lo, hi) = (1.3, 2.5);
        // Inside the non-stop boundary over the whole range.
        let rb = [lo, 1.6, 2.0, hi]
            .iter()
            .map(|&beta| {
                let (_, o) = params(beta, zeta, 0.0, 1.0);
                boundary(o) / o.a0
            })
            .fold(f64::INFINITY, f64::min);
        let (base, o) = params(lo, zeta, 0.4 * rb, mus_ratio);
        let sq = f64::sqrt(o.c);
        let s = sweep::<Coulomb>(base, "W", lo * sq, hi * sq, 9, SweepOptions::default())
            .expect("the sweep runs");
        let mut check = |w: f64, x: f64, v: f64, what: &str| {
            let n = den_hartog(Osc { w, ..o }).expect("non-stop");
            assert!(n.min_v > 1e-3, "W = {w}: {n:?}");
            let (ex, ev) = ((x - n.x0).abs() / n.x0, (v - n.max_v).abs() / n.max_v);
            assert!(
                ex < 1e-9 && ev < 1e-9,
                "{what}, ζ = {zeta}, W = {w}: max|x| {x} vs X0 {}, max|v| {v} vs {}",
                n.x0,
                n.max_v
            );
            worst = worst.max(ex).max(ev);
            compared += 1;
        };
        const NON_STOP: &str = "P_{1_11 2_11}";
        for p in &s.points {
            let ours: Vec<_> = p
                .motions
                .iter()
                .filter(|m| m.structure == NON_STOP)
                .collect();
            assert_eq!(ours.len(), 1, "W = {}: {:?}", p.value, p.motions);
            check(p.value, ours[0].max_abs_x, ours[0].max_abs_v, "grid");
        }
        for b in s.branches.iter().filter(|b| b.structure == NON_STOP) {
            for q in &b.points {
                check(q.value, q.max_abs_x, q.max_abs_v, "branch");
            }
        }
    }
    eprintln!("{compared} amplitudes compared; worst relative deviation {worst:.1e}");
    assert!(compared >= 27, "{compared}");
}

#[test]
fn beyond_the_non_stop_boundary_the_motion_has_stops() {
    for beta in BETAS {
        for zeta in ZETAS {
            let (_, o0) = params(beta, zeta, 0.0, 1.0);
            let rb = boundary(o0) / o0.a0;
            let (_, o_in) = params(beta, zeta, rb, 1.0);
            let inside = den_hartog(o_in).expect("at the boundary");
            if inside.min_v <= 1e-3 {
                continue;
            }
            // Just inside (relative 1e-6 in friction: the kick-off acceleration
            // is then ~1e-6 A0, far above rounding) the non-stop motion is
            // admissible; just outside its reversal violates the pass criterion.
            for (frac, real) in [(1.0 - 1e-6, true), (1.0 + 1e-6, false)] {
                let (p, o) = params(beta, zeta, frac * rb, 1.0);
                let n = den_hartog(o).expect("closed form");
                let m = orbit(p, &n);
                let how = format!("β = {beta}, ζ = {zeta}, r = {frac} r*");
                assert!(m.termination.converged(), "{how}");
                assert_eq!(m.is_admissible(), real, "{how}: {:?}", m.violations);
            }
            // Clearly outside, the simulation settles to a motion with stops.
            let (p, _) = params(beta, zeta, 1.3 * rb, 1.0);
            let how = format!("β = {beta}, ζ = {zeta}, r = 1.3 r*");
            match simulate(p) {
                Ok(Attractor::Periodic(m)) => {
                    assert!(
                        m.structure.has_stick(Coulomb::INFO),
                        "{how}: {}",
                        m.structure.notation(Coulomb::INFO)
                    )
                }
                other => panic!("simulate {how}: {other:?}"),
            }
        }
    }
}
