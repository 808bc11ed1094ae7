//! What lives at a parameter value where no followed branch says: found by
//! simulation, from rest or from the state of a motion that just ended.

use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::{Model, ModelInfo};
use crate::orbit::attractor::{self, Attractor};
use crate::orbit::motion::{segment_at, Motion, OrbitError};
use crate::orbit::structure::Structure;

use super::SweepOptions;

/// The name a transition's `to` gives what the simulation found:
/// `P_{...}` (with `^N` for N > 1 forcing periods; an autonomous cycle's
/// structure), `NM`, `stick`, `unsettled` or `invalid`.
pub(super) fn name(info: &ModelInfo, found: &Result<Attractor, OrbitError>) -> String {
    match found {
        Ok(Attractor::Periodic(m)) => motion_name(info, m),
        Ok(Attractor::NoMotion(_)) => "NM".into(),
        Ok(Attractor::Stick(_)) => "stick".into(),
        Ok(Attractor::Autonomous(c)) => c
            .motion(info)
            .map_or_else(|| "autonomous".into(), |m| motion_name(info, &m)),
        Err(OrbitError::Params(_)) | Err(OrbitError::Simulation(_)) => "invalid".into(),
        Err(_) => "unsettled".into(),
    }
}

/// `P_{...}`, with `^N` for a motion of N > 1 forcing periods.
pub(super) fn motion_name(info: &ModelInfo, m: &Motion) -> String {
    structure_name(info, &m.structure)
}

/// `P_{...}`, with `^N` for a structure of N > 1 forcing periods.
pub(super) fn structure_name(info: &ModelInfo, s: &Structure) -> String {
    s.label(info)
}

/// Simulate from rest.
pub(super) fn from_rest<M: Model>(
    sim: &Simulator<M>,
    opts: &SweepOptions,
) -> Result<Attractor, OrbitError> {
    let start = sim.start(0.0, 0.0, 0.0)?;
    attractor::find(sim, start, opts.attractor)
}

/// Simulate from the first switching point of `old` (a motion at a nearby
/// parameter value, usually one that ends between there and here).
pub(super) fn from_motion<M: Model>(
    sim: &Simulator<M>,
    old: &Motion,
    opts: &SweepOptions,
) -> Result<Attractor, OrbitError> {
    let start = segment_at(sim, &old.structure, &old.points, 0);
    attractor::find(sim, start, opts.attractor)
}

/// A simulator at `p`, if the parameters are valid.
pub(super) fn simulator<M: Model>(p: M::Params) -> Option<Simulator<M>> {
    Simulator::<M>::new(p, SimOptions::default()).ok()
}
