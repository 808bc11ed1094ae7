//! Bifurcation diagrams: every periodic motion along one parameter, its
//! stable and unstable parts, where it is born and where it dies (SPEC §3,
//! §7, §9, §10).
//!
//! The sweep seeds branches by simulation (from rest at both ends of the
//! range, and from a global search: many starts every k-th grid value and
//! just past every transition, each stopped as soon as it nears a known
//! stable motion), and follows every branch by pseudo-arclength
//! continuation ([`crate::bifurcation`]) around folds, with its unstable
//! parts. A branch ends at a non-smooth transition (an admissibility
//! condition's margin crosses zero: grazing, stick onset or vanishing,
//! passable onset), located to about 1e-12 in the parameter; just past it a
//! simulation finds what lives there, which is followed in turn. The
//! eigenvalue bifurcations (fold, branch point, period doubling,
//! Neimark–Sacker) are located on the branches to about 1e-10, and the
//! branches born at branch points and period doublings are followed too.
//! The motions at the grid values are read off the branches by Newton; no
//! motion (NM) regimes are checked at every grid value from their closed form.

use serde::Serialize;

use crate::bifurcation::branch::{Branch, EndReason};
use crate::bifurcation::ContinuationOptions;
use crate::model::param::{ParamError, ParamSet};
use crate::model::{Model, ModelInfo};
use crate::orbit::amplitude::{self, Amplitude};
use crate::orbit::attractor::{AttractorOptions, NoMotion, PermanentStick};
use crate::orbit::motion::{Motion, OrbitError};
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::stability::Stability;
use crate::orbit::steady::steady_response;
use crate::orbit::structure::Structure;

mod cascade;
mod explore;
mod grid;
mod rest;
mod settle;

pub use cascade::{Cascade, Doubling, FEIGENBAUM_DELTA};
use explore::Explorer;

const TAU: f64 = 2.0 * std::f64::consts::PI;

pub use crate::bifurcation::TransitionKind;

/// A located transition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Transition {
    /// The parameter value.
    pub value: f64,
    /// The motion that ends there.
    pub from: String,
    /// What the simulation finds just past it.
    pub to: String,
    /// The kind.
    pub kind: TransitionKind,
    /// The boundary involved.
    pub boundary: Option<String>,
}

/// A motion at one parameter value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MotionSummary {
    /// `P_{...}` or `NM`.
    pub structure: String,
    /// Forcing periods per cycle.
    #[serde(rename = "N")]
    pub n: u32,
    /// `W t_0 mod 2π` of the first switching point.
    #[serde(rename = "start_Wt")]
    pub start_wt: f64,
    /// `x_0`.
    pub start_x: f64,
    /// Eigenvalues `[re, im]`.
    pub eigenvalues: Vec<[f64; 2]>,
    /// Stable.
    pub stable: bool,
    /// The largest `|x|` over the cycle (the amplitude, from the closed
    /// form; NaN where it could not be evaluated).
    pub max_abs_x: f64,
    /// The largest `|v|` over the cycle.
    pub max_abs_v: f64,
    /// For NM, the largest velocity of the steady response.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_v: Option<f64>,
    /// For an autonomous cycle (`N = 0`), its period `T` (a time).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// Every switching point (phase mod 2π, x) — for the figures.
    #[serde(skip)]
    pub points: Vec<SwitchingPoint>,
}

/// All motions found at one grid value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SweepPoint {
    /// The parameter value.
    pub value: f64,
    /// The motions.
    pub motions: Vec<MotionSummary>,
}

/// A whole sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// Parameter name.
    pub param: String,
    /// Grid points, ascending.
    pub points: Vec<SweepPoint>,
    /// Transitions, ascending.
    pub transitions: Vec<Transition>,
    /// Every branch followed, stable and unstable parts, in the order found.
    pub branches: Vec<BranchSummary>,
    /// The eigenvalue bifurcations on the branches, ascending.
    pub bifurcations: Vec<BifurcationSummary>,
    /// Branches born by period doubling that were not followed, being
    /// longer than [`SweepOptions::max_period`].
    pub cuts: Vec<Cut>,
    /// The period-doubling cascades and their accumulation points.
    pub cascades: Vec<Cascade>,
}

