//! A period-doubling cascade of the Coulomb oscillator on a fixed surface
//! (`V = 0, d = 0.02, mus = 0.3, muk = 0.1, Q0 = 2`, W from 0.1071105 to
//! 0.1151105): the sweep follows branches born by doubling up to
//! `max_period` (16 by default) and reports the ones it does not follow as
//! cut; the doublings it located form a cascade with an accumulation point
//! beyond the last one; repeated structures are written compactly and read
//! back by `orbit`, which solves them to the sweep's motion.

use stickslip::model::param::ParamSet;
use stickslip::models::coulomb::{Coulomb, Params};
use stickslip::orbit::attractor::{find, Attractor, AttractorOptions};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::{sweep, SweepOptions, TransitionKind, MAX_PERIOD};

const TAU: f64 = 2.0 * std::f64::consts::PI;

fn params() -> Params {
    let mut p = Params::default();
    for (name, value) in [
        ("V", 0.0),
        ("d", 0.02),
        ("mus", 0.3),
        ("muk", 0.1),
        ("Q0", 2.0),
    ] {
        p.set(Params::index_of(name).unwrap(), value);
    }
    p
}

fn with_w(w: f64) -> Params {
    let mut p = params();
    p.set(Params::index_of("W").unwrap(), w);
    p
}

#[test]
fn the_cascade_is_cut_at_the_longest_period_and_its_limit_estimated() {
    let opts = SweepOptions::default();
    assert_eq!(opts.max_period, Some(MAX_PERIOD));
    let sw = sweep::<Coulomb>(params(), "W", 0.1071105, 0.1151105, 9, opts).unwrap();
    // No branch longer than the limit is followed; the ones born past it
    // are listed as cut, at a located period doubling.
    assert!(
        sw.branches.iter().all(|b| b.n <= MAX_PERIOD),
        "{:?}",
        sw.branches.iter().map(|b| b.n).collect::<Vec<_>>()
    );
    assert!(!sw.cuts.is_empty());
    for c in &sw.cuts {
        assert_eq!(c.n, 2 * MAX_PERIOD);
        assert!(
            c.structure.starts_with('(') && c.structure.ends_with(&format!("^{{×{}}}", c.n)),
            "{}",
            c.structure
        );
        assert!(sw
            .bifurcations
            .iter()
            .any(|b| b.kind == TransitionKind::PeriodDoubling
                && b.value == c.value
                && b.n == MAX_PERIOD));
    }
    // The cascade: doublings of one block, each of twice the period, in one
    // direction, the last the one that is cut; its limit lies beyond it.
    let c = sw.cascades.first().expect("a cascade");
    assert!(c.doublings.len() >= 3, "{c:?}");
    for w in c.doublings.windows(2) {
        assert_eq!(w[1].n, 2 * w[0].n);
        assert!(w[1].value > w[0].value);
    }
    let last = c.doublings.last().unwrap();
    assert_eq!(last.n, MAX_PERIOD);
    let limit = c.accumulation_feigenbaum.unwrap();
    assert!(limit > last.value && limit < 0.1151105, "{limit}");
    assert_eq!(c.ratios.len(), c.doublings.len() - 2);
    // Text: one compact name per long motion, never 16 blocks written out.
    let text = stickslip::output::sweep_table::text(&sw, 0.1071105, 0.1151105, 9, "", true);
    assert!(text.contains("^{×16}"), "{text}");
    assert!(
        !text.contains(&"1_11 0_11 1_11 0_11 2_11 ".repeat(4)),
        "{text}"
    );
    assert!(text.contains("accumulation W"), "{text}");
}

/// The compact name of a period-16 motion the sweep lists parses back,
/// and Newton on it from the sweep's switching points converges to an
/// admissible motion that a simulation from one of its points settles on.
#[test]
fn a_compact_structure_parses_back_and_solves() {
    let sw = sweep::<Coulomb>(
        params(),
        "W",
        0.1071105,
        0.1151105,
        9,
        SweepOptions::default(),
    )
    .unwrap();
    let b = sw
        .branches
        .iter()
        .find(|b| b.n == 8 && b.points.iter().any(|q| q.stable))
        .expect("a stable period-8 branch");
    let q = b.points.iter().find(|q| q.stable).unwrap();
    let n = stickslip_codegen::structure::implied_periods(&b.structure);
    let structure = Structure::parse(Coulomb::INFO, &b.structure, n).unwrap();
    assert_eq!(structure.periods(), 8);
    assert_eq!(structure.len(), 8 * 5);
    assert_eq!(structure.notation(Coulomb::INFO), b.structure);
    let sim = stickslip::dynamics::simulate::Simulator::<Coulomb>::new(
        with_w(q.value),
        Default::default(),
    )
    .unwrap();
    let mut pts: Vec<SwitchingPoint> = Vec::new();
    for p in &q.points {
        let mut phase = p.phase;
        while pts.last().is_some_and(|l| phase <= l.phase) {
            phase += TAU;
        }
        pts.push(SwitchingPoint { phase, x: p.x });
    }
    let m = solve(&sim, structure, pts, NewtonOptions::default());
    assert!(m.is_admissible(), "{:?}", m.termination);
    let start = sim.start(m.points[0].x, 0.0, m.points[0].phase).unwrap();
    let Ok(Attractor::Periodic(found)) = find(&sim, start, AttractorOptions::default()) else {
        panic!("no motion");
    };
    assert_eq!(found.structure.notation(Coulomb::INFO), b.structure);
    // The command line reads it back too, its period implied by the block.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "orbit",
            "--model",
            "coulomb",
            "--structure",
            &b.structure,
            "--set",
            &format!("V=0,d=0.02,mus=0.3,muk=0.1,Q0=2,W={}", q.value),
            "--guess",
            &format!("{},{}", m.points[0].phase, m.points[0].x),
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("period N = 8"), "{text}");
    assert!(text.contains("admissible: yes"), "{text}");
}
