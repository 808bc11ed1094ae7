//! Pseudo-arclength continuation of the periodic motions of one structure in
//! one parameter (the bordered system: [`super::bordered`]).
//!
//! From a point `X = (u, λ)` with unit tangent `t`, the predictor is
//! `X + ds t` and the corrector is Newton on the mapping equations with the
//! hyperplane through the predictor normal to `t`. A step is rejected (and
//! halved) when the corrector fails, moves the point by more than half the
//! step, turns the tangent by more than about 37°, or moves an eigenvalue of
//! `DP` by more than 0.25, so that neither a test function nor a margin can
//! change sign twice unseen; it grows by 1.5 after an easy correction.
//!
//! At each accepted point: `DP`, its eigenvalues and every admissibility
//! margin of SPEC §6 (`orbit::admissible::worst_margin`). Where the smallest
//! margin reaches zero the branch ends at a non-smooth transition, located
//! in arclength by regula falsi (each trial a corrected point) to
//! `transition_tolerance` in the parameter. The eigenvalue bifurcations are
//! the sign changes of the test functions over a step (`detect`),
//! located the same way to `bifurcation_tolerance` and inserted in the
//! branch.

use nalgebra::Vector2;

use crate::bifurcation::bordered::{Bordered, Correction, State, Vector};
use crate::bifurcation::branch::{Bifurcation, Branch, BranchEnd, BranchPoint, EndReason};
use crate::bifurcation::detect::{self, Tests};
use crate::bifurcation::locate::regula_falsi;
use crate::bifurcation::TransitionKind;
use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::param::ParamError;
use crate::model::{Model, ParamSet};
use crate::orbit::admissible::{worst_margin, ViolationKind};
use crate::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};
use crate::orbit::stability::Stability;
use crate::orbit::structure::Structure;

/// Settings of a continuation. Steps are arclengths in the scaled metric
/// (displacements over the motion's length scale, phases in radians, each
/// switching point weighted `1/m`, the parameter over the bounds' span), so
/// a step of `0.01` moves the parameter by at most 1 % of the span.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContinuationOptions {
    /// The parameter interval `[lo, hi]`; a branch ends on its bounds.
    pub bounds: (f64, f64),
    /// The first step.
    pub initial_step: f64,
    /// Below this step the corrector's failure ends the branch.
    pub min_step: f64,
    /// The largest step.
    pub max_step: f64,
    /// At most this many points per branch (per direction).
    pub max_points: usize,
    /// Eigenvalue bifurcations are located to this in the parameter.
    pub bifurcation_tolerance: f64,
    /// Non-smooth transitions are located to this in the parameter.
    pub transition_tolerance: f64,
    /// The corrector's tolerance (natural units, as [`NewtonOptions`]) and iteration limit.
    pub newton: NewtonOptions,
}

impl Default for ContinuationOptions {
    fn default() -> Self {
        Self {
            bounds: (0.0, 1.0),
            initial_step: 1e-2,
            min_step: 1e-9,
            max_step: 0.2,
            max_points: 5000,
            bifurcation_tolerance: 1e-10,
            transition_tolerance: 1e-12,
            newton: NewtonOptions {
                tolerance: 1e-12,
                max_iterations: 12,
            },
        }
    }
}

/// A direction in the space of switching points and parameter: `points[k]`
/// holds `(δ(W t_k), δx_k)` as a [`SwitchingPoint`], `value` holds `δλ`.
/// Its length does not matter.
#[derive(Clone, Debug, PartialEq)]
pub struct Direction {
    /// Components along the switching points.
    pub points: Vec<SwitchingPoint>,
    /// Component along the parameter.
    pub value: f64,
}

/// Where a branch starts.
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    /// The structure.
    pub structure: Structure,
    /// The parameter value.
    pub value: f64,
    /// The switching points (a guess, corrected at `value`, when `direction`
    /// is `None`; a solution when it is given).
    pub points: Vec<SwitchingPoint>,
    /// `None`: compute the tangent and follow both ways. `Some(d)`: follow
    /// one way only, along `d` (a branch born at a bifurcation).
    pub direction: Option<Direction>,
}

