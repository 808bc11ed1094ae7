//! Numerical stability at the extremes (issue 5, item 5).
//!
//! Each case is compared with an independent computation, or must end in a
//! typed error; never a silent NaN or a wrong structure. Every test prints
//! its worst observed error (`cargo test --test extremes -- --nocapture`,
//! lines starting with `[extremes]`).
//!
//! 1. `d_j² − c_j` within ±1e-12 of zero and exactly zero (paper model with
//!    the regime chosen at run time; a model with the regimes fixed at build
//!    time): flows, mapping residuals and Jacobians against `taylor`.
//! 2. Over-damped with widely separated exponents (`d_j` = 1e3, 1e4 with
//!    `c` = 1, ...): flows from τ = 1e-9 to 1e12 against `taylor` and `modal`.
//!    The closed form receives `(d_j, d_j² − c_j)`, from which the slow exponent
//!    `−c_j/(d_j + ω)` comes out with an absolute error ~`eps d_j`; the test
//!    holds it to that predicted round-off (see `separated_bound`).
//! 3. Negative effective damping (stribeck8, the paper model with `d_j < 0`
//!    in one domain, every regime): flows against `taylor`; motions growing
//!    without bound end in `SimError::NotFinite`, never in a NaN state.
//! 4. `W` from 1e-3 to 1e3 (paper model, Q0 = 70 and a forcing reaching the
//!    belt speed): `attractor::find` from rest gives a typed outcome; every
//!    motion survives 3 re-simulated cycles, every NM its forced amplitude;
//!    event sequences against `Dp` at W = 1e-2, 1e-1, 10, 100.
//! 5. Flights of 1e4 forcing periods: the state in Ω4 is the forced response;
//!    three periodic motions simulated 1e4 periods stay on their Newton points.
//! 6. Grazing within 1e-12 of tangency (overshoots ±1e-12, ±1e-13, 0): a
//!    crossing or a graze, never a miss, never a crossing short of the
//!    boundary; a graze is one event (the run resumed after it does not
//!    find the same tangency again).
//! 7. Stick with `Fnf` within 1e-12 of ±`as`: the stick ends iff `|Fnf|`
//!    passes `as` (a graze within the tolerance, one event), never an
//!    invented end.
//! 8. Parameter scales 1e-6 .. 1e6 in length, time and mass: the reference
//!    motion `P_{3_31 0_11 3_13 4_33}` at W = 3.7 maps onto the scaled motion
//!    (phases to 1e-9, x scaled), by Newton (in the unscaled number of
//!    iterations, ±1) and by simulation from rest, all with the DEFAULT
//!    options (Newton's stopping test is scale-invariant); scales beyond the
//!    floating-point range are typed parameter errors.
//!
//! Independent references used here:
//!
//! * `taylor`: a Taylor-series integrator of `x'' + 2 d_j x' + c_j x =
//!   A0 cos(W t) − b_j` (order 30, steps short enough that `|λ| h ≤ 1/4` for
//!   every exponent, so that each series is well conditioned), and its
//!   variational equations for the Jacobians. It knows nothing of the closed
//!   forms (copied from the approach of `tests/critical.rs`).
//! * `modal`: for a domain with two real exponents, the solution written in
//!   its modes `e^{λ1 τ}`, `e^{λ2 τ}` with the small exponent computed
//!   without cancellation (`λ1 = −c/(d + ω)`), for elapsed times too long
//!   for the Taylor integrator.
//! * `Dp`: an adaptive Dormand–Prince 5(4) integrator with event location and
//!   stick (copied from `tests/integrator.rs`), at a relative tolerance of 1e-13.

mod common;

use stickslip::dynamics::simulate::{
    Event, EventKind, Location, Segment, SimError, SimOptions, Simulator,
};
use stickslip::models::paper::{Paper, Params};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::{Motion, OrbitError};
use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::Model;

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// Print one line of the summary.
fn report(case: &str, what: &str, worst: f64) {
    eprintln!("[extremes] {case}: {what}: worst {worst:.3e}");
}

// ---------------------------------------------------------------------------
// The Taylor reference.
// ---------------------------------------------------------------------------

/// One domain's ODE as data: `x'' + 2 d x' + c x = a0 cos(W t) − b`.
#[derive(Clone, Copy, Debug)]
struct Ode {
    d: f64,
    c: f64,
    b: f64,
    a0: f64,
    w: f64,
}

impl Ode {
    fn of<M: Model>(p: &M::Params, j: usize) -> Self {
        let co = M::coefficients(p, j);
        let osc = M::oscillator(p);
        Self {
            d: 0.5 * co.two_d,
            c: co.c,
            b: co.b,
            a0: osc.amplitude,
            w: osc.frequency,
        }
    }

    /// The homogeneous equation (for the variational equations).
    fn homogeneous(self) -> Self {
        Self {
            b: 0.0,
            a0: 0.0,
            ..self
        }
    }

    /// `x''` at a state.
    fn accel(&self, x: f64, v: f64, phase: f64) -> f64 {
        self.a0 * phase.cos() - self.b - 2.0 * self.d * v - self.c * x
    }

    /// Largest rate in the problem: bounds every exponent and the forcing frequency.
    fn rate(&self) -> f64 {
        2.0 * self.d.abs() + self.c.abs().sqrt() + self.w
    }

    /// `(x, v)` after the elapsed time `tau` from `(x0, v0)` at phase `phi0`:
    /// Taylor series of order 30 in steps `h` with `rate · h ≤ 1/4`.
    fn taylor(&self, x0: f64, v0: f64, phi0: f64, tau: f64) -> (f64, f64) {
        const ORDER: usize = 30;
        let steps = ((tau.abs() * self.rate() * 4.0).ceil() as usize).max(16);
        let h = tau / steps as f64;
        let (mut x, mut v) = (x0, v0);
        for k in 0..steps {
            let phase = phi0 + self.w * (k as f64 * h);
            let (sn, cs) = phase.sin_cos();
            // d^n/dt^n cos(phase + W t) at 0 cycles through cos, -sin, -cos, sin.
            let cycle = [cs, -sn, -cs, sn];
            let mut a = [0.0f64; ORDER + 2];
            a[0] = x;
            a[1] = v;
            let mut wn = 1.0; // W^n / n!
            for n in 0..ORDER {
                if n > 0 {
                    wn *= self.w / n as f64;
                }
                let mut g = self.a0 * wn * cycle[n % 4];
                if n == 0 {
                    g -= self.b;
                }
                let n1 = (n + 1) as f64;
                a[n + 2] =
                    (g - 2.0 * self.d * n1 * a[n + 1] - self.c * a[n]) / (n1 * (n + 2) as f64);
            }
            let (mut xs, mut vs) = (0.0, 0.0);
            for n in (0..=ORDER).rev() {
                xs = xs * h + a[n];
                vs = vs * h + (n + 1) as f64 * a[n + 1];
            }
            x = xs;
            v = vs;
        }
        (x, v)
    }

    /// The state-transition matrix `Φ(τ)` of the homogeneous equation
    /// (columns: from `(1, 0)` and from `(0, 1)`), by the Taylor integrator.
    fn transition(&self, tau: f64) -> [[f64; 2]; 2] {
        let h = self.homogeneous();
        let (x1, v1) = h.taylor(1.0, 0.0, 0.0, tau);
        let (x2, v2) = h.taylor(0.0, 1.0, 0.0, tau);
        [[x1, x2], [v1, v2]]
    }

    /// The two real exponents `(slow, fast)` when `d² > c`, without cancellation.
    fn exponents(&self) -> (f64, f64) {
        let om = (self.d * self.d - self.c).sqrt();
        let big = -(self.d + om.copysign(self.d));
        (self.c / big, big)
    }

    /// The slowest decay rate of the homogeneous solution (`d` when under-damped).
    fn exponents_or_damping(&self) -> f64 {
        if self.d * self.d > self.c {
            -self.exponents().0
        } else {
            self.d
        }
    }

    /// Steady (forced) response `(x, v)` at `phase` (SPEC §4, from the complex amplitude).
    fn forced(&self, phase: f64) -> (f64, f64) {
        // x_p = Re(X e^{i phase}), X = a0 / (c − W² + 2 i d W).
        let (re, im) = (self.c - self.w * self.w, 2.0 * self.d * self.w);
        let den = re * re + im * im;
        let (xr, xi) = (self.a0 * re / den, -self.a0 * im / den);
        let (s, c) = phase.sin_cos();
        (
            xr * c - xi * s - self.b / self.c,
            self.w * (-xr * s - xi * c),
        )
    }

    /// `(x, v)` after `tau` by the modal form (two real exponents only):
    /// `x_h = k1 e^{λ1 τ} + k2 e^{λ2 τ}` fitted to the start.
    fn modal(&self, x0: f64, v0: f64, phi0: f64, tau: f64) -> (f64, f64) {
        let (l1, l2) = self.exponents();
        let (xp0, vp0) = self.forced(phi0);
        let (xh, vh) = (x0 - xp0, v0 - vp0);
        // xh = k1 + k2, vh = l1 k1 + l2 k2.
        let k1 = (vh - l2 * xh) / (l1 - l2);
        let k2 = (l1 * xh - vh) / (l1 - l2);
        let (e1, e2) = ((l1 * tau).exp(), (l2 * tau).exp());
        let (xp, vp) = self.forced(phi0 + self.w * tau);
        (xp + k1 * e1 + k2 * e2, vp + l1 * k1 * e1 + l2 * k2 * e2)
    }
}

/// Norm-wise relative error of `(x, v)` against `(xr, vr)`.
fn rel(x: f64, v: f64, xr: f64, vr: f64) -> f64 {
    (x - xr).hypot(v - vr) / xr.hypot(vr)
}

