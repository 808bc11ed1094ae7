//! Basins of attraction (issue 13): in the window W ∈ (3.947843, 3.948674)
//! at Q0 = 70, where the sweep finds three stable motions, each has a basin
//! of positive measure, and each is confirmed by the independent DOPRI
//! reference simulation from a start inside its basin; the fractions sum to
//! one; the basin file is the same byte for byte on one and two threads and
//! after interrupted and resumed runs (including a line cut short); the
//! basin-stability interval contains the grid fraction's estimate.

mod common;

use std::fs;
use std::path::{Path, PathBuf};

use common::events::PiecewiseOde;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::param::ParamSet;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::known::stroboscopic_states;
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::output::figure::basins::plot_basins;
use stickslip::study::basins::{
    run_basins, BasinFile, BasinOptions, BasinSettings, Basins, BasinsError,
};
use stickslip::study::map::GridAxis;
use stickslip::study::sweep::{sweep, SweepOptions};

const TAU: f64 = 2.0 * std::f64::consts::PI;
/// Inside the part of the window where the period-2 motion lives (3.948103 to 3.948410).
const W: f64 = 3.94826;
const X: &str = "x=0.98:1.02:24";
const V: &str = "v=1.30:1.40:24";

fn params() -> Params {
    let mut p = Params::default();
    p.set(Params::index_of("W").unwrap(), W);
    p.set(Params::index_of("Q0").unwrap(), 70.0);
    p
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("basins-{name}"));
    let _ = fs::remove_dir_all(&d);
    fs::create_dir_all(&d).unwrap();
    d
}

fn settings(samples: usize) -> BasinSettings {
    BasinSettings {
        samples,
        lyapunov: 0,
        ..BasinSettings::default()
    }
}

fn run(out: &Path, samples: usize, opts: BasinOptions) -> Result<Basins, BasinsError> {
    let x = GridAxis::parse(X).unwrap();
    let v = GridAxis::parse(V).unwrap();
    run_basins::<Paper>(&params(), &x, &v, &settings(samples), Some(out), &opts)
}

/// The stable motions the sweep lists at `W`, each with its states at `W t ≡ 0`.
fn sweep_motions() -> Vec<(String, Vec<(f64, f64)>)> {
    // Over the window (its global search and the branches' continuation
    // find all three), with W on the grid.
    let sw = sweep::<Paper>(
        params(),
        "W",
        W - 4e-4,
        W + 4e-4,
        9,
        SweepOptions::default(),
    )
    .unwrap();
    let at = &sw.points[4];
    assert!((at.value - W).abs() < 1e-12, "{}", at.value);
    let sim = Simulator::<Paper>::new(params(), SimOptions::default()).unwrap();
    at.motions
        .iter()
        .filter(|m| m.stable)
        .map(|m| {
            let structure = Structure::parse(Paper::INFO, &m.structure, m.n).unwrap();
            // The sweep gives phases mod 2π: make them increase again.
            let mut pts: Vec<SwitchingPoint> = Vec::new();
            for p in &m.points {
                let mut phase = p.phase;
                while pts.last().is_some_and(|q| phase <= q.phase) {
                    phase += TAU;
                }
                pts.push(SwitchingPoint { phase, x: p.x });
            }
            let motion = solve(&sim, structure, pts, NewtonOptions::default());
            assert!(motion.termination.converged(), "{}", m.structure);
            let states = stroboscopic_states(&sim, &motion, 0.0);
            let name = if m.n > 1 {
                format!("{}^{}", m.structure, m.n)
            } else {
                m.structure.clone()
            };
            (name, states.iter().map(|s| (s.x, s.v)).collect())
        })
        .collect()
}

/// The state at `t = periods · 2π / W` from `(x, v)` at `t = 0`, by the
/// independent DOPRI reference with events and stick.
fn reference_end(x: f64, v: f64, periods: u32) -> (f64, f64) {
    let ode = PiecewiseOde::of::<Paper>(&params());
    let domain = Some(ode.domain_of(v));
    let t_end = TAU * f64::from(periods) / W;
    let (_, [xe, ve], _) = ode.integrate_to(0.0, x, v, domain, t_end, 1e-11);
    (xe, ve)
}

