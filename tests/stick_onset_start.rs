//! A stick that starts with `|Fnf|` beyond `as` is a failed stick onset,
//! not a stick that ends early.
//!
//! On a law whose static bound is its kinetic limit (`as = ak`, the smooth
//! laws' N-piece models, here `stribeck8`) the stick onset's criterion
//! (`F_in above < 0 < F_in below`) is `|Fnf| < as` at the stick's start. On
//! a passable-onset curve it holds with equality. Until stop 29 the walk's
//! event search of the stick also read a start beyond `as` by rounding as
//! the stick ending at once ("the stick must last until W t = 3.9105",
//! margin −0.42), so the walk's smallest margin jumped from the stick's
//! phase tolerance to minus its length from one curve point to the next,
//! and `curves` ended the curve there at a codimension-two point where
//! nothing but the curve's own condition vanishes (on `stribeck8` over
//! W = 0.5:3 × Q0 = 1:12 one passable-onset curve was cut into four
//! pieces, ten such ends in all).
//!
//! Checked here: across the curve, at parameters 1e-6 either side, the
//! stick onset is the only condition of the motion whose margin changes
//! sign, and every other margin is the same to 1e-4 of its size on both
//! sides (the stick's end included: it ends where the structure says on
//! both sides).

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::admissible::{conditions, Violation, ViolationKind};
use stickslip::orbit::attractor;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint, Termination};
use stickslip::orbit::structure::Structure;

const MOTION: &str =
    "P_{7_76 6_65 5_51 0_11 1_12 2_23 3_34 4_44 3_43 2_32 1_21 0_11 5_15 6_56 7_67 8_77}";
/// A point of the motion's passable-onset curve on Sigma1 (a `curves` run
/// over W = 0.5:3 × Q0 = 1:12 ended a piece of it here).
const W: f64 = 1.1818719838993248;
const Q0: f64 = 6.447026259169616;

fn params(q0: f64) -> stribeck8::Params {
    stribeck8::Params {
        W,
        Q0: q0,
        ..stribeck8::Params::default()
    }
}

fn solve(
    s: &Structure,
    q0: f64,
    guess: &[SwitchingPoint],
) -> (Simulator<Stribeck8>, Vec<SwitchingPoint>) {
    let sim = Simulator::<Stribeck8>::new(params(q0), SimOptions::default()).expect("params");
    let mut pts = guess.to_vec();
    let done = PeriodicSolver::<Stribeck8>::new(s.clone()).solve(
        &params(q0),
        &mut pts,
        NewtonOptions::default(),
    );
    assert!(
        matches!(done, Termination::Converged { .. }),
        "Q0 = {q0}: {done:?}"
    );
    (sim, pts)
}

fn onset(c: &[Violation]) -> f64 {
    c.iter()
        .filter(|v| v.kind == ViolationKind::StickOnset)
        .map(|v| v.margin)
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn a_stick_starting_beyond_its_bound_fails_its_onset_only() {
    let s = Structure::parse(Stribeck8::INFO, MOTION, 1).expect("structure");
    let sim = Simulator::<Stribeck8>::new(params(Q0), SimOptions::default()).expect("params");
    let seed = attractor::seed(&sim, &s).expect("the motion is seeded by simulation");
    let (sim, on) = solve(&s, Q0, &seed);
    let here = conditions(&sim, &s, &on);
    assert!(
        onset(&here).abs() < 1e-9,
        "on the curve: stick onset margin {:e}",
        onset(&here)
    );
    let sides: Vec<Vec<Violation>> = [-1e-6, 1e-6]
        .iter()
        .map(|dq| {
            let (sim, pts) = solve(&s, Q0 + dq, &on);
            conditions(&sim, &s, &pts)
        })
        .collect();
    let (a, b) = (&sides[0], &sides[1]);
    assert!(
        onset(a) * onset(b) < 0.0,
        "the curve lies between: onset margins {:e} and {:e}",
        onset(a),
        onset(b)
    );
    assert_eq!(a.len(), b.len(), "{a:#?}\n{b:#?}");
    let mut compared = 0;
    for (x, y) in a.iter().zip(b) {
        assert_eq!(
            (x.kind, x.segment, x.boundary),
            (y.kind, y.segment, y.boundary)
        );
        if x.kind == ViolationKind::StickOnset && x.margin.abs() < 1e-3 {
            continue;
        }
        assert!(
            x.margin > 0.0 && y.margin > 0.0,
            "{:?} of segment {} changes sign across the curve: {x:#?} {y:#?}",
            x.kind,
            x.segment
        );
        assert!(
            (x.margin - y.margin).abs() <= 1e-4 * x.margin.abs().max(1e-3),
            "{:?} of segment {}: {:e} against {:e}",
            x.kind,
            x.segment,
            x.margin,
            y.margin
        );
        compared += 1;
    }
    assert!(
        compared > 40,
        "{compared} conditions compared: the motion has 16 mappings"
    );
}
