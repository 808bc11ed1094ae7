//! Every generated flow against the ODE it solves and its initial state:
//! `x(phi0) = x0`, `v(phi0) = v0`, `dx/dt = v` and
//! `dv/dt = A0 cos(W t) - b_j - 2 d_j v - c_j x`, the derivatives taken by
//! finite differences of the flow and the right-hand side assembled from the
//! generated coefficients (independently of the closed form).

mod common;

use common::{derivative, params_for, rng, TARGETS};
use rand::Rng;
use stickslip::models::paper::Paper;
use stickslip::{FrictionOscillator, Model};

#[test]
fn flows_solve_their_ode_in_every_regime() {
    let mut r = rng(11);
    for j in 0..Paper::INFO.domains.len() {
        for n in 0..400 {
            let target = TARGETS[n % TARGETS.len()];
            let p = params_for(&mut r, j, target);
            let (x0, v0) = (r.gen_range(-3.0..3.0), r.gen_range(-2.0..6.0));
            let phi0 = r.gen_range(0.0..std::f64::consts::TAU);
            let start = Paper::flow(&p, j, x0, v0, phi0, phi0);
            let co = Paper::coefficients(&p, j);
            let osc = Paper::oscillator(&p);
            // x0 - x_p + x_p round-trips to within a few ulps of the forced response's size.
            let size = 1.0
                + x0.abs()
                + v0.abs()
                + (osc.amplitude + co.b.abs()) / co.c * (1.0 + osc.frequency);
            assert!(
                (start[0] - x0).abs() <= 1e-14 * size && (start[1] - v0).abs() <= 1e-14 * size,
                "domain {j} {target:?}: initial state {start:?} != ({x0}, {v0})"
            );
            let w = osc.frequency;
            for _ in 0..4 {
                let phi = phi0 + r.gen_range(0.01..10.0);
                let [x, v] = Paper::flow(&p, j, x0, v0, phi0, phi);
                let h = 1e-3;
                let dxdt = w * derivative(|t| Paper::flow(&p, j, x0, v0, phi0, t)[0], phi, h);
                let dvdt = w * derivative(|t| Paper::flow(&p, j, x0, v0, phi0, t)[1], phi, h);
                let accel = osc.amplitude * phi.cos() - co.b - co.two_d * v - co.c * x;
                let scale = 1.0 + x.abs() + v.abs() + accel.abs() + co.b.abs() + osc.amplitude;
                assert!(
                    (dxdt - v).abs() <= 1e-7 * scale,
                    "domain {j} {target:?}: dx/dt = {dxdt}, v = {v} (params {p:?})"
                );
                assert!(
                    (dvdt - accel).abs() <= 1e-7 * scale,
                    "domain {j} {target:?}: dv/dt = {dvdt}, ODE gives {accel} (params {p:?})"
                );
            }
        }
    }
}

#[test]
fn normal_field_is_the_acceleration_and_its_rate_is_its_derivative() {
    let mut r = rng(5);
    for j in 0..Paper::INFO.domains.len() {
        for _ in 0..200 {
            let p = params_for(&mut r, j, common::Target::Under);
            let (x0, v0, phi0) = (
                r.gen_range(-2.0..2.0),
                r.gen_range(-1.0..6.0),
                r.gen_range(0.0..6.0),
            );
            let phi = phi0 + r.gen_range(0.1..3.0);
            let [x, v] = Paper::flow(&p, j, x0, v0, phi0, phi);
            let [field, rate] = Paper::normal_field(&p, j, x, v, phi);
            let w = Paper::oscillator(&p).frequency;
            let accel = w * derivative(|t| Paper::flow(&p, j, x0, v0, phi0, t)[1], phi, 1e-3);
            let jerk = w * derivative(
                |t| {
                    let [x, v] = Paper::flow(&p, j, x0, v0, phi0, t);
                    Paper::normal_field(&p, j, x, v, t)[0]
                },
                phi,
                1e-3,
            );
            let scale = 1.0 + field.abs() + rate.abs();
            assert!(
                (field - accel).abs() <= 1e-7 * scale,
                "domain {j}: F = {field}, x'' = {accel}"
            );
            assert!(
                (rate - jerk).abs() <= 1e-6 * scale,
                "domain {j}: DF = {rate}, dF/dt = {jerk}"
            );
        }
    }
}

#[test]
fn stick_forces_follow_the_force_criteria() {
    // SPEC §3 with the paper's parameters: F1_in = Fnf - ak, F3_in = Fnf + ak,
    // F_out = Fnf -+ as, ak = muk g = 3.92, as = mus g = 4.9, Fnf = A0 cos - 2 d V - c x.
    let p = stickslip::models::paper::Params::default();
    for &(x, phi) in &[(0.3, 1.0), (-0.7, 4.0), (0.0, 0.0)] {
        let f = Paper::stick_forces(&p, x, phi).expect("the paper model has a stick boundary");
        let fnf = 14.0 * f64::cos(phi) - 2.0 * 0.1 * 3.0 - 30.0 * x;
        assert!((f.non_friction - fnf).abs() < 1e-12);
        assert!((f.input_above - (fnf - 3.92)).abs() < 1e-12);
        assert!((f.input_below - (fnf + 3.92)).abs() < 1e-12);
        assert!((f.output_above - (fnf - 4.9)).abs() < 1e-12);
        assert!((f.output_below - (fnf + 4.9)).abs() < 1e-12);
    }
    assert!((Paper::static_bound(&p).expect("stick") - 4.9).abs() < 1e-12);
}

/// The event search's evaluation of a segment (`dynamics::response`: the
/// forced response at the start computed once) is the generated flow and
/// normal field, to rounding, in every damping regime.
#[test]
fn the_event_searchs_response_is_the_generated_flow() {
    use stickslip::dynamics::response::Response;
    let mut r = rng(17);
    let mut checked = 0;
    for j in 0..Paper::INFO.domains.len() {
        for n in 0..400 {
            let target = TARGETS[n % TARGETS.len()];
            let p = params_for(&mut r, j, target);
            let (x0, v0) = (r.gen_range(-3.0..3.0), r.gen_range(-2.0..6.0));
            let phi0 = r.gen_range(0.0..1e3);
            let co = Paper::coefficients(&p, j);
            let osc = Paper::oscillator(&p);
            let Some(resp) = Response::new(co, osc, x0, v0, phi0) else {
                panic!("domain {j} {target:?}: no response at {p:?}");
            };
            for _ in 0..4 {
                let phi = phi0 + r.gen_range(0.0..10.0);
                let [x, v] = Paper::flow(&p, j, x0, v0, phi0, phi);
                let [a, da] = Paper::normal_field(&p, j, x, v, phi);
                let s = resp.at(phi);
                let scale = 1.0 + x.abs() + v.abs() + (osc.amplitude + co.b.abs()) / co.c;
                for (name, got, want, sc) in [
                    ("x", s.x, x, scale),
                    ("v", s.v, v, scale * osc.frequency),
                    ("a", s.a, a, scale * (co.c + co.two_d.abs() + 1.0)),
                    (
                        "a'",
                        s.da,
                        da,
                        scale * (co.c + co.two_d.abs() + 1.0).powi(2),
                    ),
                ] {
                    assert!(
                        (got - want).abs() <= 1e-12 * sc,
                        "domain {j} {target:?}: {name} = {got}, generated {want} (params {p:?})"
                    );
                }
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 4 * 400 * Paper::INFO.domains.len());
}
