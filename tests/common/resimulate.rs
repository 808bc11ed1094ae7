//! A periodic motion re-simulated by the library's event-driven simulation
//! from its first switching point (a check that a solution of the mapping
//! equations is a motion: it comes back to itself after its period).

use std::f64::consts::TAU;

use stickslip::dynamics::simulate::{EventKind, Location, Segment, SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::orbit::structure::Structure;

/// Simulate `periods` forcing periods from the first switching point of a
/// motion of `structure` at `p` (and a hair more, so that an event due
/// exactly at the end is seen): the number of events (grazes left out) and
/// the phase and displacement of the last one.
pub fn from_first_point(
    p: Params,
    structure: &Structure,
    points: &[SwitchingPoint],
    periods: u32,
) -> (usize, f64, f64) {
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("parameters");
    let first = Paper::INFO.mappings[structure.steps()[0]];
    let p0 = points[0];
    let seg = Segment {
        x: p0.x,
        v: sim.velocity(first.from),
        phase: p0.phase,
        location: first.domain.map_or(Location::Stick, Location::Domain),
        search_from: p0.phase,
    };
    let end = p0.phase + TAU * periods as f64;
    let mut events = Vec::new();
    sim.run(seg, end + 1e-6, |e| {
        if e.kind != EventKind::Graze {
            events.push(*e)
        }
    })
    .expect("simulation runs");
    let last = events.last().expect("an event");
    (events.len(), last.phase - end, last.x)
}
