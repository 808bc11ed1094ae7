//! The two back ends of the generator compute the same numbers: every
//! shipped model and scene, loaded from its file and compiled to machine
//! code at run time (`model::loaded`), against the same model compiled in at
//! build time, at random admissible points (a property test: proptest with a
//! fixed seed).
//!
//! Compared, to 1e-13 relative: effective coefficients, boundary velocities,
//! the static bound, the oscillator, flows, normal fields and their rates,
//! stick forces, mapping residuals and their Jacobians, and whether the
//! parameters pass `check`; for a smooth law, the law and its slope. The
//! descriptions (names, parameters, domains, boundaries, mappings) must be
//! the same too.

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use stickslip::model::loaded::{load_file, LoadedModel, LoadedParams, LoadedSmoothParams};
use stickslip::model::loaded::{Loaded, LoadedSmooth};
use stickslip::models::{self, Entry};
use stickslip::{FrictionOscillator, Model, ModelVisitor, ParamSet, SmoothModel};

/// The relative difference of two numbers (0 when both are NaN, or equal).
fn relative(a: f64, b: f64) -> f64 {
    if a == b || (a.is_nan() && b.is_nan()) {
        return 0.0;
    }
    (a - b).abs() / a.abs().max(b.abs())
}

/// Compares values and keeps the worst relative difference and where.
#[derive(Default)]
struct Worst {
    rel: f64,
    what: String,
    compared: usize,
}

impl Worst {
    fn same(&mut self, what: impl Fn() -> String, a: &[f64], b: &[f64]) {
        assert_eq!(a.len(), b.len(), "{}", what());
        for (x, y) in a.iter().zip(b) {
            let r = relative(*x, *y);
            self.compared += 1;
            if r > self.rel || r.is_nan() {
                self.rel = r;
                self.what = format!("{}: {x:e} against {y:e}", what());
            }
        }
    }
}

const TOLERANCE: f64 = 1e-13;

fn model_file(model: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(format!("{model}.ssm"))
}

