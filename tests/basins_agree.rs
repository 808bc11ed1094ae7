//! Every `basins` verdict is the verdict of `simulate --from` at that start
//! (`orbit::attractor::find`, which names the motion by its own repeating
//! cycle and never stops early), on grids at points where stable motions
//! coexist: the paper model's window W ∈ (3.947843, 3.948674) at Q0 = 70
//! with its three stable motions, the point W = 3.6176858236 where a
//! period-1 and a period-2 motion have stroboscopic states 2e-3 apart, and
//! the Coulomb oscillator on a fixed surface with a mirror-image pair of
//! one structure (W = 0.37) and two mirror pairs (W = 0.39).

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::param::ParamSet;
use stickslip::models::coulomb::{self, Coulomb};
use stickslip::models::paper::{self, Paper};
use stickslip::orbit::attractor::{find, Attractor, AttractorOptions};
use stickslip::orbit::motion::OrbitError;
use stickslip::study::basins::{
    attractor_label, classify, discover, BasinHeader, Known, UNSETTLED,
};
use stickslip::study::map::{motion_label, GridAxis};
use stickslip::study::search::same_motion;
use stickslip::{Model, ModelInfo};

/// Forcing periods simulated at most, by both (`simulate`'s default).
const PERIODS: u32 = 3000;

/// What `simulate --from` says at `(x0, v0)`: the attractor, or why none
/// (a start still unsettled after `PERIODS` is simulated ten times longer,
/// as a user would: a motion a certificate names early may be approached
/// slowly).
fn simulate<M: Model>(sim: &Simulator<M>, x0: f64, v0: f64) -> Result<Attractor, String> {
    for periods in [PERIODS, 10 * PERIODS] {
        let opts = AttractorOptions {
            max_periods: periods,
            ..AttractorOptions::default()
        };
        match find(sim, sim.start(x0, v0, 0.0).unwrap(), opts) {
            Ok(a) => return Ok(a),
            Err(OrbitError::Unsettled { .. }) => continue,
            Err(e) => return Err(format!("error: {e}")),
        }
    }
    Err(UNSETTLED.to_string())
}

/// Whether the basin verdict `label` is the attractor `simulated`: the
/// known motion of that label is the simulated motion itself (same
/// switching points), or the label names the simulated attractor.
fn agrees(
    info: &ModelInfo,
    known: &Known,
    label: &str,
    simulated: &Result<Attractor, String>,
) -> bool {
    match simulated {
        Ok(Attractor::Periodic(m)) => match known.labels.iter().position(|l| l == label) {
            Some(i) => same_motion(&known.found[i], m, 1e-6),
            None => label.starts_with(&attractor_label(info, &Attractor::Periodic(m.clone()))),
        },
        Ok(a) => label == attractor_label(info, a),
        Err(why) => label == why,
    }
}

/// `(agreeing starts, starts, basin labels found)`; panics on a disagreement.
fn compare<M: Model>(p: M::Params, x: &str, v: &str) -> (usize, usize, Vec<String>) {
    let x = GridAxis::parse(x).unwrap();
    let v = GridAxis::parse(v).unwrap();
    let header = BasinHeader::new::<M>(&p, &x, &v, 0.0, 0, 1, PERIODS, 0);
    let sim = Simulator::<M>::new(p, SimOptions::default()).unwrap();
    let known = discover(&sim, &header);
    let mut agree = 0;
    let mut labels: Vec<String> = Vec::new();
    let mut wrong = Vec::new();
    for i in 0..header.grid_len() {
        let basin = classify(&sim, &known, &header, i).attractor;
        let (x0, v0) = header.start(i);
        let simulated = simulate(&sim, x0, v0);
        if agrees(sim.info(), &known, &basin, &simulated) {
            agree += 1;
        } else {
            let named = simulated.map(|a| match a {
                Attractor::Periodic(m) => {
                    format!("{} at {:?}", motion_label(sim.info(), &m), m.points[0])
                }
                other => attractor_label(sim.info(), &other),
            });
            wrong.push(format!("({x0}, {v0}): basins {basin}, simulate {named:?}"));
        }
        if !labels.contains(&basin) {
            labels.push(basin);
        }
    }
    let n = header.grid_len();
    eprintln!(
        "{} {}, {} by {}: {agree} of {n} agree; attractors {labels:?}",
        sim.info().name,
        sim.oscillator().frequency,
        x.spec(),
        v.spec()
    );
    assert!(
        wrong.is_empty(),
        "{} disagreements:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    (agree, n, labels)
}

fn paper_at(w: f64) -> paper::Params {
    let mut p = paper::Params::default();
    p.set(p.index_of("Q0").unwrap(), 70.0);
    p.set(p.index_of("W").unwrap(), w);
    p
}

fn coulomb_at(w: f64) -> coulomb::Params {
    let mut p = coulomb::Params::default();
    for (name, value) in [
        ("V", 0.0),
        ("d", 0.0),
        ("mus", 0.45),
        ("muk", 0.3),
        ("Q0", 1.5),
        ("W", w),
    ] {
        p.set(p.index_of(name).unwrap(), value);
    }
    p
}

#[test]
fn a_coexisting_period_one_motion_two_thousandths_from_a_period_two_one() {
    let (_, _, labels) = compare::<Paper>(paper_at(3.6176858236), "x=-3:3:21", "v=-4:6:21");
    assert!(labels.iter().any(|l| l == "P_{3_33 4_33}"), "{labels:?}");
    assert!(labels.len() >= 2, "{labels:?}");
}

#[test]
fn the_three_motion_window_on_wide_and_local_grids() {
    for w in [3.9482584517, 3.94826] {
        let (_, _, labels) = compare::<Paper>(paper_at(w), "x=-3:3:21", "v=-4:6:21");
        assert!(labels.len() >= 2, "{labels:?}");
    }
    let (_, _, labels) = compare::<Paper>(paper_at(3.94826), "x=0.98:1.02:24", "v=1.30:1.40:24");
    assert_eq!(labels.len(), 3, "{labels:?}");
    for w in [3.948150, 3.948380] {
        let (_, _, labels) = compare::<Paper>(paper_at(w), "x=-2.7:3.1:17", "v=-3.3:5.9:19");
        assert!(labels.len() >= 2, "{labels:?}");
    }
}

#[test]
fn mirror_image_pairs_of_the_coulomb_oscillator() {
    // One structure, two mirror-image motions (past the pitchfork at W =
    // 0.3698): both found, told apart by their first switching point.
    let (_, _, labels) = compare::<Coulomb>(coulomb_at(0.371), "x=-3:3:21", "v=-2:2:21");
    let pair: Vec<&String> = labels
        .iter()
        .filter(|l| l.starts_with("P_{0_11 1_11 0_11 2_11} (x1 = "))
        .collect();
    assert_eq!(pair.len(), 2, "{labels:?}");
    // Two mirror pairs of different structures.
    let (_, _, labels) = compare::<Coulomb>(coulomb_at(0.39), "x=-3:3:21", "v=-2:2:21");
    assert!(labels.len() >= 4, "{labels:?}");
}