/// Why a continuation could not start.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ContinuationError {
    /// Invalid parameters at the start.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// Bad bounds or options.
    #[error("bad continuation options: {0}")]
    Options(String),
    /// The start has the wrong number of points or is not finite.
    #[error("bad start: {0}")]
    Start(String),
    /// The start did not converge.
    #[error("the start does not solve the mapping equations: {0}")]
    NotConverged(String),
    /// The start is not a motion.
    #[error("the start is not a motion: {0}")]
    Inadmissible(String),
}

/// The non-smooth transition where a condition of kind `kind` starts to fail.
pub fn transition_kind(kind: ViolationKind) -> TransitionKind {
    match kind {
        ViolationKind::Interior | ViolationKind::Arrival | ViolationKind::Departure => {
            TransitionKind::Grazing
        }
        ViolationKind::StickOnset => TransitionKind::PassableOnset,
        ViolationKind::Pass => TransitionKind::StickOnset,
        ViolationKind::StickEnd | ViolationKind::Duration => TransitionKind::StickVanishing,
        ViolationKind::Other => TransitionKind::Grazing,
    }
}

/// An accepted point with everything the stepping needs.
#[derive(Clone, Debug)]
struct Sample {
    state: State,
    tangent: Vector,
    point: BranchPoint,
    /// The smallest admissibility margin (NaN counts as −∞) and its condition.
    margin: f64,
    worst: Option<(ViolationKind, Option<usize>)>,
    tests: Tests,
}

/// What one direction of a branch produced.
struct Run {
    points: Vec<BranchPoint>,
    bifurcations: Vec<Bifurcation>,
    end: BranchEnd,
}

/// Everything examined at a corrected point, or why it is not usable.
struct Continuer<'a, M: Model> {
    sys: Bordered<M>,
    opts: &'a ContinuationOptions,
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

