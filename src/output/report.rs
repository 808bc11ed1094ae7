//! What `stickslip orbit` and `stickslip simulate` print and write: the JSON
//! report (a stable schema, documented in the README's "Periodic motions"
//! section), its text form, and the sampled time history behind `--csv` and
//! `--plot`.
//!
//! A Newton solution that is not admissible is never a motion here: it is a
//! [`Report::Inadmissible`], with the violated conditions.

use std::fmt::{self, Write as _};

use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

use crate::dynamics::simulate::{Location, Segment, SimError, Simulator};
use crate::model::param::ParamSet;
use crate::model::{MappingKind, Model};
use crate::orbit::admissible::Violation;
use crate::orbit::attractor::{AutonomousCycle, NoMotion, PermanentStick};
use crate::orbit::motion::Motion;
use crate::orbit::periodic::{PeriodicSolver, Termination};
use crate::orbit::stability::{Classification, Stability};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// The free parameters of a model (or scene) with their values, in
/// declaration order; serialized as a JSON object.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamValues(pub Vec<(&'static str, f64)>);

impl ParamValues {
    /// Every field of `p`, named by `P::NAMES`.
    pub fn of<P: ParamSet>(p: &P) -> Self {
        Self(
            P::NAMES
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

impl fmt::Display for ParamValues {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (name, value)) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{name} = {value}")?;
        }
        Ok(())
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
    /// Forcing periods per cycle.
    #[serde(rename = "N")]
    pub periods: u32,
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
        let info = M::INFO;
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

    /// The report of a certified NM.
    pub fn of_no_motion<M: Model>(nm: &NoMotion) -> Self {
        Report::NoMotion(NoMotionReport {
            max_v: nm.max_v,
            model: M::INFO.name,
            min_v: nm.min_v,
            domain: M::INFO.domains[nm.domain].label,
            certified_at: nm.certified_at,
        })
    }

    /// The report of a permanent stick.
    pub fn of_stick<M: Model>(s: &PermanentStick) -> Self {
        Report::Stick(StickReport {
            x: s.x,
            v: s.v,
            since: s.since,
            max_force: s.max_force,
            static_bound: s.static_bound,
            model: M::INFO.name,
        })
    }

    /// The report of an autonomous stick-slip cycle.
    pub fn of_autonomous<M: Model>(sim: &Simulator<M>, a: &AutonomousCycle) -> Self {
        let info = M::INFO;
        let names: Vec<&str> = a
            .steps
            .iter()
            .rev()
            .map(|&k| info.mappings[k].name)
            .collect();
        Report::Autonomous(AutonomousReport {
            structure: format!("P_{{{}}}", names.join(" ")),
            x: a.x,
            v: a.v,
            onset: a.onset,
            period: a.period,
            stick: a.stick,
            slip: a.slip,
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
            Report::NotConverged(r) => Some(format!(
                "Newton did not converge{}: {}",
                if r.structure.is_empty() {
                    String::new()
                } else {
                    format!(" for {}", r.structure)
                },
                r.reason
            )),
        }
    }

    /// Pretty-printed JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("reports serialize")
    }
}

fn classification_text(s: &Stability) -> &'static str {
    match s.classification {
        Classification::Stable => "stable",
        Classification::Unstable => "unstable",
        Classification::NearSaddleNode => "near a saddle-node bifurcation (an eigenvalue near +1)",
        Classification::NearPeriodDoubling => {
            "near a period-doubling bifurcation (an eigenvalue near -1)"
        }
        Classification::NearNeimark => "near a Neimark bifurcation (a complex pair near |λ| = 1)",
    }
}

/// 12 decimals, or scientific notation for tiny nonzero values (round-off).
fn number(x: f64) -> String {
    if x == 0.0 || x.abs() >= 1e-6 {
        format!("{x:.12}")
    } else {
        format!("{x:.3e}")
    }
}

