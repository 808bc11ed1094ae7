//! How fast is the generated residual + Jacobian of the global mapping `3_31`
//! of the paper model (domain Ω3, from Σ1 at `v = V` to Σ3 at `v = V2`)
//! compared with the alternatives? See `benches/README.md` for the results.
//!
//! Every variant evaluates, at the same point, the residual `f ∈ R²` and the
//! two 2×2 blocks `∂f/∂(x_i, W t_i)` and `∂f/∂(x_{i+1}, W t_{i+1})`
//! (SPEC §5, Eq. 38), with every input — parameters included — behind
//! `black_box`, so that nothing is constant-folded that the library could not
//! fold either:
//!
//! * `jacobian/generated`: the full model through the `Model` trait (run-time
//!   mapping index), `jacobian/generated_direct`: `paper::mapping_3_31`;
//! * `jacobian/hand_written`: a closed form written here, independently of
//!   the generated code and of `stickslip::model::homogeneous` (plain `f64`, chain
//!   rule by hand), from the same `paper::Params`;
//!   `jacobian/hand_written_precomputed`: the same with the parameter-only
//!   quantities computed once outside the timed loop (what a cache could buy);
//! * `jacobian/dual_x4` (four passes of `Dual64`) and `jacobian/dual_vec4`
//!   (one pass of `DualSVec64<4>`): forward-mode AD of the same closed form;
//! * `jacobian/finite_diff`: central differences of the generated residual;
//! * `jacobian/scene_specialized`: the scene `paper::sweep_w` (only `W` free).
//!
//! `residual/generated` and `residual/scene_specialized`: the residual alone.
//!
//! Before anything is timed, every variant is checked against the generated
//! result (hand-written and dual to 1e-10 relative), so the comparison is honest.
//!
//! The baselines written here are `#[inline(never)]`: the generated
//! `mapping_3_31` is compiled out of line too (LLVM does not inline it into the
//! timing loop), so every variant costs one call per iteration. Inlined into
//! criterion's loop, `hand_written` measured ~15% slower (spills around
//! `black_box`), which would have handicapped the baseline.

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion};
use num_dual::{Derivative, Dual64, DualNum, DualSVec64};
use stickslip::models::paper::{self, sweep_w, Paper};
use stickslip::nalgebra::{Const, Matrix2, Vector2, U1};
use stickslip::{MappingEval, Model, Phase};

/// A point of the reference orbit `3_31 0_11 3_13 4_33` at `W = 3.7`,
/// `Q0 = 70` (`shared/reference/orbits.json`): the mapping `3_31` starts on
/// Σ1 at `W t_i = 11.2126…` (`4.9294… + 2π`) and ends on Σ3 at
/// `W t_{i+1} = 5.8917… + 2π`, so the residual is ~0 here.
const X0: f64 = 0.243_839_625_759_066_2;
const PHI0: f64 = 4.929_460_327_723_394 + std::f64::consts::TAU;
const X1: f64 = 0.879_956_906_893_197_8;
const PHI1: f64 = 5.891_765_347_235_473 + std::f64::consts::TAU;

/// A second point off the orbit (non-zero residual) for the agreement checks.
const OFF: [f64; 4] = [X0 - 0.05, PHI0 + 0.1, X1 + 0.1, PHI1 - 0.2];

fn params() -> paper::Params {
    paper::Params {
        W: 3.7,
        Q0: 70.0,
        ..paper::Params::default()
    }
}

// ---------------------------------------------------------------------------
// Hand-written closed form (SPEC §1, §4, §5), independent of the generated code.
// ---------------------------------------------------------------------------

/// Everything in domain Ω3 that depends on the parameters only.
///
/// Ω3: `x'' + 2 d3 x' + c x = A0 cos(W t) - b3` with `d3 = d - mu3/(2m)`,
/// `b3 = (mu3 V - FN muk)/m`, `FN = m g`. Forced response
/// `x_p = A cos φ + B sin φ + C`, `v_p = W (B cos φ - A sin φ)`, homogeneous
/// part under-damped with `ω = sqrt(c - d3²)`.
#[derive(Clone, Copy, Debug)]
struct Omega3 {
    w: f64,
    inv_w: f64,
    a0: f64,
    d: f64,
    c: f64,
    /// `2 d3 V + b3`: the velocity-independent part of the acceleration on Σ1.
    two_dv_b: f64,
    b: f64,
    a: f64,
    bb: f64,
    cc: f64,
    omega: f64,
    inv_omega: f64,
    /// Start velocity (Σ1).
    v_from: f64,
    /// End velocity (Σ3).
    v_to: f64,
}

