//! An audit of the curves runs: every traced curve's points checked by the
//! admissibility walk (`bifurcation::curve::inadmissible_point`), which
//! drops a curve traced by branch switching that runs on where its motion
//! does not exist; here applied to every curve, those traced from lines
//! too. Seven of the boxes of `benches/curves-runs.sh` (pl4 left out for
//! its four minutes):
//!
//!     cargo run --release --example curves_audit
//!
//! Stop 41: one curve of 546 was inadmissible somewhere, the stick-end
//! box's passable onset of `P_{3_31 0_11 3_13 4_33}`, by 1.2e-7 of its
//! scale at its turning point W = 2.66696, Q0 = 192.1287: a condition
//! within 1e-6 of zero at its start was taken for one vanishing with its
//! own and never watched again. Stop 42 watches such conditions
//! (`bifurcation::curve::COMPANION_SLACK`): 0 of 549 (stop 43: 0 of 535,
//! s8full having 14 curves fewer). The check runs as a
//! test on the paper's reference scene (`tests/curve_companion.rs`).

use stickslip::bifurcation::curve::inadmissible_point;
use stickslip::bifurcation::curve::Line;
use stickslip::models::coulomb::{self, Coulomb};
use stickslip::models::paper::{self, Paper};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
use stickslip::Model;

fn run<M: Model>(
    name: &str,
    base: M::Params,
    x: [f64; 2],
    y: [f64; 2],
    seeds: Vec<Line>,
    mm: usize,
) {
    let opts = CurvesOptions {
        x: ("W".into(), x),
        y: ("Q0".into(), y),
        seeds,
        at: Vec::new(),
    };
    let settings = CurvesSettings {
        max_mappings: mm,
        ..CurvesSettings::default()
    };
    let (_, curves) = traced::<M>(&base, &opts, &settings).unwrap();
    let plane = opts.plane::<M>(&base).unwrap();
    let mut bad = 0;
    for c in &curves {
        if let Some((m, q)) = inadmissible_point::<M>(&base, &plane, c) {
            bad += 1;
            println!(
                "  {name}: {:?} {} at ({}, {}): {m:e}",
                c.kind,
                c.structure
                    .as_ref()
                    .map(|s| s.notation(M::info(&base)))
                    .unwrap_or_default(),
                q.x,
                q.y
            );
        }
    }
    println!(
        "{name}: {bad} of {} curves inadmissible somewhere",
        curves.len()
    );
}

fn main() {
    let shaw = coulomb::Params {
        V: 0.0,
        d: 0.0,
        mus: 0.45,
        muk: 0.3,
        ..coulomb::Params::default()
    };
    run::<Coulomb>("shaw", shaw, [0.3, 1.2], [0.5, 2.0], vec![], 24);
    run::<Paper>(
        "cascade",
        paper::Params::default(),
        [6.6, 7.3],
        [30.0, 48.0],
        vec![],
        24,
    );
    run::<Paper>(
        "stickend",
        paper::Params::default(),
        [2.6, 2.9],
        [185.0, 215.0],
        vec![Line::Y(200.0)],
        24,
    );
    run::<Stribeck8>(
        "s8box",
        stribeck8::Params::default(),
        [2.3, 2.6],
        [1.0, 3.0],
        vec![],
        24,
    );
    run::<Paper>(
        "fig11",
        paper::Params::default(),
        [0.2, 8.0],
        [0.0, 180.0],
        vec![Line::Y(70.0)],
        24,
    );
    run::<Paper>(
        "mm40",
        paper::Params::default(),
        [5.0, 8.0],
        [20.0, 60.0],
        vec![],
        40,
    );
    run::<Stribeck8>(
        "s8full",
        stribeck8::Params::default(),
        [0.5, 3.0],
        [1.0, 12.0],
        vec![],
        24,
    );
}