/// `name` (`paper::sweep_w`) loaded from its file: `(model, scene)`.
fn loaded(name: &str) -> LoadedModel {
    let (model, scene) = match name.split_once("::") {
        Some((m, s)) => (m, Some(s)),
        None => (name, None),
    };
    load_file(&model_file(model), scene).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A parameter set near the defaults: each free value scaled by a random
/// factor in [0.7, 1.3] (a sign kept, zero kept), the same for both.
fn perturb(rng: &mut StdRng, a: &mut impl ParamSet, b: &mut impl ParamSet) {
    for i in 0..a.names().len() {
        let f = rng.gen_range(0.7..1.3);
        a.set(i, a.get(i) * f);
        b.set(i, b.get(i) * f);
    }
}

/// Compare compiled-in `M` with the loaded model at `points` random
/// admissible parameter sets (and random states at each).
struct Piecewise {
    loaded: LoadedParams,
    seed: u64,
    points: usize,
}

impl ModelVisitor for Piecewise {
    type Output = Worst;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Worst> {
        Some(compare::<M>(base, self.loaded, self.seed, self.points))
    }
}

fn compare<M: Model>(base: M::Params, loaded: LoadedParams, seed: u64, points: usize) -> Worst {
    let (ia, ib) = (M::info(&base), Loaded::info(&loaded));
    let name = ia.name;
    assert_eq!(ia.name, ib.name);
    assert_eq!(base.names(), loaded.names(), "{name}");
    assert_eq!(ia.free, ib.free, "{name}");
    assert_eq!(ia.mapping_names(), ib.mapping_names(), "{name}");
    assert_eq!(ia.structures, ib.structures, "{name}");
    assert_eq!(format!("{:?}", ia.params), format!("{:?}", ib.params));
    assert_eq!(format!("{:?}", ia.domains), format!("{:?}", ib.domains));
    assert_eq!(
        format!("{:?}", ia.boundaries),
        format!("{:?}", ib.boundaries)
    );
    assert_eq!(format!("{:?}", ia.mappings), format!("{:?}", ib.mappings));
    assert_eq!(ia.source_hash, None);
    assert!(ib.source_hash.is_some());
    let mut rng = StdRng::seed_from_u64(seed);
    let mut w = Worst::default();
    let mut admissible = 0;
    for _ in 0..points {
        let (mut pa, mut pb) = (base, loaded);
        perturb(&mut rng, &mut pa, &mut pb);
        let checked = pa.check();
        assert_eq!(
            format!("{checked:?}"),
            format!("{:?}", pb.check()),
            "{name} at {pa:?}"
        );
        if checked.is_err() {
            continue;
        }
        admissible += 1;
        let at = |what: &str| format!("{name} {what} at {pa:?}");
        let osc =
            |o: stickslip::Oscillator| [o.mass, o.damping, o.stiffness, o.amplitude, o.frequency];
        w.same(
            || at("oscillator"),
            &osc(M::oscillator(&pa)),
            &osc(Loaded::oscillator(&pb)),
        );
        let bound = |s: Option<f64>| [s.unwrap_or(-1.0)];
        w.same(
            || at("as"),
            &bound(M::static_bound(&pa)),
            &bound(Loaded::static_bound(&pb)),
        );
        for k in 0..ia.boundaries.len() {
            let (a, b) = (
                M::boundary_velocity(&pa, k),
                Loaded::boundary_velocity(&pb, k),
            );
            w.same(|| at(&format!("V{k}")), &[a], &[b]);
        }
        for j in 0..ia.domains.len() {
            let (a, b) = (M::coefficients(&pa, j), Loaded::coefficients(&pb, j));
            w.same(
                || at(&format!("coefficients {j}")),
                &[a.two_d, a.c, a.b],
                &[b.two_d, b.c, b.b],
            );
        }
        let w_forcing = M::oscillator(&pa).frequency;
        for _ in 0..6 {
            let s: [f64; 4] = std::array::from_fn(|_| rng.gen_range(-4.0..4.0));
            let later = s[2] + rng.gen_range(0.01..2.0 * w_forcing.max(0.1));
            for j in 0..ia.domains.len() {
                let (a, b) = (
                    M::flow(&pa, j, s[0], s[1], s[2], later),
                    Loaded::flow(&pb, j, s[0], s[1], s[2], later),
                );
                w.same(|| at(&format!("flow {j} from {s:?}")), &a, &b);
                let (a, b) = (
                    M::normal_field(&pa, j, s[0], s[1], s[2]),
                    Loaded::normal_field(&pb, j, s[0], s[1], s[2]),
                );
                w.same(|| at(&format!("field {j} at {s:?}")), &a, &b);
            }
            let forces = |f: Option<stickslip::StickForces>| match f {
                Some(f) => vec![
                    f.non_friction,
                    f.input_above,
                    f.input_below,
                    f.output_above,
                    f.output_below,
                ],
                None => vec![],
            };
            w.same(
                || at("stick forces"),
                &forces(M::stick_forces(&pa, s[0], s[1])),
                &forces(Loaded::stick_forces(&pb, s[0], s[1])),
            );
            for m in 0..ia.mappings.len() {
                let (a, b) = (
                    M::residual(&pa, m, s[0], s[2], s[1], later),
                    Loaded::residual(&pb, m, s[0], s[2], s[1], later),
                );
                w.same(|| at(&format!("residual {m}")), a.as_slice(), b.as_slice());
                let (a, b) = (
                    M::mapping(&pa, m, s[0], s[2], s[1], later),
                    Loaded::mapping(&pb, m, s[0], s[2], s[1], later),
                );
                let all = |e: stickslip::MappingEval| {
                    let mut v = e.residual.as_slice().to_vec();
                    v.extend(e.d_prev.as_slice());
                    v.extend(e.d_next.as_slice());
                    v
                };
                w.same(|| at(&format!("mapping {m} Jacobian")), &all(a), &all(b));
            }
        }
    }
    assert!(
        admissible * 2 >= points,
        "{name}: only {admissible} of {points} points admissible"
    );
    w
}

/// The smooth law's functions, the same way.
struct Smooth {
    loaded: LoadedSmoothParams,
    seed: u64,
    points: usize,
}

impl ModelVisitor for Smooth {
    type Output = Worst;
    fn smooth<S: SmoothModel>(self, base: S::Params) -> Option<Worst> {
        let name = S::info(&base).name;
        assert_eq!(S::info(&base).law, LoadedSmooth::info(&self.loaded).law);
        assert_eq!(S::info(&base).range, LoadedSmooth::info(&self.loaded).range);
        assert_eq!(base.names(), self.loaded.names());
        let mut rng = StdRng::seed_from_u64(self.seed);
        let mut w = Worst::default();
        for _ in 0..self.points {
            let (mut pa, mut pb) = (base, self.loaded);
            perturb(&mut rng, &mut pa, &mut pb);
            let checked = pa.check();
            assert_eq!(format!("{checked:?}"), format!("{:?}", pb.check()));
            if checked.is_err() {
                continue;
            }
            let o = |o: stickslip::Oscillator| {
                [o.mass, o.damping, o.stiffness, o.amplitude, o.frequency]
            };
            w.same(
                || format!("{name} oscillator"),
                &o(S::oscillator(&pa)),
                &o(LoadedSmooth::oscillator(&pb)),
            );
            w.same(
                || format!("{name} V"),
                &[S::belt(&pa)],
                &[LoadedSmooth::belt(&pb)],
            );
            w.same(
                || format!("{name} as"),
                &[S::static_bound(&pa)],
                &[LoadedSmooth::static_bound(&pb)],
            );
            for _ in 0..20 {
                let v = S::belt(&pa) + rng.gen_range(-6.0..6.0);
                w.same(
                    || format!("{name} law at {v}"),
                    &S::kinetic(&pa, v),
                    &LoadedSmooth::kinetic(&pb, v),
                );
            }
        }
        Some(w)
    }
}

/// Every shipped model and scene against its loaded twin.
fn all_agree(seed: u64, points: usize) -> Result<(), TestCaseError> {
    for entry in models::ALL {
        let name = entry.name();
        let w = match (entry, loaded(name)) {
            (Entry::Piecewise(_), LoadedModel::Piecewise(loaded)) => models::visit(
                name,
                Piecewise {
                    loaded,
                    seed,
                    points,
                },
            ),
            (Entry::Smooth(_), LoadedModel::Smooth(loaded)) => models::visit(
                name,
                Smooth {
                    loaded,
                    seed,
                    points,
                },
            ),
            _ => panic!("{name}: loaded as another kind"),
        }
        .expect("compiled in");
        prop_assert!(w.compared > 0, "{name}: nothing compared");
        prop_assert!(
            w.rel <= TOLERANCE,
            "{name}: relative difference {:e} at {}",
            w.rel,
            w.what
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 6,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x4a17_0046),
        ..ProptestConfig::default()
    })]

    #[test]
    fn every_shipped_model_and_scene_loaded_agrees_with_the_compiled_one(seed in any::<u64>()) {
        all_agree(seed, 4)?;
    }
}

/// The worst difference over many points, printed (`--nocapture`): what
/// the README quotes. In fact the two back ends agree to the bit here.
#[test]
fn the_two_back_ends_agree_to_the_bit_on_the_paper_model() {
    let LoadedModel::Piecewise(loaded) = loaded("paper") else {
        panic!("paper is piecewise")
    };
    let w = models::visit(
        "paper",
        Piecewise {
            loaded,
            seed: 7,
            points: 40,
        },
    )
    .expect("compiled in");
    println!(
        "paper: {} values compared, worst relative difference {:e}",
        w.compared, w.rel
    );
    assert!(w.compared > 10_000);
    assert_eq!(w.rel, 0.0, "{}", w.what);
}

#[test]
fn a_loaded_scene_takes_only_its_free_parameters() {
    let LoadedModel::Piecewise(p) = loaded("paper::sweep_w") else {
        panic!("a scene is piecewise")
    };
    assert_eq!(p.names(), ["W"]);
    let e = p
        .with_pairs(Loaded::identity(&p), &[("Q0", 1.0)])
        .unwrap_err();
    assert!(e.to_string().contains("fixed to 70"), "{e}");
}
