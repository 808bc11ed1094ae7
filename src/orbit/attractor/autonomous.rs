//! The cycle of an autonomous system (no forcing, `A0 = 0`, SPEC §14):
//! recognised in a simulation by the return of its state, with its period,
//! stick and slip times, amplitude and nontrivial Floquet multiplier.

use nalgebra::Matrix2;
use serde::Serialize;

use super::mapping_between;
use crate::dynamics::simulate::{Event, EventKind, Location, Simulator};
use crate::model::{Model, ModelInfo};
use crate::orbit::amplitude::Amplitude;
use crate::orbit::motion::Motion;
use crate::orbit::periodic::{NewtonOptions, SwitchingPoint, Termination};
use crate::orbit::stability::Stability;
use crate::orbit::structure::Structure;

/// The stick-slip cycle of an autonomous system (no forcing, `A0 = 0`):
/// time is no longer measured in forcing periods, so the cycle is found by
/// the return of the state at a stick onset (`x` on the boundary, whose
/// velocity is fixed), and its period is a time, not a whole number of
/// forcing periods.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AutonomousCycle {
    /// The mappings applied over one cycle, from a stick onset.
    pub steps: Vec<usize>,
    /// `x` at the stick onset that starts the cycle.
    pub x: f64,
    /// `v` there (the boundary's velocity).
    pub v: f64,
    /// Phase `W t` of that onset.
    pub onset: f64,
    /// Period (time).
    pub period: f64,
    /// Time stuck per cycle.
    pub stick: f64,
    /// Time slipping per cycle.
    pub slip: f64,
    /// The nontrivial Floquet multiplier: of the monodromy's two
    /// eigenvalues, the one that is not the trivial `1` along the flow
    /// (SPEC §14). A cycle with a stick has `0`: the release point is fixed
    /// by the static bound, so the stick forgets every perturbation. `None`
    /// where an arrival is tangent to its boundary (a grazing cycle).
    pub multiplier: Option<f64>,
    /// The largest `|x|` and `|v|` over the cycle, from the closed forms
    /// (`None` where a closed form does not exist).
    pub amplitude: Option<Amplitude>,
    /// The switching points (the start of each of `steps`), held with the
    /// cycle's return at `W t = 0`: the first one's phase is `−W T`
    /// ([`Structure::shift`](crate::orbit::structure::Structure::shift)).
    #[serde(skip)]
    pub points: Vec<SwitchingPoint>,
}

impl AutonomousCycle {
    /// Stable: the nontrivial multiplier inside the unit circle.
    pub fn is_stable(&self) -> Option<bool> {
        self.multiplier.map(|m| m.abs() < 1.0)
    }

    /// The cycle as a periodic motion of its autonomous structure
    /// ([`Structure::autonomous`]), its points held with the return at
    /// `W t = 0`, and `DP` the reduced map `diag(0, μ)` (the trivial
    /// eigenvalue 1 replaced by 0, as continuation holds it). `None` where
    /// the multiplier does not exist or the mappings do not form a structure.
    pub fn motion(&self, info: &ModelInfo) -> Option<Motion> {
        let mu = self.multiplier?;
        let structure = Structure::autonomous(info, &self.steps).ok()?;
        let dp = Matrix2::new(0.0, 0.0, 0.0, mu);
        Some(Motion {
            structure,
            points: self.points.clone(),
            termination: Termination::Converged {
                iterations: 0,
                residual: 0.0,
            },
            dp: Some(dp),
            stability: Some(Stability::of(&dp)),
            violations: Vec::new(),
        })
    }
}

/// The nontrivial Floquet multiplier of the autonomous cycle `steps` through
/// `points` (phase and `x` of every switching point, the last mapping
/// returning to the first point `shift` later in phase): the eigenvalue of
/// the exact monodromy that is not the trivial `1`. Its eigenvalues sum to
/// its trace, so the other is `tr DP − 1`.
pub fn autonomous_multiplier<M: Model>(
    p: &M::Params,
    steps: &[usize],
    shift: f64,
    points: &[SwitchingPoint],
) -> Option<f64> {
    let dp = crate::orbit::periodic::monodromy::<M>(p, steps, shift, points).ok()?;
    let mu = crate::orbit::periodic::nontrivial_multiplier(&dp);
    mu.is_finite().then_some(mu)
}