/// A small deterministic generator (the tests need only a few numbers).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// The flow of domain `j` against the Taylor reference at the elapsed times
/// `taus`, from random starts; returns the worst relative error.
fn flow_vs_taylor<M: Model>(
    p: &M::Params,
    j: usize,
    taus: &[f64],
    r: &mut Lcg,
    what: &str,
    tol: f64,
) -> f64 {
    let ode = Ode::of::<M>(p, j);
    let mut worst = 0.0f64;
    for &tau in taus {
        let (x0, v0, phi0) = (r.range(-2.0, 2.0), r.range(-3.0, 3.0), r.range(0.0, 6.0));
        let phi1 = phi0 + ode.w * tau;
        let [x, v] = M::flow(p, j, x0, v0, phi0, phi1);
        assert!(
            x.is_finite() && v.is_finite(),
            "{what}: domain {j}, tau {tau}: flow ({x}, {v})"
        );
        // The reference uses the elapsed time the generated code sees.
        let t = (phi1 - phi0) / ode.w;
        let (xr, vr) = ode.taylor(x0, v0, phi0, t);
        let err = rel(x, v, xr, vr);
        worst = worst.max(err);
        assert!(
            err <= tol,
            "{what}: domain {j}, tau {tau}: flow ({x}, {v}) vs reference ({xr}, {vr}): relative error {err:e} ({ode:?}, start ({x0}, {v0}) at {phi0})"
        );
    }
    worst
}

/// Every mapping of domain `j`: the generated residual against the Taylor
/// reference, and the generated Jacobian blocks against (a) the exact
/// Jacobian of the reference (variational equations) and (b) central
/// differences (one Richardson step) of the reference residual. Returns the
/// worst relative errors `(residual, jacobian, finite differences)`.
fn mappings_vs_taylor<M: Model>(
    p: &M::Params,
    j: usize,
    r: &mut Lcg,
    what: &str,
) -> (f64, f64, f64) {
    let info = M::INFO;
    let ode = Ode::of::<M>(p, j);
    let w = ode.w;
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    for (idx, m) in info
        .mappings
        .iter()
        .enumerate()
        .filter(|(_, m)| m.domain == Some(j))
    {
        let (va, vb) = (
            M::boundary_velocity(p, m.from),
            M::boundary_velocity(p, m.to),
        );
        for &span in &[0.1, 1.0, 4.0] {
            let (x0, x1, phi0) = (r.range(-2.0, 2.0), r.range(-2.0, 2.0), r.range(0.0, TAU));
            let phi1 = phi0 + span;
            let eval = M::mapping(p, idx, x0, phi0, x1, phi1);
            // The reference residual, as a function of the four arguments.
            let f_ref = |x0: f64, phi0: f64, x1: f64, phi1: f64| {
                let (x, v) = ode.taylor(x0, va, phi0, (phi1 - phi0) / w);
                [x - x1, v - vb]
            };
            let f = f_ref(x0, phi0, x1, phi1);
            let (xe, ve) = ode.taylor(x0, va, phi0, (phi1 - phi0) / w);
            let scale = xe.hypot(ve).max(x1.abs()).max(vb.abs());
            let e_res = (eval.residual[0] - f[0]).hypot(eval.residual[1] - f[1]) / scale;
            // Exact Jacobian of the reference: Φ(τ) for the start, the vector field for the times.
            let phi = ode.transition((phi1 - phi0) / w);
            let a0 = ode.accel(x0, va, phi0);
            let a1 = ode.accel(xe, ve, phi1);
            let dprev = [
                [phi[0][0], -(phi[0][0] * va + phi[0][1] * a0) / w],
                [phi[1][0], -(phi[1][0] * va + phi[1][1] * a0) / w],
            ];
            let dnext = [[-1.0, ve / w], [0.0, a1 / w]];
            let jscale = dprev
                .iter()
                .chain(dnext.iter())
                .flatten()
                .fold(1.0f64, |s, v| s.max(v.abs()));
            let mut e_jac = 0.0f64;
            let mut e_fd = 0.0f64;
            let args = [x0, phi0, x1, phi1];
            for k in 0..4 {
                for row in 0..2 {
                    let exact = if k < 2 {
                        dprev[row][k]
                    } else {
                        dnext[row][k - 2]
                    };
                    let gen = if k < 2 {
                        eval.d_prev[(row, k)]
                    } else {
                        eval.d_next[(row, k - 2)]
                    };
                    e_jac = e_jac.max((gen - exact).abs() / jscale);
                    let fd = common::derivative(
                        |t| {
                            let mut a = args;
                            a[k] = t;
                            f_ref(a[0], a[1], a[2], a[3])[row]
                        },
                        args[k],
                        1e-3,
                    );
                    e_fd = e_fd.max((gen - fd).abs() / jscale);
                }
            }
            assert!(
                e_res <= 1e-12 && e_jac <= 1e-12 && e_fd <= 1e-9,
                "{what}: mapping {} over {span} in phase: residual error {e_res:e}, Jacobian error {e_jac:e} (exact), {e_fd:e} (finite differences)",
                m.name
            );
            worst = (worst.0.max(e_res), worst.1.max(e_jac), worst.2.max(e_fd));
        }
    }
    worst
}

// ---------------------------------------------------------------------------
// 1. d_j² − c_j within ±1e-12 of zero, and exactly zero.
// ---------------------------------------------------------------------------

stickslip::model! {
    /// Domains fixed at build time at d_j² − c_j = 0, ≈ +1e-12 and ≈ −1e-12
    /// (c = 4, d = 2, slopes ±5e-13), and one far from critical.
    model edge {
        param d = 2.0;
        param c = 4.0, > 0;
        param Q0 = 3.0;
        param W = 1.3, > 0;
        param V = 1.0;
        oscillator { mass: 1.0, damping: d, stiffness: c, forcing: Q0, frequency: W }
        boundary Sigma1: v = V, stick 2.0;
        boundary Sigma2: v = V + 1.0;
        boundary Sigma3: v = V - 1.0;
        domain 1: Sigma1 < v < Sigma2 => 1.0;
        domain 2: v > Sigma2 => 1.0 + 5.0e-13 * (v - V - 1.0);
        domain 3: Sigma3 < v < Sigma1 => -1.0 - 5.0e-13 * (v - V);
        domain 4: v < Sigma3 => -1.0 - 3.0 * (v - V + 1.0);
        scene fixed { free: W, Q0; }
    }
}

/// Paper parameters with `d_j² − c_j = delta` for domain `j` as the generated
/// code computes it (`c` adjusted last so that `delta = 0` is exact).
fn paper_near_critical(j: usize, c: f64, delta: f64) -> (Params, f64) {
    let mut p = Params {
        d: 0.0,
        c,
        ..Params::default()
    };
    let half_slope = Paper::coefficients(&p, j).two_d / 2.0;
    p.d = (c + delta).sqrt() - half_slope;
    let dj = Paper::coefficients(&p, j).two_d / 2.0;
    p.c = dj * dj - delta;
    let dj = Paper::coefficients(&p, j).two_d / 2.0;
    (p, dj * dj - p.c)
}

#[test]
fn case1_critical_damping_flows_and_mappings() {
    let mut r = Lcg(11);
    let taus = [1e-6, 0.05, 0.3, 1.6, 5.0, 20.0];
    let (mut wf, mut wr, mut wj, mut wfd) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut exact_zero = 0;
    let mut worst_w2 = 0.0f64;
    for j in 0..Paper::INFO.domains.len() {
        for c in [30.0, 1.0, 0.01] {
            for delta in [-1e-12, -3e-13, -1e-14, 0.0, 1e-14, 3e-13, 1e-12] {
                let (p, w2) = paper_near_critical(j, c, delta);
                assert!(w2.abs() <= 1.01e-12, "d_j^2 - c = {w2:e}");
                worst_w2 = worst_w2.max((w2 - delta).abs());
                if w2 == 0.0 {
                    exact_zero += 1;
                    assert_eq!(
                        Paper::coefficients(&p, j).regime(),
                        stickslip::Regime::Critical
                    );
                }
                let what = format!("paper, domain {j}, c = {c}, d_j^2 - c = {w2:e}");
                wf = wf.max(flow_vs_taylor::<Paper>(&p, j, &taus, &mut r, &what, 1e-12));
                let (a, b, e) = mappings_vs_taylor::<Paper>(&p, j, &mut r, &what);
                wr = wr.max(a);
                wj = wj.max(b);
                wfd = wfd.max(e);
            }
        }
    }
    assert!(exact_zero >= 12, "only {exact_zero} exactly critical cases");
    // Regimes fixed at build time.
    use edge::fixed::{Fixed, Params as FixedParams};
    let regimes: Vec<_> = Fixed::INFO.domains.iter().map(|d| d.fixed_regime).collect();
    assert!(regimes.contains(&Some(stickslip::Regime::Critical)));
    for w in [0.2, 1.3, 7.0] {
        let p = FixedParams { W: w, Q0: 3.0 };
        for j in 0..4 {
            let co = Fixed::coefficients(&p, j);
            let w2 = 0.25 * co.two_d * co.two_d - co.c;
            let what = format!(
                "edge::fixed, domain {j} ({:?}, d_j^2 - c = {w2:e}), W = {w}",
                Fixed::INFO.domains[j].fixed_regime
            );
            wf = wf.max(flow_vs_taylor::<Fixed>(&p, j, &taus, &mut r, &what, 1e-12));
            let (a, b, e) = mappings_vs_taylor::<Fixed>(&p, j, &mut r, &what);
            wr = wr.max(a);
            wj = wj.max(b);
            wfd = wfd.max(e);
        }
    }
    report(
        "case 1",
        "|d_j^2 - c| <= 1e-12: flow vs Taylor (relative)",
        wf,
    );
    report("case 1", "mapping residual vs Taylor (relative)", wr);
    report(
        "case 1",
        "Jacobian vs variational Taylor (relative to max entry)",
        wj,
    );
    report("case 1", "Jacobian vs finite differences of Taylor", wfd);
    eprintln!("[extremes] case 1: {exact_zero} parameter sets exactly critical; d_j^2 - c off target by at most {worst_w2:.1e}");
}

// ---------------------------------------------------------------------------
// 2. Over-damped with widely separated exponents.
// ---------------------------------------------------------------------------

