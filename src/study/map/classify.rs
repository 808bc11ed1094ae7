//! What lives at one grid point: the attractors reached from the point's
//! starts, named as on the map ([`classify_point`]).

const TAU: f64 = 2.0 * std::f64::consts::PI;

use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::param::ParamSet;
use crate::model::{Model, ModelInfo};
use crate::orbit::attractor::{self, Attractor, AttractorOptions};
use crate::orbit::lyapunov::{spectrum, LyapunovOptions, Verdict};
use crate::orbit::motion::{Motion, OrbitError};
use crate::orbit::periodic::Termination;
use crate::orbit::structure::Structure;
use stickslip_codegen::structure::with_periods;

use super::file::PointResult;
use super::grid::GridAxis;
use super::{MAX_PERIODS, NO_MOTION, STICK};

/// The motion's name on the map: its structure, with `^N` for `N > 1`.
pub fn motion_label(info: &ModelInfo, motion: &Motion) -> String {
    structure_label(info, &motion.structure)
}

/// The name on the map of a motion of `structure` (see [`motion_label`]).
pub(super) fn structure_label(info: &ModelInfo, structure: &Structure) -> String {
    structure.label(info)
}

/// Whether two motions are the same orbit: same structure and period, and
/// the first switching point of one is (modulo 2π in phase) a switching point of the other.
fn same_motion(a: &Motion, b: &Motion) -> bool {
    if a.structure != b.structure {
        // A cycle started elsewhere is the same cycle only if one is a rotation of the other;
        // both come canonical from `attractor::find`, so a difference means different motions.
        return false;
    }
    let Some(p) = a.points.first() else {
        return false;
    };
    b.points.iter().any(|q| {
        let d = (p.phase - q.phase).rem_euclid(TAU);
        let d = d.min(TAU - d);
        d < 1e-6 && (p.x - q.x).abs() < 1e-6 * (1.0 + p.x.abs())
    })
}

/// Short text for a start that did not settle.
pub(super) fn failure(info: &ModelInfo, e: &OrbitError) -> String {
    match e {
        OrbitError::Unsettled { periods, .. } => format!("unsettled ({periods} periods)"),
        OrbitError::NotConverged(Termination::NotConverged { reason, .. }) => {
            format!("not_converged ({reason})")
        }
        OrbitError::NotConverged(Termination::Singular { reason, .. }) => {
            format!("not_converged (singular: {reason})")
        }
        OrbitError::Inadmissible(m) => {
            format!("inadmissible ({})", motion_label(info, m))
        }
        OrbitError::Simulation(e) => format!("simulation_error ({e})"),
        other => format!("error ({other})"),
    }
}

/// What a start that did not settle does instead, from the
/// Lyapunov spectrum after the search's periods: `chaotic (lambda1 = …)`,
/// `quasi_periodic (…)`, `cycle longer than 32 periods (…)`, or, where the
/// spectrum finds a repeat after all, the motion it settles on later.
pub(super) fn unsettled<M: Model>(
    sim: &Simulator<M>,
    start: (f64, f64, f64),
    e: &OrbitError,
) -> String {
    let opts = LyapunovOptions {
        transient: MAX_PERIODS,
        periods: UNSETTLED_PERIODS,
    };
    let Ok(s) = spectrum(sim, start, opts) else {
        return failure(sim.info(), e);
    };
    let (l, err) = (s.exponents[0], s.error);
    match s.verdict {
        Verdict::Chaotic => format!("chaotic (lambda1 = {l:.3e} +- {err:.1e})"),
        Verdict::QuasiPeriodic => format!("quasi_periodic (lambda1 = {l:.1e} +- {err:.1e})"),
        Verdict::LongCycle { longer_than } => {
            format!("cycle longer than {longer_than} periods (lambda1 = {l:.3e} +- {err:.1e})")
        }
        Verdict::Periodic { structure, n } => {
            format!(
                "{} (settles later on {})",
                failure(sim.info(), e),
                with_periods(&structure, n)
            )
        }
        Verdict::NoMotion | Verdict::Stick => failure(sim.info(), e),
    }
}

/// Forcing periods of the spectrum of a start that did not settle.
const UNSETTLED_PERIODS: u32 = 2000;

/// The two starts of every grid point: rest, and `v` one above the stick
/// boundary (or the highest boundary) half a forcing period later.
pub(super) fn starts<M: Model>(sim: &Simulator<M>) -> [(f64, f64, f64); 2] {
    let info = sim.info();
    let k = info
        .stick_boundary()
        .unwrap_or(info.boundaries.len().saturating_sub(1));
    let v = if info.boundaries.is_empty() {
        1.0
    } else {
        sim.velocity(k) + 1.0
    };
    [(0.0, 0.0, 0.0), (0.0, v, std::f64::consts::PI)]
}