/// The latest cycle between two stick onsets at the same state, if the
/// forcing vanishes (`A0 = 0`: the motion is autonomous); without a stick,
/// between two passes of one boundary in one direction at the same state
/// (a slip cycle), refined by Newton on its structure. The states must
/// agree to `1e-9` relative; every event in between defines a mapping.
pub fn autonomous_cycle<M: Model>(sim: &Simulator<M>, events: &[Event]) -> Option<AutonomousCycle> {
    let osc = sim.oscillator();
    if osc.amplitude != 0.0 || osc.frequency.is_nan() || osc.frequency <= 0.0 {
        return None;
    }
    let onsets: Vec<usize> = (0..events.len())
        .filter(|&i| events[i].kind == EventKind::StickOnset)
        .collect();
    let (first, last) = match onsets.last() {
        Some(&last) => {
            let b = &events[last];
            let &first = onsets[..onsets.len() - 1].iter().rev().find(|&&i| {
                let a = &events[i];
                a.boundary == b.boundary && (a.x - b.x).abs() <= 1e-9 * (1.0 + b.x.abs())
            })?;
            (first, last)
        }
        None => slip_window(events)?,
    };
    let b = &events[last];
    let window = &events[first..=last];
    let mut steps = Vec::with_capacity(window.len() - 1);
    let (mut stick, mut slip) = (0.0, 0.0);
    for pair in window.windows(2) {
        steps.push(mapping_between(sim.info(), &pair[0], &pair[1])?);
        let dt = (pair[1].phase - pair[0].phase) / osc.frequency;
        if pair[0].after == Location::Stick {
            stick += dt;
        } else {
            slip += dt;
        }
    }
    let points: Vec<SwitchingPoint> = window[..window.len() - 1]
        .iter()
        .map(|e| SwitchingPoint {
            phase: e.phase - b.phase,
            x: e.x,
        })
        .collect();
    let (points, shift) = if stick > 0.0 {
        (points, b.phase - window[0].phase)
    } else {
        // A slip cycle converges geometrically, not in one stick: Newton
        // on its structure from the simulated points.
        refine(sim, &steps, points)?
    };
    if stick == 0.0 {
        slip = shift / osc.frequency;
    }
    let multiplier = autonomous_multiplier::<M>(sim.params(), &steps, shift, &points);
    let amplitude = crate::orbit::amplitude::of_cycle::<M>(sim.params(), &steps, shift, &points);
    Some(AutonomousCycle {
        x: points[0].x,
        points,
        multiplier,
        amplitude,
        steps,
        v: sim.velocity(b.boundary),
        onset: window[0].phase,
        period: shift / osc.frequency,
        stick,
        slip,
    })
}

/// The latest pair of passes of one boundary in one direction at the same
/// displacement (a slip cycle's return), as indices into `events`.
fn slip_window(events: &[Event]) -> Option<(usize, usize)> {
    let last = events.iter().rposition(|e| e.kind == EventKind::Pass)?;
    let b = &events[last];
    let first = events[..last].iter().rposition(|a| {
        a.kind == EventKind::Pass
            && a.boundary == b.boundary
            && a.before == b.before
            && a.after == b.after
            && (a.x - b.x).abs() <= 1e-9 * (1.0 + b.x.abs())
    })?;
    Some((first, last))
}

/// Newton on the autonomous structure `steps` from the simulated points
/// (held with their return at `W t = 0`): the refined points and period.
fn refine<M: Model>(
    sim: &Simulator<M>,
    steps: &[usize],
    mut points: Vec<SwitchingPoint>,
) -> Option<(Vec<SwitchingPoint>, f64)> {
    let structure = Structure::autonomous(sim.info(), steps).ok()?;
    let mut solver = crate::orbit::periodic::PeriodicSolver::<M>::new(structure);
    solver
        .solve(sim.params(), &mut points, NewtonOptions::default())
        .converged()
        .then(|| {
            let shift = -points[0].phase;
            (points, shift)
        })
}
