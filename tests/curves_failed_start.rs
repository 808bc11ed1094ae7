//! A located transition whose curve cannot be traced is reported (JSON
//! `failed_starts`, and a "Missing curves" block in the text), not dropped.
//!
//! One seed line across Shaw's box (`coulomb` with `V = 0, d = 0,
//! mus = 0.45, muk = 0.3`; no spread, edge, missing-curve or refinement lines,
//! no branch switching at codimension-two points),
//! traced once as usual and once with a corrector tolerance no Newton step
//! reaches (1e-300), so that every trace fails at its start. The second
//! run must list every transition the first traced a curve from, on the
//! seed line, with the start's error.

mod common;

use stickslip::bifurcation::curve::Line;
use stickslip::models::coulomb::Coulomb;
use stickslip::output::curves_table;
use stickslip::study::curves::{curves_with, CurveSet, CurvesOptions, CurvesSettings};

const SEED: f64 = 1.8;

use common::shaw::params as base;

fn run(tolerance: Option<f64>) -> CurveSet {
    let opts = CurvesOptions {
        x: ("W".into(), [0.3, 1.2]),
        y: ("Q0".into(), [0.5, 2.0]),
        seeds: vec![Line::Y(SEED)],
        at: Vec::new(),
    };
    let mut settings = CurvesSettings {
        count: 40,
        spread: 0,
        edges: false,
        max_missing: 0,
        max_refine: 0,
        max_partners: 0,
        ..CurvesSettings::default()
    };
    if let Some(t) = tolerance {
        settings.curve.tolerance = t;
    }
    curves_with::<Coulomb>(&base(), &opts, &settings).expect("the run runs")
}

#[test]
fn every_failed_start_is_reported() {
    let traced = run(None);
    assert!(traced.curves.len() >= 3, "{} curves", traced.curves.len());
    let failed = run(Some(1e-300));
    assert!(failed.curves.is_empty(), "{} curves", failed.curves.len());
    let listed = |kind, boundary: &Option<String>, structure: &str| {
        failed
            .failed_starts
            .iter()
            .any(|f| f.kind == kind && &f.boundary == boundary && f.structure == structure)
    };
    for c in &traced.curves {
        assert!(
            listed(c.kind, &c.boundary, &c.structure),
            "the curve {:?} of {} is missing without a word",
            c.kind,
            c.structure
        );
    }
    // What fails with the usual tolerance fails with the tiny one too (the
    // symmetry-breaking branch points of Shaw's symmetric motions: their
    // curves' system is singular, see the README's "Status").
    for f in &traced.failed_starts {
        assert!(listed(f.kind, &f.boundary, &f.structure), "{f:?}");
    }
    for f in &failed.failed_starts {
        assert_eq!(f.point[1], SEED, "{f:?}");
        assert!(
            f.why.contains("start") || f.why.contains("converge"),
            "{f:?}"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&curves_table::json(&failed).unwrap()).unwrap();
    assert_eq!(
        json["failed_starts"].as_array().map(Vec::len),
        Some(failed.failed_starts.len())
    );
    assert!(curves_table::text(&failed, "").contains("Missing curves"));
}
