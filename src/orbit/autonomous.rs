//! Autonomous cycles by Newton: the periodic motion of an unforced model
//! (`A0 = 0`, SPEC §14) on a mapping structure, with its period an unknown.
//!
//! The unknowns are the switching points `(x_k, W t_k)` of the cycle's `m`
//! mappings with the last one arriving back at the first point; time has no
//! origin, so the return is held at a fixed phase and the first point's
//! phase carries the period `S = W T` (the gauge of
//! [`Structure::autonomous`]). The system stays square (`2m` unknowns, `2m`
//! residuals) and is the forced case's with one change in its closing row:
//! [`PeriodicSolver`] solves both, by elimination along the cycle on the
//! generated `2×2` blocks, with no allocation per Newton step. A natural
//! first point is a stick's onset or release, whose velocity the boundary
//! fixes.
//!
//! Where a stick-slip cycle's stick shrinks to nothing along a parameter,
//! the cycle becomes a slip cycle touching the stick boundary, and where an
//! excursion beyond a boundary shrinks to nothing, the cycle without it:
//! [`shrinking`] finds that mapping and [`without`] gives the reduced
//! cycle's structure and points, from which a sweep follows it (through a
//! non-smooth fold of cycles, and on past every excursion it loses).

use crate::model::{MappingKind, Model, ModelInfo};
use crate::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint, Termination};
use crate::orbit::structure::Structure;

/// A solved autonomous cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Cycle {
    /// The switching points; the first keeps the guess's phase.
    pub points: Vec<SwitchingPoint>,
    /// The cycle's phase length `W T`.
    pub shift: f64,
    /// Newton iterations taken.
    pub iterations: usize,
    /// The largest residual component at the last evaluation (before the
    /// final step, which was below the tolerance).
    pub residual: f64,
}

impl Cycle {
    /// The period `T = S / W`.
    pub fn period(&self, frequency: f64) -> f64 {
        self.shift / frequency
    }
}

/// Why Newton did not find the cycle.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AutonomousError {
    /// The forcing is on.
    #[error("the forcing is on (A0 = {0}): a cycle with its period unknown is a motion of the unforced oscillator only; set the forcing amplitude to 0")]
    Forced(f64),
    /// The guess does not fit the structure.
    #[error("the guess has {got} points for a structure of {want} mappings, or is not finite")]
    Guess {
        /// Points given.
        got: usize,
        /// Mappings in the structure.
        want: usize,
    },
    /// The Jacobian is singular (a grazing, or a degenerate guess).
    #[error("the Newton matrix is singular at iteration {0}: the cycle grazes a boundary, or the guess is degenerate")]
    Singular(usize),
    /// No convergence within the iteration limit.
    #[error("Newton did not converge in {iterations} iterations (residual {residual:.3e})")]
    NotConverged {
        /// Iterations taken.
        iterations: usize,
        /// The largest residual component.
        residual: f64,
    },
}

/// Solve the autonomous cycle of the mappings `steps` (applied in order)
/// from the guess `points` (one per mapping, its start) and phase length
/// `shift`. The first point's phase is held (the phase condition).
pub fn solve<M: Model>(
    p: &M::Params,
    steps: &[usize],
    points: &[SwitchingPoint],
    shift: f64,
    opts: NewtonOptions,
) -> Result<Cycle, AutonomousError> {
    let osc = M::oscillator(p);
    if osc.amplitude != 0.0 {
        return Err(AutonomousError::Forced(osc.amplitude));
    }
    let m = steps.len();
    let finite = points
        .iter()
        .all(|q| q.x.is_finite() && q.phase.is_finite())
        && shift.is_finite();
    let structure = Structure::autonomous(M::info(p), steps).ok();
    let (Some(structure), true, true) = (structure, points.len() == m, finite) else {
        return Err(AutonomousError::Guess {
            got: points.len(),
            want: m,
        });
    };
    // Held with the return at W t = 0: the first phase is −S.
    let held = points[0].phase;
    let origin = held + shift;
    let mut pts: Vec<SwitchingPoint> = points
        .iter()
        .map(|q| SwitchingPoint {
            phase: q.phase - origin,
            x: q.x,
        })
        .collect();
    let mut solver = PeriodicSolver::<M>::new(structure);
    match solver.solve(p, &mut pts, opts) {
        Termination::Converged {
            iterations,
            residual,
        } => {
            let s = -pts[0].phase;
            let back = held + s;
            for q in &mut pts {
                q.phase += back;
            }
            pts[0].phase = held;
            Ok(Cycle {
                points: pts,
                shift: s,
                iterations,
                residual,
            })
        }
        Termination::Singular { iterations, .. } => Err(AutonomousError::Singular(iterations)),
        Termination::NotConverged {
            iterations,
            residual,
            ..
        } => Err(AutonomousError::NotConverged {
            iterations,
            residual,
        }),
    }
}