impl Omega3 {
    #[inline(always)]
    fn new(p: &paper::Params) -> Self {
        let inv_m = 1.0 / p.m;
        let a0 = p.Q0 * inv_m;
        let d = p.d - 0.5 * p.mu3 * inv_m;
        let b = (p.mu3 * p.V - p.m * p.g * p.muk) * inv_m;
        let c = p.c;
        let w = p.W;
        let cw = c - w * w;
        let tdw = 2.0 * d * w;
        let inv_den = 1.0 / (cw * cw + tdw * tdw);
        let omega = (c - d * d).sqrt();
        Omega3 {
            w,
            inv_w: 1.0 / w,
            a0,
            d,
            c,
            two_dv_b: 2.0 * d * p.V + b,
            b,
            a: a0 * cw * inv_den,
            bb: a0 * tdw * inv_den,
            cc: -b / c,
            omega,
            inv_omega: 1.0 / omega,
            v_from: p.V,
            v_to: p.V2,
        }
    }

    /// Residual and Jacobian blocks, the chain rule written out.
    ///
    /// With `Φ(τ) = [[Ec + d Es, Es], [-c Es, Ec - d Es]]` the fundamental
    /// matrix (`Ec = e^{-dτ} cos ωτ`, `Es = e^{-dτ} sin ωτ / ω`) and
    /// `τ = (φ1 - φ0)/W`:
    ///
    /// * `(x, v)(τ) = Φ(τ) (x0 - x_p(φ0), V - v_p(φ0)) + (x_p, v_p)(φ1)`;
    /// * `∂(x, v)/∂x0` is the first column of `Φ`;
    /// * `∂(x, v)/∂φ0 = -Φ(τ) F0 / W` with `F0 = (V, a(x0, V, φ0))` the
    ///   vector field at the start (moving the start time along the flow);
    /// * `∂(x, v)/∂φ1 = (v, a(x, v, φ1)) / W`, the vector field at the end;
    /// * `∂f/∂x1 = (-1, 0)`.
    #[inline(always)]
    fn eval(&self, x0: f64, phi0: f64, x1: f64, phi1: f64) -> MappingEval {
        let (s0, c0) = phi0.sin_cos();
        let (s1, c1) = phi1.sin_cos();
        let x_off = x0 - (self.a * c0 + self.bb * s0 + self.cc);
        let y_off = self.v_from - self.w * (self.bb * c0 - self.a * s0);
        let tau = (phi1 - phi0) * self.inv_w;
        let e = (-self.d * tau).exp();
        let (sn, cs) = (self.omega * tau).sin_cos();
        let ec = e * cs;
        let es = e * sn * self.inv_omega;
        let des = self.d * es;
        let p11 = ec + des;
        let p21 = -self.c * es;
        let p22 = ec - des;
        let x = p11 * x_off + es * y_off + (self.a * c1 + self.bb * s1 + self.cc);
        let v = p21 * x_off + p22 * y_off + self.w * (self.bb * c1 - self.a * s1);
        let acc0 = self.a0 * c0 - self.c * x0 - self.two_dv_b;
        let acc1 = self.a0 * c1 - 2.0 * self.d * v - self.c * x - self.b;
        let vf = self.v_from;
        MappingEval {
            residual: Vector2::new(x - x1, v - self.v_to),
            d_prev: Matrix2::new(
                p11,
                -(p11 * vf + es * acc0) * self.inv_w,
                p21,
                -(p21 * vf + p22 * acc0) * self.inv_w,
            ),
            d_next: Matrix2::new(-1.0, v * self.inv_w, 0.0, acc1 * self.inv_w),
        }
    }

    /// The same closed form, residual only, generic over the number type
    /// (`f64`, `Dual64`, `DualSVec64<4>`): forward-mode AD differentiates it.
    #[inline(always)]
    fn residual_generic<D: DualNum<f64> + Copy>(&self, x0: D, phi0: D, x1: D, phi1: D) -> [D; 2] {
        let (s0, c0) = phi0.sin_cos();
        let (s1, c1) = phi1.sin_cos();
        let x_off = x0 - (c0 * self.a + s0 * self.bb + self.cc);
        let y_off = -((c0 * self.bb - s0 * self.a) * self.w) + self.v_from;
        let tau = (phi1 - phi0) * self.inv_w;
        let e = (tau * -self.d).exp();
        let (sn, cs) = (tau * self.omega).sin_cos();
        let ec = e * cs;
        let es = e * sn * self.inv_omega;
        let x = ec * x_off + es * (y_off + x_off * self.d) + (c1 * self.a + s1 * self.bb + self.cc);
        let v = ec * y_off - es * (x_off * self.c + y_off * self.d)
            + (c1 * self.bb - s1 * self.a) * self.w;
        [x - x1, v - self.v_to]
    }
}

/// Hand-written: parameters to coefficients and the point, every call.
#[inline(never)]
fn hand_written(p: &paper::Params, x0: f64, phi0: f64, x1: f64, phi1: f64) -> MappingEval {
    Omega3::new(p).eval(x0, phi0, x1, phi1)
}