/// Relative error the closed form can reach in a domain with two widely
/// separated real exponents. The homogeneous solution reaches the generated
/// code as `(d_j, w2 = d_j² − c_j, τ)`, and the slow exponent
/// `λ1 = ω − d_j = −c_j / (d_j + ω)` comes out of `ω − d_j` with an absolute
/// error of order `eps d_j` (the roundings of `w2` and of `ω = sqrt(w2)`;
/// relative: `eps d_j² / c_j`). The slow mode `k1 e^{λ1 τ}` then carries the
/// error `eps d_j τ |k1 e^{λ1 τ}|`; relative to the state:
fn separated_bound(ode: &Ode, x0: f64, v0: f64, phi0: f64, tau: f64) -> f64 {
    let (l1, l2) = ode.exponents();
    let (xp0, vp0) = ode.forced(phi0);
    let k1 = ((v0 - vp0) - l2 * (x0 - xp0)) / (l1 - l2);
    let (x, v) = ode.modal(x0, v0, phi0, tau);
    f64::EPSILON * ode.d.abs() * tau * (k1 * (l1 * tau).exp()).abs() / x.hypot(v)
}

#[test]
fn case2_overdamped_separated_exponents() {
    let mut r = Lcg(22);
    let mut worst_small = 0.0f64;
    let mut worst_large = 0.0f64;
    let mut worst_cross = 0.0f64;
    let mut worst_ratio = 0.0f64;
    for (d, c) in [(1e3, 1.0), (1e3, 30.0), (1e4, 1.0), (50.0, 1e-3)] {
        // Domain 4 (index 0) with mu4 = 0: d_4 = d exactly.
        let p = Params {
            d,
            c,
            mu4: 0.0,
            W: 3.0,
            ..Params::default()
        };
        for j in 0..4 {
            let ode = Ode::of::<Paper>(&p, j);
            let (l1, l2) = ode.exponents();
            let what = format!("paper d = {d}, c = {c}, domain {j}: exponents {l1:e}, {l2:e}");
            for &tau in &[
                1e-9, 1e-6, 1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0, 1e2, 1e3, 1e4, 1e5, 1e7, 1e12,
            ] {
                let (x0, v0, phi0) = (r.range(-2.0, 2.0), r.range(-3.0, 3.0), r.range(0.0, 6.0));
                let phi1 = phi0 + ode.w * tau;
                let t = (phi1 - phi0) / ode.w;
                let [x, v] = Paper::flow(&p, j, x0, v0, phi0, phi1);
                assert!(
                    x.is_finite() && v.is_finite(),
                    "{what}: tau {tau}: ({x}, {v})"
                );
                let (xm, vm) = ode.modal(x0, v0, phi0, t);
                let bound = separated_bound(&ode, x0, v0, phi0, t);
                let tol = 1e-12 + 4.0 * bound;
                // Taylor where it is affordable (at most 1e5 steps), else the modal form.
                if t * ode.rate() <= 2.5e4 {
                    let (xt, vt) = ode.taylor(x0, v0, phi0, t);
                    worst_cross = worst_cross.max(rel(xm, vm, xt, vt));
                    let err = rel(x, v, xt, vt);
                    assert!(err <= tol, "{what}: tau {tau}: flow ({x}, {v}) vs Taylor ({xt}, {vt}): {err:e} > {tol:e}");
                    worst_small = worst_small.max(err);
                }
                let err = rel(x, v, xm, vm);
                assert!(
                    err <= tol,
                    "{what}: tau {tau}: flow ({x}, {v}) vs modal ({xm}, {vm}): {err:e} > {tol:e}"
                );
                worst_large = worst_large.max(err);
                if bound > 1e-13 {
                    worst_ratio = worst_ratio.max(err / bound);
                }
            }
        }
    }
    report(
        "case 2",
        "flow vs Taylor (elapsed time up to 1e5 steps)",
        worst_small,
    );
    report(
        "case 2",
        "flow vs modal form, tau 1e-9 .. 1e12",
        worst_large,
    );
    report(
        "case 2",
        "modal form vs Taylor (reference consistency)",
        worst_cross,
    );
    report(
        "case 2",
        "error / (eps d t |k1 e^(l1 t)| / |state|), the predicted round-off",
        worst_ratio,
    );
}

// ---------------------------------------------------------------------------
// 3. Negative effective damping.
// ---------------------------------------------------------------------------

#[test]
fn case3_negative_damping_flows() {
    let mut r = Lcg(33);
    let mut worst = 0.0f64;
    let taus = [1e-6, 0.01, 0.1, 1.0, 3.0, 10.0];
    // stribeck8 at its defaults: 2 d_j ≈ −5.2 in domain 1 (and in 5).
    let p = stribeck8::Params::default();
    let mut negative = 0;
    for j in 0..Stribeck8::INFO.domains.len() {
        let co = Stribeck8::coefficients(&p, j);
        if co.two_d < 0.0 {
            negative += 1;
        }
        let what = format!(
            "stribeck8 domain {} (2 d_j = {}, c = {})",
            Stribeck8::INFO.domains[j].label,
            co.two_d,
            co.c
        );
        worst = worst.max(flow_vs_taylor::<Stribeck8>(
            &p, j, &taus, &mut r, &what, 1e-12,
        ));
    }
    assert!(negative >= 2, "stribeck8 has negatively damped domains");
    // The paper model with d_j < 0 chosen in one domain, in each regime.
    let sets = [
        (
            "mu2 = 2: d_1 = -0.1 (under-damped)",
            Params {
                mu2: 2.0,
                ..Params::default()
            },
        ),
        (
            "mu4 = -3: d_4 = -0.2 (under-damped)",
            Params {
                mu4: -3.0,
                ..Params::default()
            },
        ),
        (
            "mu2 = 80: d_1 = -7.9 (over-damped)",
            Params {
                mu2: 80.0,
                ..Params::default()
            },
        ),
        ("mu3 = 2 sqrt(30) m + 2 d m: d_3 = -sqrt(30) (critical)", {
            let mut p = Params {
                d: 0.0,
                ..Params::default()
            };
            p.mu3 = 2.0 * p.m * p.c.sqrt();
            let dj = Paper::coefficients(&p, 1).two_d / 2.0;
            p.c = dj * dj;
            p
        }),
    ];
    for (name, p) in sets {
        let mut neg = false;
        for j in 0..4 {
            let co = Paper::coefficients(&p, j);
            neg |= co.two_d < 0.0;
            let what = format!(
                "paper {name}, domain {} (2 d_j = {}, regime {:?})",
                Paper::INFO.domains[j].label,
                co.two_d,
                co.regime()
            );
            worst = worst.max(flow_vs_taylor::<Paper>(&p, j, &taus, &mut r, &what, 1e-12));
        }
        assert!(neg, "{name}: a negatively damped domain");
    }
    report(
        "case 3",
        "negative damping: flow vs Taylor (relative)",
        worst,
    );
}

#[test]
fn case3_unbounded_growth_is_a_typed_error() {
    let mut blow_ups = 0;
    // Every domain negatively damped: the motion grows without bound.
    for (name, p) in [
        (
            "all d_j = -1",
            Params {
                d: 0.0,
                mu1: -10.0,
                mu2: 10.0,
                mu3: 10.0,
                mu4: -10.0,
                ..Params::default()
            },
        ),
        (
            "all d_j = -0.05",
            Params {
                d: 0.0,
                mu1: -0.5,
                mu2: 0.5,
                mu3: 0.5,
                mu4: -0.5,
                ..Params::default()
            },
        ),
        (
            "all d_j = -20 (over-damped)",
            Params {
                d: 0.0,
                mu1: -200.0,
                mu2: 200.0,
                mu3: 200.0,
                mu4: -200.0,
                ..Params::default()
            },
        ),
    ] {
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        let mut events = 0usize;
        let mut last = (0.0, 0.0, 0.0);
        let mut last_event = None;
        let t0 = std::time::Instant::now();
        let res = sim.run(start, 1e5 * TAU, |e| {
            assert!(
                e.x.is_finite() && e.v.is_finite() && e.phase.is_finite(),
                "{name}: an event with a NaN state: {e:?}"
            );
            events += 1;
            last = (e.phase, e.x, e.v);
            last_event = Some(*e);
        });
        eprintln!(
            "{name}: {events} events in {:?}, last {last:?}: {res:?}",
            t0.elapsed()
        );
        match &res {
            Err(
                err @ SimError::NotFinite {
                    phase,
                    time,
                    location,
                    x,
                    v,
                    last_phase,
                    last_x,
                    last_v,
                },
            ) => {
                // Where it blew up: after the last event (if any), in the
                // location that event led to (or the start's), at t = W t / W; the last finite state
                // just before (to the rounding of the phase).
                let (after, since) =
                    last_event.map_or((start.location, start.phase), |e: Event| (e.after, e.phase));
                assert_eq!(*location, after, "{name}: {err}");
                assert!(since <= *last_phase && last_phase <= phase, "{name}: {err}");
                assert!(
                    phase - last_phase <= 1e-12 * phase.abs().max(1.0),
                    "{name}: the last finite phase {last_phase} is not next to the blow-up at {phase}"
                );
                assert_eq!(*time, phase / p.W, "{name}: {err}");
                // Not finite there, or finite and the acceleration (or the
                // bound on its rate) is what overflowed: then that is the
                // last finite state.
                assert!(
                    !(x.is_finite() && v.is_finite())
                        || (last_phase, last_x, last_v) == (phase, x, v),
                    "{name}: {err}"
                );
                assert!(last_x.is_finite() && last_v.is_finite(), "{name}: {err}");
                let text = err.to_string();
                for part in [
                    format!("at W t = {phase:.9e}"),
                    format!("(t = {time:.6e})"),
                    format!("in {location}"),
                    format!("last finite state x = {last_x:.6e}, v = {last_v:.6e}"),
                ] {
                    assert!(text.contains(&part), "{name}: `{part}` not in: {text}");
                }
                eprintln!("{name}: {text}");
            }
            Ok(seg) => {
                let (x, v) = sim.state_at(seg, 1e5 * TAU);
                assert!(
                    x.is_finite() && v.is_finite(),
                    "{name}: the run ended without error in a non-finite state"
                );
            }
            Err(e) => panic!("{name}: {e}"),
        }
        // The same through `attractor::find`: a typed outcome, never a NaN motion.
        let outcome = attractor::find(&sim, start, AttractorOptions::default());
        match &outcome {
            Err(OrbitError::Simulation(SimError::NotFinite { phase, .. })) => {
                assert!(phase.is_finite(), "{name}: {outcome:?}");
                blow_ups += 1;
            }
            Ok(Attractor::Periodic(m)) => {
                assert!(m.is_admissible(), "{name}: {m:?}");
                assert!(
                    m.points
                        .iter()
                        .all(|p| p.x.is_finite() && p.phase.is_finite()),
                    "{name}: {m:?}"
                );
            }
            Ok(Attractor::NoMotion(nm)) => assert!(nm.max_v.is_finite(), "{name}: {nm:?}"),
            Ok(Attractor::Stick(s)) => assert!(s.x.is_finite(), "{name}: {s:?}"),
            Ok(Attractor::Autonomous(a)) => assert!(a.period.is_finite(), "{name}: {a:?}"),
            Err(e) => eprintln!("{name}: attractor::find: {e}"),
        }
        eprintln!(
            "{name}: attractor::find: {}",
            match &outcome {
                Ok(Attractor::Periodic(m)) => m.structure.notation(Paper::INFO),
                Ok(Attractor::NoMotion(_)) => "NM".to_string(),
                Ok(Attractor::Stick(_)) => "stick".to_string(),
                Ok(Attractor::Autonomous(_)) => "autonomous".to_string(),
                Err(e) => e.to_string(),
            }
        );
    }
    assert!(blow_ups >= 2, "only {blow_ups} runs blew up");
    eprintln!("[extremes] case 3: {blow_ups} unbounded motions ended in SimError::NotFinite; no NaN state reported");
}