/// The excursion of a cycle that shrinks to nothing where a branch ends:
/// of the mappings that leave boundary `boundary` and return to it (a stick
/// on it, or a flow beyond it and back; any boundary when `None`), the
/// shortest in time, if its neighbours are two flows of one domain (which
/// merge when it is gone: [`without`]). `sticks` restricts the choice to
/// stick mappings.
pub fn shrinking(
    info: &ModelInfo,
    structure: &Structure,
    points: &[SwitchingPoint],
    boundary: Option<usize>,
    sticks: bool,
) -> Option<usize> {
    let steps = structure.steps();
    let m = steps.len();
    if points.len() != m || m < 3 {
        return None;
    }
    let shift = crate::orbit::periodic::cycle_shift(structure, points);
    let duration =
        |k: usize| crate::orbit::periodic::arrival(points, k, shift).phase - points[k].phase;
    (0..m)
        .filter(|&k| {
            let q = &info.mappings[steps[k]];
            let (a, b) = (
                &info.mappings[steps[(k + m - 1) % m]],
                &info.mappings[steps[(k + 1) % m]],
            );
            q.from == q.to
                && boundary.is_none_or(|b| q.from == b)
                && (!sticks || q.kind == MappingKind::Stick)
                && a.domain.is_some()
                && a.domain == b.domain
        })
        .min_by(|&a, &b| duration(a).total_cmp(&duration(b)))
}

/// The cycle of `structure` through `points` (held as
/// [`Structure::autonomous`] holds them) with mapping `k` removed, where
/// it has shrunk to nothing: a stick that vanishes (the stick-slip cycle
/// becomes a slip cycle touching the stick boundary) or a flow beyond a
/// boundary and back that vanishes at a grazing. The two flows around it,
/// in one domain, merge into one flow of that domain that touches the
/// boundary inside. The cycle is rotated to start after the merged flow
/// and held again with its return at `W t = 0`. `None` if the neighbours
/// are not two flows of one domain or the model has no merged mapping.
pub fn without(
    info: &ModelInfo,
    structure: &Structure,
    points: &[SwitchingPoint],
    k: usize,
) -> Option<(Structure, Vec<SwitchingPoint>)> {
    let steps = structure.steps();
    let m = steps.len();
    if !structure.is_autonomous() || points.len() != m || m < 3 || k >= m {
        return None;
    }
    let (before, after) = ((k + m - 1) % m, (k + 1) % m);
    let (a, b) = (&info.mappings[steps[before]], &info.mappings[steps[after]]);
    if a.domain.is_none() || a.domain != b.domain {
        return None;
    }
    let merged = info.mappings.iter().position(|q| {
        q.kind != MappingKind::Stick && q.domain == a.domain && q.from == a.from && q.to == b.to
    })?;
    // Applied order from the mapping after `after`, ending with the merged
    // one (which starts where the flow into the stick started).
    let first = (after + 1) % m;
    let idx: Vec<usize> = (0..m - 2).map(|j| (first + j) % m).collect();
    debug_assert_eq!(idx.last(), Some(&before));
    let applied: Vec<usize> = idx
        .iter()
        .map(|&i| if i == before { merged } else { steps[i] })
        .collect();
    let shift = crate::orbit::periodic::cycle_shift(structure, points);
    let structure = Structure::autonomous(info, &applied).ok()?;
    // Phases past the old return come one period later; the new return is
    // a period after the new first point.
    let unwrapped = |i: usize| {
        if i >= first {
            points[i].phase
        } else {
            points[i].phase + shift
        }
    };
    let ret = unwrapped(first) + shift;
    let pts = idx
        .iter()
        .map(|&i| SwitchingPoint {
            phase: unwrapped(i) - ret,
            x: points[i].x,
        })
        .collect();
    Some((structure, pts))
}