/// Hand-written with the parameter-only part precomputed.
#[inline(never)]
fn hand_written_precomputed(k: &Omega3, x0: f64, phi0: f64, x1: f64, phi1: f64) -> MappingEval {
    k.eval(x0, phi0, x1, phi1)
}

/// Four passes of `Dual64`, one per input.
#[inline(never)]
fn dual_x4(p: &paper::Params, x0: f64, phi0: f64, x1: f64, phi1: f64) -> MappingEval {
    let k = Omega3::new(p);
    let vars = [x0, phi0, x1, phi1];
    let mut cols = [[0.0; 2]; 4];
    let mut res = [0.0; 2];
    for (i, col) in cols.iter_mut().enumerate() {
        let s = |j: usize| {
            if i == j {
                Dual64::from_re(vars[j]).derivative()
            } else {
                Dual64::from_re(vars[j])
            }
        };
        let [f1, f2] = k.residual_generic(s(0), s(1), s(2), s(3));
        res = [f1.re, f2.re];
        *col = [f1.eps, f2.eps];
    }
    MappingEval {
        residual: Vector2::new(res[0], res[1]),
        d_prev: Matrix2::new(cols[0][0], cols[1][0], cols[0][1], cols[1][1]),
        d_next: Matrix2::new(cols[2][0], cols[3][0], cols[2][1], cols[3][1]),
    }
}

/// One pass of `DualSVec64<4>` (all four directions at once).
#[inline(never)]
fn dual_vec4(p: &paper::Params, x0: f64, phi0: f64, x1: f64, phi1: f64) -> MappingEval {
    let k = Omega3::new(p);
    let s = |v: f64, i: usize| {
        DualSVec64::<4>::new(v, Derivative::derivative_generic(Const::<4>, U1, i))
    };
    let [f1, f2] = k.residual_generic(s(x0, 0), s(phi0, 1), s(x1, 2), s(phi1, 3));
    let g1 = f1.eps.unwrap_generic(Const::<4>, U1);
    let g2 = f2.eps.unwrap_generic(Const::<4>, U1);
    MappingEval {
        residual: Vector2::new(f1.re, f2.re),
        d_prev: Matrix2::new(g1[0], g1[1], g2[0], g2[1]),
        d_next: Matrix2::new(g1[2], g1[3], g2[2], g2[3]),
    }
}

/// Central differences of the generated residual: 8 perturbed evaluations + 1,
/// step `1e-6 max(1, |u|)` per input `u`.
#[inline(never)]
fn finite_diff(p: &paper::Params, x0: f64, phi0: f64, x1: f64, phi1: f64) -> MappingEval {
    let u = [x0, phi0, x1, phi1];
    let r = |u: [f64; 4]| paper::residual_3_31(p, u[0], Phase::new(u[1]), u[2], Phase::new(u[3]));
    let residual = r(u);
    let mut cols = [Vector2::zeros(); 4];
    for (i, col) in cols.iter_mut().enumerate() {
        let h = 1e-6 * u[i].abs().max(1.0);
        let (mut up, mut dn) = (u, u);
        up[i] += h;
        dn[i] -= h;
        *col = (r(up) - r(dn)) / (up[i] - dn[i]);
    }
    MappingEval {
        residual,
        d_prev: Matrix2::from_columns(&[cols[0], cols[1]]),
        d_next: Matrix2::from_columns(&[cols[2], cols[3]]),
    }
}

// ---------------------------------------------------------------------------
// Agreement checks (outside timing).
// ---------------------------------------------------------------------------

fn entries(e: &MappingEval) -> [f64; 10] {
    let (r, a, b) = (e.residual, e.d_prev, e.d_next);
    [
        r[0],
        r[1],
        a[(0, 0)],
        a[(0, 1)],
        a[(1, 0)],
        a[(1, 1)],
        b[(0, 0)],
        b[(0, 1)],
        b[(1, 0)],
        b[(1, 1)],
    ]
}

/// Largest `|a - b| / max(|a|, |b|, 1)` over the ten entries. The floor 1 is
/// the size of the terms that cancel in a residual at an orbit point (~1e-15).
fn max_rel_diff(a: &MappingEval, b: &MappingEval) -> f64 {
    entries(a)
        .iter()
        .zip(entries(b))
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1.0))
        .fold(0.0, f64::max)
}

