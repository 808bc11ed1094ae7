//! The independent references of `tests/common/` against closed-form
//! solutions, so that a wrong coefficient in a reference fails here and not
//! as a puzzling disagreement elsewhere.

mod common;

use common::events::PiecewiseOde;
use common::roots::{bisect, first_point};
use common::taylor::Ode;
use common::{dopri, rng};
use rand::Rng;
use stickslip::dynamics::simulate::EventKind;
use stickslip::models::paper::{Paper, Params};
use stickslip::Model;

/// `x'' = −x` from `(1, 0)`: `x = cos t`, `v = −sin t`.
fn harmonic(_t: f64, y: &[f64; 2]) -> [f64; 2] {
    [y[1], -y[0]]
}

/// Error at `t = 1` of `n` equal Dormand–Prince steps of the harmonic oscillator.
fn dopri_error(n: usize) -> f64 {
    let h = 1.0 / n as f64;
    let mut y = [1.0, 0.0];
    for i in 0..n {
        y = dopri::step(harmonic, i as f64 * h, y, h).y;
    }
    (y[0] - 1f64.cos()).hypot(y[1] + 1f64.sin())
}

#[test]
fn dormand_prince_is_fifth_order() {
    // Global error O(h^5): halving h divides it by 32.
    for n in [4, 8, 16] {
        let ratio = dopri_error(n) / dopri_error(2 * n);
        assert!(
            (28.0..36.0).contains(&ratio),
            "n = {n}: error ratio {ratio}, want 32"
        );
    }
    assert!(dopri_error(64) < 1e-11, "{}", dopri_error(64));
}

#[test]
fn dormand_prince_error_estimate_and_dense_output_converge() {
    // Local error estimate y5 − y4: O(h^5), ratio 32. Dense output at θ:
    // local error O(h^5) as well (4th-order continuous extension).
    let one = |h: f64| dopri::step(harmonic, 0.0, [1.0, 0.0], h);
    for h in [0.4, 0.2, 0.1] {
        let (a, b) = (one(h), one(h / 2.0));
        let est = |s: &dopri::Step<2>| s.err[0].hypot(s.err[1]);
        let ratio = est(&a) / est(&b);
        assert!(
            (26.0..38.0).contains(&ratio),
            "h = {h}: estimate ratio {ratio}"
        );
        // The estimate is of the size of the 4th-order solution's true error.
        let true4 = ((a.y[0] - a.err[0]) - h.cos()).hypot((a.y[1] - a.err[1]) + h.sin());
        assert!(
            (0.5..2.0).contains(&(est(&a) / true4)),
            "h = {h}: estimate {} vs error {true4}",
            est(&a)
        );
        for theta in [0.0, 0.3, 0.5, 0.8, 1.0] {
            let dense = |s: &dopri::Step<2>, h: f64| {
                let y = s.dense(theta);
                (y[0] - (theta * h).cos()).hypot(y[1] + (theta * h).sin())
            };
            let (ea, eb) = (dense(&a, h), dense(&b, h / 2.0));
            if theta == 0.0 {
                assert_eq!((ea, eb), (0.0, 0.0));
            } else if theta == 1.0 {
                assert_eq!(a.dense(1.0), a.y);
            } else {
                assert!(
                    ea < 2e-4 * h.powi(5) / 0.4f64.powi(5),
                    "h = {h}, θ = {theta}: {ea}"
                );
                let ratio = ea / eb;
                assert!(ratio > 20.0, "h = {h}, θ = {theta}: dense ratio {ratio}");
            }
        }
    }
}

#[test]
fn bisection_finds_the_first_point_to_the_last_bit() {
    let r = bisect(1.0, 2.0, |x| x * x >= 2.0, 0.0);
    assert!(r * r >= 2.0);
    let below = f64::from_bits(r.to_bits() - 1);
    assert!(below * below < 2.0, "{r} is not the first point");
    // Scanning finds the first of several roots (sin: π, not 2π or 3π).
    let p = first_point(0.5, 0.1, 10.0, |x| x.sin() <= 0.0, 1e-15).expect("a root");
    assert!((p - std::f64::consts::PI).abs() < 1e-14, "{p}");
    assert_eq!(first_point(0.5, 0.1, 3.0, |x| x.sin() <= 0.0, 1e-15), None);
}