// ---------------------------------------------------------------------------
// The Dormand–Prince reference (copied from tests/integrator.rs, generic).
// ---------------------------------------------------------------------------

/// An event of the reference integration.
#[derive(Clone, Copy, Debug)]
struct RefEvent {
    phase: f64,
    x: f64,
    boundary: usize,
    kind: EventKind,
}

/// The ODE as data: read once from the model, then integrated numerically.
struct Dp {
    a0: f64,
    w: f64,
    two_d: f64,
    c: f64,
    coeff: Vec<(f64, f64, f64)>,
    bands: Vec<(Option<usize>, Option<usize>)>,
    velocities: Vec<f64>,
    stick: Option<(usize, f64)>,
}

impl Dp {
    fn of<M: Model>(p: &M::Params) -> Self {
        let info = M::INFO;
        let osc = M::oscillator(p);
        Self {
            a0: osc.amplitude,
            w: osc.frequency,
            two_d: 2.0 * osc.damping,
            c: osc.stiffness,
            coeff: (0..info.domains.len())
                .map(|j| {
                    let co = M::coefficients(p, j);
                    (co.two_d, co.c, co.b)
                })
                .collect(),
            bands: info.domains.iter().map(|d| (d.lower, d.upper)).collect(),
            velocities: (0..info.boundaries.len())
                .map(|k| M::boundary_velocity(p, k))
                .collect(),
            stick: info
                .stick_boundary()
                .map(|k| (k, M::static_bound(p).expect("stick boundary has a bound"))),
        }
    }

    fn accel(&self, j: usize, t: f64, x: f64, v: f64) -> f64 {
        let (two_d, c, b) = self.coeff[j];
        self.a0 * (self.w * t).cos() - b - two_d * v - c * x
    }

    fn domain_of(&self, v: f64) -> usize {
        self.bands
            .iter()
            .position(|&(lo, hi)| {
                lo.is_none_or(|k| self.velocities[k] < v)
                    && hi.is_none_or(|k| v < self.velocities[k])
            })
            .expect("v inside a band")
    }

    fn dp_step(&self, j: usize, t: f64, y: [f64; 2], h: f64) -> ([f64; 2], [f64; 2]) {
        const C2: f64 = 1.0 / 5.0;
        const C3: f64 = 3.0 / 10.0;
        const C4: f64 = 4.0 / 5.0;
        const C5: f64 = 8.0 / 9.0;
        const A21: f64 = 1.0 / 5.0;
        const A31: f64 = 3.0 / 40.0;
        const A32: f64 = 9.0 / 40.0;
        const A41: f64 = 44.0 / 45.0;
        const A42: f64 = -56.0 / 15.0;
        const A43: f64 = 32.0 / 9.0;
        const A51: f64 = 19372.0 / 6561.0;
        const A52: f64 = -25360.0 / 2187.0;
        const A53: f64 = 64448.0 / 6561.0;
        const A54: f64 = -212.0 / 729.0;
        const A61: f64 = 9017.0 / 3168.0;
        const A62: f64 = -355.0 / 33.0;
        const A63: f64 = 46732.0 / 5247.0;
        const A64: f64 = 49.0 / 176.0;
        const A65: f64 = -5103.0 / 18656.0;
        const B1: f64 = 35.0 / 384.0;
        const B3: f64 = 500.0 / 1113.0;
        const B4: f64 = 125.0 / 192.0;
        const B5: f64 = -2187.0 / 6784.0;
        const B6: f64 = 11.0 / 84.0;
        const E1: f64 = 71.0 / 57600.0;
        const E3: f64 = -71.0 / 16695.0;
        const E4: f64 = 71.0 / 1920.0;
        const E5: f64 = -17253.0 / 339200.0;
        const E6: f64 = 22.0 / 525.0;
        const E7: f64 = -1.0 / 40.0;
        let f = |t: f64, y: [f64; 2]| [y[1], self.accel(j, t, y[0], y[1])];
        let add = |y: [f64; 2], ks: &[([f64; 2], f64)]| {
            let mut out = y;
            for (k, a) in ks {
                out[0] += h * a * k[0];
                out[1] += h * a * k[1];
            }
            out
        };
        let k1 = f(t, y);
        let k2 = f(t + C2 * h, add(y, &[(k1, A21)]));
        let k3 = f(t + C3 * h, add(y, &[(k1, A31), (k2, A32)]));
        let k4 = f(t + C4 * h, add(y, &[(k1, A41), (k2, A42), (k3, A43)]));
        let k5 = f(
            t + C5 * h,
            add(y, &[(k1, A51), (k2, A52), (k3, A53), (k4, A54)]),
        );
        let k6 = f(
            t + h,
            add(y, &[(k1, A61), (k2, A62), (k3, A63), (k4, A64), (k5, A65)]),
        );
        let y5 = add(y, &[(k1, B1), (k3, B3), (k4, B4), (k5, B5), (k6, B6)]);
        let k7 = f(t + h, y5);
        let err = add(
            [0.0, 0.0],
            &[(k1, E1), (k3, E3), (k4, E4), (k5, E5), (k6, E6), (k7, E7)],
        );
        (y5, err)
    }

    fn fnf(&self, vs: f64, t: f64, x: f64) -> f64 {
        self.a0 * (self.w * t).cos() - self.two_d * vs - self.c * x
    }

