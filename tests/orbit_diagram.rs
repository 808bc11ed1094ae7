//! The orbit diagram (issue 13) against the exact analysis: where `sweep`
//! reports a single stable period-1 motion every sample is that motion's
//! stroboscopic point (computed in closed form from its switching points)
//! to 1e-6; in a window with a single stable period-2 motion the samples
//! form two clusters, its two points; in the bistable window
//! W ∈ (3.613467, 3.621905) at Q0 = 70, where the period-1 motion
//! P_{3_33 4_33} and a period-2 motion coexist, the sweep up stays on the
//! first and the sweep down on the second (hysteresis); the branches drawn
//! over the diagram pass through the samples; two runs give the same
//! diagram; the figure is drawn.

use std::fs;
use std::path::Path;

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::param::ParamSet;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::known::stroboscopic_states;
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::output::figure::diagram::plot_diagram;
use stickslip::study::diagram::{branch_sections, orbit_diagram, Column, DiagramOptions};
use stickslip::study::sweep::{sweep, SweepOptions, SweepPoint};

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn params(w: f64) -> Params {
    let mut p = Params::default();
    p.set(Params::index_of("W").unwrap(), w);
    p.set(Params::index_of("Q0").unwrap(), 70.0);
    p
}

/// The stable motions `sweep` lists at `point`, each with its states at `W t ≡ 0`.
fn exact(point: &SweepPoint) -> Vec<(String, Vec<(f64, f64)>)> {
    let sim = Simulator::<Paper>::new(params(point.value), SimOptions::default()).unwrap();
    point
        .motions
        .iter()
        .filter(|m| m.stable)
        .map(|m| {
            let info = Paper::INFO;
            let structure = Structure::parse(info, &m.structure, m.n).unwrap();
            let mut pts: Vec<SwitchingPoint> = Vec::new();
            for p in &m.points {
                let mut phase = p.phase;
                while pts.last().is_some_and(|q| phase <= q.phase) {
                    phase += TAU;
                }
                pts.push(SwitchingPoint { phase, x: p.x });
            }
            let motion = solve(&sim, structure, pts, NewtonOptions::default());
            assert!(motion.termination.converged());
            let states = stroboscopic_states(&sim, &motion, 0.0);
            (
                format!("{}^{}", m.structure, m.n),
                states.iter().map(|s| (s.x, s.v)).collect(),
            )
        })
        .collect()
}

/// Every sample of `c` is within `tol` of one of `states`, and every state has a sample.
fn samples_are(c: &Column, states: &[(f64, f64)], tol: f64) {
    assert!(c.error.is_none(), "{:?}", c.error);
    let mut hit = vec![false; states.len()];
    for (&x, &v) in c.x.iter().zip(&c.v) {
        let (k, d) = states
            .iter()
            .map(|&(sx, sv)| (x - sx).abs().max((v - sv).abs()))
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!(
            d < tol,
            "W = {}: sample ({x}, {v}) is {d:e} from {states:?}",
            c.value
        );
        hit[k] = true;
    }
    assert!(hit.iter().all(|&h| h), "W = {}: {hit:?}", c.value);
}

fn at(cols: &[Column], w: f64) -> &Column {
    cols.iter()
        .find(|c| (c.value - w).abs() < 1e-9)
        .unwrap_or_else(|| panic!("no column at {w}"))
}

#[test]
fn the_diagram_shows_the_exact_motions_and_the_hysteresis() {
    let (from, to, count) = (3.60, 3.63, 61);
    let opts = DiagramOptions {
        transient: 400,
        periods: 12,
        lyapunov: 200,
        ..DiagramOptions::default()
    };
    let mut d = orbit_diagram::<Paper>(params(3.6), "W", from, to, count, opts).unwrap();
    assert_eq!((d.up.len(), d.down.len()), (count, count));
    assert!(d.up.windows(2).all(|w| w[0].value < w[1].value));
    assert!(d.down.windows(2).all(|w| w[0].value > w[1].value));
    let sw = sweep::<Paper>(params(3.6), "W", from, to, count, SweepOptions::default()).unwrap();
    let point = |w: f64| {
        sw.points
            .iter()
            .find(|p| (p.value - w).abs() < 1e-9)
            .unwrap()
    };

    // W = 3.6: a single stable period-1 motion; both directions sit on it.
    let single = exact(point(3.6));
    assert_eq!(single.len(), 1, "{single:?}");
    assert_eq!(single[0].1.len(), 1);
    samples_are(at(&d.up, 3.6), &single[0].1, 1e-6);
    samples_are(at(&d.down, 3.6), &single[0].1, 1e-6);
    // Its largest exponent is negative (a stable motion).
    assert!(at(&d.up, 3.6).exponent.is_some_and(|e| e < 0.0));

    // W = 3.623: a single stable period-2 motion: two clusters, its two points.
    let double = exact(point(3.623));
    assert_eq!(double.len(), 1, "{double:?}");
    assert_eq!(double[0].1.len(), 2);
    let gap = (double[0].1[0].0 - double[0].1[1].0).abs();
    assert!(gap > 1e-3, "the two points are apart: {gap}");
    samples_are(at(&d.up, 3.623), &double[0].1, 1e-6);
    samples_are(at(&d.down, 3.623), &double[0].1, 1e-6);

    // W = 3.617: bistable. Up from the period-1 side stays period-1, down from
    // the period-2 side stays period-2.
    let both = exact(point(3.617));
    assert_eq!(both.len(), 2, "{both:?}");
    let p1 = both.iter().find(|(_, s)| s.len() == 1).unwrap();
    let p2 = both.iter().find(|(_, s)| s.len() == 2).unwrap();
    samples_are(at(&d.up, 3.617), &p1.1, 1e-6);
    samples_are(at(&d.down, 3.617), &p2.1, 1e-6);

    // The branch at the section passes through the exact point.
    d.branches = branch_sections::<Paper>(params(3.6), &sw);
    let p1_branch = d
        .branches
        .iter()
        .find(|b| b.n == 1 && b.points.iter().any(|p| (p.value - 3.6).abs() < 1e-12))
        .unwrap();
    let q = p1_branch
        .points
        .iter()
        .find(|p| (p.value - 3.6).abs() < 1e-12)
        .unwrap();
    assert!((q.x[0] - single[0].1[0].0).abs() < 1e-8 && (q.v[0] - single[0].1[0].1).abs() < 1e-8);

    // Deterministic.
    let again = orbit_diagram::<Paper>(params(3.6), "W", from, to, count, opts).unwrap();
    assert_eq!(again.up, d.up);
    assert_eq!(again.down, d.down);

    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("orbit_diagram.svg");
    plot_diagram(&d, "paper: orbit diagram over W, Q0 = 70", &out).unwrap();
    assert!(fs::metadata(&out).unwrap().len() > 1000);
}