impl<M: Model> Continuer<'_, M> {
    /// The margins, `DP` and stability at `x` (with its tangent).
    fn examine(&self, x: State, tangent: Vector) -> Result<Sample, String> {
        let p = self.sys.params(x.value);
        p.check().map_err(|e| format!("invalid parameters: {e}"))?;
        let dp = self
            .sys
            .poincare_jacobian(&x)
            .map_err(|k| format!("mapping {k}: the arrival is tangent to the boundary"))?;
        let stability = Stability::of(&dp);
        let sim = Simulator::<M>::new(p, SimOptions::default()).map_err(|e| e.to_string())?;
        let (margin, worst) = match worst_margin(&sim, self.sys.structure(), &x.points) {
            Some(w) if w.margin.is_nan() => (f64::NEG_INFINITY, Some((w.kind, w.boundary))),
            Some(w) => (w.margin, Some((w.kind, w.boundary))),
            None => (f64::INFINITY, None),
        };
        let tests = Tests::of(&dp, tangent.dl);
        Ok(Sample {
            point: BranchPoint {
                value: x.value,
                points: x.points.clone(),
                dp,
                stability,
            },
            state: x,
            tangent,
            margin,
            worst,
            tests,
        })
    }

    /// The corrected point at arclength `s` from `from` along its tangent
    /// (predictor `from + s t`, hyperplane normal to `t` through it), with
    /// its tangent; `None` if the corrector fails.
    fn point_at(&mut self, from: &Sample, s: f64) -> Result<(State, Vector, usize), String> {
        let (x, it) = self.corrected(from, s, self.opts.newton.max_iterations)?;
        let mut t = from.tangent.clone();
        self.sys
            .tangent(&x, &from.tangent, &mut t)
            .map_err(|e| e.describe())?;
        Ok((x, t, it))
    }

    /// The corrected point at arclength `s` from `from` (no tangent).
    fn corrected(
        &mut self,
        from: &Sample,
        s: f64,
        max_iterations: usize,
    ) -> Result<(State, usize), String> {
        let mut x = from.state.clone();
        Bordered::<M>::advance(&from.state, s, &from.tangent, &mut x);
        self.corrected_from(from, s, x, max_iterations)
    }

    /// [`Self::corrected`], Newton started from `guess` (on the same
    /// hyperplane, normal to `from`'s tangent at arclength `s`).
    fn corrected_from(
        &mut self,
        from: &Sample,
        s: f64,
        mut x: State,
        max_iterations: usize,
    ) -> Result<(State, usize), String> {
        let mut anchor = x.clone();
        Bordered::<M>::advance(&from.state, s, &from.tangent, &mut anchor);
        let it = match self.sys.correct(
            &mut x,
            &from.tangent,
            &anchor,
            self.opts.newton.tolerance,
            max_iterations,
        ) {
            Correction::Converged { iterations } => iterations,
            Correction::Failed(why) => return Err(why),
        };
        Ok((x, it))
    }

    /// Regula falsi (Illinois) in arclength on `g` over `[0, s_bad]` from
    /// `from` (`g > 0` there, `g(s_bad) <= 0` or undefined; `bad`: the
    /// corrected point there) until the bracket is below `s_tol`
    /// ([`super::locate::regula_falsi`]); returns the last good sample (or
    /// `from`) and the last bad one.
    ///
    /// Each trial is corrected on the hyperplane at its arclength from the
    /// chord between the bracket's ends (from the last good one along the
    /// step's tangent while the bad end has no point): the predictor from
    /// `from` along its tangent is off the branch by the branch's curvature
    /// times the whole step squared, and where another solution family
    /// crosses the branch (a mapping shrinking to nothing: the solutions in
    /// which it takes no time at all, near the branch's end) Newton from
    /// there may converge onto that family, whose margins are not the
    /// branch's, and the bracket closes on a point where no transition is.
    fn locate(
        &mut self,
        from: &Sample,
        (s_bad, bad): (f64, Option<&State>),
        g_bad: f64,
        s_tol: f64,
        g: impl Fn(&Sample) -> f64,
    ) -> (Sample, Option<Sample>) {
        let iterations = 4 * self.opts.newton.max_iterations;
        let g = &g;
        let mut lo = (0.0, from.state.clone());
        let mut hi = bad.map(|x| (s_bad, x.clone()));
        // No tangent at the trials: near a branch point it is ill-posed,
        // and the located quantities do not need it (the trial keeps
        // the step's tangent; a fold is classified by the step's ends).
        let trial = |s: f64| {
            let mut guess = lo.1.clone();
            match &hi {
                Some((sh, xh)) if *sh > lo.0 => {
                    let theta = (s - lo.0) / (sh - lo.0);
                    for ((q, a), b) in guess.points.iter_mut().zip(&lo.1.points).zip(&xh.points) {
                        q.x = a.x + theta * (b.x - a.x);
                        q.phase = a.phase + theta * (b.phase - a.phase);
                    }
                    guess.value = lo.1.value + theta * (xh.value - lo.1.value);
                }
                _ => Bordered::<M>::advance(&lo.1, s - lo.0, &from.tangent, &mut guess),
            }
            let smp = self
                .corrected_from(from, s, guess, iterations)
                .and_then(|(x, _)| self.examine(x, from.tangent.clone()));
            // The bracket's ends as regula falsi moves them.
            match &smp {
                Ok(x) if g(x) > 0.0 => lo = (s, x.state.clone()),
                Ok(x) => hi = Some((s, x.state.clone())),
                Err(_) => hi = None,
            }
            smp.ok()
        };
        let (good, bad) = regula_falsi(g(from), s_bad, g_bad, s_tol, trial, g);
        (good.unwrap_or_else(|| from.clone()), bad)
    }

    /// The bifurcations whose test functions change sign between `a` and
    /// `b` (`b` at arclength `s_b` from `a`), located and in arclength order.
    fn bifurcations(&mut self, a: &Sample, b: &Sample, s_b: f64) -> Vec<(Sample, TransitionKind)> {
        let mut found = Vec::new();
        for (kind, which) in detect::crossings(&a.tests, &b.tests) {
            let g = move |s: &Sample| which.sign_from(&a.tests) * s.tests.value(which);
            let g_b = g(b);
            let s_tol = (self.opts.bifurcation_tolerance / self.sys.span).min(1e-11);
            let (good, bad) = self.locate(a, (s_b, Some(&b.state)), g_b, s_tol, g);
            // The end of the bracket with the smaller test function.
            let at = match bad {
                Some(bd) if bd.tests.value(which).abs() < good.tests.value(which).abs() => bd,
                _ => good,
            };
            if at.margin > 0.0 && detect::is_critical(kind, &at.point.stability) {
                found.push((at, kind));
            }
        }
        found.sort_by(|x, y| {
            let sx = self.sys.dot_diff(&a.tangent, &x.0.state, &a.state);
            let sy = self.sys.dot_diff(&a.tangent, &y.0.state, &a.state);
            sx.total_cmp(&sy)
        });
        found
    }

    /// The corrected point on the parameter bound `bound`, between `a` and `b`.
    fn on_bound(&mut self, a: &Sample, b: &State, bound: f64) -> Option<Sample> {
        let theta = (bound - a.state.value) / (b.value - a.state.value);
        let mut x = a.state.clone();
        for ((q, p0), p1) in x.points.iter_mut().zip(&a.state.points).zip(&b.points) {
            q.x = p0.x + theta * (p1.x - p0.x);
            q.phase = p0.phase + theta * (p1.phase - p0.phase);
        }
        x.value = bound;
        let anchor = x.clone();
        let border = Vector::parameter(x.points.len());
        match self.sys.correct(
            &mut x,
            &border,
            &anchor,
            self.opts.newton.tolerance,
            self.opts.newton.max_iterations,
        ) {
            Correction::Converged { .. } => {}
            Correction::Failed(_) => return None,
        }
        x.value = bound;
        let mut t = a.tangent.clone();
        self.sys.tangent(&x, &a.tangent, &mut t).ok()?;
        self.examine(x, t).ok()
    }

    /// Whether the step from `a` to `b` passes the start again (phases
    /// compared modulo 2π: the same motion relabelled).
    fn passes_start(&self, start: &Sample, a: &Sample, b: &Sample) -> bool {
        // An autonomous cycle's phases are absolute (its return at 0).
        let turns = if self.sys.structure().is_autonomous() {
            0.0
        } else {
            ((b.state.points[0].phase - start.state.points[0].phase) / std::f64::consts::TAU)
                .round()
        };
        let mut x0 = start.state.clone();
        for q in &mut x0.points {
            q.phase += turns * std::f64::consts::TAU;
        }
        let step = self.sys.distance(&a.state, &b.state);
        if step == 0.0 {
            return false;
        }
        // The nearest point of the segment a–b to x0.
        let mut seg = Vector::zeros(x0.points.len());
        for ((d, p), q) in seg.du.iter_mut().zip(&b.state.points).zip(&a.state.points) {
            *d = Vector2::new(p.x - q.x, p.phase - q.phase);
        }
        seg.dl = b.state.value - a.state.value;
        let theta = (self.sys.dot_diff(&seg, &x0, &a.state) / (step * step)).clamp(0.0, 1.0);
        let mut near = a.state.clone();
        Bordered::<M>::advance(&a.state, theta, &seg, &mut near);
        self.sys.distance(&near, &x0) <= 0.25 * step
    }

    /// Follow from `start` along its tangent until an end.
    fn run(&mut self, start: Sample, loop_check: bool) -> Run {
        let opts = *self.opts;
        let (lo, hi) = opts.bounds;
        let mut points = vec![start.point.clone()];
        let mut bifs: Vec<Bifurcation> = Vec::new();
        let mut prev = start.clone();
        let mut ds = opts.initial_step;
        let mut travelled = 0.0;
        let end = |reason: EndReason, at: &Sample| BranchEnd {
            reason,
            at: at.point.clone(),
        };
        // Already on a bound and leaving the interval.
        let span_tol = opts.transition_tolerance;
        if (close(prev.state.value, lo, span_tol) && prev.tangent.dl < 0.0)
            || (close(prev.state.value, hi, span_tol) && prev.tangent.dl > 0.0)
        {
            return Run {
                points,
                bifurcations: bifs,
                end: end(EndReason::ParameterBound, &prev),
            };
        }
        loop {
            if points.len() >= opts.max_points {
                return Run {
                    points,
                    bifurcations: bifs,
                    end: end(EndReason::MaxPoints, &prev),
                };
            }
            // Predictor and corrector, with the step control.
            let accepted = self.point_at(&prev, ds).and_then(|(x, t, it)| {
                let mut pred = prev.state.clone();
                Bordered::<M>::advance(&prev.state, ds, &prev.tangent, &mut pred);
                let moved = self.sys.distance(&x, &pred);
                let turn = self.sys.dot(&t, &prev.tangent);
                if moved > 0.5 * ds {
                    return Err(format!(
                        "the corrector moves the point by {moved:.3e}, more than half the step {ds:.3e}"
                    ));
                }
                if turn < 0.8 {
                    return Err(format!("the tangent turns by {:.1}° over the step", turn.clamp(-1.0, 1.0).acos().to_degrees()));
                }
                let smp = self.examine(x, t)?;
                let jump = detect::eigenvalue_jump(&prev.point.stability, &smp.point.stability);
                if jump > 0.25 && ds > 16.0 * opts.min_step {
                    return Err(format!("an eigenvalue of DP jumps by {jump:.3e} over the step"));
                }
                Ok((smp, it))
            });
            let (mut cand, iterations) = match accepted {
                Ok(c) => c,
                Err(_) if ds > opts.min_step => {
                    ds = (0.5 * ds).max(opts.min_step);
                    continue;
                }
                Err(why) => {
                    return Run {
                        points,
                        bifurcations: bifs,
                        end: end(EndReason::NewtonFailure(why), &prev),
                    };
                }
            };
            let mut s_c = self.sys.dot_diff(&prev.tangent, &cand.state, &prev.state);
            let mut reason = None;
            // The parameter bound.
            if cand.state.value < lo || cand.state.value > hi {
                let bound = if cand.state.value < lo { lo } else { hi };
                match self.on_bound(&prev, &cand.state, bound) {
                    Some(b) => {
                        s_c = self.sys.dot_diff(&prev.tangent, &b.state, &prev.state);
                        cand = b;
                        reason = Some(EndReason::ParameterBound);
                    }
                    None => {
                        ds *= 0.5;
                        if ds >= opts.min_step {
                            continue;
                        }
                        return Run {
                            points,
                            bifurcations: bifs,
                            end: end(
                                EndReason::NewtonFailure(format!(
                                    "the corrector fails on the parameter bound {bound}"
                                )),
                                &prev,
                            ),
                        };
                    }
                }
            }
            // A non-smooth transition.
            if cand.margin.is_nan() || cand.margin <= 0.0 {
                let s_tol = opts.transition_tolerance / self.sys.span;
                let g_bad = cand.margin;
                let (mut good, _) = self.locate(
                    &prev,
                    (s_c, Some(&cand.state)),
                    g_bad,
                    s_tol,
                    |s: &Sample| s.margin,
                );
                // The located end carries the step's tangent (the trials
                // have none): its own, so that a fold on the truncated step
                // is told from a branch point by the tangent's turn.
                let mut t = prev.tangent.clone();
                if self.sys.tangent(&good.state, &prev.tangent, &mut t).is_ok() {
                    good.tests = Tests::of(&good.point.dp, t.dl);
                    good.tangent = t;
                }
                let (kind, boundary) = good
                    .worst
                    .or(cand.worst)
                    .map_or((TransitionKind::Grazing, None), |(k, b)| {
                        (transition_kind(k), b)
                    });
                s_c = self.sys.dot_diff(&prev.tangent, &good.state, &prev.state);
                cand = good;
                reason = Some(EndReason::Transition { kind, boundary });
            }
            // Eigenvalue bifurcations on the step.
            if s_c > 0.0 {
                let mut before: Option<Sample> = None;
                let mut found = self.bifurcations(&prev, &cand, s_c);
                if matches!(reason, Some(EndReason::Transition { .. })) {
                    // At a grazing arrival `DP` diverges (the arrival's
                    // block is singular), so its eigenvalues leave the unit
                    // disc as the branch's end is approached: a crossing the
                    // locator cannot tell from the end is the transition's,
                    // not a bifurcation of its own (`P_{3_33 4_33}` at its
                    // grazing of Σ3, Q0 = 100: |λ| = 0.63 at 1e-12 before
                    // the end, 1 at it). Measured in the parameter: the
                    // switching points move like the square root of the
                    // distance to a grazing, the arclength with them.
                    let tol = self.opts.bifurcation_tolerance;
                    found.retain(|(at, _)| (at.state.value - cand.state.value).abs() > tol);
                }
                for (at, kind) in found {
                    // Two bifurcations on one step (a Neimark–Sacker point
                    // and a period doubling near a 1:2 resonance): a point
                    // between them, so that the stretch between has a point
                    // of its own stability (the located points lie on the
                    // unit circle, their stability is round-off).
                    if let Some(b) = &before {
                        let sb = self.sys.dot_diff(&prev.tangent, &b.state, &prev.state);
                        let sa = self.sys.dot_diff(&prev.tangent, &at.state, &prev.state);
                        let mid = self
                            .corrected(&prev, 0.5 * (sa + sb), 4 * opts.newton.max_iterations)
                            .and_then(|(x, _)| self.examine(x, prev.tangent.clone()));
                        if let Ok(m) = mid {
                            if m.margin > 0.0 {
                                points.push(m.point);
                            }
                        }
                    }
                    before = Some(at.clone());
                    let eigenvalue = detect::critical(kind, &at.point.stability);
                    points.push(at.point.clone());
                    bifs.push(Bifurcation {
                        kind,
                        at: at.point,
                        eigenvalue,
                        index: points.len() - 1,
                    });
                }
            }
            if s_c > 0.0 || reason.is_none() {
                points.push(cand.point.clone());
            }
            travelled += s_c.abs();
            if let Some(reason) = reason {
                return Run {
                    points,
                    bifurcations: bifs,
                    end: end(reason, &cand),
                };
            }
            if loop_check
                && points.len() > 3
                && travelled > 4.0 * opts.initial_step
                && self.passes_start(&start, &prev, &cand)
            {
                return Run {
                    points,
                    bifurcations: bifs,
                    end: end(EndReason::ClosedLoop, &cand),
                };
            }
            if iterations <= 3 {
                ds = (1.5 * ds).min(opts.max_step);
            } else if iterations >= 6 {
                ds = (0.7 * ds).max(opts.min_step);
            }
            prev = cand;
        }
    }
}

