//! No located answer hangs on the last bit. The cases of the sweep, curves
//! and map tests are run with every parameter of the model moved by ±4
//! ulps, and with the forced response rounded both ways (`x / den` and
//! `x · (1 / den)`, [`ForcedRounding`]); the structures, kinds and counts
//! of the located transitions, bifurcations, curves and codimension-two
//! points must not change, positions must agree within each test's
//! tolerance, and every map point must list the same motions.
//!
//! One test function: the rounding is process-wide, so the runs go one
//! after the other.

use stickslip::model::{set_forced_rounding, ForcedRounding, ParamSet};
use stickslip::models::coulomb::Coulomb;
use stickslip::models::paper::Paper;
use stickslip::study::curves::{curves_with, CurveSet, CurvesOptions, CurvesSettings};
use stickslip::study::map::{classify_tile, GridAxis};
use stickslip::study::sweep::{sweep, Sweep, SweepOptions};

/// `p` with every free parameter moved by `ulps` units in the last place
/// (away from zero for positive `ulps`); zeros stay zero.
fn nudged<P: ParamSet>(p: &P, ulps: i64) -> P {
    let mut q = *p;
    for i in 0..p.names().len() {
        let v = p.get(i);
        if v != 0.0 && v.is_finite() {
            let bits = v.to_bits() as i64 + ulps;
            q.set(i, f64::from_bits(bits as u64));
        }
    }
    q
}

fn set<P: ParamSet + Default>(pairs: &[(&str, f64)]) -> P {
    let mut p = P::default();
    for &(name, value) in pairs {
        p.set(p.index_of(name).expect("a parameter"), value);
    }
    p
}

/// The variants of a case: both roundings, each at 0 and ±4 ulps.
const VARIANTS: [(ForcedRounding, i64); 6] = [
    (ForcedRounding::Quotient, 0),
    (ForcedRounding::Quotient, 4),
    (ForcedRounding::Quotient, -4),
    (ForcedRounding::Reciprocal, 0),
    (ForcedRounding::Reciprocal, 4),
    (ForcedRounding::Reciprocal, -4),
];

/// Every variant of `run` at `base`, each compared with the first by `same`.
fn each_variant<P: ParamSet, T>(
    what: &str,
    base: &P,
    run: impl Fn(&P) -> T,
    same: impl Fn(&T, &T) -> Result<(), String>,
    failures: &mut Vec<String>,
) {
    set_forced_rounding(ForcedRounding::Quotient);
    let reference = run(base);
    for (rounding, ulps) in &VARIANTS[1..] {
        set_forced_rounding(*rounding);
        let other = run(&nudged(base, *ulps));
        if let Err(why) = same(&reference, &other) {
            failures.push(format!(
                "{what}, {rounding:?} rounding, {ulps:+} ulps: {why}"
            ));
        }
    }
    set_forced_rounding(ForcedRounding::Quotient);
}

/// The sweep tests' tolerance on a located transition (`tests/sweep.rs`):
/// a stick's vanishing, where the motion's own system turns singular, is
/// located only to about 1e-8 (it moves by 5e-9 here).
const SWEEP_TOLERANCE: f64 = 1e-8;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(1.0)
}

/// Transitions and bifurcations: the same kinds, structures and counts, at
/// the same values to `tol`.
fn same_sweep(a: &Sweep, b: &Sweep, tol: f64) -> Result<(), String> {
    let key = |s: &Sweep| -> Vec<String> {
        let mut k: Vec<String> = s
            .transitions
            .iter()
            .map(|t| format!("{} {} -> {} {:?}", t.kind.name(), t.from, t.to, t.boundary))
            .chain(
                s.bifurcations
                    .iter()
                    .map(|f| format!("{} {} {}", f.kind.name(), f.structure, f.n)),
            )
            .collect();
        k.sort();
        k
    };
    if key(a) != key(b) {
        let (ka, kb) = (key(a), key(b));
        let count = |k: &Vec<String>, x: &String| k.iter().filter(|y| *y == x).count();
        let differ: Vec<String> = ka
            .iter()
            .chain(&kb)
            .filter(|x| count(&ka, x) != count(&kb, x))
            .map(|x| format!("{x} ({} before, {} after)", count(&ka, x), count(&kb, x)))
            .collect();
        return Err(format!("transitions differ: {differ:?}"));
    }
    let values = |s: &Sweep| -> Vec<f64> {
        let mut v: Vec<f64> = s
            .transitions
            .iter()
            .map(|t| t.value)
            .chain(s.bifurcations.iter().map(|f| f.value))
            .collect();
        v.sort_by(f64::total_cmp);
        v
    };
    for (x, y) in values(a).iter().zip(values(b)) {
        if !close(*x, y, tol) {
            return Err(format!("a transition moved from {x} to {y}"));
        }
    }
    let motions = |s: &Sweep| -> Vec<Vec<String>> {
        s.points
            .iter()
            .map(|p| {
                let mut m: Vec<String> = p
                    .motions
                    .iter()
                    .map(|m| format!("{} {} {}", m.structure, m.n, m.stable))
                    .collect();
                m.sort();
                m
            })
            .collect()
    };
    if motions(a) != motions(b) {
        return Err("the motions at the grid values differ".into());
    }
    Ok(())
}

