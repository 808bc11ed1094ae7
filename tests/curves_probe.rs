//! Probes (`stickslip curves --probes K`): short sweeps across every curve
//! the lines traced find the bands no line crosses.
//!
//! On `coulomb` (default parameters), box W ∈ [0.55, 0.8], Q0 ∈ [0.3, 0.6],
//! seed line Q0 = 0.45 only: the grazing curve of `P_{0_11 2_11}^2` and the
//! passable-onset curve of `P_{0_11 2_11}` cross near (0.662, 0.434). Above
//! the crossing (on the seed line) the two motions overlap; below it a
//! period-adding cascade opens between them, `P_{(0_11 2_11)^k}^{2k−1}`,
//! each band about 1e-3 wide in W at Q0 = 0.39. No line crosses it.
//!
//! Checked independently: without probes no curve of the cascade's
//! `P_{0_11 2_11 0_11 2_11 0_11 2_11}^5` is traced; with them its grazing
//! and passable-onset curves are, and a sweep along W at Q0 = 0.39 (60
//! values over [0.685, 0.6895], a line the run never swept) locates that
//! motion's birth (passable onset) and death (grazing) where those curves
//! cross the line, to 1e-8 in W.

use stickslip::bifurcation::curve::{crossings, Curve, CurveOptions, Line};
use stickslip::models::coulomb::{Coulomb, Params};
use stickslip::study::curves::{traced, CurveSet, CurvesOptions, CurvesSettings};
use stickslip::study::sweep::{sweep, SweepOptions};
use stickslip::ParamSet;

/// Its name: the block `0_11 2_11` three times over five forcing periods.
const BAND: &str = "(P_{0_11 2_11})^{×3}^5";

/// The box, with the one seed line Q0 = 0.45.
fn box_opts() -> CurvesOptions {
    CurvesOptions {
        x: ("W".into(), [0.55, 0.8]),
        y: ("Q0".into(), [0.3, 0.6]),
        seeds: vec![Line::Y(0.45)],
        at: Vec::new(),
    }
}

fn run(probes: usize) -> (CurveSet, Vec<Curve>) {
    let settings = CurvesSettings {
        spread: 0,
        max_mappings: 8,
        probes,
        ..CurvesSettings::default()
    };
    traced::<Coulomb>(&Params::default(), &box_opts(), &settings).expect("the run runs")
}

#[test]
fn probes_find_a_cascade_band_no_line_crosses() {
    let (without, _) = run(0);
    assert!(
        without.curves.iter().all(|c| c.structure != BAND),
        "the seed line alone already finds {BAND}: the box no longer tests probes"
    );

    let (set, curves) = run(4);
    let base = Params::default();
    let plane = box_opts().plane::<Coulomb>(&base).expect("a valid box");
    let mut p = base;
    p.set(plane.y, 0.39);
    let s = sweep::<Coulomb>(
        p,
        "W",
        0.685,
        0.6895,
        60,
        SweepOptions {
            max_mappings: Some(48),
            ..SweepOptions::default()
        },
    )
    .expect("the sweep runs");
    let band = s
        .branches
        .iter()
        .find(|b| format!("{}^{}", b.structure, b.n) == BAND)
        .expect("the sweep at Q0 = 0.39 follows the band's motion");
    let ends: Vec<(&str, f64)> = band
        .ends
        .iter()
        .filter(|e| e.reason == "grazing" || e.reason == "passable_onset")
        .map(|e| (e.reason.as_str(), e.value))
        .collect();
    assert_eq!(ends.len(), 2, "born and dying inside the line: {ends:?}");
    let opts = CurveOptions::default();
    for (kind, w) in ends {
        let crossed: Vec<f64> = set
            .curves
            .iter()
            .zip(&curves)
            .filter(|(c, _)| c.structure == BAND && c.kind.name() == kind)
            .flat_map(|(_, c)| crossings::<Coulomb>(&base, &plane, c, Line::Y(0.39), &opts))
            .map(|q| q.x)
            .collect();
        assert!(
            crossed.iter().any(|x| (x - w).abs() <= 1e-8),
            "the sweep's {kind} at W = {w}: the {BAND} curves cross Q0 = 0.39 at {crossed:?}"
        );
    }
}