#[test]
fn taylor_matches_closed_forms() {
    let mut r = rng(17);
    for _ in 0..20 {
        let (d, w) = (r.gen_range(0.05..1.5), r.gen_range(0.3..4.0));
        let c = d * d + r.gen_range(0.2..9.0);
        let ode = Ode {
            d,
            c,
            b: r.gen_range(-2.0..2.0),
            a0: r.gen_range(0.0..5.0),
            w,
        };
        let tau = r.gen_range(0.01..6.0);
        // Homogeneous, under-damped: x = e^{−dt}(cos ωt + d/ω sin ωt) from (1, 0).
        let om = (c - d * d).sqrt();
        let e = (-d * tau).exp();
        let (s, co) = (om * tau).sin_cos();
        let (x, v) = ode.homogeneous().taylor(1.0, 0.0, 0.0, tau);
        let (xe, ve) = (e * (co + d / om * s), -e * (c / om) * s);
        // The transition matrix is the homogeneous flow from the unit vectors.
        let phi = ode.transition(tau);
        let x01 = e * s / om;
        assert!(
            (phi[0][0] - xe).abs() < 1e-13 && (phi[1][0] - ve).abs() < 1e-13,
            "{phi:?}"
        );
        assert!((phi[0][1] - x01).abs() < 1e-13, "{phi:?} vs {x01}");
        assert!(
            (x - xe).hypot(v - ve) <= 1e-13 * (1.0 + xe.hypot(ve)),
            "{ode:?}, τ {tau}: ({x}, {v}) vs ({xe}, {ve})"
        );
        // The forced response stays the forced response.
        let phi0 = r.gen_range(0.0..6.0);
        let (xf, vf) = ode.forced(phi0);
        let (x, v) = ode.taylor(xf, vf, phi0, tau);
        let (xe, ve) = ode.forced(phi0 + w * tau);
        assert!(
            (x - xe).hypot(v - ve) <= 1e-12 * (1.0 + xe.hypot(ve)),
            "{ode:?}, τ {tau}: forced ({x}, {v}) vs ({xe}, {ve})"
        );
        // Over-damped: the modal form against the series.
        let ode = Ode {
            c: d * d * r.gen_range(0.05..0.9),
            ..ode
        };
        let (x0, v0) = (r.gen_range(-2.0..2.0), r.gen_range(-2.0..2.0));
        let (xm, vm) = ode.modal(x0, v0, phi0, tau);
        let (xt, vt) = ode.taylor(x0, v0, phi0, tau);
        assert!(
            (xm - xt).hypot(vm - vt) <= 1e-11 * (1.0 + xt.hypot(vt)),
            "{ode:?}, τ {tau}: modal ({xm}, {vm}) vs series ({xt}, {vt})"
        );
    }
}

#[test]
fn event_integration_crosses_where_the_series_reaches_the_boundary() {
    // From rest, the paper model's first events: the state the integration
    // reports at each pass is where the Taylor series of the domain it
    // leaves reaches the boundary velocity.
    let p = Params::default();
    let ode = PiecewiseOde::of::<Paper>(&p);
    let start = ode.domain_of(0.0);
    let events = ode.integrate(0.0, 0.0, 0.0, Some(start), 20.0 / ode.w, 1e-13);
    let first = events.first().expect("an event within 20 phase units");
    assert!(
        matches!(first.kind, EventKind::Pass | EventKind::StickOnset),
        "{first:?}"
    );
    let taylor = Ode::of::<Paper>(&p, start);
    let (x, v) = taylor.taylor(0.0, 0.0, 0.0, first.phase / ode.w);
    let vb = Paper::boundary_velocity(&p, first.boundary);
    assert!(
        (v - vb).abs() < 1e-9 && (x - first.x).abs() < 1e-9,
        "event {first:?}: series ({x}, {v}), boundary velocity {vb}"
    );
}
