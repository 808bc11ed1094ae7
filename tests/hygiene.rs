//! Generated code is hygienic: the paper model with every identifier renamed
//! to hostile names — the generator's own locals and temporaries (`p`, `x0`,
//! `phi1`, `t0`, `t3`, `ec0`), its items (`INFO`, `Params`, `oscillator`,
//! `boundary_velocities`), prelude and primitive names (`Some`, `None`,
//! `Default`, `Option`, `f64`, `core`), keywords (`r#fn`, `r#type`,
//! `r#struct`, 2024's `gen`), Unicode (`μs`, `ω`, `Ω1`), names without a
//! camel case (`_1`), scenes whose type names collide after case
//! conversion (`sweep_w`, `sweepW`, `SweepW`) — compiles, and every public
//! generated function gives bit for bit the numbers of
//! `stickslip::models::paper` over a set of points.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use stickslip::{Model, ParamSet};

// The paper model: m → p, d → x0, c → t3, V → INFO, V1 → Params, V2 → r#type,
// mus → μs, muk → t0, mu1 → ω, mu2 → Ω1, mu3 → phi1, mu4 → oscillator,
// g → ec0, Q0 → Some, W → r#fn, FN → t1; scenes sweep_w → _1, reference → INFO.
stickslip::model! {
    model params {
        param p = 5.0, > 0;
        param x0 = 0.1, >= 0;
        param t3 = 30.0, > 0;
        param INFO = 3.0;
        param Params = 4.5;
        param r#type = 1.5;
        param μs = 0.5, >= 0;
        param t0 = 0.4, >= 0;
        param ω = 0.1;
        param Ω1 = 0.5;
        param phi1 = 0.1;
        param oscillator = 0.5;
        param ec0 = 9.8, > 0;
        param Some = 70.0;
        param r#fn = 3.0, > 0;
        let t1 = p * ec0;
        oscillator {
            mass: p,
            damping: x0,
            stiffness: t3,
            forcing: Some / p,
            frequency: r#fn,
        }
        boundary Sigma1: v = INFO, stick μs * t1 / p;
        boundary Sigma2: v = Params;
        boundary Sigma3: v = r#type;
        domain 2: v > Sigma2 => (ω * (v - Params) - Ω1 * (Params - INFO) + t1 * t0) / p;
        domain 1: Sigma1 < v < Sigma2 => (-Ω1 * (v - INFO) + t1 * t0) / p;
        domain 3: Sigma3 < v < Sigma1 => (-phi1 * (v - INFO) - t1 * t0) / p;
        domain 4: v < Sigma3 => (oscillator * (v - r#type) - phi1 * (r#type - INFO) - t1 * t0) / p;
        scene _1 {
            free: r#fn;
        }
        scene INFO {
            free: r#fn, Some;
            structures: "3_33 4_33", "3_31 0_11 3_13 4_33", "3_31 1_12 2_22 1_21 3_13 4_33",
                "3_31 0_11 1_11 3_13 4_33", "3_31 1_11 3_13 4_33";
        }
    }
}

// m → value, d → index, c → self_, V → phi0, V1 → v0, V2 → x1, mus → es0,
// muk → t20, mu1 → Default, mu2 → None, mu3 → f64, mu4 → core, g → gen,
// Q0 → stickslip, W → boundary_velocities, FN → y; scenes sweep_w → Default,
// reference → Option, and three more sweeps whose types are all `SweepW`.
stickslip::model! {
    model r#struct {
        param value = 5.0, > 0;
        param index = 0.1, >= 0;
        param self_ = 30.0, > 0;
        param phi0 = 3.0;
        param v0 = 4.5;
        param x1 = 1.5;
        param es0 = 0.5, >= 0;
        param t20 = 0.4, >= 0;
        param Default = 0.1;
        param None = 0.5;
        param f64 = 0.1;
        param core = 0.5;
        param gen = 9.8, > 0;
        param stickslip = 70.0;
        param boundary_velocities = 3.0, > 0;
        let y = value * gen;
        oscillator {
            mass: value,
            damping: index,
            stiffness: self_,
            forcing: stickslip / value,
            frequency: boundary_velocities,
        }
        boundary Sigma1: v = phi0, stick es0 * y / value;
        boundary Sigma2: v = v0;
        boundary Sigma3: v = x1;
        domain 2: v > Sigma2 => (Default * (v - v0) - None * (v0 - phi0) + y * t20) / value;
        domain 1: Sigma1 < v < Sigma2 => (-None * (v - phi0) + y * t20) / value;
        domain 3: Sigma3 < v < Sigma1 => (-f64 * (v - phi0) - y * t20) / value;
        domain 4: v < Sigma3 => (core * (v - x1) - f64 * (x1 - phi0) - y * t20) / value;
        scene Default {
            free: boundary_velocities;
        }
        scene Option {
            free: boundary_velocities, stickslip;
            structures: "3_33 4_33", "3_31 0_11 3_13 4_33", "3_31 1_12 2_22 1_21 3_13 4_33",
                "3_31 0_11 1_11 3_13 4_33", "3_31 1_11 3_13 4_33";
        }
        scene sweep_w {
            free: boundary_velocities;
        }
        scene sweepW {
            free: boundary_velocities;
        }
        scene SweepW {
            free: boundary_velocities;
        }
    }
}

use stickslip::models::paper;

/// `value` as text that differs whenever the bits differ (shortest
/// round-trip `Debug`, `-0.0` and NaN included).
fn bits<T: std::fmt::Debug>(value: T) -> String {
    format!("{value:?}")
}

/// Parameter sets of `A` (and of `B`, index for index) at the defaults and
/// at random points around them; the free ones only.
fn points<A: Model>(n: usize) -> Vec<Vec<f64>>
where
    A::Params: Default,
{
    let mut rng = StdRng::seed_from_u64(9);
    let base = A::Params::default();
    let k = base.names().len();
    let mut out = vec![(0..k).map(|i| base.get(i)).collect::<Vec<_>>()];
    for _ in 0..n {
        out.push(
            (0..k)
                .map(|i| base.get(i) * rng.gen_range(0.7..1.3))
                .collect(),
        );
    }
    out
}

fn params_of<P: ParamSet + Default>(values: &[f64]) -> P {
    let mut p = P::default();
    for (i, &x) in values.iter().enumerate() {
        p.set(i, x);
    }
    p
}

/// Every function of the `Model` interface (each dispatches to one
/// generated function per domain or mapping), bit for bit, over the
/// parameter points and a grid of states; plus the static description.
fn same_numbers<A: Model, B: Model>()
where
    A::Params: Default,
    B::Params: Default,
{
    let (a0, b0) = (A::Params::default(), B::Params::default());
    let (ia, ib) = (A::info(&a0), B::info(&b0));
    assert_eq!(a0.names().len(), b0.names().len());
    assert_eq!(ia.free, ib.free);
    assert_eq!(ia.mapping_names(), ib.mapping_names());
    assert_eq!(ia.structures, ib.structures);
    assert_eq!(ia.boundaries.len(), ib.boundaries.len());
    assert_eq!(ia.domains.len(), ib.domains.len());
    for (a, b) in ia.params.iter().zip(ib.params) {
        assert_eq!(bits(a.default), bits(b.default));
        assert_eq!(a.free, b.free);
    }
    for (a, b) in ia.domains.iter().zip(ib.domains) {
        assert_eq!(bits(a.fixed_regime), bits(b.fixed_regime));
    }
    let mut rng = StdRng::seed_from_u64(17);
    let mut compared = 0usize;
    for values in points::<A>(12) {
        let pa: A::Params = params_of(&values);
        let pb: B::Params = params_of(&values);
        assert_eq!(pa.check().is_ok(), pb.check().is_ok());
        assert_eq!(bits(A::oscillator(&pa)), bits(B::oscillator(&pb)));
        assert_eq!(bits(A::static_bound(&pa)), bits(B::static_bound(&pb)));
        for j in 0..=ia.domains.len() {
            assert_eq!(bits(A::coefficients(&pa, j)), bits(B::coefficients(&pb, j)));
        }
        for k in 0..=ia.boundaries.len() {
            assert_eq!(
                bits(A::boundary_velocity(&pa, k)),
                bits(B::boundary_velocity(&pb, k))
            );
        }
        for _ in 0..8 {
            let s: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-4.0..4.0));
            for j in 0..=ia.domains.len() {
                assert_eq!(
                    bits(A::flow(&pa, j, s[0], s[1], s[2], s[3])),
                    bits(B::flow(&pb, j, s[0], s[1], s[2], s[3]))
                );
                assert_eq!(
                    bits(A::normal_field(&pa, j, s[0], s[1], s[2])),
                    bits(B::normal_field(&pb, j, s[0], s[1], s[2]))
                );
                compared += 2;
            }
            assert_eq!(
                bits(A::stick_forces(&pa, s[0], s[1])),
                bits(B::stick_forces(&pb, s[0], s[1]))
            );
            for m in 0..=ia.mappings.len() {
                assert_eq!(
                    bits(A::residual(&pa, m, s[0], s[1], s[2], s[3])),
                    bits(B::residual(&pb, m, s[0], s[1], s[2], s[3]))
                );
                assert_eq!(
                    bits(A::mapping(&pa, m, s[0], s[1], s[2], s[3])),
                    bits(B::mapping(&pb, m, s[0], s[1], s[2], s[3]))
                );
                compared += 2;
            }
        }
    }
    assert!(compared > 1000, "compared only {compared} values");
}

