//! Every generated Jacobian block against central finite differences of the
//! generated residual, at 1000 random points per mapping spread over all
//! damping regimes (under-, over-, critically damped, near-critical,
//! negative effective damping).

mod common;

use common::roots::bracket;
use common::{derivative, params_for, rng, TARGETS};
use stickslip::models::paper::Paper;
use stickslip::{MappingKind, Model};

#[test]
fn generated_jacobians_match_finite_differences_in_every_regime() {
    let info = Paper::INFO;
    let mut r = rng(7);
    let mut worst = 0.0f64;
    for (idx, m) in info.mappings.iter().enumerate() {
        for n in 0..1000 {
            let target = TARGETS[n % TARGETS.len()];
            // Stick mappings have no domain: exercise them at random parameters.
            let j = m.domain.unwrap_or(0);
            let p = params_for(&mut r, j, target);
            use rand::Rng;
            let x0 = r.gen_range(-3.0..3.0);
            let phi0 = r.gen_range(0.0..std::f64::consts::TAU);
            let x1 = r.gen_range(-3.0..3.0);
            // Elapsed time up to ~4 forcing periods; shorter under negative damping.
            let span = if m.kind == MappingKind::Stick {
                3.0
            } else {
                12.0
            };
            let phi1 = phi0 + r.gen_range(0.05..span);
            let eval = Paper::mapping(&p, idx, x0, phi0, x1, phi1);
            let f = Paper::residual(&p, idx, x0, phi0, x1, phi1);
            assert_eq!(
                eval.residual, f,
                "{}: residual-only and full evaluation differ",
                m.name
            );
            let args = [x0, phi0, x1, phi1];
            let scale = eval.d_prev.amax().max(eval.d_next.amax()).max(1.0);
            for (k, &a) in args.iter().enumerate() {
                let h = 1e-4 * a.abs().max(1.0);
                for row in 0..2 {
                    let fd = derivative(
                        |t| {
                            let mut v = args;
                            v[k] = t;
                            Paper::residual(&p, idx, v[0], v[1], v[2], v[3])[row]
                        },
                        a,
                        h,
                    );
                    let an = if k < 2 {
                        eval.d_prev[(row, k)]
                    } else {
                        eval.d_next[(row, k - 2)]
                    };
                    let err = (fd - an).abs() / scale;
                    worst = worst.max(err);
                    assert!(
                        err <= 1e-6,
                        "mapping {} ({target:?}, point {n}): d f{row} / d arg{k}: analytic {an}, finite difference {fd}, relative error {err:e}\nparams {p:?}\nargs {args:?}",
                        m.name
                    );
                }
            }
        }
    }
    eprintln!("worst relative error over all mappings: {worst:e}");
}

#[test]
fn local_jacobian_is_minus_inverse_next_times_prev() {
    // DP = -(df/dnext)^-1 df/dprev, ordered (W t, x): check that a first-order
    // step of the mapping solved with DP keeps the residual at zero.
    let p = stickslip::models::paper::Params {
        W: 3.7,
        ..Default::default()
    };
    let idx = Paper::INFO
        .mapping_index("3_31", None)
        .expect("3_31 exists");
    // A point on the mapping: start on Sigma1, follow the flow to v = V2 by bisection.
    let (x0, phi0) = (0.2438396257590662, 4.929460327723394);
    let dom = Paper::INFO.mappings[idx].domain.expect("flow mapping");
    let v_at = |phi: f64| Paper::flow(&p, dom, x0, 3.0, phi0, phi)[1] - 1.5;
    let (a, b) = (phi0 + 0.1, phi0 + 1.2);
    assert!(v_at(a) > 0.0 && v_at(b) < 0.0);
    let (a, b) = bracket(a, b, |phi| v_at(phi) <= 0.0, 0.0);
    let phi1 = 0.5 * (a + b);
    let x1 = Paper::flow(&p, dom, x0, 3.0, phi0, phi1)[0];
    let eval = Paper::mapping(&p, idx, x0, phi0, x1, phi1);
    assert!(eval.residual.amax() < 1e-12);
    let dp = eval.local_jacobian().expect("transversal crossing");
    let (dphi0, dx0) = (1e-6, -2e-6);
    let (phi1p, x1p) = (
        phi1 + dp[(0, 0)] * dphi0 + dp[(0, 1)] * dx0,
        x1 + dp[(1, 0)] * dphi0 + dp[(1, 1)] * dx0,
    );
    let r = Paper::residual(&p, idx, x0 + dx0, phi0 + dphi0, x1p, phi1p);
    assert!(r.amax() < 1e-10, "first-order residual {r:?}");
}
