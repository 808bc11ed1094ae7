//! The other analyses that settle starts agree with `simulate --from` where
//! stable motions coexist: the Lyapunov spectrum's verdict (what
//! `lyapunov` and `orbit-diagram` report) names the motion a plain
//! simulation settles on, and a map by continuation (whose starts stop
//! early on a certificate) lists at every point each motion the map by
//! simulation finds there (which settles its starts as `simulate` does).

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::ParamSet;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::{find, Attractor, AttractorOptions};
use stickslip::orbit::lyapunov::{spectrum, LyapunovOptions, Verdict};
use stickslip::study::map::{classify_point, classify_tile, motion_label, GridAxis};
use stickslip_codegen::structure::with_periods;

fn paper_at(w: f64) -> Params {
    let mut p = Params::default();
    p.set(Params::index_of("Q0").unwrap(), 70.0);
    p.set(Params::index_of("W").unwrap(), w);
    p
}

#[test]
fn the_spectrum_names_the_motion_a_simulation_settles_on() {
    let cases: [(f64, &[(f64, f64)]); 2] = [
        // The starts: the period-1 motion beside the period-2 one.
        (
            3.6176858236,
            &[
                (0.6, -4.0),
                (0.6, -3.5),
                (-3.0, 6.0),
                (0.0, 0.0),
                (1.5, 2.0),
            ],
        ),
        // The three-motion window.
        (
            3.94826,
            &[
                (0.98, 1.3),
                (1.0, 1.35),
                (1.02, 1.4),
                (0.99, 1.38),
                (1.01, 1.31),
                (0.0, 0.0),
            ],
        ),
    ];
    let opts = LyapunovOptions {
        transient: 600,
        periods: 400,
    };
    let mut names = Vec::new();
    for (w, starts) in cases {
        let sim = Simulator::<Paper>::new(paper_at(w), SimOptions::default()).unwrap();
        for &(x, v) in starts {
            let s = spectrum(&sim, (x, v, 0.0), opts).unwrap();
            let Verdict::Periodic { structure, n } = &s.verdict else {
                panic!("W = {w} from ({x}, {v}): {:?}", s.verdict);
            };
            let plain = find(
                &sim,
                sim.start(x, v, 0.0).unwrap(),
                AttractorOptions::default(),
            );
            let Ok(Attractor::Periodic(m)) = plain else {
                panic!("W = {w} from ({x}, {v}): {plain:?}");
            };
            let label = with_periods(structure, *n);
            assert_eq!(
                label,
                motion_label(sim.info(), &m),
                "W = {w} from ({x}, {v})"
            );
            names.push(label);
        }
    }
    names.sort();
    names.dedup();
    // The cases do reach coexisting motions.
    assert!(names.len() >= 4, "{names:?}");
}

#[test]
fn a_map_by_continuation_lists_what_simulation_finds() {
    let base = paper_at(3.948);
    let x = GridAxis::parse("W=3.9478:3.9487:10").unwrap();
    let y = GridAxis::parse("Q0=69.8:70.2:6").unwrap();
    let tile = classify_tile::<Paper>(&base, &x, &y, 0);
    let mut coexisting = 0;
    for r in &tile {
        let simulated = classify_point::<Paper>(&base, &x, &y, r.index);
        for m in &simulated.motions {
            assert!(
                r.motions.contains(m),
                "point {} (W = {}, Q0 = {}): simulation finds {m}, continuation lists {:?}",
                r.index,
                r.x,
                r.y,
                r.motions
            );
        }
        if r.motions.len() > 1 {
            coexisting += 1;
        }
    }
    assert!(coexisting > 0);
}