/// Which motions exist at grid point `index` (see the module doc). Never
/// panics on bad parameters: they give the status `invalid: …`.
pub fn classify_point<M: Model>(
    base: &M::Params,
    x_axis: &GridAxis,
    y_axis: &GridAxis,
    index: usize,
) -> PointResult {
    let (x, y, p) = match point_params::<M>(base, x_axis, y_axis, index) {
        Ok(at) => at,
        Err((x, y, status)) => {
            return PointResult {
                index,
                x,
                y,
                status,
                motions: Vec::new(),
            }
        }
    };
    let mut result = PointResult {
        index,
        x,
        y,
        status: String::new(),
        motions: Vec::new(),
    };
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| settle::<M>(p)));
    match outcome {
        Ok((status, motions)) => {
            result.status = status;
            result.motions = motions;
        }
        Err(panic) => result.status = format!("panic: {}", panic_text(&*panic)),
    }
    result
}

/// A grid point's coordinates and checked parameters, or its coordinates
/// and the `invalid: …` status.
pub(super) type PointParams<P> = Result<(f64, f64, P), (f64, f64, String)>;

/// Grid point `index`: `(x, y, parameters)`, checked; or `(x, y, "invalid: …")`.
pub(super) fn point_params<M: Model>(
    base: &M::Params,
    x_axis: &GridAxis,
    y_axis: &GridAxis,
    index: usize,
) -> PointParams<M::Params> {
    let nx = x_axis.count.max(1);
    let (ix, iy) = (index % nx, index / nx);
    let (x, y) = (x_axis.value(ix), y_axis.value(iy));
    let mut p = *base;
    for (axis, value) in [(x_axis, x), (y_axis, y)] {
        match base.index_of(&axis.name) {
            Some(i) => p.set(i, value),
            None => {
                let e = match axis.check_for::<M>(base) {
                    Err(e) => e.to_string(),
                    Ok(()) => format!("`{}` is not a run-time parameter", axis.name),
                };
                return Err((x, y, format!("invalid: {e}")));
            }
        }
    }
    if let Err(e) = p.check() {
        return Err((x, y, format!("invalid: {e}")));
    }
    Ok((x, y, p))
}

/// The text of a caught panic.
pub(super) fn panic_text(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown".to_string())
}

/// Simulate from both starts at checked parameters `p`: `(status, motions)`.
fn settle<M: Model>(p: M::Params) -> (String, Vec<String>) {
    let sim = match Simulator::<M>::new(p, SimOptions::default()) {
        Ok(sim) => sim,
        Err(e) => return (format!("invalid: {e}"), Vec::new()),
    };
    let opts = AttractorOptions {
        max_periods: MAX_PERIODS,
        ..AttractorOptions::default()
    };
    let mut found: Vec<Motion> = Vec::new();
    // Unforced: stable steady sliding is known without a simulation, whose
    // starts may all miss its basin where it is small (near its loss of
    // stability).
    let mut no_motion = crate::orbit::equilibrium::steady_sliding::<M>(sim.params())
        .is_ok_and(|e| e.verdict == crate::orbit::equilibrium::Verdict::Stable);
    let mut stick = false;
    let mut cycles: Vec<&'static str> = Vec::new();
    let mut problems: Vec<String> = Vec::new();
    for (k, (x0, v0, phase0)) in starts(&sim).into_iter().enumerate() {
        let outcome = sim
            .start(x0, v0, phase0)
            .map_err(OrbitError::from)
            .and_then(|seg| attractor::find(&sim, seg, opts));
        match outcome {
            Ok(Attractor::Periodic(m)) => {
                if !found.iter().any(|f| same_motion(f, &m)) {
                    found.push(m);
                }
            }
            Ok(Attractor::NoMotion(_)) => no_motion = true,
            Ok(Attractor::Stick(_)) => stick = true,
            Ok(Attractor::Autonomous(c)) => {
                let name = super::cycle_label(&c);
                if !cycles.contains(&name) {
                    cycles.push(name);
                }
            }
            Err(e @ OrbitError::Unsettled { .. }) => problems.push(format!(
                "start {}: {}",
                k + 1,
                unsettled::<M>(&sim, (x0, v0, phase0), &e)
            )),
            Err(e) => problems.push(format!("start {}: {}", k + 1, failure(sim.info(), &e))),
        }
    }
    let mut motions: Vec<String> = found.iter().map(|m| motion_label(sim.info(), m)).collect();
    if no_motion {
        motions.push(NO_MOTION.to_string());
    }
    if stick {
        motions.push(STICK.to_string());
    }
    motions.extend(cycles.iter().map(|c| c.to_string()));
    motions.sort();
    let status = if problems.is_empty() {
        "ok".to_string()
    } else {
        problems.join("; ")
    };
    (status, motions)
}