fn check_agreement() {
    let p = params();
    let scene = sweep_w::Params { W: p.W };
    let idx = Paper::INFO
        .mapping_index("3_31", None)
        .expect("paper has 3_31");
    for (label, [x0, phi0, x1, phi1]) in [("orbit", [X0, PHI0, X1, PHI1]), ("off-orbit", OFF)] {
        let gen = paper::mapping_3_31(&p, x0, Phase::new(phi0), x1, Phase::new(phi1));
        let k = Omega3::new(&p);
        let generic = k.residual_generic(x0, phi0, x1, phi1);
        let mut generic_eval = gen;
        generic_eval.residual = Vector2::new(generic[0], generic[1]);
        let cases: [(&str, MappingEval, f64); 7] = [
            (
                "generated (trait)",
                Paper::mapping(&p, idx, x0, phi0, x1, phi1),
                0.0,
            ),
            ("hand_written", hand_written(&p, x0, phi0, x1, phi1), 1e-10),
            ("hand_written (generic f64 residual)", generic_eval, 1e-10),
            ("dual_x4", dual_x4(&p, x0, phi0, x1, phi1), 1e-10),
            ("dual_vec4", dual_vec4(&p, x0, phi0, x1, phi1), 1e-10),
            ("finite_diff", finite_diff(&p, x0, phi0, x1, phi1), 1e-6),
            (
                "scene_specialized",
                sweep_w::mapping_3_31(&scene, x0, Phase::new(phi0), x1, Phase::new(phi1)),
                1e-12,
            ),
        ];
        eprintln!(
            "[{label}] generated residual = ({:.3e}, {:.3e})",
            gen.residual[0], gen.residual[1]
        );
        for (name, eval, tol) in cases {
            let diff = max_rel_diff(&gen, &eval);
            eprintln!(
                "[{label}] {name:<36} max rel. diff vs generated = {diff:.2e} (tol {tol:.0e})"
            );
            assert!(
                diff <= tol,
                "{label}: {name} disagrees with the generated mapping: {diff:e}\n{eval:?}\nvs\n{gen:?}"
            );
        }
        let r_full = paper::residual_3_31(&p, x0, Phase::new(phi0), x1, Phase::new(phi1));
        let r_scene = sweep_w::residual_3_31(&scene, x0, Phase::new(phi0), x1, Phase::new(phi1));
        assert!((r_full - gen.residual).amax() <= 1e-14);
        assert!((r_scene - gen.residual).amax() <= 1e-12);
    }
}

// ---------------------------------------------------------------------------
// Benchmarks.
// ---------------------------------------------------------------------------

/// Benchmark `f(params, X0, PHI0, X1, PHI1)` as `name` in the group `g`.
fn at_point<P, R>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    params: &P,
    f: impl Fn(&P, f64, f64, f64, f64) -> R,
) {
    g.bench_function(name, |b| {
        b.iter(|| {
            f(
                black_box(params),
                black_box(X0),
                black_box(PHI0),
                black_box(X1),
                black_box(PHI1),
            )
        })
    });
}

fn bench_jacobian(c: &mut Criterion) {
    check_agreement();
    let p = params();
    let scene = sweep_w::Params { W: p.W };
    let idx = Paper::INFO
        .mapping_index("3_31", None)
        .expect("paper has 3_31");
    let pre = Omega3::new(&p);

    let mut g = c.benchmark_group("jacobian");
    g.bench_function("generated", |b| {
        b.iter(|| {
            Paper::mapping(
                black_box(&p),
                black_box(idx),
                black_box(X0),
                black_box(PHI0),
                black_box(X1),
                black_box(PHI1),
            )
        })
    });
    at_point(&mut g, "generated_direct", &p, |p, x0, phi0, x1, phi1| {
        paper::mapping_3_31(p, x0, Phase::new(phi0), x1, Phase::new(phi1))
    });
    at_point(&mut g, "hand_written", &p, hand_written);
    at_point(
        &mut g,
        "hand_written_precomputed",
        &pre,
        hand_written_precomputed,
    );
    at_point(&mut g, "dual_x4", &p, dual_x4);
    at_point(&mut g, "dual_vec4", &p, dual_vec4);
    at_point(&mut g, "finite_diff", &p, finite_diff);
    at_point(
        &mut g,
        "scene_specialized",
        &scene,
        |p, x0, phi0, x1, phi1| {
            sweep_w::mapping_3_31(p, x0, Phase::new(phi0), x1, Phase::new(phi1))
        },
    );
    g.finish();
}

fn bench_residual(c: &mut Criterion) {
    let p = params();
    let scene = sweep_w::Params { W: p.W };
    let mut g = c.benchmark_group("residual");
    at_point(&mut g, "generated", &p, |p, x0, phi0, x1, phi1| {
        paper::residual_3_31(p, x0, Phase::new(phi0), x1, Phase::new(phi1))
    });
    at_point(
        &mut g,
        "scene_specialized",
        &scene,
        |p, x0, phi0, x1, phi1| {
            sweep_w::residual_3_31(p, x0, Phase::new(phi0), x1, Phase::new(phi1))
        },
    );
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(50);
    targets = bench_jacobian, bench_residual
}
criterion_main!(benches);