fn write_motion(f: &mut fmt::Formatter<'_>, r: &MotionReport) -> fmt::Result {
    writeln!(
        f,
        "{}: {}, period N = {} (model {})",
        if r.admissible {
            "periodic motion"
        } else {
            "NOT A MOTION (inadmissible Newton solution)"
        },
        r.structure,
        r.periods,
        r.model
    )?;
    writeln!(f, "parameters: {}", r.params)?;
    writeln!(
        f,
        "Newton: converged in {} iteration{}, residual {}",
        r.newton.iterations,
        if r.newton.iterations == 1 { "" } else { "s" },
        r.newton
            .residual
            .map_or_else(|| "unknown".to_string(), |x| format!("{x:.1e}"))
    )?;
    writeln!(f)?;
    writeln!(
        f,
        "{:>3}  {:<8} {:<9} {:>17} {:>17} {:>18} {:>8}",
        "k", "mapping", "boundary", "W t", "W t mod 2π", "x", "v"
    )?;
    for p in &r.points {
        writeln!(
            f,
            "{:>3}  {:<8} {:<9} {:>17.12} {:>17.12} {:>18.12} {:>8}",
            p.k, p.mapping, p.boundary, p.phase, p.phase_mod_2pi, p.x, p.v
        )?;
    }
    writeln!(f, "(point k is the start of the k-th mapping applied)")?;
    writeln!(f)?;
    match &r.stability {
        Some(s) => {
            writeln!(f, "eigenvalues of DP (in (W t, x)):")?;
            for (i, e) in s.eigenvalues.iter().enumerate() {
                let value = if e[1] == 0.0 {
                    number(e[0])
                } else {
                    let sign = if e[1] < 0.0 { '-' } else { '+' };
                    format!("{} {sign} {}i", number(e[0]), number(e[1].abs()))
                };
                writeln!(
                    f,
                    "  λ{} = {value:<36} |λ{}| = {}",
                    i + 1,
                    i + 1,
                    number(e[0].hypot(e[1]))
                )?;
            }
            write!(
                f,
                "stability: {} (largest |λ| = {:.6})",
                classification_text(s),
                s.largest_modulus
            )?;
            if s.has_zero_eigenvalue {
                write!(f, "; one eigenvalue is 0 to round-off (stick)")?;
            }
            writeln!(f)?;
        }
        None => writeln!(
            f,
            "eigenvalues: none (DP does not exist: an arrival is tangent to its boundary)"
        )?,
    }
    if r.violations.is_empty() {
        writeln!(
            f,
            "admissible: yes (every segment, crossing and force criterion checked)"
        )
    } else {
        writeln!(f, "admissible: NO, violated conditions:")?;
        for v in &r.violations {
            let mapping = r.points.get(v.segment).map_or("?", |p| p.mapping);
            writeln!(
                f,
                "  mapping {} ({mapping}): {} (margin {:.3e})",
                v.segment, v.condition, v.margin
            )?;
        }
        Ok(())
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Report::Periodic(r) | Report::Inadmissible(r) => write_motion(f, r),
            Report::NeutralFamily(r) => {
                write_motion(f, r)?;
                writeln!(
                    f,
                    "neutral family: DP has the eigenvalue 1 (to round-off): this motion is one \
                     of a continuum of neutrally stable periodic motions; other starts settle on \
                     other members (Csernák, Stépán & Shaw 2007: the undamped Coulomb oscillator \
                     at W = sqrt(c) / (2 n))"
                )
            }
            Report::NoMotion(r) => writeln!(
                f,
                "NM (no motion touches a boundary; model {}): the steady motion stays in domain {} \
                 with {:.6} <= v <= {:.6} (certified by a bound on the transient at W t = {:.6})",
                r.model, r.domain, r.min_v, r.max_v, r.certified_at
            ),
            Report::Stick(r) => writeln!(
                f,
                "permanent stick (model {}): the mass sticks from W t = {:.6} on at x = {:.12}, \
                 v = {}; the non-friction force never exceeds {:.6} <= as = {:.6}",
                r.model, r.since, r.x, r.v, r.max_force, r.static_bound
            ),
            Report::Autonomous(r) => writeln!(
                f,
                "autonomous stick-slip cycle (no forcing; model {}): {}, period T = {:.12} \
                 (stick {:.12}, slip {:.12}); the stick begins at x = {:.12}, v = {} \
                 (W t = {:.6}; W only sets the phase unit)",
                r.model, r.structure, r.period, r.stick, r.slip, r.x, r.v, r.onset
            ),
            Report::NotConverged(r) => {
                writeln!(
                    f,
                    "Newton did not converge{}: {}",
                    if r.structure.is_empty() {
                        String::new()
                    } else {
                        format!(" for {}", r.structure)
                    },
                    r.reason
                )?;
                writeln!(
                    f,
                    "iterations: {}, residual: {}",
                    r.newton.iterations,
                    r.newton
                        .residual
                        .map_or_else(|| "unknown".to_string(), |x| format!("{x:.3e}"))
                )
            }
        }
    }
}

/// One sample of a time history.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Sample {
    /// Time `t = W t / W`.
    pub t: f64,
    /// Phase `W t`.
    pub phase: f64,
    /// Displacement.
    pub x: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration `x''` (0 while stuck).
    pub a: f64,
    /// The domain's label, 0 while stuck (as in the stick mapping `0_11`).
    pub domain: u32,
    /// Friction force per unit mass: `A0 cos W t − 2 d v − c x − x''`, the
    /// kinetic law `f(v)` in a domain and `Fnf` while stuck.
    pub friction: f64,
}

/// A stretch of motion in one domain, or stuck.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Where.
    pub location: Location,
    /// The domain's label, 0 while stuck.
    pub label: u32,
    /// Whether it starts at a switching point (an event of the motion).
    pub switching: bool,
    /// Its samples, both ends included.
    pub samples: Vec<Sample>,
}

/// A sampled time history: one period of a motion, or a simulated stretch.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// Consecutive pieces; consecutive pieces share their switching instant.
    pub pieces: Vec<Piece>,
    /// The boundaries at the edges of the visited bands, `(label, v)`.
    pub boundaries: Vec<(&'static str, f64)>,
}