    /// Integrate from `(x0, v0)` at `t0` in `domain` (`None`: stuck; the
    /// domain containing `v0` when `start` is `None`) to `t_end`, recording events.
    fn integrate(
        &self,
        t0: f64,
        x0: f64,
        v0: f64,
        start: Option<Option<usize>>,
        t_end: f64,
        rtol: f64,
    ) -> Vec<RefEvent> {
        let mut events = Vec::new();
        let (mut t, mut y) = (t0, [x0, v0]);
        let mut domain: Option<usize> = start.unwrap_or_else(|| Some(self.domain_of(v0)));
        let mut h = 1e-3f64;
        let w = self.w;
        while t < t_end {
            match domain {
                None => {
                    let (k, bound) = self.stick.expect("stuck on the stick boundary");
                    let vs = self.velocities[k];
                    let (t0, x0) = (t, y[0]);
                    let g = |s: f64| {
                        let f = self.fnf(vs, t0 + s, x0 + vs * s);
                        (f - bound, f + bound)
                    };
                    let ds = 1e-3 / w;
                    let mut s = 0.0;
                    let mut found = None;
                    while t0 + s < t_end {
                        let (u1, l1) = g(s + ds);
                        if u1 >= 0.0 || l1 <= 0.0 {
                            let upper = u1 >= 0.0;
                            let (mut a, mut b) = (s, s + ds);
                            for _ in 0..200 {
                                let mid = 0.5 * (a + b);
                                let (u, l) = g(mid);
                                let out = if upper { u >= 0.0 } else { l <= 0.0 };
                                if out {
                                    b = mid;
                                } else {
                                    a = mid;
                                }
                                if b - a <= 1e-16 * (t0 + b) {
                                    break;
                                }
                            }
                            found = Some((b, upper));
                            break;
                        }
                        s += ds;
                    }
                    let Some((s, upper)) = found else {
                        return events;
                    };
                    t = t0 + s;
                    y = [x0 + vs * s, vs];
                    events.push(RefEvent {
                        phase: w * t,
                        x: y[0],
                        boundary: k,
                        kind: EventKind::StickEnd,
                    });
                    domain = Some(if upper { k + 1 } else { k });
                }
                Some(j) => {
                    let (lo, hi) = self.bands[j];
                    let lo_v = lo.map(|k| self.velocities[k]);
                    let hi_v = hi.map(|k| self.velocities[k]);
                    let gap = |v: f64| {
                        (
                            lo_v.map_or(f64::INFINITY, |l| v - l),
                            hi_v.map_or(f64::INFINITY, |u| u - v),
                        )
                    };
                    let hs = h.min(t_end + 1.0 - t);
                    let (y1, err) = self.dp_step(j, t, y, hs);
                    let sc = |i: usize| rtol * (1.0 + y[i].abs().max(y1[i].abs()));
                    let en = (err[0] / sc(0)).abs().max((err[1] / sc(1)).abs());
                    if en > 1.0 {
                        h = hs * (0.9 * en.powf(-0.2)).max(0.2);
                        continue;
                    }
                    let (g_lo, g_hi) = gap(y1[1]);
                    let mut cross: Option<(f64, bool)> = None;
                    if g_lo < 0.0 || g_hi < 0.0 {
                        cross = Some((hs, g_lo < 0.0));
                    } else {
                        let a0 = self.accel(j, t, y[0], y[1]);
                        let a1 = self.accel(j, t + hs, y1[0], y1[1]);
                        for i in 1..16 {
                            let s = i as f64 / 16.0;
                            let (h00, h10, h01, h11) = (
                                2.0 * s * s * s - 3.0 * s * s + 1.0,
                                s * s * s - 2.0 * s * s + s,
                                -2.0 * s * s * s + 3.0 * s * s,
                                s * s * s - s * s,
                            );
                            let v = h00 * y[1] + h10 * hs * a0 + h01 * y1[1] + h11 * hs * a1;
                            let (gl, gh) = gap(v);
                            if gl < 0.0 || gh < 0.0 {
                                let ys = self.dp_step(j, t, y, s * hs).0;
                                let (gl, gh) = gap(ys[1]);
                                if gl < 0.0 || gh < 0.0 {
                                    cross = Some((s * hs, gl < 0.0));
                                    break;
                                }
                            }
                        }
                    }
                    let Some((s_hi, lower)) = cross else {
                        t += hs;
                        y = y1;
                        h = hs * (0.9 * en.max(1e-10).powf(-0.2)).min(5.0);
                        continue;
                    };
                    let gfun = |s: f64| {
                        let ys = self.dp_step(j, t, y, s).0;
                        let (gl, gh) = gap(ys[1]);
                        (if lower { gl } else { gh }, ys)
                    };
                    let (mut a, mut fa) = (0.0, if lower { gap(y[1]).0 } else { gap(y[1]).1 });
                    let (mut b, mut fb) = (s_hi, gfun(s_hi).0);
                    let mut side = 0i32;
                    for _ in 0..200 {
                        let mut s = (a * fb - b * fa) / (fb - fa);
                        if !(s > a && s < b) {
                            s = 0.5 * (a + b);
                        }
                        let fs = gfun(s).0;
                        if fs >= 0.0 {
                            a = s;
                            fa = fs;
                            if side == 1 {
                                fb *= 0.5;
                            }
                            side = 1;
                        } else {
                            b = s;
                            fb = fs;
                            if side == -1 {
                                fa *= 0.5;
                            }
                            side = -1;
                        }
                        if b - a <= 4.0 * f64::EPSILON * (t + b) {
                            break;
                        }
                    }
                    let s = 0.5 * (a + b);
                    let ys = gfun(s).1;
                    t += s;
                    let k = if lower { lo } else { hi }.expect("crossed a present boundary");
                    let vb = self.velocities[k];
                    y = [ys[0], vb];
                    let into = if lower { j - 1 } else { j + 1 };
                    let (kind, next) = match self.stick {
                        Some((ks, _)) if ks == k => {
                            let f_above = self.accel(k + 1, t, y[0], vb);
                            let f_below = self.accel(k, t, y[0], vb);
                            let pass = if lower {
                                f_above < 0.0 && f_below < 0.0
                            } else {
                                f_above > 0.0 && f_below > 0.0
                            };
                            if pass {
                                (EventKind::Pass, Some(into))
                            } else {
                                (EventKind::StickOnset, None)
                            }
                        }
                        _ => (EventKind::Pass, Some(into)),
                    };
                    if t <= t_end {
                        events.push(RefEvent {
                            phase: w * t,
                            x: y[0],
                            boundary: k,
                            kind,
                        });
                    }
                    domain = next;
                    h = h.min(1e-3);
                }
            }
        }
        events
    }
}

// ---------------------------------------------------------------------------
// 4. W from 1e-3 to 1e3.
// ---------------------------------------------------------------------------

/// The segment that starts mapping `idx` at `pt`.
fn segment_for<M: Model>(sim: &Simulator<M>, idx: usize, pt: SwitchingPoint) -> Segment {
    let mi = M::INFO.mappings[idx];
    Segment {
        x: pt.x,
        v: sim.velocity(mi.from),
        phase: pt.phase,
        location: mi.domain.map_or(Location::Stick, Location::Domain),
        search_from: pt.phase,
    }
}

/// Re-simulate `cycles` cycles of a motion from its point 0 with the event
/// simulator: the events must be the switching points, in order, modulo
/// `2πN`. Returns the worst deviation in phase and in x (relative to 1 + |x|).
fn resimulate<M: Model>(sim: &Simulator<M>, motion: &Motion, cycles: usize, what: &str) -> f64 {
    let pts = &motion.points;
    let m = pts.len();
    let steps = motion.structure.steps();
    let shift = TAU * motion.structure.periods() as f64;
    let seg = segment_for(sim, steps[0], pts[0]);
    let mut events = Vec::new();
    sim.run(seg, pts[0].phase + cycles as f64 * shift + 1e-6, |e| {
        if e.kind != EventKind::Graze {
            events.push(*e)
        }
    })
    .unwrap_or_else(|e| panic!("{what}: re-simulation failed: {e}"));
    assert_eq!(
        events.len(),
        cycles * m,
        "{what}: {} events in {cycles} cycles of {m} mappings",
        events.len()
    );
    let mut worst = 0.0f64;
    for (n, e) in events.iter().enumerate() {
        let (cycle, k) = ((n / m) as f64, (n + 1) % m);
        let want = pts[k].phase + shift * (cycle + if k == 0 { 1.0 } else { 0.0 });
        assert!(e.x.is_finite() && e.phase.is_finite(), "{what}: {e:?}");
        assert_eq!(
            e.boundary,
            M::INFO.mappings[steps[k]].from,
            "{what}: event {n} on the wrong boundary"
        );
        let dev = ((e.phase - want).abs() / want.abs().max(1.0))
            .max((e.x - pts[k].x).abs() / (1.0 + pts[k].x.abs()));
        worst = worst.max(dev);
        assert!(
            dev < 1e-8,
            "{what}: event {n} at ({}, {}), switching point ({want}, {}): {dev:e}",
            e.phase,
            e.x,
            pts[k].x
        );
    }
    worst
}

/// The forcing amplitude `Q0` of the paper model at which the steady
/// velocity amplitude in Ω4 (linear response) would be `v_amp`.
fn q0_for_velocity(w: f64, v_amp: f64) -> f64 {
    let p = Params {
        W: w,
        ..Params::default()
    };
    let ode = Ode::of::<Paper>(&p, 0);
    v_amp * (ode.c - w * w).hypot(2.0 * ode.d * w) / w * p.m
}

