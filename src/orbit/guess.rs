//! A periodic motion's switching points from its first one: the user's
//! guess `(W t, x)` on the first mapping's start boundary, the others read
//! off a simulation from there, or the reason the flow does not follow the
//! structure.

use std::cmp::Ordering;
use std::f64::consts::TAU;

use crate::dynamics::simulate::{EventKind, Location, Segment, SimError, Simulator};
use crate::model::{MappingKind, Model, ModelInfo};
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::structure::Structure;

/// Why the flow from a guessed first switching point does not follow the structure.
#[derive(Debug, thiserror::Error)]
pub enum Departure {
    /// The first mapping's flow does not leave its start boundary into its domain.
    #[error(
        "there the flow does not leave {boundary} into domain {domain}, where {mapping} runs (acceleration {acceleration:.3e})"
    )]
    NotLeaving {
        /// The start boundary.
        boundary: &'static str,
        /// The first mapping's domain.
        domain: u32,
        /// The first mapping.
        mapping: &'static str,
        /// The normal acceleration there.
        acceleration: f64,
    },
    /// Mapping `index` does not end within the simulated time.
    #[error("the simulated motion does not reach the end of mapping {index} ({mapping}) in time")]
    Late {
        /// Its index in the structure.
        index: usize,
        /// Its name.
        mapping: &'static str,
    },
    /// Mapping `index` ends on another boundary, or goes on elsewhere.
    #[error(
        "the simulated motion ends mapping {index} ({mapping}) on {boundary} and goes on in {after}, but the structure needs {want_boundary} and then {want_after}"
    )]
    Elsewhere {
        /// Its index in the structure.
        index: usize,
        /// Its name.
        mapping: &'static str,
        /// The boundary it ends on.
        boundary: &'static str,
        /// Where the motion goes on.
        after: String,
        /// The boundary the structure needs.
        want_boundary: &'static str,
        /// Where the structure goes on.
        want_after: String,
    },
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] SimError),
}

/// Where the flow of mapping `index` runs.
fn location_of(info: &ModelInfo, index: usize) -> Location {
    let mi = &info.mappings[index];
    match (mi.kind, mi.domain) {
        (MappingKind::Stick, _) | (_, None) => Location::Stick,
        (_, Some(j)) => Location::Domain(j),
    }
}

fn location_name(info: &ModelInfo, location: Location) -> String {
    match location {
        Location::Domain(j) => format!("domain {}", info.domains[j].label),
        Location::Stick => "stick".to_string(),
    }
}

/// Switching points of `structure` from its first one, `(W t, x)` on the
/// first mapping's start boundary: simulate from there and read the next
/// events. Fails (with the reason) when the flow does not follow the structure.
pub fn points_from_guess<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    phase: f64,
    x: f64,
) -> Result<Vec<SwitchingPoint>, Departure> {
    let info = sim.info();
    let steps = structure.steps();
    let m = steps.len();
    let first = &info.mappings[steps[0]];
    let v0 = sim.velocity(first.from);
    let location = location_of(info, steps[0]);
    if let Location::Domain(j) = location {
        let acc = M::normal_field(sim.params(), j, x, v0, phase)[0];
        let into = if info.domains[j].lower == Some(first.from) {
            1.0
        } else {
            -1.0
        };
        // Leaving into the domain, strictly (NaN included in the refusal).
        if (into * acc).partial_cmp(&0.0) != Some(Ordering::Greater) {
            return Err(Departure::NotLeaving {
                boundary: info.boundaries[first.from].label,
                domain: info.domains[j].label,
                mapping: first.name,
                acceleration: acc,
            });
        }
    }
    let mut seg = Segment {
        x,
        v: v0,
        phase,
        location,
        search_from: phase,
    };
    // An autonomous cycle's period is not known in forcing periods: its
    // mappings may take any time.
    let limit = if structure.is_autonomous() {
        phase + TAU * AUTONOMOUS_PERIODS
    } else {
        phase + TAU * (2 * structure.periods() + 1) as f64
    };
    let mut points = vec![SwitchingPoint { phase, x }];
    let mut back = phase;
    let mut k = 0;
    while k < m {
        let mi = &info.mappings[steps[k]];
        let Some((event, next)) = sim.next_event(&seg, limit)? else {
            return Err(Departure::Late {
                index: k,
                mapping: mi.name,
            });
        };
        seg = next;
        if event.kind == EventKind::Graze {
            continue;
        }
        let want = location_of(info, steps[(k + 1) % m]);
        if event.boundary != mi.to || event.after != want {
            return Err(Departure::Elsewhere {
                index: k,
                mapping: mi.name,
                boundary: info.boundaries[event.boundary].label,
                after: location_name(info, event.after),
                want_boundary: info.boundaries[mi.to].label,
                want_after: location_name(info, want),
            });
        }
        if k + 1 < m {
            points.push(SwitchingPoint {
                phase: event.phase,
                x: event.x,
            });
        }
        back = event.phase;
        k += 1;
    }
    if structure.is_autonomous() {
        // Held with the return at W t = 0 (`Structure::shift`).
        for q in &mut points {
            q.phase -= back;
        }
    }
    Ok(points)
}

/// How many units of `W t / 2π` the flow from an autonomous cycle's guess
/// may take to follow its structure once.
const AUTONOMOUS_PERIODS: f64 = 1000.0;
