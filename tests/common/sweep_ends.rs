//! The ends of a sweep's branches as curve starts: each branch sample keeps
//! its phases mod 2π (for the figures), which a curve's start must have
//! increasing along the cycle.

use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::study::sweep::Sweep;

/// The ends of the branches of `structure` that the sweep `s` names
/// `reason` (`"stick_vanishing"`, `"grazing"`, …), with the switching
/// points there, each phase made to increase along the cycle.
pub fn branch_ends(s: &Sweep, structure: &str, reason: &str) -> Vec<(f64, Vec<SwitchingPoint>)> {
    let mut out = Vec::new();
    for b in s.branches.iter().filter(|b| b.structure == structure) {
        for e in b.ends.iter().filter(|e| e.reason == reason) {
            let sample = b
                .points
                .iter()
                .find(|p| p.value == e.value)
                .expect("the branch's sample at its end");
            let mut pts = sample.points.clone();
            for k in 1..pts.len() {
                while pts[k].phase <= pts[k - 1].phase {
                    pts[k].phase += std::f64::consts::TAU;
                }
            }
            out.push((e.value, pts));
        }
    }
    out
}
