//! Stepping along a curve: predictor along the tangent, corrector on the
//! extended system, adaptive step, and the ends (box edge, back to the
//! start, a codimension-two point, the corrector's failure, the point
//! limit) and the special points met on the way.
//!
//! A step is rejected (and halved) when the corrector fails, moves the
//! point by more than half the step, turns the tangent by more than about
//! 37°, or moves an eigenvalue of `DP` by more than 0.25 (as
//! [`crate::bifurcation::continuation`]) unless the half step moved it as
//! much (then `DP` is singular along the curve, as on a passable onset where
//! an arrival is tangential, and its eigenvalues are noise); it grows by 1.5 after an easy
//! correction. Codimension-two points and special points are located by
//! regula falsi (Illinois) in arclength, each trial a corrected point, until
//! the bracket is below `location_tolerance` in both parameters. Where the
//! curve's system turns singular at a codimension-two point (an arrival
//! before a stick turning tangential leaves the stick's start free along
//! the stick to first order: the curves of a period-adding cascade's
//! grazings meeting its passable onsets) the trials fail short of it, and
//! the point is solved directly with both conditions
//! ([`Extended::correct_pair`]): from the last good trial, or from the last
//! point where the corrector fails at the smallest step as the other
//! margin falls towards zero.

use crate::bifurcation::bordered::Correction;
use crate::bifurcation::continuation::transition_kind;
use crate::bifurcation::detect;
use crate::bifurcation::TransitionKind;
use crate::model::{Model, ParamSet};
use crate::orbit::admissible::{ConditionId, ViolationKind, SAME_EVENT};
use crate::orbit::periodic::monodromy_spectral;
use crate::orbit::stability::Stability;

use super::condition::exit_rates;
use super::extended::Extended;
use super::stop::PAIR_REACH;
use super::{Condition, CurveEndReason, CurveOptions, Plane};
use crate::bifurcation::locate::regula_falsi;

/// An accepted point and what is watched there.
#[derive(Clone, Debug)]
pub(super) struct Sample {
    pub x: Vec<f64>,
    pub t: Vec<f64>,
    /// The smallest margin of the conditions that must keep holding (a
    /// stick's end by its smooth margin), and which.
    pub other: f64,
    pub worst: Option<ConditionId>,
    /// The same with a stick's end by the event search: where it turns
    /// non-positive a codimension-two end is located.
    pub other_event: f64,
    pub worst_event: Option<ConditionId>,
    /// How far the companions (the conditions that vanished with the
    /// curve's own at its start) lie above their floors
    /// ([`super::condition::COMPANION_SLACK`]; `+∞` without any), and
    /// which is lowest: where it turns negative a codimension-two end is
    /// located, at that companion's zero.
    pub companion: f64,
    pub companion_id: Option<ConditionId>,
    /// `det(I − DP)`, `det(I + DP)` times the sticks' exit rates
    /// ([`exit_rates`]: cleared of `DP`'s pole where an exit turns
    /// tangential, so that they change sign only where `DP` has the
    /// eigenvalue ±1; NaN without `DP`). On the curve of a stick whose exit
    /// turns tangential the raw ones flip with the rounding of that exit's
    /// rate at every step, and locating each flip as a special point made
    /// the stick-end box's run (`tests/curve_stick_end.rs`) 3× slower.
    pub plus: f64,
    pub minus: f64,
    /// `tr² − 4 det` (negative: a complex pair).
    pub disc: f64,
    pub stability: Option<Stability>,
}

/// A special point found on a step: its sample and kind, in the run's
/// numbering (between `points[index]` and `points[index + 1]`).
#[derive(Clone, Debug)]
pub(super) struct Found {
    pub index: usize,
    pub kind: TransitionKind,
    pub at: Sample,
}

/// What one direction produced.
pub(super) struct Run {
    pub points: Vec<Sample>,
    pub special: Vec<Found>,
    pub end: Option<(CurveEndReason, Sample)>,
}

/// The stepping machinery of one curve.
pub(super) struct Tracer<'a, M: Model> {
    pub sys: Extended<M>,
    pub opts: &'a CurveOptions,
    pub plane: Plane,
}

const NEWTON_ITERATIONS: usize = 12;