/// A branch born by period doubling and not followed: its period exceeds
/// [`SweepOptions::max_period`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cut {
    /// Where it is born (keyed by the parameter's name in JSON).
    #[serde(skip)]
    pub value: f64,
    /// Its structure.
    pub structure: String,
    /// Its forcing periods per cycle.
    #[serde(rename = "N")]
    pub n: u32,
    /// The largest period followed.
    pub max_period: u32,
}

/// One computed point of a branch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchSample {
    /// The parameter value (keyed by the parameter's name in JSON).
    #[serde(skip)]
    pub value: f64,
    /// `W t_0 mod 2π` of the first switching point.
    #[serde(rename = "start_Wt")]
    pub start_wt: f64,
    /// `x_0`.
    pub start_x: f64,
    /// Eigenvalues of `DP`, `[re, im]`, largest modulus first.
    pub eigenvalues: Vec<[f64; 2]>,
    /// Both eigenvalues inside the unit circle.
    pub stable: bool,
    /// The largest `|x|` over the cycle (the amplitude, from the closed
    /// form; NaN where it could not be evaluated).
    pub max_abs_x: f64,
    /// The largest `|v|` over the cycle.
    pub max_abs_v: f64,
    /// For an autonomous cycle (`N = 0`), its period `T` (a time).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// Every switching point (phase mod 2π, x) — for the figures.
    #[serde(skip)]
    pub points: Vec<SwitchingPoint>,
}

/// Why a branch ends, and where.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchEndSummary {
    /// The parameter value (keyed by the parameter's name in JSON).
    #[serde(skip)]
    pub value: f64,
    /// `parameter_bound`, a non-smooth transition's kind (`grazing`,
    /// `stick_onset`, `stick_vanishing`, `passable_onset`), `closed_loop`,
    /// `newton_failure` or `max_points`.
    pub reason: String,
    /// For a transition, the boundary involved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub boundary: Option<String>,
    /// For `newton_failure`, why Newton failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// A branch of periodic motions of one structure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BranchSummary {
    /// Its number, referred to by `bifurcations[].branch` and `born`.
    pub id: usize,
    /// `P_{...}`.
    pub structure: String,
    /// Forcing periods per cycle.
    #[serde(rename = "N")]
    pub n: u32,
    /// Its points in arclength order (a branch may turn back at folds).
    pub points: Vec<BranchSample>,
    /// How it ends at each side (two ends; one for a branch born at a
    /// bifurcation and followed away from it; none for a closed loop).
    pub ends: Vec<BranchEndSummary>,
}

/// An eigenvalue bifurcation on a branch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BifurcationSummary {
    /// The parameter value (keyed by the parameter's name in JSON).
    #[serde(skip)]
    pub value: f64,
    /// `fold`, `branch_point`, `period_doubling` or `neimark_sacker`.
    pub kind: TransitionKind,
    /// The motion's structure.
    pub structure: String,
    /// Its forcing periods per cycle.
    #[serde(rename = "N")]
    pub n: u32,
    /// The critical eigenvalue `[re, im]` (`im ≥ 0`).
    pub eigenvalue: [f64; 2],
    /// The branch it lies on.
    pub branch: usize,
    /// The branches born there.
    pub born: Vec<usize>,
    /// `W t_0 mod 2π` of the motion there.
    #[serde(rename = "start_Wt")]
    pub start_wt: f64,
    /// `x_0` of the motion there.
    pub start_x: f64,
    /// The largest `|x|` over the cycle (the amplitude, from the closed
    /// form; NaN where it could not be evaluated).
    pub max_abs_x: f64,
    /// The largest `|v|` over the cycle.
    pub max_abs_v: f64,
}

impl Sweep {
    /// Today's view without unstable motions: the unstable points of every
    /// branch and the unstable motions at the grid points are dropped
    /// (branches left with no point go too); transitions and bifurcations stay.
    pub fn stable_only(&self) -> Sweep {
        let mut out = self.clone();
        for p in &mut out.points {
            p.motions.retain(|m| m.stable);
        }
        for b in &mut out.branches {
            b.points.retain(|q| q.stable);
        }
        out.branches.retain(|b| !b.points.is_empty());
        out
    }
}

