//! Bifurcation diagrams: periodic motions followed along one parameter by
//! continuation, with every transition located precisely (SPEC §3, §9, §10).
//!
//! Each branch is followed grid point by grid point with Newton from the
//! previous solution. Where a motion stops being admissible or stable, the
//! condition that fails has a signed margin that crosses zero (an input force
//! at a stick onset, the distance of an arc's velocity extremum to a
//! boundary, the duration of a stick, `1 − |λ|max`, ...). The transition is
//! the root of that margin as a function of the parameter, each evaluation
//! solving the motion's equations at that parameter value: the motion's
//! equations together with the vanishing condition, solved to about 1e-12 in
//! the parameter. Just past it a simulation finds what lives there, which is
//! followed in turn. The sweep runs both ways, so that motions coexisting in
//! hysteresis (bistable) windows are all reported, and a simulation that
//! settles on a cycle of N > 1 forcing periods reports it with its N.

use serde::Serialize;

use crate::dynamics::simulate::{Location, Segment, SimOptions, Simulator};
use crate::model::param::{ParamError, ParamSet};
use crate::model::Model;
use crate::orbit::admissible::{conditions, ViolationKind};
use crate::orbit::attractor::{self, Attractor, AttractorOptions, NoMotion, PermanentStick};
use crate::orbit::motion::{solve, solve_with, Motion, OrbitError};
use crate::orbit::periodic::{NewtonOptions, SwitchingPoint};
use crate::orbit::stability::Stability;
use crate::orbit::structure::Structure;

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
    /// For NM, the largest velocity of the steady response.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_v: Option<f64>,
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
    /// Not a parameter of the model.
    #[error("`{0}` is not a free parameter of the model")]
    UnknownParam(String),
    /// A bad range.
    #[error("bad sweep range: {0}")]
    Range(String),
    /// The first motion could not be found.
    #[error(transparent)]
    Orbit(#[from] OrbitError),
}

/// The sweep's settings.
#[derive(Clone, Copy, Debug)]
pub struct SweepOptions {
    /// Transitions are located to this absolute tolerance in the parameter.
    pub tolerance: f64,
    /// Options of the simulations that find new motions.
    pub attractor: AttractorOptions,
}

impl Default for SweepOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            attractor: AttractorOptions {
                max_periods: 1500,
                ..AttractorOptions::default()
            },
        }
    }
}

/// The state of a followed branch.
#[derive(Clone, Debug)]
enum Branch {
    Periodic {
        structure: Structure,
        points: Vec<SwitchingPoint>,
    },
    NoMotion {
        domain: usize,
    },
    Lost,
}

fn with<P: ParamSet>(base: &P, index: usize, value: f64) -> Result<P, ParamError> {
    let mut p = *base;
    p.set(index, value);
    p.check()?;
    Ok(p)
}