#[test]
fn generator_names_as_parameter_names_change_no_number() {
    same_numbers::<paper::Paper, params::ModelParams>();
    same_numbers::<paper::sweep_w::SweepW, params::_1::Scene1>();
    same_numbers::<paper::reference::Reference, params::INFO::SceneINFO>();
}

#[test]
fn prelude_primitive_and_keyword_names_change_no_number() {
    same_numbers::<paper::Paper, r#struct::Struct>();
    same_numbers::<paper::sweep_w::SweepW, r#struct::Default::SceneDefault>();
    same_numbers::<paper::reference::Reference, r#struct::Option::SceneOption>();
    same_numbers::<paper::sweep_w::SweepW, r#struct::sweep_w::SweepW>();
    same_numbers::<paper::sweep_w::SweepW, r#struct::sweepW::SweepW>();
    same_numbers::<paper::sweep_w::SweepW, r#struct::SweepW::SweepW>();
}

#[test]
fn hostile_names_are_fields_and_names_as_written() {
    // Fields keep the model's spelling (raw for keywords), run-time names
    // drop the `r#`.
    let p = params::Params {
        r#fn: 4.4,
        Some: 60.0,
        ..Default::default()
    };
    assert_eq!(p.get(14), 4.4);
    assert_eq!(params::Params::NAMES[14], "fn");
    assert_eq!(params::Params::NAMES[5], "type");
    assert_eq!(params::Params::NAMES[6], "μs");
    assert_eq!(params::ModelParams::INFO.name, "params");
    assert_eq!(params::INFO::SceneINFO::INFO.name, "params::INFO");
    let q = r#struct::Params {
        r#gen: 9.0,
        ..Default::default()
    };
    assert_eq!(q.get(12), 9.0);
    assert_eq!(r#struct::Struct::INFO.name, "struct");
    assert_eq!(r#struct::Params::NAMES[12], "gen");
    // A hostile model computes what the paper model computes at the same
    // values, read through the names.
    let a = paper::Params {
        W: 4.4,
        Q0: 60.0,
        ..Default::default()
    };
    let x = paper::Paper::mapping(&a, 3, 0.5, 1.0, -0.5, 2.0);
    let y = params::ModelParams::mapping(&p, 3, 0.5, 1.0, -0.5, 2.0);
    assert_eq!(bits(x), bits(y));
}