#[test]
fn case4_forcing_frequency_from_1e_3_to_1e3() {
    let mut outcomes = std::collections::BTreeMap::<&str, usize>::new();
    let mut worst_resim = 0.0f64;
    let mut worst_nm = 0.0f64;
    let t0 = std::time::Instant::now();
    // Q0 = 70, and a forcing whose steady velocity amplitude in Ω4 would be
    // 4 (so that the motion reaches the belt speed at every W).
    let cases = (0..=24).flat_map(|k| {
        let w = 1e-3 * 10f64.powf(k as f64 / 4.0);
        [(w, 70.0), (w, q0_for_velocity(w, 4.0))]
    });
    for (w, q0) in cases {
        let p = Params {
            W: w,
            Q0: q0,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        let t = std::time::Instant::now();
        // At the smallest W a strongly forced cycle holds hundreds of mappings
        // (stick-slip at the natural frequency within each forcing period: 512
        // at W = 1e-3); at the largest, the transient lasts ~W·20 periods.
        let opts = AttractorOptions {
            max_periods: 300.max((20.0 * w) as u32),
            max_cycle: Some(1024),
            ..AttractorOptions::default()
        };
        let res = attractor::find(&sim, start, opts);
        let what = format!("paper W = {w:e}, Q0 = {q0:e}");
        let kind = match &res {
            Ok(Attractor::Periodic(m)) => {
                assert!(m.is_admissible(), "{what}: {m:?}");
                assert!(
                    m.points
                        .iter()
                        .all(|pt| pt.x.is_finite() && pt.phase.is_finite()),
                    "{what}: {m:?}"
                );
                worst_resim = worst_resim.max(resimulate(&sim, m, 3, &what));
                "periodic"
            }
            Ok(Attractor::Stick(s)) => panic!("{what}: a permanent stick on a moving belt: {s:?}"),
            Ok(Attractor::Autonomous(c)) => {
                panic!("{what}: an autonomous cycle with forcing: {c:?}")
            }
            Ok(Attractor::NoMotion(nm)) => {
                // The steady response of the domain, independently: |v| = A0 W / |c_j - W^2 + 2 i d_j W|.
                let ode = Ode::of::<Paper>(&p, nm.domain);
                let amp = ode.a0 * w / (ode.c - w * w).hypot(2.0 * ode.d * w);
                let err = (nm.max_v - amp).abs() / amp;
                worst_nm = worst_nm.max(err);
                assert!(
                    err < 1e-12 && nm.min_v.is_finite(),
                    "{what}: {nm:?} vs amplitude {amp}"
                );
                "NM"
            }
            Err(OrbitError::Unsettled { .. }) => "unsettled",
            Err(e) => panic!("{what}: {e}"),
        };
        eprintln!(
            "{what}: {kind} in {:?}{}",
            t.elapsed(),
            match &res {
                Ok(Attractor::Periodic(m)) => format!(" {}", m.structure.notation(Paper::INFO)),
                _ => String::new(),
            }
        );
        *outcomes.entry(kind).or_default() += 1;
    }
    eprintln!(
        "[extremes] case 4: outcomes {outcomes:?} in {:?}",
        t0.elapsed()
    );
    report(
        "case 4",
        "reported motions re-simulated 3 cycles (relative deviation)",
        worst_resim,
    );
    report(
        "case 4",
        "NM max_v vs forced amplitude (relative)",
        worst_nm,
    );
}

/// Simulator and Dormand–Prince from the same start: the same sequence of
/// (boundary, kind) events, phases and displacements within `tol` (relative
/// to `max(1, |phase|)` and `1 + |x|`). Returns the worst deviation and the
/// number of events compared.
fn compare_with_dp<M: Model>(
    sim: &Simulator<M>,
    seg: Segment,
    phase_end: f64,
    tol: f64,
    what: &str,
) -> (f64, usize) {
    let p = sim.params();
    let mut simulated = Vec::new();
    sim.run(seg, phase_end, |e| {
        if e.kind != EventKind::Graze {
            simulated.push(*e)
        }
    })
    .unwrap_or_else(|e| panic!("{what}: simulation failed: {e}"));
    let dp = Dp::of::<M>(p);
    let w = dp.w;
    let start = match seg.location {
        Location::Domain(j) => Some(j),
        Location::Stick => None,
    };
    let reference = dp.integrate(
        seg.phase / w,
        seg.x,
        seg.v,
        Some(start),
        phase_end / w,
        1e-13,
    );
    let keep = |phase: f64| phase < phase_end - 1e-6 * phase_end.abs().max(1.0);
    let simulated: Vec<_> = simulated.into_iter().filter(|e| keep(e.phase)).collect();
    let reference: Vec<_> = reference.into_iter().filter(|e| keep(e.phase)).collect();
    let mut worst = 0.0f64;
    for (n, (a, b)) in simulated.iter().zip(&reference).enumerate() {
        let dev = ((a.phase - b.phase).abs() / a.phase.abs().max(1.0))
            .max((a.x - b.x).abs() / (1.0 + a.x.abs()));
        assert!(
            a.boundary == b.boundary && a.kind == b.kind && dev < tol,
            "{what}: event {n}: simulation {:?} on {} at ({}, {}), integration {:?} on {} at ({}, {}): {dev:e}",
            a.kind, a.boundary, a.phase, a.x, b.kind, b.boundary, b.phase, b.x
        );
        worst = worst.max(dev);
    }
    assert_eq!(
        simulated.len(),
        reference.len(),
        "{what}: {} simulated events, {} integrated",
        simulated.len(),
        reference.len()
    );
    (worst, simulated.len())
}

#[test]
fn case4_event_times_against_the_integrator() {
    let mut worst = 0.0f64;
    let mut total = 0;
    for (w, periods) in [(1e-2, 2.0), (1e-1, 4.0), (10.0, 30.0), (100.0, 200.0)] {
        for q0 in [70.0, q0_for_velocity(w, 4.0)] {
            let p = Params {
                W: w,
                Q0: q0,
                ..Params::default()
            };
            let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
            let what = format!("paper W = {w:e}, Q0 = {q0:e}");
            let t = std::time::Instant::now();
            // From rest.
            let (dev, n) = compare_with_dp(
                &sim,
                sim.start(0.0, 0.0, 0.0).expect("start"),
                periods * TAU,
                1e-8,
                &what,
            );
            worst = worst.max(dev);
            total += n;
            // From the reported motion's point 0, one cycle.
            let opts = AttractorOptions {
                max_periods: 300.max((20.0 * w) as u32),
                max_cycle: Some(1024),
                ..AttractorOptions::default()
            };
            let mut cycle = 0;
            if let Ok(Attractor::Periodic(m)) =
                attractor::find(&sim, sim.start(0.0, 0.0, 0.0).expect("start"), opts)
            {
                let seg = segment_for(&sim, m.structure.steps()[0], m.points[0]);
                let end = m.points[0].phase + TAU * m.structure.periods() as f64 + 1e-3;
                let (dev, n) = compare_with_dp(
                    &sim,
                    seg,
                    end,
                    1e-8,
                    &format!("{what}, motion {}", m.structure.notation(Paper::INFO)),
                );
                assert_eq!(n, m.points.len(), "{what}: one cycle of the motion");
                worst = worst.max(dev);
                total += n;
                cycle = n;
            }
            eprintln!(
                "{what}: {n} events from rest, {cycle} on the motion's cycle, in {:?}",
                t.elapsed()
            );
        }
    }
    assert!(total > 100, "only {total} events compared");
    report(
        "case 4",
        &format!(
            "{total} events vs Dormand-Prince at W = 1e-2, 1e-1, 10, 100 (relative deviation)"
        ),
        worst,
    );
}

// ---------------------------------------------------------------------------
// 5. Flights of 1e4 forcing periods.
// ---------------------------------------------------------------------------

#[test]
fn case5_long_flight_in_a_domain_is_the_forced_response() {
    // W = 1 (NM, paper) for 1e4 periods, and W = 1 with a strongly
    // over-damped Ω4 (d_4 = 1e3, c = 1) for 1e3 periods: there the event
    // search steps by W / (2 (sqrt c + d_j)) in phase, about 1.3e7 steps
    // per 1e3 periods (the fast exponent sets the step).
    for (name, p, periods) in [
        (
            "paper W = 1",
            Params {
                W: 1.0,
                ..Params::default()
            },
            1e4,
        ),
        (
            "paper W = 1, d = 1e3, c = 1, mu4 = 0",
            Params {
                W: 1.0,
                d: 1e3,
                c: 1.0,
                mu4: 0.0,
                ..Params::default()
            },
            1e3,
        ),
    ] {
        let mut worst = 0.0f64;
        let t = std::time::Instant::now();
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
        let ode = Ode::of::<Paper>(&p, 0);
        let (xf0, vf0) = ode.forced(0.0);
        for (x0, v0) in [(xf0, vf0), (xf0 + 0.1, vf0 - 0.2), (0.0, 0.0)] {
            let start = sim.start(x0, v0, 0.0).expect("start");
            let mut events = Vec::new();
            let end = sim
                .run(start, periods * TAU, |e| events.push(*e))
                .expect("a finite flight");
            // From rest the transient reaches Σ3 at first; then the motion stays in Ω4.
            assert!(
                events.iter().all(|e| e.phase < 20.0 * TAU),
                "{name}: late events {events:?}"
            );
            if (x0, v0) != (0.0, 0.0) {
                assert!(
                    events.is_empty(),
                    "{name}: a start near the forced response stays in Ω4: {events:?}"
                );
            }
            assert_eq!(end.location, Location::Domain(0), "{name}");
            for k in [1.0, 10.0, 100.0, 1000.0, 1e4]
                .into_iter()
                .filter(|&k| k <= periods)
            {
                let phase = k * TAU + 0.3;
                let (x, v) = sim.state_at(&end, phase);
                assert!(
                    x.is_finite() && v.is_finite(),
                    "{name}: ({x}, {v}) at {phase}"
                );
                // The reference: the modal form (over-damped); the forced
                // response once the transient is below 1e-17 (under-damped).
                let tau = (phase - end.phase) / ode.w;
                let (xr, vr, tol) = if ode.d * ode.d > ode.c {
                    let (xm, vm) = ode.modal(end.x, end.v, end.phase, tau);
                    (
                        xm,
                        vm,
                        1e-12 + 4.0 * separated_bound(&ode, end.x, end.v, end.phase, tau),
                    )
                } else if (-ode.d * tau).exp() < 1e-17 {
                    let (xf, vf) = ode.forced(phase);
                    (xf, vf, 1e-12)
                } else {
                    continue;
                };
                let err = rel(x, v, xr, vr);
                worst = worst.max(err);
                assert!(err < tol, "{name}: state ({x}, {v}) after {k} periods, reference ({xr}, {vr}): {err:e} > {tol:e}");
            }
            let phase = periods * TAU + 0.3;
            let (x, v) = sim.state_at(&end, phase);
            let (xf, vf) = ode.forced(phase);
            if (-ode.exponents_or_damping() * (phase - end.phase) / ode.w).exp() < 1e-17 {
                let err = rel(x, v, xf, vf);
                assert!(
                    err < 1e-12,
                    "{name}: after {periods:e} periods ({x}, {v}), forced response ({xf}, {vf})"
                );
                worst = worst.max(err);
            }
        }
        eprintln!(
            "{name}: 3 flights of {periods:e} periods in {:?}",
            t.elapsed()
        );
        report("case 5", &format!("{name}: state after {periods:e} periods vs forced response / modal form (relative)"), worst);
    }
}

#[test]
fn case5_periodic_motion_for_1e4_periods_stays_on_it() {
    let periods = 10_000usize;
    let mut worst = 0.0f64;
    let mut events_total = 0;
    for (w, want) in [
        (3.7, "P_{3_31 0_11 3_13 4_33}"),
        (5.0, "P_{3_31 1_12 2_22 1_21 3_13 4_33}"),
        (3.0, "P_{3_33 4_33}"),
    ] {
        let p = Params {
            W: w,
            Q0: 70.0,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
        let Ok(Attractor::Periodic(m)) = attractor::find(
            &sim,
            sim.start(0.0, 0.0, 0.0).expect("start"),
            AttractorOptions::default(),
        ) else {
            panic!("W = {w}: no periodic motion");
        };
        assert_eq!(m.structure.notation(Paper::INFO), want);
        assert_eq!(m.structure.periods(), 1);
        let pts = &m.points;
        let n = pts.len();
        let steps = m.structure.steps();
        let seg = segment_for(&sim, steps[0], pts[0]);
        let mut k = 0usize;
        let mut w_dev = 0.0f64;
        let t = std::time::Instant::now();
        sim.run(seg, pts[0].phase + periods as f64 * TAU + 1e-6, |e| {
            assert_ne!(e.kind, EventKind::Graze, "W = {w}: a graze at {e:?}");
            let (cycle, j) = ((k / n) as f64, (k + 1) % n);
            let want = pts[j].phase + TAU * (cycle + if j == 0 { 1.0 } else { 0.0 });
            assert_eq!(
                e.boundary,
                Paper::INFO.mappings[steps[j]].from,
                "W = {w}: event {k}"
            );
            let dev = (e.phase - want).abs().max((e.x - pts[j].x).abs());
            assert!(
                dev < 1e-8,
                "W = {w}: event {k} at ({}, {}) vs ({want}, {}): {dev:e}",
                e.phase,
                e.x,
                pts[j].x
            );
            w_dev = w_dev.max(dev);
            k += 1;
        })
        .expect("a finite simulation");
        assert_eq!(k, periods * n, "W = {w}: {k} events in {periods} periods");
        eprintln!(
            "W = {w}: {k} events in {:?}, worst deviation {w_dev:e}",
            t.elapsed()
        );
        worst = worst.max(w_dev);
        events_total += k;
    }
    report(
        "case 5",
        &format!("{events_total} events over 1e4 periods vs Newton points (phase and x, absolute)"),
        worst,
    );
}

// ---------------------------------------------------------------------------
// 8. Parameter scales from 1e-6 to 1e6.
// ---------------------------------------------------------------------------

/// The paper model in units scaled by length `l`, time `t` and mass `m`:
/// `x_s(t_s) = l x(t_s / t)` solves the scaled model when `x` solves the
/// original one (the dimensionless problem is the same): `d/t`, `c/t²`,
/// velocities `l/t`, accelerations (g, Q0/m) `l/t²`, friction slopes per
/// unit mass `1/t`, masses `m`. Phases `W t` are unchanged.
fn scaled_paper(base: &Params, l: f64, t: f64, m: f64) -> Params {
    let p = base;
    Params {
        m: p.m * m,
        d: p.d / t,
        c: p.c / (t * t),
        V: p.V * l / t,
        V1: p.V1 * l / t,
        V2: p.V2 * l / t,
        mus: p.mus,
        muk: p.muk,
        mu1: p.mu1 * m / t,
        mu2: p.mu2 * m / t,
        mu3: p.mu3 * m / t,
        mu4: p.mu4 * m / t,
        g: p.g * l / (t * t),
        Q0: p.Q0 * m * l / (t * t),
        W: p.W / t,
    }
}

/// Largest deviation between two lists of switching points, phases
/// absolute and displacements divided by `l` (relative to 1 + |x|).
fn scaled_deviation(a: &[SwitchingPoint], reference: &[SwitchingPoint], l: f64) -> f64 {
    a.iter()
        .zip(reference)
        .map(|(a, b)| {
            (a.phase - b.phase)
                .abs()
                .max((a.x / l - b.x).abs() / (1.0 + b.x.abs()))
        })
        .fold(0.0, f64::max)
}

#[test]
fn case8_parameter_scales() {
    use stickslip::orbit::motion::solve;
    use stickslip::orbit::periodic::{NewtonOptions, Termination};
    use stickslip::ParamError;
    let base = Params {
        W: 3.7,
        Q0: 70.0,
        ..Params::default()
    };
    let sim0 = Simulator::<Paper>::new(base, SimOptions::default()).expect("valid");
    let Ok(Attractor::Periodic(m0)) = attractor::find(
        &sim0,
        sim0.start(0.0, 0.0, 0.0).expect("start"),
        AttractorOptions::default(),
    ) else {
        panic!("the reference motion at W = 3.7");
    };
    assert_eq!(
        m0.structure.notation(Paper::INFO),
        "P_{3_31 0_11 3_13 4_33}"
    );
    let mut scales = Vec::new();
    for s in [1e-6, 1e-3, 1e3, 1e6] {
        scales.push((s, 1.0, 1.0));
        scales.push((1.0, s, 1.0));
        scales.push((1.0, 1.0, s));
    }
    scales.extend([
        (1e-6, 1e-6, 1e6),
        (1e6, 1e6, 1e-6),
        (1e-3, 1e3, 1e6),
        (1e6, 1e-3, 1e-6),
    ]);
    // Newton's stopping test is scale-invariant (the step in natural units:
    // phases in radians, displacements over the motion's length scale), so
    // the DEFAULT options serve every scaling: Newton from the same
    // (scaled) guess converges, to the same motion, in the same iterations
    // (give or take one, from rounding), and the simulation from rest with
    // the default options finds the same motion.
    let unscaled_guess: Vec<SwitchingPoint> = m0
        .points
        .iter()
        .map(|q| SwitchingPoint {
            phase: q.phase + 1e-3,
            x: q.x * (1.0 + 1e-3),
        })
        .collect();
    let reference_iterations = match solve(
        &sim0,
        m0.structure.clone(),
        unscaled_guess.clone(),
        NewtonOptions::default(),
    )
    .termination
    {
        Termination::Converged { iterations, .. } => iterations,
        other => panic!("unscaled: {other:?}"),
    };
    let (mut worst_newton, mut worst_attr) = (0.0f64, 0.0f64);
    for &(l, t, m) in &scales {
        let p = scaled_paper(&base, l, t, m);
        let what = format!("length x{l:e}, time x{t:e}, mass x{m:e}");
        let sim = Simulator::<Paper>::new(p, SimOptions::default())
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        // Newton from the scaled reference points, perturbed.
        let guess: Vec<SwitchingPoint> = unscaled_guess
            .iter()
            .map(|q| SwitchingPoint {
                phase: q.phase,
                x: q.x * l,
            })
            .collect();
        let mo = solve(&sim, m0.structure.clone(), guess, NewtonOptions::default());
        match mo.termination {
            Termination::Converged { iterations, .. } => assert!(
                iterations.abs_diff(reference_iterations) <= 1,
                "{what}: {iterations} Newton iterations, {reference_iterations} unscaled"
            ),
            ref other => panic!("{what}, default options: {other:?}"),
        }
        assert!(
            mo.is_admissible(),
            "{what}: {:?} {:?}",
            mo.termination,
            mo.violations
        );
        let dev = scaled_deviation(&mo.points, &m0.points, l);
        assert!(dev < 1e-9, "{what}: Newton points deviate by {dev:e}");
        worst_newton = worst_newton.max(dev);
        // Simulation from rest, default options.
        match attractor::find(
            &sim,
            sim.start(0.0, 0.0, 0.0).expect("start"),
            AttractorOptions::default(),
        ) {
            Ok(Attractor::Periodic(mm)) => {
                assert!(mm.termination.converged(), "{what}: {:?}", mm.termination);
                assert_eq!(
                    mm.structure,
                    m0.structure,
                    "{what}: {}",
                    mm.structure.notation(Paper::INFO)
                );
                let dev = scaled_deviation(&mm.points, &m0.points, l);
                assert!(dev < 1e-9, "{what}: simulated motion deviates by {dev:e}");
                worst_attr = worst_attr.max(dev);
            }
            other => panic!("{what}: {other:?}"),
        }
    }
    // Scales outside the floating-point range: typed parameter errors.
    for (l, t, m) in [
        (1.0, 1e-160, 1.0),
        (1.0, 1e200, 1.0),
        (1e300, 1e-10, 1.0),
        (1.0, 1.0, 0.0),
        (1.0, 1.0, -1.0),
    ] {
        let p = scaled_paper(&base, l, t, m);
        match Simulator::<Paper>::new(p, SimOptions::default()) {
            Err(SimError::Params(
                ParamError::NotFinite { .. }
                | ParamError::NotPositive { .. }
                | ParamError::OutOfRange { .. }
                | ParamError::StaticBelowKinetic { .. },
            )) => {}
            other => panic!(
                "length x{l:e}, time x{t:e}, mass x{m:e}: {:?}",
                other.map(|_| "accepted")
            ),
        }
    }
    report(
        "case 8",
        &format!(
            "{} scalings: Newton points vs scaled reference (phase, x/l)",
            scales.len()
        ),
        worst_newton,
    );
    report(
        "case 8",
        "simulation from rest vs scaled reference (phase, x/l)",
        worst_attr,
    );
}

// ---------------------------------------------------------------------------
// 6. Grazing within 1e-12 of tangency.
// ---------------------------------------------------------------------------

/// The band of domain `j`.
fn band(sim: &Simulator<Paper>, j: usize) -> (f64, f64) {
    let d = Paper::INFO.domains[j];
    (
        d.lower.map_or(f64::NEG_INFINITY, |k| sim.velocity(k)),
        d.upper.map_or(f64::INFINITY, |k| sim.velocity(k)),
    )
}

/// A flow in domain `j` whose velocity has an extremum passing the upper
/// (`upper`) or lower boundary by `overshoot` (negative: staying short),
/// strictly inside the band before it (as in tests/grazing.rs): the state
/// at the extremum (zero acceleration, the rate of the right sign) run
/// backwards by the closed form. Returns `(x0, v0, phi0, phi_m)`.
fn near_graze(
    sim: &Simulator<Paper>,
    j: usize,
    upper: bool,
    phi_base: f64,
    overshoot: f64,
) -> Option<(f64, f64, f64, f64)> {
    let p = sim.params();
    let (lo, hi) = band(sim, j);
    let sign = if upper { 1.0 } else { -1.0 };
    let vm = if upper { hi } else { lo } + sign * overshoot;
    let co = Paper::coefficients(p, j);
    let a0 = sim.oscillator().amplitude;
    for k in 0..628 {
        let phi_m = phi_base + 0.01 * k as f64;
        let xm = (a0 * phi_m.cos() - co.b - co.two_d * vm) / co.c;
        let [_, rate] = Paper::normal_field(p, j, xm, vm, phi_m);
        if sign * rate > -1e-3 {
            continue;
        }
        for back in [2.0, 1.0, 0.5, 0.25] {
            let phi0 = phi_m - back;
            let [x0, v0] = Paper::flow(p, j, xm, vm, phi_m, phi0);
            let inside = |v: f64| v > lo && v < hi;
            let clear = (0..2000).all(|i| {
                let phi = phi0 + back * i as f64 / 2000.0;
                inside(Paper::flow(p, j, xm, vm, phi_m, phi)[1])
            });
            if clear && inside(v0) {
                return Some((x0, v0, phi0, phi_m));
            }
        }
    }
    None
}

#[test]
fn case6_grazing_within_1e_12_of_tangency() {
    let sims = [(3.0, 70.0), (5.0, 70.0), (7.0, 150.0)].map(|(w, q0)| {
        Simulator::<Paper>::new(
            Params {
                W: w,
                Q0: q0,
                ..Params::default()
            },
            SimOptions::default(),
        )
        .expect("valid")
    });
    let info = Paper::INFO;
    let cases = [
        (0, true),
        (1, true),
        (1, false),
        (2, true),
        (2, false),
        (3, false),
    ];
    let (mut found, mut grazes, mut crossings, mut quiet) = (0, 0, 0, 0);
    let mut worst_construction = 0.0f64;
    let mut worst_cross = 0.0f64;
    let mut worst_repeats = 0usize;
    for (j, upper) in cases {
        for base in [0.3, 2.0, 4.4, 10.0 * TAU + 1.1] {
            for eps in [1e-12, 1e-13, 0.0, -1e-13, -1e-12] {
                let (sim, (x0, v0, phi0, at)) = sims
                    .iter()
                    .find_map(|sim| near_graze(sim, j, upper, base, eps).map(|r| (sim, r)))
                    .unwrap_or_else(|| panic!("no flow near phase {base} grazes domain {j} (upper {upper}) by {eps:e}"));
                let k = if upper {
                    info.domains[j].upper
                } else {
                    info.domains[j].lower
                }
                .expect("bounded side");
                let vb = sim.velocity(k);
                // The overshoot, independently: the Taylor reference from the start to the extremum.
                let ode = Ode::of::<Paper>(sim.params(), j);
                let (_, v_ref) = ode.taylor(x0, v0, phi0, (at - phi0) / ode.w);
                let built = if upper { v_ref - vb } else { vb - v_ref };
                worst_construction = worst_construction.max((built - eps).abs());
                assert!(
                    (built - eps).abs() < 2e-14,
                    "construction: overshoot {built:e}, wanted {eps:e}"
                );
                let what = format!(
                    "W {} Q0 {}: domain {} {} from ({x0}, {v0}) at {phi0}, extremum at {at} passing by {eps:e}",
                    sim.params().W,
                    sim.params().Q0,
                    info.domains[j].label,
                    if upper { "up" } else { "down" }
                );
                let seg = Segment {
                    x: x0,
                    v: v0,
                    phase: phi0,
                    location: Location::Domain(j),
                    search_from: phi0,
                };
                let res = sim
                    .next_event(&seg, at + 0.05)
                    .expect("no simulation error");
                match res {
                    Some((e, next)) => {
                        assert_eq!(e.boundary, k, "{what}: {e:?}");
                        assert!(
                            (e.phase - at).abs() < 1e-3,
                            "{what}: event far from the extremum: {e:?}"
                        );
                        if e.kind == EventKind::Graze {
                            grazes += 1;
                            // The run goes on past the tangency: the search resumes just past
                            // the graze, and one tangency is one graze.
                            assert!(next.search_from > e.phase, "{what}: {next:?}");
                            let mut after = Vec::new();
                            sim.run(seg, at + 0.05, |e| after.push(*e))
                                .expect("no error");
                            let repeats = after
                                .iter()
                                .take_while(|e| e.kind == EventKind::Graze)
                                .count();
                            worst_repeats = worst_repeats.max(repeats);
                            assert_eq!(
                                repeats,
                                1,
                                "{what}: one tangency, {repeats} grazes: {:?}",
                                &after[..repeats.min(4)]
                            );
                            if let Some(e2) = after.get(repeats) {
                                assert!(
                                    eps >= 0.0 || e2.phase - at > 1e-3,
                                    "{what}: a crossing after the graze: {e2:?}"
                                );
                            }
                        } else {
                            crossings += 1;
                            assert!(
                                eps >= 0.0,
                                "{what}: the flow stays short of the boundary, yet {e:?}"
                            );
                            // Where the reference crosses: before the extremum by about sqrt(2 eps / |v''|).
                            let (_, v_at) = ode.taylor(x0, v0, phi0, (e.phase - phi0) / ode.w);
                            worst_cross = worst_cross.max((v_at - vb).abs());
                            assert!(
                                (v_at - vb).abs() < 1e-13,
                                "{what}: v = {v_at} at the crossing {e:?}"
                            );
                        }
                        found += 1;
                    }
                    None => {
                        assert!(
                            eps < 0.0,
                            "{what}: the flow reaches the boundary (by {eps:e}), no event reported"
                        );
                        quiet += 1;
                    }
                }
            }
        }
    }
    eprintln!(
        "[extremes] case 6: {found} found ({crossings} crossings, {grazes} grazes, each tangency reported {worst_repeats} time(s)), {quiet} short of the boundary without an event"
    );
    report(
        "case 6",
        "constructed overshoot vs Taylor reference (absolute, velocity)",
        worst_construction,
    );
    report(
        "case 6",
        "|v - V_b| of the Taylor reference at reported crossings",
        worst_cross,
    );
}

// ---------------------------------------------------------------------------
// 7. Stick with Fnf within 1e-12 of ±as.
// ---------------------------------------------------------------------------

#[test]
fn case7_stick_end_within_1e_12_of_the_static_bound() {
    // W = 5, Q0 = 150: Fnf' = -A0 sin(Wt) - c V / W changes sign, so Fnf has extrema.
    let p = Params {
        W: 5.0,
        Q0: 150.0,
        ..Params::default()
    };
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid");
    let osc = sim.oscillator();
    let vs = sim.velocity(1);
    let bound = Paper::static_bound(&p).expect("as");
    let (a0, w, c) = (osc.amplitude, osc.frequency, osc.stiffness);
    let s = -c * vs / (w * a0);
    assert!(s.abs() < 1.0);
    let (mut ends, mut grazes, mut quiet) = (0, 0, 0);
    let mut worst_peak = 0.0f64;
    let mut worst_end = 0.0f64;
    let mut worst_repeats = 0usize;
    // The maximum of Fnf at as + eps (exit above, into Ω1 = index 2), and the
    // minimum at -as - eps (exit below, into Ω3 = index 1).
    for (maximum, exit) in [(true, 2usize), (false, 1usize)] {
        let sign = if maximum { 1.0 } else { -1.0 };
        for turn in [0.0, 1.0, 3.0] {
            let peak = if maximum {
                s.asin()
            } else {
                std::f64::consts::PI - s.asin()
            }
            .rem_euclid(TAU)
                + turn * TAU;
            let phi0 = peak - 0.5;
            let fnf = |x0: f64, phi: f64| {
                Paper::stick_forces(&p, x0 + vs * (phi - phi0) / w, phi)
                    .expect("stick")
                    .non_friction
            };
            for eps in [1e-12, 1e-13, 0.0, -1e-13, -1e-12] {
                let target = sign * (bound + eps);
                let mut x0 = (target - fnf(0.0, peak)) / -c;
                for _ in 0..3 {
                    x0 -= (fnf(x0, peak) - target) / -c;
                }
                assert!(fnf(x0, phi0).abs() < bound, "a valid stick");
                // The extremum, independently: golden-section search of Fnf near the peak.
                let (mut lo, mut hi) = (peak - 0.3, peak + 0.3);
                let g = 0.5 * (5f64.sqrt() - 1.0);
                for _ in 0..200 {
                    let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
                    if sign * fnf(x0, m1) > sign * fnf(x0, m2) {
                        hi = m2;
                    } else {
                        lo = m1;
                    }
                }
                let extremum = sign * fnf(x0, 0.5 * (lo + hi)) - bound;
                worst_peak = worst_peak.max((extremum - eps).abs());
                assert!(
                    (extremum - eps).abs() < 2e-14,
                    "Fnf extremum {extremum:e} beyond as, wanted {eps:e}"
                );
                let seg = Segment {
                    x: x0,
                    v: vs,
                    phase: phi0,
                    location: Location::Stick,
                    search_from: phi0,
                };
                let what = format!(
                    "stick from {phi0}, Fnf {} at {}as {eps:+e}",
                    if maximum { "max" } else { "min" },
                    if maximum { "+" } else { "-" }
                );
                match sim
                    .next_event(&seg, peak + 0.05)
                    .expect("no simulation error")
                {
                    Some((e, next)) if e.kind == EventKind::StickEnd => {
                        assert!(eps >= 0.0, "{what}: a stick end invented: {e:?}");
                        assert!(
                            e.phase <= peak + 1e-6 && peak - e.phase < 1e-3,
                            "{what}: {e:?}"
                        );
                        assert_eq!(next.location, Location::Domain(exit), "{what}");
                        // |Fnf| = as at the end, to round-off.
                        let off = (fnf(x0, e.phase).abs() - bound).abs();
                        worst_end = worst_end.max(off);
                        assert!(off < 1e-12, "{what}: |Fnf| - as = {off:e} at the end");
                        ends += 1;
                    }
                    Some((e, next)) => {
                        assert_eq!(e.kind, EventKind::Graze, "{what}: {e:?}");
                        assert!((e.phase - peak).abs() < 1e-3, "{what}: {e:?}");
                        assert_eq!(next.location, Location::Stick, "{what}");
                        // The run goes on: past the one graze of this tangency
                        // the stick lasts until |Fnf| really reaches as.
                        // One graze, over the same search (same limit) as next_event.
                        let mut near = Vec::new();
                        sim.run(seg, peak + 0.05, |e| near.push(*e))
                            .expect("no error");
                        let once = near
                            .iter()
                            .take_while(|e| e.kind == EventKind::Graze)
                            .count();
                        worst_repeats = worst_repeats.max(once);
                        assert_eq!(
                            once,
                            1,
                            "{what}: one tangency, {once} grazes: {:?}",
                            &near[..once.min(4)]
                        );
                        let mut after = Vec::new();
                        sim.run(seg, peak + 1.0, |e| after.push(*e))
                            .expect("no error");
                        let repeats = after
                            .iter()
                            .take_while(|e| e.kind == EventKind::Graze)
                            .count();
                        assert!(repeats <= 1, "{what}: {:?}", &after[..repeats.min(4)]);
                        // Short of as (eps < 0) the stick must not end at this
                        // tangency; exactly at as either verdict holds (round-off).
                        if let Some(e2) = after.get(repeats) {
                            assert!(
                                eps >= 0.0 || e2.phase - peak > 0.1,
                                "{what}: {e2:?} right after the graze"
                            );
                        }
                        grazes += 1;
                    }
                    None => {
                        assert!(
                            eps < 0.0,
                            "{what}: |Fnf| reaches as (by {eps:e}) and the stick end is missed"
                        );
                        quiet += 1;
                    }
                }
            }
        }
    }
    eprintln!(
        "[extremes] case 7: {ends} stick ends, {grazes} grazes (each tangency reported {worst_repeats} time(s)), {quiet} sticks that go on without an event"
    );
    report(
        "case 7",
        "constructed Fnf extremum vs golden-section search (absolute)",
        worst_peak,
    );
    report(
        "case 7",
        "||Fnf| - as| at the reported stick ends",
        worst_end,
    );
}