impl History {
    fn boundaries_of<M: Model>(sim: &Simulator<M>, pieces: &[Piece]) -> Vec<(&'static str, f64)> {
        let info = M::INFO;
        let mut ks: Vec<usize> = Vec::new();
        for piece in pieces {
            let edges = match piece.location {
                Location::Domain(j) => [info.domains[j].lower, info.domains[j].upper],
                Location::Stick => [info.stick_boundary(), None],
            };
            for k in edges.into_iter().flatten() {
                if !ks.contains(&k) {
                    ks.push(k);
                }
            }
        }
        ks.sort_unstable();
        ks.into_iter()
            .map(|k| (info.boundaries[k].label, sim.velocity(k)))
            .collect()
    }

    /// Samples of the segment `seg` (evaluated from its start) on
    /// `[from, to]`: both ends, and every phase `origin + 2π i / per_period`
    /// strictly between.
    fn piece<M: Model>(
        sim: &Simulator<M>,
        seg: &Segment,
        from: f64,
        to: f64,
        origin: f64,
        per_period: usize,
        switching: bool,
    ) -> Piece {
        let info = M::INFO;
        let osc = sim.oscillator();
        let label = match seg.location {
            Location::Domain(j) => info.domains[j].label,
            Location::Stick => 0,
        };
        let step = TAU / per_period.max(1) as f64;
        let sample = |phase: f64| {
            let (x, v) = sim.state_at(seg, phase);
            let a = sim.acceleration(seg.location, x, v, phase);
            Sample {
                t: phase / osc.frequency,
                phase,
                x,
                v,
                a,
                domain: label,
                friction: osc.amplitude * phase.cos()
                    - 2.0 * osc.damping * v
                    - osc.stiffness * x
                    - a,
            }
        };
        let mut samples = vec![sample(from)];
        let mut i = ((from - origin) / step).floor() as i64 + 1;
        loop {
            let phase = origin + i as f64 * step;
            if phase >= to {
                break;
            }
            if phase > from {
                samples.push(sample(phase));
            }
            i += 1;
        }
        if to > from {
            samples.push(sample(to));
        }
        Piece {
            location: seg.location,
            label,
            switching,
            samples,
        }
    }

    /// One cycle (`N` forcing periods) of a periodic motion, each mapping's
    /// segment evaluated from its switching point, `per_period` samples per
    /// forcing period plus every switching point (at a switching instant the
    /// segment ending there and the one starting there each give a sample).
    pub fn of_motion<M: Model>(sim: &Simulator<M>, motion: &Motion, per_period: usize) -> Self {
        let info = M::INFO;
        let m = motion.points.len();
        let cycle = TAU * motion.structure.periods() as f64;
        let origin = motion.points[0].phase;
        let pieces: Vec<Piece> = (0..m)
            .map(|k| {
                let mi = &info.mappings[motion.structure.steps()[k]];
                let a = motion.points[k];
                let end = if k + 1 < m {
                    motion.points[k + 1].phase
                } else {
                    origin + cycle
                };
                let location = match (mi.kind, mi.domain) {
                    (MappingKind::Stick, _) | (_, None) => Location::Stick,
                    (_, Some(j)) => Location::Domain(j),
                };
                let seg = Segment {
                    x: a.x,
                    v: sim.velocity(mi.from),
                    phase: a.phase,
                    location,
                    search_from: a.phase,
                };
                Self::piece(sim, &seg, a.phase, end, origin, per_period, true)
            })
            .collect();
        let boundaries = Self::boundaries_of(sim, &pieces);
        Self { pieces, boundaries }
    }

    /// The simulated motion on `[from, to]`, starting with `seg` (the
    /// segment in force at `from`, possibly started earlier); a new piece at
    /// every event (grazes do not split a piece).
    pub fn simulated<M: Model>(
        sim: &Simulator<M>,
        mut seg: Segment,
        from: f64,
        to: f64,
        per_period: usize,
    ) -> Result<Self, SimError> {
        let mut pieces = Vec::new();
        let mut start = from;
        let mut switching = false;
        loop {
            let next = sim.next_event(&seg, to)?;
            let end = next.as_ref().map_or(to, |(e, _)| e.phase);
            match next {
                Some((_, n)) if n.phase == seg.phase && n.location == seg.location => {
                    // A graze: the same segment goes on.
                    seg = n;
                    continue;
                }
                _ => {}
            }
            pieces.push(Self::piece(
                sim, &seg, start, end, from, per_period, switching,
            ));
            match next {
                None => break,
                Some((_, n)) => {
                    seg = n;
                    start = end;
                    switching = true;
                }
            }
        }
        let boundaries = Self::boundaries_of(sim, &pieces);
        Ok(Self { pieces, boundaries })
    }

    /// Every sample in time order.
    pub fn samples(&self) -> impl Iterator<Item = &Sample> {
        self.pieces.iter().flat_map(|p| p.samples.iter())
    }

    /// CSV: `t,Wt,x,v,a,domain,F`, one row per sample.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("t,Wt,x,v,a,domain,F\n");
        for s in self.samples() {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{}",
                s.t, s.phase, s.x, s.v, s.a, s.domain, s.friction
            );
        }
        out
    }
}