#[test]
fn the_three_stable_motions_of_the_window_each_have_a_basin() {
    let d = dir("window");
    let out = d.join("window.csv");
    let b = run(&out, 200, BasinOptions::default()).unwrap();
    assert!(b.complete);
    let file = BasinFile::read(&out).unwrap();
    let nx = file.header.x.count;
    let grid = file.header.grid_len();

    // Fractions sum to 1 on the grid and over the samples; counts add up.
    let sum: f64 = b.attractors.iter().map(|a| a.fraction).sum();
    assert!((sum - 1.0).abs() < 1e-12, "{sum}");
    let stab: f64 = b.attractors.iter().map(|a| a.stability).sum();
    assert!((stab - 1.0).abs() < 1e-12, "{stab}");
    assert_eq!(b.attractors.iter().map(|a| a.points).sum::<usize>(), grid);
    assert_eq!(b.attractors.iter().map(|a| a.samples).sum::<usize>(), 200);

    // Exactly the sweep's three stable motions, each with a basin.
    let motions = sweep_motions();
    assert_eq!(motions.len(), 3, "{motions:?}");
    let mut found: Vec<&str> = b.attractors.iter().map(|a| a.name.as_str()).collect();
    let mut expected: Vec<&str> = motions.iter().map(|(n, _)| n.as_str()).collect();
    found.sort_unstable();
    expected.sort_unstable();
    assert_eq!(found, expected);
    for a in &b.attractors {
        assert!(a.points > 0 && a.fraction > 0.01, "{a:?}");
        assert!(a.interval[0] <= a.stability && a.stability <= a.interval[1]);
    }

    // Each attractor from a start inside its basin (its four neighbours in
    // the same basin), simulated by the independent reference: the end state
    // is on that motion, nearer to it than to the others.
    let label = |i: usize| file.starts[i].attractor.as_str();
    for (name, states) in &motions {
        let inner = (0..grid)
            .find(|&i| {
                let (ix, iv) = (i % nx, i / nx);
                ix > 0
                    && iv > 0
                    && ix + 1 < nx
                    && i + nx < grid
                    && [i, i - 1, i + 1, i - nx, i + nx]
                        .iter()
                        .all(|&j| label(j) == name)
            })
            .unwrap_or_else(|| panic!("no inner start of {name}"));
        let s = &file.starts[inner];
        let (xe, ve) = reference_end(s.x, s.v, 400);
        let dist = |states: &[(f64, f64)]| {
            states
                .iter()
                .map(|&(x, v)| (x - xe).abs().max((v - ve).abs() / W))
                .fold(f64::INFINITY, f64::min)
        };
        let own = dist(states);
        assert!(own < 1e-6, "{name} from ({}, {}): {own:e} away", s.x, s.v);
        for (other, st) in &motions {
            if other != name {
                assert!(dist(st) > 100.0 * own, "{name} vs {other}");
            }
        }
    }
    plot_basins(&out, &d.join("window.svg")).unwrap();
    assert!(fs::metadata(d.join("window.svg")).unwrap().len() > 1000);
}

#[test]
fn the_file_is_the_same_on_one_and_two_threads_and_after_resumes() {
    let d = dir("threads");
    let on = |threads: usize, out: &Path| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run(out, 60, BasinOptions::default()).unwrap())
    };
    let one = d.join("one.csv");
    let two = d.join("two.csv");
    on(1, &one);
    on(2, &two);
    let reference = fs::read(&one).unwrap();
    assert_eq!(reference, fs::read(&two).unwrap());

    // Interrupted twice (by a point limit), resumed to the end.
    let cut = d.join("cut.csv");
    let first = run(
        &cut,
        60,
        BasinOptions {
            max_points: Some(150),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(!first.complete);
    assert_eq!(first.computed, 150);
    assert!(matches!(
        run(&cut, 60, BasinOptions::default()),
        Err(BasinsError::OutputExists(_))
    ));
    let resume = BasinOptions {
        resume: true,
        ..Default::default()
    };
    let second = run(
        &cut,
        60,
        BasinOptions {
            max_points: Some(200),
            ..resume
        },
    )
    .unwrap();
    assert_eq!((second.already_done, second.computed), (150, 200));
    // A kill in the middle of a line: a partial last line.
    let mut bytes = fs::read(&cut).unwrap();
    bytes.extend_from_slice(b"9999,0.98");
    fs::write(&cut, &bytes).unwrap();
    let last = run(&cut, 60, resume).unwrap();
    assert!(last.complete);
    assert_eq!(last.already_done, 350);
    assert_eq!(fs::read(&cut).unwrap(), reference);

    // A resume of another run is refused, naming the difference.
    let other = BasinSettings {
        seed: 2,
        ..settings(60)
    };
    let x = GridAxis::parse(X).unwrap();
    let v = GridAxis::parse(V).unwrap();
    let e = run_basins::<Paper>(&params(), &x, &v, &other, Some(&cut), &resume).unwrap_err();
    assert!(matches!(e, BasinsError::Mismatch { .. }), "{e}");
    assert!(e.to_string().contains("seed=2"), "{e}");
}