/// A point is accepted only where its condition holds to this fraction of
/// the condition's scale ([`Extended::held`]). The corrector's own test
/// is on the Newton step and the residuals over their rows' gradients;
/// where an interior extremum merges with a departure turning tangential
/// the gradient grows without bound and those tests passed points whose
/// condition was 5e-9 of its scale. An eigenvalue test function whose
/// rounding floor is above this also holds at that floor
/// ([`Extended::at_rounding_floor`]).
pub(super) const HOLDS_TO: f64 = 1e-10;

impl<M: Model> Tracer<'_, M> {
    /// Everything watched at a corrected point `x` with tangent `t`.
    pub fn examine(&mut self, x: Vec<f64>, t: Vec<f64>) -> Result<Sample, String> {
        let p = self.sys.params(&x);
        p.check().map_err(|e| format!("invalid parameters: {e}"))?;
        let m = (x.len() - 2) / 2;
        let mut pts = vec![crate::orbit::periodic::SwitchingPoint { phase: 0.0, x: 0.0 }; m];
        Extended::<M>::points_into(&x, &mut pts);
        let dp = if m > 0 {
            monodromy_spectral::<M>(&p, &self.sys.eval.steps, self.sys.eval.shift, &pts).ok()
        } else {
            None
        };
        let (other, worst) = self.sys.eval.other(&p, &pts);
        let (other_event, worst_event) = self.sys.eval.other_event(&p, &pts);
        let (companion, companion_id) = self.sys.eval.companion(&p, &pts);
        let (plus, minus, disc) = dp.map_or((f64::NAN, f64::NAN, f64::NAN), |d| {
            let (tr, det) = (d.trace(), d.determinant());
            let rates = exit_rates::<M>(&p, &self.sys.eval.steps, self.sys.eval.shift, &pts);
            (
                (1.0 - tr + det) * rates,
                (1.0 + tr + det) * rates,
                tr * tr - 4.0 * det,
            )
        });
        Ok(Sample {
            x,
            t,
            other,
            worst,
            other_event,
            worst_event,
            companion,
            companion_id,
            plus,
            minus,
            disc,
            stability: dp.map(|d| Stability::of(&d)),
        })
    }

    /// The corrected point at arclength `s` from `from` along its tangent.
    pub fn corrected(
        &mut self,
        from: &Sample,
        s: f64,
        max_iterations: usize,
    ) -> Result<(Vec<f64>, usize), String> {
        let mut x: Vec<f64> = from.x.iter().zip(&from.t).map(|(a, d)| a + s * d).collect();
        let anchor = x.clone();
        match self.sys.correct(
            &mut x,
            &from.t,
            &anchor,
            self.opts.tolerance,
            max_iterations,
        ) {
            Correction::Converged { iterations } => Ok((x, iterations)),
            Correction::Failed(why) => Err(why),
        }
    }

    /// Regula falsi (Illinois) in arclength on `g` over `[0, s_bad]` from
    /// `from` (`g > 0` there, `g(s_bad) <= 0` or undefined) to the location
    /// tolerance ([`crate::bifurcation::locate::regula_falsi`]); returns the
    /// last good sample (or `from`) and the last bad one.
    fn locate(
        &mut self,
        from: &Sample,
        s_bad: f64,
        g_bad: f64,
        g: impl Fn(&Sample) -> f64,
    ) -> (Sample, Option<Sample>) {
        let spans = self.sys.spans();
        let s_tol = self.opts.location_tolerance / spans[0].max(spans[1]);
        // A trial the corrector carries further from its prediction than
        // half its step is refused, as a step of [`Self::run`] is: it
        // jumped to another stretch of the curve (Shaw's second pitchfork
        // with `--edges`: a trial between W = 0.46727 and 0.46569 landed
        // at W = 0.44240, Q0 = 1.23592, where the curve had passed on its
        // way down, and was taken for the bracket's good end).
        let trial = |s: f64| {
            self.corrected(from, s, 4 * NEWTON_ITERATIONS)
                .and_then(|(x, _)| {
                    self.within_step(from, s, &x)?;
                    self.examine(x, from.t.clone())
                })
                .ok()
        };
        let (good, bad) = regula_falsi(g(from), s_bad, g_bad, s_tol, trial, g);
        (good.unwrap_or_else(|| from.clone()), bad)
    }

    /// The corrected point where the step from `a` to `b` leaves the box
    /// (that parameter fixed on the edge), if it does.
    fn on_edge(&mut self, a: &Sample, b: &[f64]) -> Option<Result<Sample, String>> {
        let n = a.x.len();
        let ranges = [self.plane.x_range, self.plane.y_range];
        // The edge crossed first along the chord.
        let mut first: Option<(f64, usize, f64)> = None;
        for (axis, r) in ranges.iter().enumerate() {
            let (va, vb) = (a.x[n - 2 + axis], b[n - 2 + axis]);
            for edge in *r {
                let out = if edge == r[0] { vb < edge } else { vb > edge };
                if out && vb != va {
                    let theta = ((edge - va) / (vb - va)).clamp(0.0, 1.0);
                    if first.is_none_or(|f| theta < f.0) {
                        first = Some((theta, axis, edge));
                    }
                }
            }
        }
        let (theta, axis, edge) = first?;
        let mut x: Vec<f64> =
            a.x.iter()
                .zip(b)
                .map(|(p, q)| p + theta * (q - p))
                .collect();
        x[n - 2 + axis] = edge;
        let anchor = x.clone();
        let mut border = vec![0.0; n];
        self.sys.axis(axis, &mut border);
        Some(
            match self.sys.correct(
                &mut x,
                &border,
                &anchor,
                self.opts.tolerance,
                4 * NEWTON_ITERATIONS,
            ) {
                Correction::Converged { .. } => {
                    x[n - 2 + axis] = edge;
                    let mut t = a.t.clone();
                    self.sys
                        .tangent(&x, &a.t, &mut t)
                        .and_then(|()| self.examine(x, t))
                }
                Correction::Failed(why) => Err(why),
            },
        )
    }

    /// The point where the curve leaves the box from `a`, solved on the
    /// edge that the predictor `s` along `a`'s tangent crosses first: `None`
    /// if the predictor stays in the box, if the edge's solve fails or lands
    /// outside the box, or if the curve does not leave the box there (its
    /// tangent turned back in).
    fn edge_past_predictor(&mut self, a: &Sample, s: f64) -> Option<Sample> {
        let predicted: Vec<f64> = a.x.iter().zip(&a.t).map(|(p, d)| p + s * d).collect();
        if !self.out_of_box(&predicted) {
            return None;
        }
        let b = self.on_edge(a, &predicted)?.ok()?;
        (!self.out_of_box(&b.x) && self.on_box_edge_leaving(&b)).then_some(b)
    }

    /// Whether the step from `a` to `b` passes `start` again (phases
    /// compared modulo 2π: the same motion relabelled).
    fn passes_start(&self, start: &Sample, a: &Sample, b: &Sample) -> bool {
        let n = start.x.len();
        let mut x0 = start.x.clone();
        if n > 2 {
            let turns = ((b.x[1] - start.x[1]) / std::f64::consts::TAU).round();
            for k in 0..(n - 2) / 2 {
                x0[2 * k + 1] += turns * std::f64::consts::TAU;
            }
        }
        let step = self.sys.distance(&a.x, &b.x);
        if step == 0.0 {
            return false;
        }
        let seg: Vec<f64> = b.x.iter().zip(&a.x).map(|(p, q)| p - q).collect();
        let theta = (self.sys.dot_diff(&seg, &x0, &a.x) / (step * step)).clamp(0.0, 1.0);
        let near: Vec<f64> = a.x.iter().zip(&seg).map(|(p, d)| p + theta * d).collect();
        self.sys.distance(&near, &x0) <= 0.25 * step
    }

    /// The special points (a fold or period-doubling curve met) between
    /// `a` and `b` (`b` at arclength `s_b`), located, in arclength order.
    pub(super) fn specials(
        &mut self,
        a: &Sample,
        b: &Sample,
        s_b: f64,
    ) -> Vec<(Sample, TransitionKind)> {
        let mut out = Vec::new();
        let condition = self.sys.eval.condition;
        if !matches!(condition, Condition::Margin { .. }) {
            return out;
        }
        type Psi = fn(&Sample) -> f64;
        let tests: [(TransitionKind, Psi); 2] = [
            (TransitionKind::Fold, |s| s.plus),
            (TransitionKind::PeriodDoubling, |s| s.minus),
        ];
        for (kind, psi) in tests {
            let (va, vb) = (psi(a), psi(b));
            if !(va.is_finite() && vb.is_finite()) || va == 0.0 || (va > 0.0) == (vb > 0.0) {
                continue;
            }
            let sign = va.signum();
            let (good, bad) = self.locate(a, s_b, sign * vb, |s| sign * psi(s));
            let at = match bad {
                Some(bd) if psi(&bd).abs() < psi(&good).abs() => bd,
                _ => good,
            };
            // A sign change through a pole (a singular arrival) is none.
            if at
                .stability
                .as_ref()
                .is_some_and(|st| detect::is_critical(kind, st))
            {
                out.push((at, kind));
            }
        }
        out.sort_by(|x, y| {
            let sx = self.sys.dot_diff(&a.t, &x.0.x, &a.x);
            let sy = self.sys.dot_diff(&a.t, &y.0.x, &a.x);
            sx.total_cmp(&sy)
        });
        out
    }

    /// `Err` where the corrector carried `x`, the point corrected from the
    /// step of length `s` along `from`'s tangent, more than half the step
    /// from that prediction: it jumped to another stretch of the curve.
    fn within_step(&self, from: &Sample, s: f64, x: &[f64]) -> Result<(), String> {
        let pred: Vec<f64> = from.x.iter().zip(&from.t).map(|(a, d)| a + s * d).collect();
        let moved = self.sys.distance(x, &pred);
        if moved > 0.5 * s.abs() {
            return Err(format!(
                "the corrector moves the point by {moved:.3e}, more than half the step {s:.3e}"
            ));
        }
        Ok(())
    }

    /// How far (in the plane, each parameter over its span) a codimension-two
    /// end located on an arrival's or departure's sign change may lie from
    /// the tangential point it approximates ([`Self::codim2`]): that margin's
    /// zero is double there, so rounding and the finite differences move
    /// its sign change by about the square root of their error.
    const TANGENCY_REACH: f64 = 1e-5;

    /// A codimension-two end between `prev` and `cand` (at arclength
    /// `s_c`), located, with its kind and boundary.
    fn codim2(
        &mut self,
        prev: &Sample,
        cand: &Sample,
        s_c: f64,
    ) -> Option<(Sample, CurveEndReason)> {
        let ns = matches!(
            self.sys.eval.condition,
            Condition::Eigen(TransitionKind::NeimarkSacker)
        );
        // The pair of a Neimark–Sacker curve turns real: a 1:1 or 1:2 resonance.
        let turns_real =
            ns && prev.disc < 0.0 && cand.disc.partial_cmp(&0.0) != Some(std::cmp::Ordering::Less);
        let lost = cand.other_event.is_nan() || cand.other_event <= 0.0;
        // A companion leaving rounding before the other conditions fail
        // (by the chord's estimate): the end is where it vanishes.
        let left = cand.companion < 0.0 && prev.companion >= 0.0;
        let first = |a: f64, b: f64| if a > b { a / (a - b) } else { 0.0 };
        if left
            && (!lost
                || cand.other_event.is_nan()
                || first(prev.companion, cand.companion)
                    < first(prev.other_event, cand.other_event))
        {
            if let Some(end) = self.companion_end(prev, cand, s_c) {
                return Some(end);
            }
        }
        if lost {
            let (good, bad) = self.locate(prev, s_c, cand.other_event, |s| s.other_event);
            // Named by the smooth margins (the event search's margin of a
            // stick's end is its phase tolerance wherever the stick ends as
            // claimed: the smallest, but not what vanishes): the last good
            // trial's smallest where that one vanishes there (to
            // `SAME_EVENT`), else the condition violated just beyond, on
            // the first bad trial (a margin born at zero there, as an
            // interior extremum entering its segment through an end: on
            // `stribeck8` W=2.3:2.6 × Q0=1:3 a grazing curve's end was named
            // a stick's vanishing by a stick lasting 8e-2 while a grazing
            // margin born there was -1.7e-11 beyond).
            let beyond = bad.as_ref().and_then(|b| {
                if b.other < 0.0 {
                    b.worst
                } else {
                    b.worst_event
                }
            });
            let vanishes = good.other.abs() <= SAME_EVENT;
            let named = if vanishes {
                good.worst.or(beyond)
            } else {
                beyond.or(good.worst)
            };
            let (kind, boundary) = named
                .or(good.worst_event)
                .or(cand.worst)
                .map_or((TransitionKind::Grazing, None), |(k, _, b)| {
                    (transition_kind(k), b)
                });
            // Where the corrector fails near the point (the curve's system
            // turning singular there, as where an arrival before a stick
            // turns tangential) the bracket closes on failed trials, or on
            // a candidate on the far root of that arrival's equation: solve
            // the point directly.
            // Within a few of the step's lengths in the plane (no bracket:
            // the candidate may lie on another root).
            let bound = PAIR_REACH * self.plane_distance(&prev.x, &cand.x);
            // An arrival (or departure) lost on a grazing curve may be one
            // turning tangential, where the grazed extremum merges into it:
            // that margin has a double zero there, and the bracket on its
            // sign closes short of the point (on `stribeck8` W=2.3:2.6 ×
            // Q0=1:3, 8e-8 before it, the field there 1.2e-9 and its rate
            // 4.4e-4): the point where the field and its rate vanish
            // ([`Self::tangency_point`]) is the end if it lies ahead, within
            // [`Self::TANGENCY_REACH`] of the box (the steps there are shorter
            // than that sign change's offset: 3e-9 of the box there).
            let tangential = matches!(
                named.map(|(k, _, _)| k),
                Some(ViolationKind::Arrival | ViolationKind::Departure)
            );
            let tangency = if tangential {
                self.tangency_point(&good, bound.max(Self::TANGENCY_REACH))
            } else {
                None
            };
            let good = if let Some(at) = tangency {
                at
            } else if good.other.is_nan() || good.other <= 0.0 {
                good
            } else {
                // The solved point, where one was found, even within the
                // location tolerance of the trial: the trial holds the
                // second condition only as well as the bracket closed on
                // it, where that margin is steep (a stick onset of a long
                // motion on `coulomb` with `V = 0`: 6e-8, 2e-8 of its scale).
                // With the condition that names the end first (violated
                // just beyond the bracket), else with the smallest margin
                // at the trial: the two differ where the bracket closes on
                // failed trials short of the point (on `stribeck8`
                // W=0.5:3 × Q0=1:12 a period-doubling curve's trial holds a
                // stick's duration at 6e-4 while the stick onset beyond is
                // what vanishes; on the paper model's cascade window,
                // `tests/curve_cascade.rs`, the `^7` grazing curve's end
                // held its passable onset to 9.4e-6 before, 3.3e-16 now).
                let worst = good.worst.filter(|w| Some(*w) != named);
                [named, worst]
                    .into_iter()
                    .flatten()
                    .find_map(|id| self.pair_point(&good, id, bound))
                    .unwrap_or(good)
            };
            let reason = CurveEndReason::Codim2 { kind, boundary };
            if !(turns_real && good.disc >= 0.0) {
                return Some((good, reason));
            }
        }
        if turns_real {
            let (good, _) = self.locate(prev, s_c, -cand.disc, |s| -s.disc);
            let n = good.x.len();
            let p = self.sys.params(&good.x);
            let m = (n - 2) / 2;
            let mut pts = vec![crate::orbit::periodic::SwitchingPoint { phase: 0.0, x: 0.0 }; m];
            Extended::<M>::points_into(&good.x, &mut pts);
            let tr = monodromy_spectral::<M>(&p, &self.sys.eval.steps, self.sys.eval.shift, &pts)
                .ok()
                .map_or(0.0, |d| d.trace());
            let kind = if tr >= 0.0 {
                TransitionKind::Fold
            } else {
                TransitionKind::PeriodDoubling
            };
            return Some((
                good,
                CurveEndReason::Codim2 {
                    kind,
                    boundary: None,
                },
            ));
        }
        None
    }

    /// The codimension-two end where the companion lowest at `cand` (below
    /// its floor there, above it at `prev`) vanishes: the bracket on its
    /// floor located, then the point where it and the curve's own
    /// condition vanish solved from the bracket's good end
    /// ([`Self::pair_point`]), or that end if the solve fails.
    fn companion_end(
        &mut self,
        prev: &Sample,
        cand: &Sample,
        s_c: f64,
    ) -> Option<(Sample, CurveEndReason)> {
        let (good, bad) = self.locate(prev, s_c, cand.companion, |s| s.companion);
        let id = bad
            .as_ref()
            .and_then(|b| b.companion_id)
            .or(cand.companion_id)?;
        let bound = PAIR_REACH * self.plane_distance(&prev.x, &cand.x);
        // The interior contact of a tangential arrival or departure leaves
        // its end where that end's field turns tangential to second order:
        // there, ahead of `prev` (its depth grows as the cube of the
        // distance, and falls below its slack some way beyond).
        let end = self.sys.eval.tangential_end(id);
        let at = end
            .and_then(|(segment, arrival)| {
                self.field_point(prev, segment, arrival, bound.max(Self::TANGENCY_REACH))
            })
            .or_else(|| self.pair_point(&good, id, bound))
            .unwrap_or(good);
        let reason = CurveEndReason::Codim2 {
            kind: transition_kind(id.0),
            boundary: id.2,
        };
        Some((at, reason))
    }

    /// The distance of `x` and `y` in the parameter plane alone (each
    /// parameter over its range's span).
    pub(super) fn plane_distance(&self, x: &[f64], y: &[f64]) -> f64 {
        let n = x.len();
        let spans = self.sys.spans();
        ((x[n - 2] - y[n - 2]) / spans[0]).hypot((x[n - 1] - y[n - 1]) / spans[1])
    }

    pub(super) fn out_of_box(&self, x: &[f64]) -> bool {
        let n = x.len();
        let (a, b) = (x[n - 2], x[n - 1]);
        a < self.plane.x_range[0]
            || a > self.plane.x_range[1]
            || b < self.plane.y_range[0]
            || b > self.plane.y_range[1]
    }

    fn on_box_edge_leaving(&self, s: &Sample) -> bool {
        let n = s.x.len();
        let tol = self.opts.location_tolerance;
        let ranges = [self.plane.x_range, self.plane.y_range];
        (0..2).any(|axis| {
            let (v, d) = (s.x[n - 2 + axis], s.t[n - 2 + axis]);
            ((v - ranges[axis][0]).abs() <= tol && d < 0.0)
                || ((v - ranges[axis][1]).abs() <= tol && d > 0.0)
        })
    }

    /// Follow from `start` along its tangent until an end (`None`: closed).
    pub fn run(&mut self, start: Sample, loop_check: bool) -> Run {
        let opts = *self.opts;
        let mut points = vec![start.clone()];
        let mut special = Vec::new();
        let mut prev = start.clone();
        let mut ds = opts.initial_step;
        let mut travelled = 0.0;
        // The eigenvalue jump that rejected the last step, if one did.
        let mut last_jump: Option<f64> = None;
        // Whether `DP` has shown itself singular along this curve.
        let mut erratic = false;
        // How many steps in a row were accepted at the smallest step.
        let mut at_min = 0;
        if self.on_box_edge_leaving(&prev) {
            return Run {
                points,
                special,
                end: Some((CurveEndReason::BoxEdge, prev)),
            };
        }
        loop {
            if points.len() >= opts.max_points {
                return Run {
                    points,
                    special,
                    end: Some((CurveEndReason::MaxPoints, prev)),
                };
            }
            let accepted = self
                .corrected(&prev, ds, NEWTON_ITERATIONS)
                .and_then(|(x, it)| {
                    self.within_step(&prev, ds, &x)?;
                    let mut t = prev.t.clone();
                    self.sys.tangent(&x, &prev.t, &mut t)?;
                    let turn = self.sys.dot(&t, &prev.t);
                    if turn < 0.8 {
                        return Err(format!(
                            "the tangent turns by {:.1}° over the step",
                            turn.clamp(-1.0, 1.0).acos().to_degrees()
                        ));
                    }
                    let smp = self.examine(x, t)?;
                    let held = self.sys.held(&smp.x);
                    if held > HOLDS_TO && !self.sys.at_rounding_floor(&smp.x) {
                        return Err(format!(
                            "the condition holds only to {held:.1e} of its scale there"
                        ));
                    }
                    if let (Some(a), Some(b)) = (&prev.stability, &smp.stability) {
                        let jump = detect::eigenvalue_jump(a, b);
                        // Eigenvalues that move continuously move less over
                        // half the step. When halving it leaves the jump as
                        // large, `DP` is singular or discontinuous along the
                        // curve (an arrival tangential all along it, as on a
                        // passable onset) and the check protects nothing.
                        if last_jump.is_some_and(|j| jump > 0.9 * j) {
                            erratic = true;
                        }
                        if jump > 0.25 && ds > 16.0 * opts.min_step && !erratic {
                            last_jump = Some(jump);
                            return Err(format!(
                                "an eigenvalue of DP jumps by {jump:.3e} over the step"
                            ));
                        }
                    }
                    Ok((smp, it))
                });
            // A step the corrector cannot take whose predictor leaves the
            // box: the curve may leave through an edge on a bound of the
            // model's parameters (`d >= 0` on `d = 0`), beyond which nothing
            // can be evaluated. Solved on the edge from the predictor.
            let mut through_edge = false;
            let accepted = match accepted {
                Err(why) => match self.edge_past_predictor(&prev, ds) {
                    Some(b) => {
                        through_edge = true;
                        Ok((b, 0))
                    }
                    None => Err(why),
                },
                ok => ok,
            };
            let (mut cand, iterations) = match accepted {
                Ok(c) => {
                    last_jump = None;
                    c
                }
                Err(ref e) if ds > opts.min_step => {
                    ds = (0.5 * ds).max(opts.min_step);
                    continue;
                }
                Err(why) => {
                    let end = self.stop(&mut points, &mut special, prev, why);
                    return Run {
                        points,
                        special,
                        end: Some(end),
                    };
                }
            };
            let mut s_c = self.sys.dot_diff(&prev.t, &cand.x, &prev.x);
            let mut reason = through_edge.then_some(CurveEndReason::BoxEdge);
            if self.out_of_box(&cand.x) {
                match self.on_edge(&prev, &cand.x) {
                    Some(Ok(b)) if !self.out_of_box(&b.x) => {
                        s_c = self.sys.dot_diff(&prev.t, &b.x, &prev.x);
                        cand = b;
                        reason = Some(CurveEndReason::BoxEdge);
                    }
                    _ if ds > opts.min_step => {
                        ds = (0.5 * ds).max(opts.min_step);
                        continue;
                    }
                    other => {
                        let why = match other {
                            Some(Err(e)) => e,
                            _ => "the edge point lies outside the box".into(),
                        };
                        return Run {
                            points,
                            special,
                            end: Some((
                                CurveEndReason::NewtonFailure(format!(
                                    "the corrector fails on the box's edge: {why}"
                                )),
                                prev,
                            )),
                        };
                    }
                }
            }
            if let Some((at, why)) = self.codim2(&prev, &cand, s_c) {
                s_c = self.sys.dot_diff(&prev.t, &at.x, &prev.x);
                cand = at;
                reason = Some(why);
            }
            if s_c > 0.0 {
                for (at, kind) in self.specials(&prev, &cand, s_c) {
                    special.push(Found {
                        index: points.len() - 1,
                        kind,
                        at,
                    });
                }
            }
            if s_c > 0.0 || reason.is_none() {
                points.push(cand.clone());
            }
            travelled += s_c.abs();
            if let Some(reason) = reason {
                return Run {
                    points,
                    special,
                    end: Some((reason, cand)),
                };
            }
            if loop_check
                && points.len() > 3
                && travelled > 4.0 * opts.initial_step
                && self.passes_start(&start, &prev, &cand)
            {
                // Closed: the last point is the start again.
                points.pop();
                return Run {
                    points,
                    special,
                    end: None,
                };
            }
            if ds <= opts.min_step {
                at_min += 1;
            } else {
                at_min = 0;
            }
            if let Some(why) = self.stalled(&points, at_min) {
                let end = self.stop(&mut points, &mut special, cand, why);
                return Run {
                    points,
                    special,
                    end: Some(end),
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