fn to_vector(d: &Direction) -> Vector {
    Vector {
        du: d
            .points
            .iter()
            .map(|q| Vector2::new(q.x, q.phase))
            .collect(),
        dl: d.value,
    }
}

pub(crate) fn to_direction(v: &Vector) -> Direction {
    Direction {
        points: v
            .du
            .iter()
            .map(|d| SwitchingPoint {
                x: d[0],
                phase: d[1],
            })
            .collect(),
        value: v.dl,
    }
}

/// The bordered system for a branch through `points` at `value`: length
/// scale of the motion there, span of the bounds.
pub(crate) fn system<M: Model>(
    base: &M::Params,
    index: usize,
    structure: &Structure,
    value: f64,
    points: &[SwitchingPoint],
    opts: &ContinuationOptions,
) -> Bordered<M> {
    let mut p = *base;
    p.set(index, value);
    let length = PeriodicSolver::<M>::length_scale(&p, points);
    let span = opts.bounds.1 - opts.bounds.0;
    Bordered::new(structure.clone(), *base, index, length, span)
}

/// Follow the branch of periodic motions of `start.structure` through
/// `start` in parameter `index` of `base` (see [`Start::direction`]).
pub fn follow<M: Model>(
    base: &M::Params,
    index: usize,
    start: &Start,
    opts: &ContinuationOptions,
) -> Result<Branch, ContinuationError> {
    let (lo, hi) = opts.bounds;
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(ContinuationError::Options(format!(
            "the bounds ({lo}, {hi}) must be finite with lo < hi"
        )));
    }
    if !(opts.min_step > 0.0
        && opts.min_step <= opts.initial_step
        && opts.initial_step <= opts.max_step)
    {
        return Err(ContinuationError::Options(format!(
            "need 0 < min_step <= initial_step <= max_step (got {}, {}, {})",
            opts.min_step, opts.initial_step, opts.max_step
        )));
    }
    let m = start.structure.len();
    if start.points.len() != m {
        return Err(ContinuationError::Start(format!(
            "{} switching points for a structure of {m} mappings",
            start.points.len()
        )));
    }
    if !(start.value >= lo && start.value <= hi) {
        return Err(ContinuationError::Start(format!(
            "the start value {} lies outside the bounds ({lo}, {hi})",
            start.value
        )));
    }
    if !start
        .points
        .iter()
        .all(|q| q.x.is_finite() && q.phase.is_finite())
    {
        return Err(ContinuationError::Start(
            "a switching point is not finite".into(),
        ));
    }
    let mut p = *base;
    p.set(index, start.value);
    p.check()?;
    let held = M::oscillator(&p).amplitude == 0.0 && start.points[0].phase < 0.0;
    if start.structure.is_autonomous() && !held {
        return Err(ContinuationError::Start(
            "an autonomous cycle needs the forcing off and its return held at W t = 0".into(),
        ));
    }
    let mut sys = system::<M>(
        base,
        index,
        &start.structure,
        start.value,
        &start.points,
        opts,
    );
    let mut x = State {
        points: start.points.clone(),
        value: start.value,
    };
    // Phase origin: 0 <= W t_0 < 2π (an autonomous cycle keeps its return at 0).
    let origin = if start.structure.is_autonomous() {
        0.0
    } else {
        std::f64::consts::TAU * (x.points[0].phase / std::f64::consts::TAU).floor()
    };
    for q in &mut x.points {
        q.phase -= origin;
    }
    let (tangent, both) = match &start.direction {
        None => {
            let border = Vector::parameter(m);
            let anchor = x.clone();
            if let Correction::Failed(why) = sys.correct(
                &mut x,
                &border,
                &anchor,
                opts.newton.tolerance,
                opts.newton.max_iterations.max(40),
            ) {
                return Err(ContinuationError::NotConverged(why));
            }
            x.value = start.value;
            let mut t = Vector::parameter(m);
            sys.tangent(&x, &border, &mut t)
                .map_err(|e| ContinuationError::NotConverged(e.describe()))?;
            (t, true)
        }
        Some(d) => {
            if d.points.len() != m {
                return Err(ContinuationError::Start(format!(
                    "a direction of {} points for a structure of {m} mappings",
                    d.points.len()
                )));
            }
            let mut t = to_vector(d);
            sys.normalize(&mut t);
            if !(t.dl.is_finite() && t.du.iter().all(|v| v.iter().all(|c| c.is_finite())))
                || sys.dot(&t, &t) == 0.0
            {
                return Err(ContinuationError::Start(
                    "the direction is zero or not finite".into(),
                ));
            }
            let r = sys.residual(&x);
            let floor = 1e-9 * sys.length * M::oscillator(&p).frequency.abs().max(1.0);
            if r.is_nan() || r > floor {
                return Err(ContinuationError::NotConverged(format!(
                    "residual {r:.3e} at a start given with a direction"
                )));
            }
            (t, false)
        }
    };
    let mut run = Continuer::<M> { sys, opts };
    let first = run
        .examine(x, tangent.clone())
        .map_err(ContinuationError::Inadmissible)?;
    if first.margin.is_nan() || first.margin < 0.0 {
        return Err(ContinuationError::Inadmissible(format!(
            "an admissibility condition fails ({:?}, margin {:e})",
            first.worst, first.margin
        )));
    }
    let forward = run.run(first.clone(), both);
    if !both || forward.end.reason == EndReason::ClosedLoop {
        return Ok(Branch {
            structure: start.structure.clone(),
            points: forward.points,
            ends: vec![forward.end],
            bifurcations: forward.bifurcations,
        });
    }
    let mut back_start = first;
    back_start.tangent = tangent.neg();
    back_start.tests = Tests::of(&back_start.point.dp, back_start.tangent.dl);
    let backward = run.run(back_start, false);
    // Backward points reversed, then the forward ones (which start at the start).
    let nb = backward.points.len() - 1;
    let mut points: Vec<BranchPoint> = backward.points.into_iter().skip(1).rev().collect();
    points.extend(forward.points);
    let mut bifurcations: Vec<Bifurcation> = backward
        .bifurcations
        .into_iter()
        .map(|mut b| {
            b.index = nb - b.index;
            b
        })
        .collect();
    bifurcations.reverse();
    bifurcations.extend(forward.bifurcations.into_iter().map(|mut b| {
        b.index += nb;
        b
    }));
    Ok(Branch {
        structure: start.structure.clone(),
        points,
        ends: vec![backward.end, forward.end],
        bifurcations,
    })
}
