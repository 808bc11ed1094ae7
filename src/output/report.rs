//! What `stickslip orbit` and `stickslip simulate` find, as a report: a
//! stable schema, printed as JSON with `--json` (documented in the README's
//! "Periodic motions" section). Its text form is [`crate::output::text`];
//! the sampled time history behind `--csv` and `--plot` is
//! [`crate::output::history`].
//!
//! A Newton solution that is not admissible is never a motion here: it is a
//! [`Report::Inadmissible`], with the violated conditions.

use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

use crate::dynamics::simulate::Simulator;
use crate::model::param::ParamSet;
use crate::model::{Model, ModelInfo};
use crate::orbit::admissible::Violation;
use crate::orbit::attractor::{AutonomousCycle, NoMotion, PermanentStick};
use crate::orbit::equilibrium::{steady_sliding, Equilibrium};
use crate::orbit::motion::Motion;
use crate::orbit::periodic::{PeriodicSolver, Termination};
use crate::orbit::stability::Stability;

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// The free parameters of a model (or scene) with their values, in
/// declaration order; serialized as a JSON object.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamValues(pub Vec<(&'static str, f64)>);

impl ParamValues {
    /// Every field of `p`, named by [`ParamSet::names`].
    pub fn of<P: ParamSet>(p: &P) -> Self {
        Self(
            p.names()
                .iter()
                .enumerate()
                .map(|(i, &n)| (n, p.get(i)))
                .collect(),
        )
    }
}

impl Serialize for ParamValues {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// The result of `orbit` or `simulate`, as printed with `--json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind")]
pub enum Report {
    /// A periodic motion: converged and admissible.
    #[serde(rename = "periodic")]
    Periodic(MotionReport),
    /// Newton converged, but the solution violates an admissibility
    /// condition: it is not a motion (the command exits non-zero).
    #[serde(rename = "inadmissible")]
    Inadmissible(MotionReport),
    /// A periodic motion with an eigenvalue `+1` to round-off: one member of
    /// a continuum of neutrally stable motions (the start decides which).
    #[serde(rename = "neutral_family")]
    NeutralFamily(MotionReport),
    /// No boundary contact (certified).
    #[serde(rename = "NM")]
    NoMotion(NoMotionReport),
    /// The mass sticks forever (certified: `|Fnf|` never reaches `as`).
    #[serde(rename = "stick")]
    Stick(StickReport),
    /// The stick-slip cycle of an unforced system (`A0 = 0`): a period in
    /// time, found by the return of the stick-onset state.
    #[serde(rename = "autonomous_cycle")]
    Autonomous(AutonomousReport),
    /// Newton did not converge (the command exits non-zero).
    #[serde(rename = "not_converged")]
    NotConverged(NotConvergedReport),
}

/// A converged solution of a structure's mapping equations.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MotionReport {
    /// `P_{σm … σ1}`.
    pub structure: String,
    /// Forcing periods per cycle (0: an autonomous cycle).
    #[serde(rename = "N")]
    pub periods: u32,
    /// An autonomous cycle's period `T` (a time).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// The model's free parameters.
    pub params: ParamValues,
    /// Point `k` is the start of the `k`-th mapping applied.
    pub points: Vec<PointReport>,
    /// Eigenvalues of `DP` as `[re, im]`, largest modulus first (`null`
    /// where `DP` does not exist: an arrival tangent to its boundary).
    pub eigenvalues: Option<[[f64; 2]; 2]>,
    /// Both eigenvalues inside the unit circle.
    pub stable: bool,
    /// Every admissibility condition holds.
    pub admissible: bool,
    /// The violated conditions (empty for a motion).
    pub violations: Vec<ViolationReport>,
    /// How Newton ended.
    pub newton: NewtonReport,
    /// The model's name (text output only).
    #[serde(skip)]
    pub model: &'static str,
    /// Eigenvalues with their classification (text output only).
    #[serde(skip)]
    pub stability: Option<Stability>,
}

/// A switching point.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointReport {
    /// Its index: the start of the `k`-th mapping applied.
    pub k: usize,
    /// `W t`, unwrapped (`0 ≤ W t_0 < 2π`).
    #[serde(rename = "Wt")]
    pub phase: f64,
    /// `W t mod 2π`.
    #[serde(rename = "Wt_mod_2pi")]
    pub phase_mod_2pi: f64,
    /// Displacement.
    pub x: f64,
    /// Velocity: the boundary's.
    pub v: f64,
    /// The boundary's label (`Sigma3`).
    pub boundary: &'static str,
    /// The mapping that starts here (`4_33`).
    pub mapping: &'static str,
}

/// A violated admissibility condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ViolationReport {
    /// Index of the mapping (in application order) where it happens.
    pub segment: usize,
    /// What is violated, in the model's terms.
    pub condition: String,
    /// By how much (zero or negative: violated; `null` when unknown).
    pub margin: f64,
}