/// Why a sweep could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// Bad parameters.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// A bad range.
    #[error("bad sweep range: {0}")]
    Range(String),
    /// Bad settings.
    #[error("bad sweep settings: {0}")]
    Options(String),
    /// The first motion could not be found.
    #[error(transparent)]
    Orbit(#[from] OrbitError),
}

/// The sweep's settings.
#[derive(Clone, Copy, Debug)]
pub struct SweepOptions {
    /// Non-smooth transitions are located to this absolute tolerance in the parameter.
    pub tolerance: f64,
    /// Options of the simulations that find new motions.
    pub attractor: AttractorOptions,
    /// The continuation's settings (its bounds are the sweep's range).
    pub continuation: ContinuationOptions,
    /// Starts of the global search (`--starts K`; 0: no global search).
    pub starts: usize,
    /// The global search runs at every k-th grid value (`--every k`; 0:
    /// never) and just past every transition.
    pub every: usize,
    /// At most this many branches are followed.
    pub max_branches: usize,
    /// Branches of motions of more mappings than this are not followed
    /// (`None`: every one). A period-doubling cascade into chaos otherwise
    /// follows branches of hundreds of mappings, each continuation step a
    /// Newton step on twice that many unknowns; the motion is still named
    /// where a simulation finds it (a transition's far side).
    pub max_mappings: Option<usize>,
    /// Branches born by period doubling with more forcing periods than
    /// this are not followed (`None`: every one), and are reported as cut
    /// ([`Sweep::cuts`]): a cascade to chaos doubles without end, and
    /// each doubling costs twice the last.
    pub max_period: Option<u32>,
}

/// The longest period a sweep follows by default ([`SweepOptions::max_period`]).
pub const MAX_PERIOD: u32 = 16;

impl Default for SweepOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            attractor: AttractorOptions {
                max_periods: 1500,
                ..AttractorOptions::default()
            },
            continuation: ContinuationOptions::default(),
            starts: 4,
            every: 50,
            max_branches: 64,
            max_mappings: None,
            max_period: Some(MAX_PERIOD),
        }
    }
}

fn with<P: ParamSet>(base: &P, index: usize, value: f64) -> Result<P, ParamError> {
    let mut p = *base;
    p.set(index, value);
    p.check()?;
    Ok(p)
}

