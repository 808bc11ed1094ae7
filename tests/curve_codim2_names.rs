//! A codimension-two end is named by the condition that vanishes there.
//! Where the curve's last good point has all its smooth margins clearly
//! positive (the condition that ends it is born at zero just beyond, as an
//! interior extremum entering its segment through an end), it is named by
//! the condition violated just beyond. Until stop 28 it was named by the
//! smallest margin at the last good point: on `stribeck8` W = 2.3…2.6 ×
//! Q0 = 1…3 two grazing curves ended at a "stick vanishing" whose stick
//! lasted 8e-2 of a forcing period in phase.
//!
//! Checked independently: at every end named a stick's vanishing, a stick
//! of the motion lasts less than 1e-6 in phase, or its `|Fnf|` reaches the
//! static bound at an interior extremum (to 1e-6 of `1 + as`, sampled at
//! 20 000 phases from the generated stick forces).

mod common;

use common::cycle::traced_wq;
use stickslip::bifurcation::curve::CurveEndReason;
use stickslip::bifurcation::TransitionKind;
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::{FrictionOscillator, MappingKind, Model, ParamSet};

#[test]
fn an_end_named_a_stick_vanishing_has_a_stick_that_vanishes() {
    let base = stribeck8::Params::default();
    let (curves, plane) = traced_wq::<Stribeck8>(&base, [2.3, 2.6], [1.0, 3.0]);
    let (iw, iq) = (plane.x, plane.y);
    let info = Stribeck8::INFO;
    let mut named = 0;
    for c in &curves {
        let s = c.structure.as_ref().expect("a motion");
        for e in &c.ends {
            let CurveEndReason::Codim2 {
                kind: TransitionKind::StickVanishing,
                ..
            } = e.reason
            else {
                continue;
            };
            named += 1;
            let mut p = base;
            p.set(iw, e.at.x);
            p.set(iq, e.at.y);
            let bound = Stribeck8::static_bound(&p).expect("a stick law");
            let w = Stribeck8::oscillator(&p).frequency;
            let pts = &e.at.points;
            let shift = std::f64::consts::TAU * f64::from(s.periods());
            let mut closest = f64::INFINITY;
            for (k, &step) in s.steps().iter().enumerate() {
                let mi = info.mappings[step];
                if mi.kind != MappingKind::Stick {
                    continue;
                }
                let a = pts[k];
                let end = pts.get(k + 1).map_or(pts[0].phase + shift, |b| b.phase);
                let length = end - a.phase;
                if length <= 1e-6 {
                    closest = 0.0;
                    continue;
                }
                let v = Stribeck8::boundary_velocity(&p, mi.from);
                let gap: Vec<f64> = (0..=20_000)
                    .map(|i| {
                        let phase = a.phase + length * f64::from(i) / 20_000.0;
                        let x = a.x + v * (phase - a.phase) / w;
                        let f = Stribeck8::stick_forces(&p, x, phase).expect("on the stick");
                        (bound - f.non_friction.abs()) / (1.0 + bound)
                    })
                    .collect();
                // An interior extremum of `|Fnf|` (the stick ends where
                // `|Fnf|` reaches `as` anyway).
                for i in 1..gap.len() - 1 {
                    if gap[i] <= gap[i - 1] && gap[i] <= gap[i + 1] {
                        closest = closest.min(gap[i]);
                    }
                }
            }
            assert!(
                closest <= 1e-6,
                "{:?} {} ends at W = {}, Q0 = {} named a stick's vanishing, but every stick's interior extrema keep |Fnf| {closest:e} below as",
                c.kind,
                s.notation(info),
                e.at.x,
                e.at.y
            );
        }
    }
    eprintln!("{named} ends named a stick's vanishing");
}