impl From<&Violation> for ViolationReport {
    fn from(v: &Violation) -> Self {
        Self {
            segment: v.segment,
            condition: v.condition.clone(),
            margin: v.margin,
        }
    }
}

/// Newton's iterations and final residual (max norm; `null` when unknown).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NewtonReport {
    /// Iterations taken.
    pub iterations: usize,
    /// Largest residual component at the end.
    pub residual: Option<f64>,
}

/// No boundary contact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NoMotionReport {
    /// Largest velocity of the steady response.
    pub max_v: f64,
    /// The model's name (text output only).
    #[serde(skip)]
    pub model: &'static str,
    /// Smallest velocity of the steady response (text output only).
    #[serde(skip)]
    pub min_v: f64,
    /// The domain's label (text output only).
    #[serde(skip)]
    pub domain: u32,
    /// Phase of the certificate (text output only).
    #[serde(skip)]
    pub certified_at: f64,
    /// With no forcing, the motion at rest: steady sliding, its
    /// eigenvalues and stability.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steady_sliding: Option<Equilibrium>,
    /// Where it rests (`domain 15`; text output only).
    #[serde(skip)]
    pub seat: String,
}

/// A permanent stick.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StickReport {
    /// Where the mass rests.
    pub x: f64,
    /// Its velocity (the belt speed).
    pub v: f64,
    /// Phase `W t` at which the stick began.
    pub since: f64,
    /// The largest `|Fnf|` over a forcing period.
    pub max_force: f64,
    /// The static friction bound `as`.
    pub static_bound: f64,
    /// The model's name (text output only).
    #[serde(skip)]
    pub model: &'static str,
}

/// An autonomous stick-slip cycle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AutonomousReport {
    /// The mappings over one cycle from a stick onset, `P_{σm … σ1}`.
    pub structure: String,
    /// `x` at the stick onset.
    pub x: f64,
    /// `v` there (the belt speed).
    pub v: f64,
    /// `W t` of that onset (`W` only sets the time unit of the phase).
    #[serde(rename = "Wt_onset")]
    pub onset: f64,
    /// Period in time.
    pub period: f64,
    /// Time stuck per cycle.
    pub stick: f64,
    /// Time slipping per cycle.
    pub slip: f64,
    /// The nontrivial Floquet multiplier (the trivial `1` removed; `0` for
    /// a cycle with a stick); `null` at a grazing.
    pub multiplier: Option<f64>,
    /// The largest `|x|` over the cycle, from the closed forms.
    pub max_abs_x: Option<f64>,
    /// The largest `|v|` over the cycle.
    pub max_abs_v: Option<f64>,
    /// The model's parameters.
    pub params: ParamValues,
    /// The model's name (text output only).
    #[serde(skip)]
    pub model: &'static str,
}

/// Newton failed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NotConvergedReport {
    /// Iterations and residual.
    pub newton: NewtonReport,
    /// Why.
    pub reason: String,
    /// The structure (text output only).
    #[serde(skip)]
    pub structure: String,
}

impl NotConvergedReport {
    /// `Newton did not converge for P_{…}: reason` (the text report's first
    /// line and the CLI's failure message).
    pub fn headline(&self) -> String {
        let target = if self.structure.is_empty() {
            String::new()
        } else {
            format!(" for {}", self.structure)
        };
        format!("Newton did not converge{target}: {}", self.reason)
    }
}

fn newton_of(t: &Termination, residual: impl FnOnce() -> Option<f64>) -> (NewtonReport, String) {
    match t {
        Termination::Converged {
            iterations,
            residual,
        } => (
            NewtonReport {
                iterations: *iterations,
                residual: Some(*residual),
            },
            String::new(),
        ),
        Termination::NotConverged {
            iterations,
            residual,
            reason,
        } => (
            NewtonReport {
                iterations: *iterations,
                residual: Some(*residual).filter(|r| r.is_finite()),
            },
            reason.clone(),
        ),
        Termination::Singular {
            iterations,
            segment,
            reason,
        } => (
            NewtonReport {
                iterations: *iterations,
                residual: residual(),
            },
            match segment {
                Some(k) => format!("singular Jacobian at mapping {k}: {reason}"),
                None => format!("singular Jacobian: {reason}"),
            },
        ),
    }
}