/// The amplitude of the motion of `structure` through `points` at `p`
/// (NaN, NaN where it cannot be evaluated).
fn amplitude_of<M: Model>(
    p: &M::Params,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Amplitude {
    amplitude::of_motion::<M>(p, structure, points).unwrap_or(Amplitude {
        x: f64::NAN,
        v: f64::NAN,
    })
}

fn summary<M: Model>(m: &Motion, p: &M::Params) -> MotionSummary {
    let info = M::info(p);
    let st = m
        .stability
        .unwrap_or_else(|| Stability::of(&nalgebra::Matrix2::zeros()));
    let amp = amplitude_of::<M>(p, &m.structure, &m.points);
    MotionSummary {
        structure: m.structure.notation(info),
        n: m.structure.periods(),
        start_wt: m.points[0].phase.rem_euclid(TAU),
        start_x: m.points[0].x,
        eigenvalues: st.eigenvalues.to_vec(),
        stable: st.is_stable(),
        max_abs_x: amp.x,
        max_abs_v: amp.v,
        max_v: None,
        period: period_of::<M>(p, &m.structure, &m.points),
        points: m
            .points
            .iter()
            .map(|p| SwitchingPoint {
                phase: p.phase.rem_euclid(TAU),
                x: p.x,
            })
            .collect(),
    }
}

fn nm_summary<M: Model>(nm: &NoMotion, p: &M::Params) -> MotionSummary {
    let amp = steady_response::<M>(p, nm.domain).map_or(
        Amplitude {
            x: f64::NAN,
            v: f64::NAN,
        },
        |s| Amplitude::of_steady(&s),
    );
    MotionSummary {
        structure: "NM".into(),
        n: 1,
        start_wt: f64::NAN,
        start_x: f64::NAN,
        eigenvalues: vec![],
        stable: true,
        max_abs_x: amp.x,
        max_abs_v: amp.v,
        max_v: Some(nm.max_v),
        period: None,
        points: vec![],
    }
}

fn stick_summary(s: &PermanentStick) -> MotionSummary {
    MotionSummary {
        structure: "stick".into(),
        n: 1,
        start_wt: s.since.rem_euclid(TAU),
        start_x: s.x,
        eigenvalues: vec![],
        stable: true,
        max_abs_x: s.x.abs(),
        max_abs_v: s.v.abs(),
        max_v: None,
        period: None,
        points: vec![],
    }
}

impl MotionSummary {
    fn same_as(&self, other: &MotionSummary) -> bool {
        if self.structure != other.structure || self.n != other.n {
            return false;
        }
        if self.structure == "NM" {
            return true;
        }
        if self.structure == "stick" {
            return (self.start_x - other.start_x).abs() < 1e-6;
        }
        let d = (self.start_wt - other.start_wt).abs();
        (d.min(TAU - d) < 1e-6) && (self.start_x - other.start_x).abs() < 1e-6
    }
}

/// The period `T` of an autonomous cycle (`None` for a forced motion).
fn period_of<M: Model>(p: &M::Params, s: &Structure, points: &[SwitchingPoint]) -> Option<f64> {
    s.is_autonomous()
        .then(|| crate::orbit::periodic::cycle_shift(s, points) / M::oscillator(p).frequency)
}

fn sample(
    value: f64,
    points: &[SwitchingPoint],
    st: &Stability,
    amp: Amplitude,
    period: Option<f64>,
) -> BranchSample {
    BranchSample {
        period,
        value,
        start_wt: points[0].phase.rem_euclid(TAU),
        start_x: points[0].x,
        eigenvalues: st.eigenvalues.to_vec(),
        stable: st.is_stable(),
        max_abs_x: amp.x,
        max_abs_v: amp.v,
        points: points
            .iter()
            .map(|p| SwitchingPoint {
                phase: p.phase.rem_euclid(TAU),
                x: p.x,
            })
            .collect(),
    }
}

/// The samples of a branch. A point where a bifurcation is located has its
/// critical eigenvalue on the unit circle, so its own stability is
/// round-off: it takes that of the point before it in arclength order (of
/// the point after it for the first point of a branch born at a
/// bifurcation), and a stretch of one stability then ends at the
/// bifurcation.
fn branch_samples<M: Model>(
    b: &Branch,
    at: &impl Fn(f64) -> Option<M::Params>,
) -> Vec<BranchSample> {
    let mut out: Vec<BranchSample> = b
        .points
        .iter()
        .map(|q| {
            let p = at(q.value);
            let amp = p.as_ref().map_or(
                Amplitude {
                    x: f64::NAN,
                    v: f64::NAN,
                },
                |p| amplitude_of::<M>(p, &b.structure, &q.points),
            );
            let period = p.and_then(|p| period_of::<M>(&p, &b.structure, &q.points));
            sample(q.value, &q.points, &q.stability, amp, period)
        })
        .collect();
    let mut critical: Vec<usize> = b.bifurcations.iter().map(|f| f.index).collect();
    critical.sort_unstable();
    for k in critical {
        if k > 0 && k < out.len() {
            out[k].stable = out[k - 1].stable;
        }
    }
    // Born at a bifurcation: one end, and the first point is the birth point.
    if b.ends.len() == 1 && out.len() > 1 {
        out[0].stable = out[1].stable;
    }
    out
}

fn branch_summary<M: Model>(
    info: &ModelInfo,
    id: usize,
    b: &Branch,
    at: &impl Fn(f64) -> Option<M::Params>,
) -> BranchSummary {
    BranchSummary {
        id,
        structure: b.structure.notation(info),
        n: b.structure.periods(),
        points: branch_samples::<M>(b, at),
        ends: b
            .ends
            .iter()
            .map(|e| {
                let detail = match &e.reason {
                    EndReason::NewtonFailure(why) => Some(why.clone()),
                    _ => None,
                };
                let boundary = match e.reason {
                    EndReason::Transition {
                        boundary: Some(k), ..
                    } => Some(info.boundaries[k].label.to_string()),
                    _ => None,
                };
                BranchEndSummary {
                    value: e.at.value,
                    reason: e.reason.name().to_string(),
                    boundary,
                    detail,
                }
            })
            .collect(),
    }
}

/// Sweep parameter `name` over `count` values from `from` to `to`.
pub fn sweep<M: Model>(
    base: M::Params,
    name: &str,
    from: f64,
    to: f64,
    count: usize,
    opts: SweepOptions,
) -> Result<Sweep, SweepError> {
    sweep_branches::<M>(base, name, from, to, count, opts).map(|(sweep, _)| sweep)
}

/// Sweep parameter `name` over the given grid `values` (at least two,
/// finite, strictly increasing; not necessarily evenly spaced): the branches
/// are followed over `[first, last]` and read off at every value.
pub fn sweep_values<M: Model>(
    base: M::Params,
    name: &str,
    values: &[f64],
    opts: SweepOptions,
) -> Result<Sweep, SweepError> {
    let increasing = values.windows(2).all(|w| w[0] < w[1]);
    if values.len() < 2 || !increasing || values.iter().any(|v| !v.is_finite()) {
        return Err(SweepError::Range(format!(
            "{name}: {} values: need at least 2, finite and strictly increasing",
            values.len()
        )));
    }
    sweep_grid::<M>(base, name, values.to_vec(), opts).map(|(sweep, _)| sweep)
}

/// [`sweep`], with the branches it followed as continuation gave them
/// (structures, switching points at their ends and bifurcations; indexed
/// like [`Sweep::branches`]): the curves run starts from them.
pub(crate) fn sweep_branches<M: Model>(
    base: M::Params,
    name: &str,
    from: f64,
    to: f64,
    count: usize,
    opts: SweepOptions,
) -> Result<(Sweep, Vec<Branch>), SweepError> {
    base.index_of(name)
        .ok_or_else(|| ParamError::not_free(M::identity(&base), name))?;
    if count < 2 || !from.is_finite() || !to.is_finite() || from >= to {
        return Err(SweepError::Range(format!(
            "{name}={from}:{to}:{count}: need from < to and at least 2 points"
        )));
    }
    let values: Vec<f64> = (0..count)
        .map(|i| from + (to - from) * i as f64 / (count - 1) as f64)
        .collect();
    sweep_grid::<M>(base, name, values, opts)
}

/// The sweep over `values` (checked by the callers: increasing, finite).
fn sweep_grid<M: Model>(
    base: M::Params,
    name: &str,
    values: Vec<f64>,
    opts: SweepOptions,
) -> Result<(Sweep, Vec<Branch>), SweepError> {
    let index = base
        .index_of(name)
        .ok_or_else(|| ParamError::not_free(M::identity(&base), name))?;
    if opts.max_mappings == Some(0) {
        return Err(SweepError::Options(
            "the longest branch followed (--max-mappings, max_mappings) must have at least 1 mapping, not 0".into(),
        ));
    }
    let (from, to) = (values[0], values[values.len() - 1]);
    // The parameters must be valid at both ends (the error says which).
    with(&base, index, from)?;
    with(&base, index, to)?;
    let mut explorer = Explorer::<M>::new(&base, index, (from, to), &opts);
    explorer.seed(&values);
    let nm = rest::regimes::<M>(&base, index, &values, &opts, &mut explorer);
    explorer.search_all();
    // The parameters at a value of the swept one (for the amplitudes).
    let at = |value: f64| with(&base, index, value).ok();
    let nan = Amplitude {
        x: f64::NAN,
        v: f64::NAN,
    };

    let points = values
        .iter()
        .zip(&nm)
        .map(|(&value, nm)| {
            let mut motions: Vec<MotionSummary> = Vec::new();
            let p = at(value);
            for (_, m) in explorer.motions_at(value) {
                let s = match &p {
                    Some(p) => summary::<M>(&m, p),
                    None => continue,
                };
                if !motions.iter().any(|x| x.same_as(&s)) {
                    motions.push(s);
                }
            }
            for n in nm {
                let Some(p) = &p else { continue };
                let s = nm_summary::<M>(n, p);
                if !motions.iter().any(|x| x.same_as(&s)) {
                    motions.push(s);
                }
            }
            for (v, s) in &explorer.sticks {
                if *v == value && !motions.iter().any(|x| x.same_as(s)) {
                    motions.push(s.clone());
                }
            }
            SweepPoint { value, motions }
        })
        .collect();
    let branches: Vec<BranchSummary> = explorer
        .branches
        .iter()
        .enumerate()
        .map(|(id, b)| branch_summary::<M>(M::info(&base), id, b, &at))
        .collect();
    let mut bifurcations: Vec<BifurcationSummary> = explorer
        .bifurcations
        .iter()
        .map(|l| {
            let b = &explorer.branches[l.branch];
            let bif = &b.bifurcations[l.which];
            let amp = at(bif.at.value)
                .map_or(nan, |p| amplitude_of::<M>(&p, &b.structure, &bif.at.points));
            BifurcationSummary {
                value: bif.at.value,
                kind: bif.kind,
                structure: b.structure.notation(M::info(&base)),
                n: b.structure.periods(),
                eigenvalue: bif.eigenvalue,
                branch: l.branch,
                born: l.born.clone(),
                start_wt: bif.at.points[0].phase.rem_euclid(TAU),
                start_x: bif.at.points[0].x,
                max_abs_x: amp.x,
                max_abs_v: amp.v,
            }
        })
        .collect();
    let located: Vec<cascade::Located> = bifurcations
        .iter()
        .map(|b| cascade::Located {
            value: b.value,
            kind: b.kind,
            n: b.n,
            structure: &b.structure,
        })
        .collect();
    let cascades = cascade::cascades(&located);
    bifurcations.sort_by(|a, b| a.value.total_cmp(&b.value));
    let mut cuts = std::mem::take(&mut explorer.cuts);
    cuts.sort_by(|a, b| a.value.total_cmp(&b.value));
    let mut transitions = explorer.transitions;
    transitions.sort_by(|a, b| a.value.total_cmp(&b.value));
    // One transition found from both sides (or from two branches) is listed
    // once, whatever else lies at the same value: mirror-image motions put
    // theirs there too, so equal transitions need not be adjacent.
    let unforced = M::oscillator(&base).amplitude == 0.0;
    let rests: Vec<f64> = transitions
        .iter()
        .filter(|u| u.kind == TransitionKind::SteadySliding)
        .map(|u| u.value)
        .collect();
    let mut unique: Vec<Transition> = Vec::with_capacity(transitions.len());
    for t in transitions {
        let near = |u: &Transition| (u.value - t.value).abs() < 1e-8 * t.value.abs().max(1.0);
        let same = |u: &Transition| near(u) && u.kind == t.kind && u.boundary == t.boundary;
        // Of an unforced model, whose unstable cycles are followed past
        // their excursions, a change of structure met from both of its
        // sides (A -> B, and B's own end at that value) is one transition
        // too: the first kept, unless only the second names the structure
        // on the other side.
        if let Some(u) = unique
            .iter_mut()
            .find(|u| unforced && same(u) && u.from == t.to)
        {
            if !u.to.starts_with('P') && !u.to.starts_with('(') {
                *u = t;
            }
            continue;
        }
        // An unstable autonomous cycle shrinking onto steady sliding where
        // it changes stability is that transition.
        let onto_rest = t.kind == TransitionKind::Grazing
            && rests
                .iter()
                .any(|r| (r - t.value).abs() < 1e-8 * t.value.abs().max(1.0));
        let seen = unique
            .iter()
            .any(|u| same(u) && (u.from == t.from || (unforced && u.to == t.from)));
        if !seen && !onto_rest {
            unique.push(t);
        }
    }
    let transitions = unique;
    Ok((
        Sweep {
            param: name.to_string(),
            points,
            transitions,
            branches,
            bifurcations,
            cuts,
            cascades,
        },
        explorer.branches,
    ))
}
