//! A condition that is within `SAME_EVENT` (1e-6, absolute) of zero where a
//! curve starts is taken for one vanishing with the curve's own (a
//! companion: a shrinking segment's duration, departure and arrival vanish
//! together), and left out of what ends the curve. Near a band's tip the
//! band's other border is that close over much of the box without
//! vanishing with it. Since stop 42 every companion is still watched, to
//! `COMPANION_SLACK` (1e-8) of its scale: the curve ends where it vanishes,
//! and a start where it is already below fails.
//!
//! On the paper's reference scene over W = 3…4 × Q0 = 65…75 (the band tips
//! of the period-adding cascade near W = 3.58, Q0 = 72 and W = 3.65,
//! Q0 = 68.8), each curve's codimension-two ends are switched from
//! (`partner_start`) and the second curve traced by plain `trace`, then
//! from those curves in turn (60 switches): without the branch switch's
//! own guards (`trace_watching`, which watches the first curve's condition
//! exactly, and the cover's `inadmissible_point` filter). Checked
//! independently by the admissibility walk with its event search
//! (`inadmissible_point`, as `orbit` checks a motion): every point of every
//! curve traced satisfies every other condition of its motion to 1e-8 of
//! its scale. With the companions' watch switched off (measured while
//! writing this test), 10 of the 60 curves failed, by 1.9e-7 to 1.1e-4 of
//! the scale: passable-onset curves of the band of
//! `P_{3_31 0_11 3_13 4_33 3_31 0_11 3_13 4_33 3_33 4_33}^3` ran across its
//! tip at W = 3.5838, Q0 = 72.017 (or started beyond it), and grazing
//! curves of a period-4 motion ran on to Q0 = 74.7.
//!
//! The curves the lines trace are checked the same way.

use stickslip::bifurcation::curve::{
    codim2_places, inadmissible_point, partner_start, trace, CurveOptions, PARTNER_STEP,
};
use stickslip::models::paper::reference::{Params, Reference};
use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};

#[test]
fn curves_switched_to_without_guards_stay_where_their_motion_exists() {
    let base = Params::default();
    let opts = CurvesOptions {
        x: ("W".into(), [3.0, 4.0]),
        y: ("Q0".into(), [65.0, 75.0]),
        seeds: Vec::new(),
        at: Vec::new(),
    };
    let settings = CurvesSettings {
        max_partners: 0,
        ..CurvesSettings::default()
    };
    let (_, curves) = traced::<Reference>(&base, &opts, &settings).expect("the curves");
    let plane = opts.plane::<Reference>(&base).unwrap();
    let copts = CurveOptions::default();
    let mut lines = Vec::new();
    for c in &curves {
        if let Some((m, q)) = inadmissible_point::<Reference>(&base, &plane, c) {
            lines.push(format!("{:?} at ({}, {}): {m:e}", c.kind, q.x, q.y));
        }
    }
    assert!(lines.is_empty(), "traced from lines: {lines:#?}");
    // From the lines' curves, then from the curves switched to (a
    // worklist, as the cover's), up to `LIMIT` switches.
    const LIMIT: usize = 60;
    let mut all = curves.clone();
    let mut next = 0;
    let mut switched = 0;
    let mut bad = Vec::new();
    while next < all.len() && switched < LIMIT {
        let c = all[next].clone();
        next += 1;
        for place in codim2_places(&c) {
            let Some(s) = partner_start::<Reference>(
                &base,
                &plane,
                &c,
                &place,
                PARTNER_STEP,
                copts.tolerance,
            ) else {
                continue;
            };
            let Ok(second) = trace::<Reference>(
                &base,
                &plane,
                Some(&s.structure),
                &s.point,
                s.condition,
                &copts,
            ) else {
                continue;
            };
            switched += 1;
            if let Some((m, q)) = inadmissible_point::<Reference>(&base, &plane, &second) {
                bad.push(format!(
                    "{:?} of {} at ({}, {}): {m:e}",
                    second.kind,
                    s.structure.notation(Reference::INFO),
                    q.x,
                    q.y
                ));
            }
            all.push(second);
        }
    }
    // Enough switched curves for the check to mean something.
    assert!(switched >= 40, "{switched} curves switched to");
    assert!(bad.is_empty(), "{bad:#?}");
}
