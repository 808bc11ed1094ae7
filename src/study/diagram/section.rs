//! The periodic branches of a sweep at the orbit diagram's stroboscopic
//! section `W t ≡ 0 (mod 2π)`: each branch sample's motion re-solved from
//! its switching points at its parameter value (Newton starts on the
//! solution) and its `N` states at the section computed in closed form
//! ([`stroboscopic_states`]).

use serde::Serialize;

use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::param::ParamSet;
use crate::model::Model;
use crate::orbit::known::stroboscopic_states;
use crate::orbit::motion::solve;
use crate::orbit::periodic::{NewtonOptions, SwitchingPoint};
use crate::orbit::structure::Structure;
use crate::study::sweep::{sweep, BranchSummary, Sweep, SweepOptions};

use super::OrbitDiagram;

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// One branch sample at the section.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SectionPoint {
    /// The parameter value.
    pub value: f64,
    /// Displacements of the motion's `N` states at the section, in time order.
    pub x: Vec<f64>,
    /// Their velocities.
    pub v: Vec<f64>,
    /// Whether the motion is stable.
    pub stable: bool,
}

/// A sweep branch at the section.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchSection {
    /// `P_{…}`.
    pub structure: String,
    /// Forcing periods per cycle.
    #[serde(rename = "N")]
    pub n: u32,
    /// Its samples in arclength order (those whose motion re-solves).
    pub points: Vec<SectionPoint>,
}

/// Every branch of `sweep` (a sweep of `M` at `base` over its parameter) at the section.
pub fn branch_sections<M: Model>(base: M::Params, sweep: &Sweep) -> Vec<BranchSection> {
    let Some(index) = base.index_of(&sweep.param) else {
        return Vec::new();
    };
    sweep
        .branches
        .iter()
        .filter_map(|b| branch_section::<M>(base, index, b))
        .collect()
}

fn branch_section<M: Model>(
    base: M::Params,
    index: usize,
    b: &BranchSummary,
) -> Option<BranchSection> {
    let structure = Structure::parse(M::info(&base), &b.structure, b.n).ok()?;
    let points = b
        .points
        .iter()
        .filter_map(|q| {
            let mut p = base;
            p.set(index, q.value);
            let sim = Simulator::<M>::new(p, SimOptions::default()).ok()?;
            let motion = solve(
                &sim,
                structure.clone(),
                unwrap(&q.points),
                NewtonOptions::default(),
            );
            if !motion.termination.converged() {
                return None;
            }
            let states = stroboscopic_states(&sim, &motion, 0.0);
            if states.len() != b.n as usize {
                return None;
            }
            Some(SectionPoint {
                value: q.value,
                x: states.iter().map(|s| s.x).collect(),
                v: states.iter().map(|s| s.v).collect(),
                stable: q.stable,
            })
        })
        .collect();
    Some(BranchSection {
        structure: b.structure.clone(),
        n: b.n,
        points,
    })
}

/// Switching points given modulo 2π made increasing again: a phase below
/// its predecessor's lies in the next forcing period.
fn unwrap(points: &[SwitchingPoint]) -> Vec<SwitchingPoint> {
    let mut out: Vec<SwitchingPoint> = Vec::with_capacity(points.len());
    for p in points {
        let mut phase = p.phase;
        if let Some(prev) = out.last() {
            while phase <= prev.phase {
                phase += TAU;
            }
        }
        out.push(SwitchingPoint { phase, x: p.x });
    }
    out
}

/// Place the branches of a sweep over the diagram's range (the default
/// sweep options) on `diagram`'s section. A sweep that fails leaves the
/// diagram without branches and returns the note that says why.
pub fn overlay_branches<M: Model>(base: M::Params, diagram: &mut OrbitDiagram) -> Option<String> {
    let values: Vec<f64> = diagram.up.iter().map(|c| c.value).collect();
    let (Some(&a), Some(&b)) = (values.first(), values.last()) else {
        return None;
    };
    let (from, to) = (a.min(b), a.max(b));
    match sweep::<M>(
        base,
        &diagram.param,
        from,
        to,
        values.len(),
        SweepOptions::default(),
    ) {
        Ok(sw) => {
            diagram.branches = branch_sections::<M>(base, &sw);
            None
        }
        Err(e) => Some(format!("note: no branches drawn: the sweep failed: {e}")),
    }
}