fn summary<M: Model>(m: &Motion) -> MotionSummary {
    let st = m
        .stability
        .unwrap_or_else(|| Stability::of(&nalgebra::Matrix2::zeros()));
    MotionSummary {
        structure: m.structure.notation(M::INFO),
        n: m.structure.periods(),
        start_wt: m.points[0].phase.rem_euclid(TAU),
        start_x: m.points[0].x,
        eigenvalues: st.eigenvalues.to_vec(),
        stable: st.is_stable(),
        max_v: None,
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

fn nm_summary(nm: &NoMotion) -> MotionSummary {
    MotionSummary {
        structure: "NM".into(),
        n: 1,
        start_wt: f64::NAN,
        start_x: f64::NAN,
        eigenvalues: vec![],
        stable: true,
        max_v: Some(nm.max_v),
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
        max_v: None,
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

/// Which margin to follow to locate a transition.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Watch {
    Condition {
        kind: ViolationKind,
        segment: usize,
        boundary: Option<usize>,
    },
    Stability,
}

fn kind_of(watch: Watch, eigenvalue: [f64; 2]) -> TransitionKind {
    match watch {
        Watch::Stability if eigenvalue[1] != 0.0 => TransitionKind::NeimarkSacker,
        Watch::Stability if eigenvalue[0] > 0.0 => TransitionKind::Fold,
        Watch::Stability => TransitionKind::PeriodDoubling,
        Watch::Condition { kind, .. } => match kind {
            ViolationKind::Interior | ViolationKind::Arrival | ViolationKind::Departure => {
                TransitionKind::Grazing
            }
            ViolationKind::StickOnset => TransitionKind::PassableOnset,
            ViolationKind::Pass => TransitionKind::StickOnset,
            ViolationKind::StickEnd | ViolationKind::Duration => TransitionKind::StickVanishing,
            ViolationKind::Other => TransitionKind::Grazing,
        },
    }
}

/// Solve at one parameter value and evaluate the watched margin (or, with
/// `None`, find the most violated condition).
struct Probe<'a, M: Model> {
    base: &'a M::Params,
    index: usize,
    structure: &'a Structure,
}

impl<M: Model> Probe<'_, M> {
    fn solve(&self, value: f64, guess: &[SwitchingPoint]) -> Option<(Motion, Simulator<M>)> {
        let p = with(self.base, self.index, value).ok()?;
        let sim = Simulator::<M>::new(p, SimOptions::default()).ok()?;
        let m = solve_with(
            &sim,
            self.structure.clone(),
            guess.to_vec(),
            NewtonOptions::default(),
            false,
        );
        m.termination.converged().then_some((m, sim))
    }

    /// The smallest margin and what it watches (stability counts as `1 − |λ|`).
    fn worst(&self, sim: &Simulator<M>, m: &Motion) -> (f64, Watch) {
        let mut best = (f64::INFINITY, Watch::Stability);
        for c in conditions(sim, &m.structure, &m.points) {
            let margin = if c.margin.is_nan() { -1.0 } else { c.margin };
            if margin < best.0 {
                best = (
                    margin,
                    Watch::Condition {
                        kind: c.kind,
                        segment: c.segment,
                        boundary: c.boundary,
                    },
                );
            }
        }
        if let Some(st) = m.stability {
            let margin = 1.0 - st.largest_modulus;
            if margin < best.0 {
                best = (margin, Watch::Stability);
            }
        }
        best
    }

    fn margin(&self, sim: &Simulator<M>, m: &Motion, watch: Watch) -> f64 {
        match watch {
            Watch::Stability => m.stability.map_or(f64::NAN, |s| 1.0 - s.largest_modulus),
            Watch::Condition {
                kind,
                segment,
                boundary,
            } => conditions(sim, &m.structure, &m.points)
                .into_iter()
                .filter(|c| c.kind == kind && c.segment == segment && c.boundary == boundary)
                .map(|c| c.margin)
                .fold(f64::NAN, |a: f64, b| if a.is_nan() { b } else { a.min(b) }),
        }
    }
}

/// Locate where the margin of `watch` crosses zero between `good` (positive
/// margin, solution `good_pts`) and `bad`, by regula falsi (Illinois) safeguarded
/// with bisection; each evaluation re-solves the motion from the nearest good
/// solution. Returns the last good value and its points.
fn locate<M: Model>(
    probe: &Probe<'_, M>,
    watch: Watch,
    mut good: (f64, f64, Vec<SwitchingPoint>),
    mut bad: (f64, f64),
    tol: f64,
) -> (f64, Vec<SwitchingPoint>) {
    let mut side = 0i8;
    for _ in 0..200 {
        if (good.0 - bad.0).abs() <= tol {
            break;
        }
        let (g0, g1) = (good.1, bad.1);
        let mut t = if g0.is_finite() && g1.is_finite() && g0 != g1 {
            let (wg, wb) = match side {
                1 => (0.5, 1.0),
                -1 => (1.0, 0.5),
                _ => (1.0, 1.0),
            };
            good.0 + (bad.0 - good.0) * (wg * g0) / (wg * g0 - wb * g1)
        } else {
            0.5 * (good.0 + bad.0)
        };
        // Keep the trial strictly inside and away from the ends.
        let (lo, hi) = (good.0.min(bad.0), good.0.max(bad.0));
        let span = hi - lo;
        if !(t > lo + 1e-3 * span && t < hi - 1e-3 * span) {
            t = 0.5 * (good.0 + bad.0);
        }
        match probe.solve(t, &good.2) {
            Some((m, sim)) => {
                let g = probe.margin(&sim, &m, watch);
                if g > 0.0 {
                    good = (t, g, m.points);
                    side = if side == 1 { 2 } else { 1 };
                } else {
                    bad = (t, if g.is_nan() { f64::NAN } else { g });
                    side = if side == -1 { -2 } else { -1 };
                }
            }
            None => {
                bad = (t, f64::NAN);
                side = 0;
            }
        }
        if side.abs() == 2 {
            side = 0;
        }
    }
    (good.0, good.2)
}

/// Follow one direction through the grid `values` (in the order given).
fn follow<M: Model>(
    base: &M::Params,
    index: usize,
    values: &[f64],
    opts: &SweepOptions,
    found: &mut [Vec<MotionSummary>],
    transitions: &mut Vec<Transition>,
) -> Result<(), SweepError> {
    let info = M::INFO;
    let first = with(base, index, values[0])?;
    let sim = Simulator::<M>::new(first, SimOptions::default()).map_err(OrbitError::from)?;
    let start = sim.start(0.0, 0.0, 0.0).map_err(OrbitError::from)?;
    let mut branch = match attractor::find(&sim, start, opts.attractor) {
        Ok(Attractor::Periodic(m)) => {
            found[0].push(summary::<M>(&m));
            Branch::Periodic {
                structure: m.structure,
                points: m.points,
            }
        }
        Ok(Attractor::NoMotion(nm)) => {
            found[0].push(nm_summary(&nm));
            Branch::NoMotion { domain: nm.domain }
        }
        Ok(Attractor::Stick(s)) => {
            found[0].push(stick_summary(&s));
            Branch::Lost
        }
        // Unforced: no periodic motion in forcing periods to follow.
        Ok(Attractor::Autonomous(_)) => Branch::Lost,
        Err(_) => Branch::Lost,
    };
    let mut prev = values[0];
    for (i, &value) in values.iter().enumerate().skip(1) {
        let mut guard = 0;
        loop {
            guard += 1;
            match branch.clone() {
                Branch::Periodic { structure, points } => {
                    let probe = Probe::<M> {
                        base,
                        index,
                        structure: &structure,
                    };
                    let at = probe.solve(value, &points).map(|(m, sim)| {
                        let (w, watch) = probe.worst(&sim, &m);
                        (m, w, watch)
                    });
                    if let Some((m, w, _)) = &at {
                        if *w > 0.0 {
                            found[i].push(summary::<M>(m));
                            branch = Branch::Periodic {
                                structure,
                                points: m.points.clone(),
                            };
                            break;
                        }
                    }
                    // The motion ends between prev and value: which margin, where.
                    let good_sim =
                        Simulator::<M>::new(with(base, index, prev)?, SimOptions::default())
                            .map_err(OrbitError::from)?;
                    let good_m = solve(
                        &good_sim,
                        structure.clone(),
                        points.clone(),
                        NewtonOptions::default(),
                    );
                    let watch = match &at {
                        Some((_, _, watch)) => *watch,
                        None => probe.worst(&good_sim, &good_m).1,
                    };
                    let g_good = probe
                        .margin(&good_sim, &good_m, watch)
                        .max(f64::MIN_POSITIVE);
                    let g_bad = at.as_ref().map_or(f64::NAN, |(m, _, _)| {
                        let sim = Simulator::<M>::new(
                            with(base, index, value).expect("checked"),
                            SimOptions::default(),
                        )
                        .expect("checked");
                        probe.margin(&sim, m, watch)
                    });
                    let (edge, edge_pts) = locate(
                        &probe,
                        watch,
                        (prev, g_good, good_m.points.clone()),
                        (value, g_bad),
                        opts.tolerance,
                    );
                    // What lives just past it: simulate from the end of the old motion.
                    let boundary = match watch {
                        Watch::Condition {
                            boundary: Some(k), ..
                        } => Some(info.boundaries[k].label.to_string()),
                        _ => None,
                    };
                    // Just past the transition; a little further if the motion
                    // there is too close to it to settle (or to be checked).
                    let dir = (value - prev).signum();
                    let mut past = edge;
                    let mut found_next = (Branch::Lost, "unsettled".to_string());
                    for rel in [1e-7, 1e-5, 1e-3] {
                        let step = (rel * edge.abs().max(1.0))
                            .min(0.5 * (value - edge).abs())
                            .max(4.0 * opts.tolerance);
                        past = edge + dir * step;
                        found_next = settle::<M>(base, index, past, &structure, &edge_pts, opts);
                        if !matches!(found_next.0, Branch::Lost) {
                            break;
                        }
                    }
                    let (next_branch, to) = found_next;
                    transitions.push(Transition {
                        value: edge,
                        from: structure.notation(info),
                        to,
                        kind: kind_of(
                            watch,
                            good_m.stability.map_or([0.0; 2], |st| st.eigenvalues[0]),
                        ),
                        boundary,
                    });
                    branch = next_branch;
                    prev = past;
                    if guard > 8 {
                        break;
                    }
                }
                Branch::NoMotion { domain } => {
                    let p = with(base, index, value)?;
                    let sim =
                        Simulator::<M>::new(p, SimOptions::default()).map_err(OrbitError::from)?;
                    if let Some(nm) = steady_nm(&sim, domain) {
                        found[i].push(nm_summary(&nm));
                        break;
                    }
                    // The forced response grazes a boundary between prev and value.
                    let (mut lo, mut hi) = (prev, value);
                    for _ in 0..200 {
                        if (hi - lo).abs() <= opts.tolerance {
                            break;
                        }
                        let mid = 0.5 * (lo + hi);
                        let ok = with(base, index, mid)
                            .ok()
                            .and_then(|p| Simulator::<M>::new(p, SimOptions::default()).ok())
                            .and_then(|s| steady_nm(&s, domain))
                            .is_some();
                        if ok {
                            lo = mid
                        } else {
                            hi = mid
                        }
                    }
                    let past = hi;
                    let (next_branch, to) = settle_from_rest::<M>(base, index, past, opts);
                    let dom = info.domains[domain];
                    let boundary = [dom.upper, dom.lower]
                        .into_iter()
                        .flatten()
                        .next()
                        .map(|k| info.boundaries[k].label.to_string());
                    transitions.push(Transition {
                        value: lo,
                        from: "NM".into(),
                        to,
                        kind: TransitionKind::Grazing,
                        boundary,
                    });
                    branch = next_branch;
                    prev = past;
                    if guard > 8 {
                        break;
                    }
                }
                Branch::Lost => {
                    let (b, _) = settle_from_rest::<M>(base, index, value, opts);
                    if let Branch::Periodic { structure, points } = &b {
                        let p = with(base, index, value)?;
                        let sim = Simulator::<M>::new(p, SimOptions::default())
                            .map_err(OrbitError::from)?;
                        let m = solve(
                            &sim,
                            structure.clone(),
                            points.clone(),
                            NewtonOptions::default(),
                        );
                        if m.is_admissible() {
                            found[i].push(summary::<M>(&m));
                        }
                    } else if let Branch::NoMotion { domain } = &b {
                        let p = with(base, index, value)?;
                        let sim = Simulator::<M>::new(p, SimOptions::default())
                            .map_err(OrbitError::from)?;
                        if let Some(nm) = steady_nm(&sim, *domain) {
                            found[i].push(nm_summary(&nm));
                        }
                    }
                    branch = b;
                    break;
                }
            }
        }
        prev = value;
    }
    Ok(())
}

/// The steady forced response in `domain`, if it stays inside the band.
fn steady_nm<M: Model>(sim: &Simulator<M>, domain: usize) -> Option<NoMotion> {
    // On the forced response itself the homogeneous part is zero.
    let p = sim.params();
    let co = M::coefficients(p, domain);
    let osc = sim.oscillator();
    let (d, c, w) = (0.5 * co.two_d, co.c, osc.frequency);
    let den = (c - w * w).powi(2) + (2.0 * d * w).powi(2);
    let a = osc.amplitude * (c - w * w) / den;
    let b = 2.0 * d * w * osc.amplitude / den;
    let x = a - co.b / c;
    let v = w * b;
    attractor::no_motion_certificate(sim, domain, x, v, 0.0)
}

fn settle_from_rest<M: Model>(
    base: &M::Params,
    index: usize,
    value: f64,
    opts: &SweepOptions,
) -> (Branch, String) {
    let Ok(p) = with(base, index, value) else {
        return (Branch::Lost, "invalid".into());
    };
    let Ok(sim) = Simulator::<M>::new(p, SimOptions::default()) else {
        return (Branch::Lost, "invalid".into());
    };
    let Ok(start) = sim.start(0.0, 0.0, 0.0) else {
        return (Branch::Lost, "invalid".into());
    };
    to_branch::<M>(attractor::find(&sim, start, opts.attractor))
}

fn to_branch<M: Model>(a: Result<Attractor, OrbitError>) -> (Branch, String) {
    match a {
        Ok(Attractor::Periodic(m)) => {
            let name = if m.structure.periods() > 1 {
                format!(
                    "{}^{}",
                    m.structure.notation(M::INFO),
                    m.structure.periods()
                )
            } else {
                m.structure.notation(M::INFO)
            };
            (
                Branch::Periodic {
                    structure: m.structure,
                    points: m.points,
                },
                name,
            )
        }
        Ok(Attractor::NoMotion(nm)) => (Branch::NoMotion { domain: nm.domain }, "NM".into()),
        Ok(Attractor::Stick(_)) => (Branch::Lost, "stick".into()),
        Ok(Attractor::Autonomous(_)) => (Branch::Lost, "autonomous".into()),
        Err(_) => (Branch::Lost, "unsettled".into()),
    }
}

/// Simulate at `value` from the first switching point of the old motion.
fn settle<M: Model>(
    base: &M::Params,
    index: usize,
    value: f64,
    old: &Structure,
    pts: &[SwitchingPoint],
    opts: &SweepOptions,
) -> (Branch, String) {
    let Ok(p) = with(base, index, value) else {
        return (Branch::Lost, "invalid".into());
    };
    let Ok(sim) = Simulator::<M>::new(p, SimOptions::default()) else {
        return (Branch::Lost, "invalid".into());
    };
    let info = M::INFO;
    let first = info.mappings[old.steps()[0]];
    let start = match first.domain {
        Some(j) => Segment {
            x: pts[0].x,
            v: sim.velocity(first.from),
            phase: pts[0].phase,
            location: Location::Domain(j),
            search_from: pts[0].phase,
        },
        None => Segment {
            x: pts[0].x,
            v: sim.velocity(first.from),
            phase: pts[0].phase,
            location: Location::Stick,
            search_from: pts[0].phase,
        },
    };
    to_branch::<M>(attractor::find(&sim, start, opts.attractor))
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
    let index = <M::Params as ParamSet>::index_of(name)
        .ok_or_else(|| SweepError::UnknownParam(name.to_string()))?;
    if count < 2 || !from.is_finite() || !to.is_finite() || from >= to {
        return Err(SweepError::Range(format!(
            "{name}={from}:{to}:{count}: need from < to and at least 2 points"
        )));
    }
    let values: Vec<f64> = (0..count)
        .map(|i| from + (to - from) * i as f64 / (count - 1) as f64)
        .collect();
    let mut up: Vec<Vec<MotionSummary>> = vec![Vec::new(); count];
    let mut transitions = Vec::new();
    follow::<M>(&base, index, &values, &opts, &mut up, &mut transitions)?;
    let rev: Vec<f64> = values.iter().rev().copied().collect();
    let mut down: Vec<Vec<MotionSummary>> = vec![Vec::new(); count];
    follow::<M>(&base, index, &rev, &opts, &mut down, &mut transitions)?;
    down.reverse();
    let points = values
        .iter()
        .zip(up.into_iter().zip(down))
        .map(|(&value, (mut a, b))| {
            for m in b {
                if !a.iter().any(|x| x.same_as(&m)) {
                    a.push(m);
                }
            }
            SweepPoint { value, motions: a }
        })
        .collect();
    transitions.sort_by(|a, b| a.value.total_cmp(&b.value));
    transitions
        .dedup_by(|a, b| (a.value - b.value).abs() < 1e-8 && a.kind == b.kind && a.from == b.from);
    Ok(Sweep {
        param: name.to_string(),
        points,
        transitions,
        branches: Vec::new(),
        bifurcations: Vec::new(),
    })
}
