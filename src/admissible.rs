//! Admissibility of a solution of the mapping equations (SPEC §6): is it a
//! real motion? Every violated condition is reported with its segment and
//! margin (positive margin = satisfied), so that a sweep knows why a motion
//! does not exist.

use serde::Serialize;

use crate::model::{MappingKind, Model, Side};
use crate::periodic::SwitchingPoint;
use crate::simulate::{EventKind, Location, Segment, Simulator};
use crate::structure::Structure;

/// One violated condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Violation {
    /// Index of the mapping (in application order) where it happens.
    pub segment: usize,
    /// What is violated, in the model's terms.
    pub condition: String,
    /// By how much (negative or zero: violated; units of the quantity compared).
    pub margin: f64,
}

/// Tolerance on phases when comparing a simulated event with a switching point.
fn phase_tol(phase: f64) -> f64 {
    1e-7 * phase.abs().max(1.0)
}

/// Check every condition of SPEC §6 for `points` of `structure`.
pub fn violations<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Vec<Violation> {
    let info = M::INFO;
    let p = sim.params();
    let m = points.len();
    let shift = 2.0 * std::f64::consts::PI * structure.periods() as f64;
    let mut out = Vec::new();
    let label = |k: usize| info.boundaries[k].label;
    for k in 0..m {
        let mi = info.mappings[structure.steps()[k]];
        let next_mi = info.mappings[structure.steps()[(k + 1) % m]];
        let a = points[k];
        let b = if k + 1 < m {
            points[k + 1]
        } else {
            SwitchingPoint {
                phase: points[0].phase + shift,
                x: points[0].x,
            }
        };
        let mut bad = |condition: String, margin: f64| {
            out.push(Violation {
                segment: k,
                condition,
                margin,
            })
        };
        if !(b.phase > a.phase) {
            bad(
                format!(
                    "mapping {} takes no time: W t goes from {} to {}",
                    mi.name, a.phase, b.phase
                ),
                b.phase - a.phase,
            );
            continue;
        }
        match (mi.kind, mi.domain) {
            (MappingKind::Stick, _) => {
                let seg = Segment {
                    x: a.x,
                    v: sim.velocity(mi.from),
                    phase: a.phase,
                    location: Location::Stick,
                    search_from: a.phase,
                };
                match sim.next_event(&seg, b.phase + phase_tol(b.phase)) {
                    Ok(Some((e, _))) if e.kind == EventKind::StickEnd => {
                        let exit_ok = match (e.after, mi.exit) {
                            (Location::Domain(j), Some(Side::Above)) => j == mi.from + 1,
                            (Location::Domain(j), Some(Side::Below)) => j == mi.from,
                            _ => false,
                        };
                        if (e.phase - b.phase).abs() > phase_tol(b.phase) {
                            bad(
                                format!("the stick on {} ends at W t = {} (|Fnf| = as), not at W t = {}", label(mi.from), e.phase, b.phase),
                                e.phase - b.phase,
                            );
                        } else if !exit_ok {
                            bad(
                                format!("the stick on {} ends to the other side", label(mi.from)),
                                0.0,
                            );
                        }
                    }
                    Ok(Some((e, _))) => bad(
                        format!(
                            "unexpected {:?} during the stick at W t = {}",
                            e.kind, e.phase
                        ),
                        0.0,
                    ),
                    Ok(None) => bad(
                        format!(
                            "|Fnf| < as until W t = {}: the stick does not end there",
                            b.phase
                        ),
                        0.0,
                    ),
                    Err(e) => bad(format!("simulation failed: {e}"), f64::NAN),
                }
            }
            (_, Some(j)) => {
                let dom = info.domains[j];
                let (va, vb) = (sim.velocity(mi.from), sim.velocity(mi.to));
                // Departure into the domain.
                let [acc0, rate0] = M::normal_field(p, j, a.x, va, a.phase);
                let into = if dom.lower == Some(mi.from) {
                    1.0
                } else {
                    -1.0
                };
                let dep = into * acc0;
                if dep < 0.0 || (dep == 0.0 && into * rate0 <= 0.0) {
                    bad(
                        format!(
                            "the flow does not leave {} into domain {}",
                            label(mi.from),
                            dom.label
                        ),
                        dep,
                    );
                }
                // The arrival on β is the first boundary contact.
                let seg = Segment {
                    x: a.x,
                    v: va,
                    phase: a.phase,
                    location: Location::Domain(j),
                    search_from: a.phase,
                };
                match sim.next_event(&seg, b.phase + phase_tol(b.phase)) {
                    Ok(Some((e, _))) if e.phase < b.phase - phase_tol(b.phase) => {
                        let what = if e.kind == EventKind::Graze {
                            "grazes"
                        } else {
                            "crosses"
                        };
                        bad(
                            format!(
                                "the flow of {} {what} {} at W t = {} before reaching {}",
                                mi.name,
                                label(e.boundary),
                                e.phase,
                                label(mi.to)
                            ),
                            e.phase - b.phase,
                        );
                    }
                    Ok(Some((e, _))) if e.boundary != mi.to => bad(
                        format!(
                            "the flow of {} arrives on {}, not {}",
                            mi.name,
                            label(e.boundary),
                            label(mi.to)
                        ),
                        0.0,
                    ),
                    Ok(Some(_)) => {}
                    Ok(None) => {
                        let (_, v) = sim.state_at(&seg, b.phase);
                        bad(
                            format!(
                                "the flow of {} does not reach {} by W t = {}",
                                mi.name,
                                label(mi.to),
                                b.phase
                            ),
                            -(v - vb).abs(),
                        );
                    }
                    Err(e) => bad(format!("simulation failed: {e}"), f64::NAN),
                }
                // Transversal arrival.
                let acc1 = M::normal_field(p, j, b.x, vb, b.phase)[0];
                let out_sign = if dom.upper == Some(mi.to) { 1.0 } else { -1.0 };
                if out_sign * acc1 <= 0.0 {
                    bad(
                        format!(
                            "the arrival on {} is not transversal (grazing)",
                            label(mi.to)
                        ),
                        out_sign * acc1,
                    );
                }
                // What happens at β.
                if next_mi.kind != MappingKind::Stick && next_mi.domain == Some(j) {
                    bad(
                        format!(
                            "{} arrives on {} from domain {} and {} leaves into the same domain",
                            mi.name,
                            label(mi.to),
                            dom.label,
                            next_mi.name
                        ),
                        -(acc1.abs()),
                    );
                }
                if let (Some(f), true) = (
                    M::stick_forces(p, b.x, b.phase),
                    info.boundaries[mi.to].stick,
                ) {
                    let from_above = dom.lower == Some(mi.to);
                    let (fa, fb) = (f.input_above, f.input_below);
                    if next_mi.kind == MappingKind::Stick {
                        let margin = (-fa).min(fb);
                        if margin <= 0.0 {
                            bad(format!("stick onset on {} needs F_in above < 0 < F_in below (F_in above = {fa}, F_in below = {fb})", label(mi.to)), margin);
                        }
                    } else if next_mi.domain != Some(j) {
                        let margin = if from_above {
                            (-fa).min(-fb)
                        } else {
                            fa.min(fb)
                        };
                        if margin <= 0.0 {
                            let need = if from_above {
                                "both input forces < 0"
                            } else {
                                "both input forces > 0"
                            };
                            bad(format!("passing {} needs {need} (F_in above = {fa}, F_in below = {fb})", label(mi.to)), margin);
                        }
                    }
                }
            }
            (_, None) => bad("a flow mapping without a domain".into(), f64::NAN),
        }
    }
    out
}