/// Curves: the same conditions, structures and end reasons; codim-2 points
/// the same kinds at the same places to `tol`.
fn same_curves(a: &CurveSet, b: &CurveSet, tol: f64) -> Result<(), String> {
    let key = |s: &CurveSet| -> Vec<String> {
        let mut k: Vec<String> = s
            .curves
            .iter()
            .map(|c| {
                let end = |e: &Option<stickslip::study::curves::EndSummary>| {
                    e.as_ref()
                        .map_or("closed".to_string(), |e| e.reason.clone())
                };
                let mut ends = [end(&c.from), end(&c.to)];
                ends.sort();
                format!(
                    "{} {:?} {} {:?}",
                    c.kind.name(),
                    c.boundary,
                    c.structure,
                    ends
                )
            })
            .collect();
        k.sort();
        k
    };
    if key(a) != key(b) {
        let (ka, kb) = (key(a), key(b));
        let only_a: Vec<&String> = ka.iter().filter(|k| !kb.contains(k)).collect();
        let only_b: Vec<&String> = kb.iter().filter(|k| !ka.contains(k)).collect();
        return Err(format!(
            "curves differ: only before {only_a:?}, only after {only_b:?}"
        ));
    }
    if a.codim2.len() != b.codim2.len() {
        return Err(format!(
            "{} codim-2 points against {}",
            a.codim2.len(),
            b.codim2.len()
        ));
    }
    for p in &a.codim2 {
        let found = b
            .codim2
            .iter()
            .any(|q| q.kinds == p.kinds && close(p.x, q.x, tol) && close(p.y, q.y, tol));
        if !found {
            return Err(format!("the codim-2 point {p:?} moved or changed"));
        }
    }
    if a.failed_starts.len() != b.failed_starts.len() {
        return Err("failed starts differ".into());
    }
    Ok(())
}

#[test]
fn located_answers_do_not_hang_on_the_last_bit() {
    let mut failures = Vec::new();

    // Sweeps: the paper model through the bistable window, and the
    // Coulomb oscillator's cascade (to period 8).
    let paper: <Paper as stickslip::FrictionOscillator>::Params = set(&[("Q0", 70.0)]);
    each_variant(
        "sweep paper W=3.4:4.4:21",
        &paper,
        |p| sweep::<Paper>(*p, "W", 3.4, 4.4, 21, SweepOptions::default()).expect("sweeps"),
        |a, b| same_sweep(a, b, SWEEP_TOLERANCE),
        &mut failures,
    );
    let coulomb: <Coulomb as stickslip::FrictionOscillator>::Params = set(&[
        ("V", 0.0),
        ("d", 0.02),
        ("mus", 0.3),
        ("muk", 0.1),
        ("Q0", 2.0),
    ]);
    let cascade = SweepOptions {
        max_period: Some(8),
        ..SweepOptions::default()
    };
    each_variant(
        "sweep coulomb cascade",
        &coulomb,
        |p| sweep::<Coulomb>(*p, "W", 0.1071105, 0.1151105, 9, cascade).expect("sweeps"),
        |a, b| same_sweep(a, b, SWEEP_TOLERANCE),
        &mut failures,
    );

    // Curves: the paper model's box around the window.
    let box_opts = CurvesOptions {
        x: ("W".into(), [3.6, 4.2]),
        y: ("Q0".into(), [60.0, 80.0]),
        seeds: Vec::new(),
        at: Vec::new(),
    };
    let settings = CurvesSettings {
        count: 24,
        spread: 1,
        ..CurvesSettings::default()
    };
    each_variant(
        "curves paper W=3.6:4.2 x Q0=60:80",
        &paper,
        |p| curves_with::<Paper>(p, &box_opts, &settings).expect("traces"),
        |a, b| same_curves(a, b, 1e-7),
        &mut failures,
    );

    // A map tile by continuation.
    let x = GridAxis::parse("W=3.6:4.2:16").unwrap();
    let y = GridAxis::parse("Q0=60:80:16").unwrap();
    each_variant(
        "map paper W=3.6:4.2 x Q0=60:80",
        &paper,
        |p| {
            classify_tile::<Paper>(p, &x, &y, 0)
                .into_iter()
                .map(|r| (r.index, r.motions, r.status))
                .collect::<Vec<_>>()
        },
        |a, b| {
            if a == b {
                Ok(())
            } else {
                let diff: Vec<_> = a.iter().zip(b).filter(|(u, v)| u != v).take(3).collect();
                Err(format!("map points differ: {diff:?}"))
            }
        },
        &mut failures,
    );

    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