impl Report {
    /// The report of a Newton solution: periodic, inadmissible or not converged.
    pub fn of_motion<M: Model>(sim: &Simulator<M>, motion: &Motion) -> Self {
        let info = sim.info();
        let p = sim.params();
        let structure = motion.structure.notation(info);
        let (newton, reason) = newton_of(&motion.termination, || {
            let r = PeriodicSolver::<M>::new(motion.structure.clone()).residual(p, &motion.points);
            r.is_finite().then_some(r)
        });
        if !motion.termination.converged() {
            return Report::NotConverged(NotConvergedReport {
                newton,
                reason,
                structure,
            });
        }
        let points = motion
            .points
            .iter()
            .zip(motion.structure.steps())
            .enumerate()
            .map(|(k, (pt, &step))| {
                let mi = &info.mappings[step];
                PointReport {
                    k,
                    phase: pt.phase,
                    phase_mod_2pi: pt.phase.rem_euclid(TAU),
                    x: pt.x,
                    v: sim.velocity(mi.from),
                    boundary: info.boundaries[mi.from].label,
                    mapping: mi.name,
                }
            })
            .collect();
        let report = MotionReport {
            structure,
            periods: motion.structure.periods(),
            period: motion.structure.is_autonomous().then(|| {
                crate::orbit::periodic::cycle_shift(&motion.structure, &motion.points)
                    / M::oscillator(p).frequency
            }),
            params: ParamValues::of(p),
            points,
            eigenvalues: motion.stability.map(|s| s.eigenvalues),
            stable: motion.stability.is_some_and(|s| s.is_stable()),
            admissible: motion.is_admissible(),
            violations: motion.violations.iter().map(Into::into).collect(),
            newton,
            model: info.name,
            stability: motion.stability,
        };
        if report.admissible {
            if motion.stability.is_some_and(|s| s.has_unit_eigenvalue()) {
                Report::NeutralFamily(report)
            } else {
                Report::Periodic(report)
            }
        } else {
            Report::Inadmissible(report)
        }
    }

    /// The report of a certified NM; with no forcing, it names the
    /// equilibrium the motion rests at (steady sliding).
    pub fn of_no_motion<M: Model>(p: &M::Params, nm: &NoMotion) -> Self {
        let info = M::info(p);
        let steady = steady_sliding::<M>(p).ok();
        let seat = steady.map_or_else(String::new, |e| e.seat.label(info));
        Report::NoMotion(NoMotionReport {
            max_v: nm.max_v,
            model: info.name,
            min_v: nm.min_v,
            domain: info.domains[nm.domain].label,
            certified_at: nm.certified_at,
            steady_sliding: steady,
            seat,
        })
    }

    /// The report of a permanent stick.
    pub fn of_stick(info: &ModelInfo, s: &PermanentStick) -> Self {
        Report::Stick(StickReport {
            x: s.x,
            v: s.v,
            since: s.since,
            max_force: s.max_force,
            static_bound: s.static_bound,
            model: info.name,
        })
    }

    /// The report of an autonomous stick-slip cycle.
    pub fn of_autonomous<M: Model>(sim: &Simulator<M>, a: &AutonomousCycle) -> Self {
        let info = sim.info();
        let names: Vec<&str> = a
            .steps
            .iter()
            .rev()
            .map(|&k| info.mappings[k].name)
            .collect();
        Report::Autonomous(AutonomousReport {
            structure: stickslip_codegen::structure::notation(&names),
            x: a.x,
            v: a.v,
            onset: a.onset,
            period: a.period,
            stick: a.stick,
            slip: a.slip,
            multiplier: a.multiplier,
            max_abs_x: a.amplitude.map(|a| a.x),
            max_abs_v: a.amplitude.map(|a| a.v),
            params: ParamValues::of(sim.params()),
            model: info.name,
        })
    }

    /// The report of a Newton failure known only by its termination.
    pub fn of_termination<M: Model>(t: &Termination, structure: Option<String>) -> Self {
        let (newton, reason) = newton_of(t, || None);
        Report::NotConverged(NotConvergedReport {
            newton,
            reason,
            structure: structure.unwrap_or_default(),
        })
    }

    /// A periodic motion or a certified NM (the command succeeds).
    pub fn is_motion(&self) -> bool {
        matches!(
            self,
            Report::Periodic(_)
                | Report::NeutralFamily(_)
                | Report::NoMotion(_)
                | Report::Stick(_)
                | Report::Autonomous(_)
        )
    }

    /// For a report that is not a motion, the one-line reason.
    pub fn failure(&self) -> Option<String> {
        match self {
            Report::Periodic(_)
            | Report::NeutralFamily(_)
            | Report::NoMotion(_)
            | Report::Stick(_)
            | Report::Autonomous(_) => None,
            Report::Inadmissible(r) => {
                let first = r.violations.first().map_or_else(String::new, |v| {
                    let mapping = r.points.get(v.segment).map_or("?", |p| p.mapping);
                    format!(
                        ": mapping {} ({}): {} (margin {:.3e})",
                        v.segment, mapping, v.condition, v.margin
                    )
                });
                let more = match r.violations.len() {
                    0 | 1 => String::new(),
                    n => format!(", and {} more violated condition(s)", n - 1),
                };
                Some(format!(
                    "the Newton solution of {} is not a motion{first}{more}",
                    r.structure
                ))
            }
            Report::NotConverged(r) => Some(r.headline()),
        }
    }

    /// Pretty-printed JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("reports serialize")
    }
}
