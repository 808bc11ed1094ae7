//! The smooth (nonlinear) friction law integrated numerically — "only the
//! numerical investigation can be carried out" (the paper) — with stick by
//! the same force criteria as the piecewise models (SPEC §3), and periodic
//! motions found by shooting.
//!
//! The integrator is an adaptive Dormand–Prince 5(4) with a relative
//! tolerance knob. No well-kept Rust ODE crate offers event location with
//! the set-valued stick of this problem (an event that switches the vector
//! field to a constraint and back on a force criterion), so the stepping is
//! written here: the event `v = V` is detected by a sign change at the end of
//! a step or on the step's cubic Hermite interpolant, and located by regula
//! falsi on one-step solutions; a stick ends at the first root of
//! `|Fnf| = as`, which is known in closed form during the stick.

use nalgebra::{Matrix2, Vector2};
use serde::Serialize;

use crate::model::param::{ParamError, ParamSet};
use crate::model::smooth::SmoothModel;

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// Where the motion is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Slipping faster than the belt.
    Above,
    /// Slipping slower than the belt.
    Below,
    /// Stuck to the belt.
    Stick,
}

/// An event at the belt speed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BeltEvent {
    /// Phase `W t`.
    pub phase: f64,
    /// Displacement.
    pub x: f64,
    /// Where the motion was before.
    pub before: Side,
    /// Where it is after.
    pub after: Side,
}

/// A state.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct State {
    /// Phase `W t`.
    pub phase: f64,
    /// Displacement.
    pub x: f64,
    /// Velocity.
    pub v: f64,
    /// Side of the belt speed (or stuck).
    pub side: Side,
}

/// Why an integration failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IntegrateError {
    /// Invalid parameters.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// The state blew up or the step size collapsed.
    #[error("the integration failed at phase {phase}: {reason}")]
    Failed {
        /// Where.
        phase: f64,
        /// Why.
        reason: String,
    },
    /// Shooting did not converge.
    #[error("shooting did not converge: residual {residual:.3e} after {iterations} iterations")]
    Shooting {
        /// Last residual.
        residual: f64,
        /// Iterations.
        iterations: usize,
    },
}

/// The nonlinear model at fixed parameters, ready to integrate.
#[derive(Clone, Debug)]
pub struct Integrator<M: SmoothModel> {
    p: M::Params,
    a0: f64,
    w: f64,
    two_d: f64,
    c: f64,
    belt: f64,
    bound: f64,
    /// `f(V+)` and `f(V−)`: the law's one-sided limits at the belt speed.
    limits: (f64, f64),
    /// `f'(V+)` and `f'(V−)`: its one-sided slopes there.
    slopes: (f64, f64),
    /// Relative tolerance of the steps.
    pub rtol: f64,
}

impl<M: SmoothModel> Integrator<M> {
    /// An integrator at `p` with relative tolerance `rtol`.
    pub fn new(p: M::Params, rtol: f64) -> Result<Self, IntegrateError> {
        p.check()?;
        let osc = M::oscillator(&p);
        let belt = M::belt(&p);
        let delta = 1e-12 * belt.abs().max(1.0);
        let (above, below) = (M::kinetic(&p, belt + delta), M::kinetic(&p, belt - delta));
        let (limits, slopes) = ((above[0], below[0]), (above[1], below[1]));
        Ok(Self {
            p,
            a0: osc.amplitude,
            w: osc.frequency,
            two_d: 2.0 * osc.damping,
            c: osc.stiffness,
            belt,
            bound: M::static_bound(&p),
            limits,
            slopes,
            rtol: rtol.clamp(1e-14, 1e-2),
        })
    }

    /// The belt speed.
    pub fn belt(&self) -> f64 {
        self.belt
    }

    /// The acceleration while slipping on `side`. Beyond the belt speed
    /// the side's law is continued by its tangent at `V` (the other side's
    /// law never enters a step of this one), so that a step reaching the
    /// belt speed overshoots it smoothly and the crossing is located even
    /// where both sides' fields point at the belt (the motion sticks).
    fn accel(&self, side: Side, t: f64, x: f64, v: f64) -> f64 {
        let friction = match side {
            Side::Above if v <= self.belt => self.limits.0 + self.slopes.0 * (v - self.belt),
            Side::Below if v >= self.belt => self.limits.1 + self.slopes.1 * (v - self.belt),
            _ => M::kinetic(&self.p, v)[0],
        };
        self.a0 * (self.w * t).cos() - self.two_d * v - self.c * x - friction
    }

    fn fnf(&self, t: f64, x: f64) -> f64 {
        self.a0 * (self.w * t).cos() - self.two_d * self.belt - self.c * x
    }

    /// One Dormand–Prince 5(4) step: the 5th-order solution and the error estimate.
    fn step(&self, side: Side, t: f64, y: [f64; 2], h: f64) -> ([f64; 2], [f64; 2]) {
        const A: [[f64; 6]; 6] = [
            [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
            [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
            [
                19372.0 / 6561.0,
                -25360.0 / 2187.0,
                64448.0 / 6561.0,
                -212.0 / 729.0,
                0.0,
                0.0,
            ],
            [
                9017.0 / 3168.0,
                -355.0 / 33.0,
                46732.0 / 5247.0,
                49.0 / 176.0,
                -5103.0 / 18656.0,
                0.0,
            ],
            [
                35.0 / 384.0,
                0.0,
                500.0 / 1113.0,
                125.0 / 192.0,
                -2187.0 / 6784.0,
                11.0 / 84.0,
            ],
        ];
        const C: [f64; 6] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
        const E: [f64; 7] = [
            71.0 / 57600.0,
            0.0,
            -71.0 / 16695.0,
            71.0 / 1920.0,
            -17253.0 / 339200.0,
            22.0 / 525.0,
            -1.0 / 40.0,
        ];
        let f = |t: f64, y: [f64; 2]| [y[1], self.accel(side, t, y[0], y[1])];
        let mut k = [[0.0; 2]; 7];
        k[0] = f(t, y);
        for s in 0..6 {
            let mut ys = y;
            for (j, a) in A[s].iter().enumerate().take(s + 1) {
                ys[0] += h * a * k[j][0];
                ys[1] += h * a * k[j][1];
            }
            k[s + 1] = f(t + C[s] * h, ys);
        }
        // Row 5 of A is the 5th-order solution (FSAL).
        let mut y5 = y;
        for (j, a) in A[5].iter().enumerate() {
            y5[0] += h * a * k[j][0];
            y5[1] += h * a * k[j][1];
        }
        let mut err = [0.0; 2];
        for (j, e) in E.iter().enumerate() {
            err[0] += h * e * k[j][0];
            err[1] += h * e * k[j][1];
        }
        (y5, err)
    }

    /// Integrate from `start` to phase `phase_end`, calling `on_event` at
    /// every event at the belt speed; returns the final state.
    pub fn run(
        &self,
        start: State,
        phase_end: f64,
        on_event: impl FnMut(&BeltEvent),
    ) -> Result<State, IntegrateError> {
        self.run_until(start, phase_end, None, on_event)
            .map(|(end, _)| end)
    }

    /// Integrate from `start` until the motion crosses the Poincaré section
    /// `v = level` downwards (from above `level` to below it, while
    /// slipping), or until phase `phase_end`, whichever comes first, calling
    /// `on_event` at every event at the belt speed on the way. Returns the
    /// state where it stopped and whether that is on the section (then
    /// with `v = level` exactly). A start on the section does not count:
    /// the motion must rise above `level` and fall through it again.
    pub fn to_section(
        &self,
        start: State,
        level: f64,
        phase_end: f64,
        on_event: impl FnMut(&BeltEvent),
    ) -> Result<(State, bool), IntegrateError> {
        self.run_until(start, phase_end, Some(level), on_event)
    }

    /// The first point in `(0, hs]` of the step from `(t, y)` to `y1` where
    /// `gap(v)` has turned negative, from the end point or the step's cubic
    /// Hermite interpolant (confirmed on a one-step solution): an upper
    /// bracket for the crossing.
    fn first_drop(
        &self,
        side: Side,
        t: f64,
        y: [f64; 2],
        hs: f64,
        y1: [f64; 2],
        gap: impl Fn(f64) -> f64,
    ) -> Option<f64> {
        if gap(y1[1]) < 0.0 {
            return Some(hs);
        }
        let a0 = self.accel(side, t, y[0], y[1]);
        let a1 = self.accel(side, t + hs, y1[0], y1[1]);
        for i in 1..16 {
            let s = i as f64 / 16.0;
            let (h00, h10, h01, h11) = (
                2.0 * s * s * s - 3.0 * s * s + 1.0,
                s * s * s - 2.0 * s * s + s,
                -2.0 * s * s * s + 3.0 * s * s,
                s * s * s - s * s,
            );
            let v = h00 * y[1] + h10 * hs * a0 + h01 * y1[1] + h11 * hs * a1;
            if gap(v) < 0.0 {
                let ys = self.step(side, t, y, s * hs).0;
                if gap(ys[1]) < 0.0 {
                    return Some(s * hs);
                }
            }
        }
        None
    }

    /// The crossing `gap(v) = 0` in `(0, s_hi]` by regula falsi (Illinois)
    /// on one-step solutions from `(t, y)`: its step length and state.
    fn locate(
        &self,
        side: Side,
        t: f64,
        y: [f64; 2],
        s_hi: f64,
        gap: impl Fn(f64) -> f64,
    ) -> (f64, [f64; 2]) {
        let g = |s: f64| {
            let ys = self.step(side, t, y, s).0;
            (gap(ys[1]), ys)
        };
        let (mut a, mut fa) = (0.0, gap(y[1]));
        let (mut b, mut fb) = (s_hi, g(s_hi).0);
        let mut last = 0i32;
        for _ in 0..200 {
            let mut s = (a * fb - b * fa) / (fb - fa);
            if !(s > a && s < b) {
                s = 0.5 * (a + b);
            }
            let fs = g(s).0;
            if fs >= 0.0 {
                a = s;
                fa = fs;
                if last == 1 {
                    fb *= 0.5;
                }
                last = 1;
            } else {
                b = s;
                fb = fs;
                if last == -1 {
                    fa *= 0.5;
                }
                last = -1;
            }
            if b - a <= 4.0 * f64::EPSILON * (t + b).abs().max(1.0) {
                break;
            }
        }
        let s = 0.5 * (a + b);
        (s, g(s).1)
    }

    /// [`Integrator::run`], stopping on the section `v = section` if given;
    /// the flag says whether it stopped there.
    fn run_until(
        &self,
        start: State,
        phase_end: f64,
        section: Option<f64>,
        mut on_event: impl FnMut(&BeltEvent),
    ) -> Result<(State, bool), IntegrateError> {
        let w = self.w;
        let (mut t, t_end) = (start.phase / w, phase_end / w);
        let mut y = [start.x, start.v];
        let mut side = start.side;
        let mut h = 1e-2 / w.max(1.0);
        let mut steps = 0usize;
        while t < t_end {
            steps += 1;
            if steps > 50_000_000 {
                return Err(IntegrateError::Failed {
                    phase: w * t,
                    reason: "too many steps".into(),
                });
            }
            if !(y[0].is_finite() && y[1].is_finite()) {
                return Err(IntegrateError::Failed {
                    phase: w * t,
                    reason: "the state is not finite".into(),
                });
            }
            if side == Side::Stick {
                // x = x_i + V (t − t_i) until |Fnf| = as.
                let (t0, x0) = (t, y[0]);
                let g = |s: f64| {
                    let f = self.fnf(t0 + s, x0 + self.belt * s);
                    (f - self.bound, f + self.bound)
                };
                let ds = 1e-3 / w.max(1e-3);
                let mut s = 0.0;
                let mut found = None;
                while t0 + s < t_end {
                    let (u1, l1) = g(s + ds);
                    if u1 >= 0.0 || l1 <= 0.0 {
                        let upper = u1 >= 0.0;
                        let (mut a, mut b) = (s, s + ds);
                        for _ in 0..200 {
                            let mid = 0.5 * (a + b);
                            let (u, l) = g(mid);
                            if (upper && u >= 0.0) || (!upper && l <= 0.0) {
                                b = mid;
                            } else {
                                a = mid;
                            }
                            if b - a <= 4.0 * f64::EPSILON * (t0 + b).abs().max(1.0) {
                                break;
                            }
                        }
                        found = Some((b, upper));
                        break;
                    }
                    s += ds;
                }
                let Some((s, upper)) = found else {
                    let dt = t_end - t0;
                    let end = State {
                        phase: phase_end,
                        x: x0 + self.belt * dt,
                        v: self.belt,
                        side: Side::Stick,
                    };
                    return Ok((end, false));
                };
                t = t0 + s;
                y = [x0 + self.belt * s, self.belt];
                let after = if upper { Side::Above } else { Side::Below };
                on_event(&BeltEvent {
                    phase: w * t,
                    x: y[0],
                    before: Side::Stick,
                    after,
                });
                side = after;
                h = h.min(1e-3 / w.max(1.0));
                continue;
            }
            let sign = if side == Side::Above { 1.0 } else { -1.0 };
            let gap = |v: f64| sign * (v - self.belt);
            let hs = h.min(t_end - t).max(1e-15 * t.abs().max(1.0));
            let (y1, err) = self.step(side, t, y, hs);
            let sc = |i: usize| self.rtol * (1.0 + y[i].abs().max(y1[i].abs()));
            let en = (err[0] / sc(0)).abs().max((err[1] / sc(1)).abs());
            if en.is_nan() || en > 1.0 {
                if !en.is_finite() && hs < 1e-12 {
                    return Err(IntegrateError::Failed {
                        phase: w * t,
                        reason: "the error estimate is not finite".into(),
                    });
                }
                h = hs * (0.9 * en.powf(-0.2)).clamp(0.1, 0.9);
                continue;
            }
            // Crossing: the gap negative at the end or on the Hermite interpolant.
            let cross = self.first_drop(side, t, y, hs, y1, gap);
            if let Some(level) = section {
                // The section, downwards, before any crossing of the belt speed.
                let above = |v: f64| v - level;
                if above(y[1]) > 0.0 {
                    let limit = cross.unwrap_or(hs);
                    let y_limit = if limit < hs {
                        self.step(side, t, y, limit).0
                    } else {
                        y1
                    };
                    if let Some(s_hi) = self.first_drop(side, t, y, limit, y_limit, above) {
                        let (s, ys) = self.locate(side, t, y, s_hi, above);
                        let end = State {
                            phase: w * (t + s),
                            x: ys[0],
                            v: level,
                            side,
                        };
                        return Ok((end, true));
                    }
                }
            }
            let Some(s_hi) = cross else {
                t += hs;
                y = y1;
                h = hs * (0.9 * en.max(1e-10).powf(-0.2)).min(5.0);
                continue;
            };
            let (s, ys) = self.locate(side, t, y, s_hi, gap);
            t += s;
            y = [ys[0], self.belt];
            // Force criteria at the belt speed (SPEC §3) with the law's one-sided limits.
            let fnf = self.fnf(t, y[0]);
            let (in_above, in_below) = (fnf - self.limits.0, fnf - self.limits.1);
            let after = if side == Side::Above {
                if in_above < 0.0 && in_below < 0.0 {
                    Side::Below
                } else {
                    Side::Stick
                }
            } else if in_above > 0.0 && in_below > 0.0 {
                Side::Above
            } else {
                Side::Stick
            };
            on_event(&BeltEvent {
                phase: w * t,
                x: y[0],
                before: side,
                after,
            });
            side = after;
            h = h.min(1e-3 / w.max(1.0));
        }
        Ok((
            State {
                phase: w * t,
                x: y[0],
                v: y[1],
                side,
            },
            false,
        ))
    }

    /// The state that follows `start` after `periods` forcing periods.
    pub fn period_map(&self, start: State, periods: u32) -> Result<State, IntegrateError> {
        self.run(start, start.phase + TAU * periods as f64, |_| {})
    }

    /// A periodic motion of period `periods` by shooting: Newton on
    /// `P(x, v) − (x, v) = 0` at the section `W t ≡ start.phase (mod 2π)`,
    /// with a finite-difference Jacobian and a least-squares step (a stick
    /// makes the map's Jacobian singular), from `start` (for example a
    /// state after the transient). Returns the periodic state.
    pub fn shoot(&self, start: State, periods: u32, tol: f64) -> Result<State, IntegrateError> {
        let mut s = start;
        let mut last = f64::INFINITY;
        for it in 0..30 {
            let end = self.period_map(s, periods)?;
            let r = Vector2::new(end.x - s.x, end.v - s.v);
            let norm = r.amax();
            if norm <= tol * (1.0 + s.x.abs().max(s.v.abs())) {
                return Ok(end);
            }
            if !norm.is_finite() || (it > 5 && norm > last) {
                return Err(IntegrateError::Shooting {
                    residual: norm,
                    iterations: it,
                });
            }
            last = norm;
            // Differences well above the integration error, well below the motion.
            let h = self.rtol.sqrt().clamp(1e-7, 1e-2) * (1.0 + s.x.abs().max(s.v.abs()));
            let mut jac = Matrix2::zeros();
            for (col, (dx, dv)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
                let plus = self.period_map(
                    State {
                        x: s.x + dx,
                        v: s.v + dv,
                        ..s
                    },
                    periods,
                )?;
                let minus = self.period_map(
                    State {
                        x: s.x - dx,
                        v: s.v - dv,
                        ..s
                    },
                    periods,
                )?;
                jac[(0, col)] = (plus.x - minus.x) / (2.0 * h);
                jac[(1, col)] = (plus.v - minus.v) / (2.0 * h);
            }
            let a = jac - Matrix2::identity();
            let step = a.svd(true, true).solve(&(-r), 1e-10).unwrap_or_else(|_| -r);
            // Starting on the other side of the belt speed would change the branch: keep the side.
            s = State {
                x: s.x + step[0],
                v: s.v + step[1],
                ..s
            };
            if (s.side == Side::Above && s.v <= self.belt)
                || (s.side == Side::Below && s.v >= self.belt)
            {
                s.side = if s.v > self.belt {
                    Side::Above
                } else {
                    Side::Below
                };
            }
        }
        Err(IntegrateError::Shooting {
            residual: last,
            iterations: 30,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::stribeck::{Params, Stribeck};

    #[test]
    fn the_law_and_its_slope_are_consistent() {
        let p = Params::default();
        for v in [-1.0, 0.2, 0.9, 1.1, 2.0, 4.0] {
            let [f, df] = Stribeck::kinetic(&p, v);
            let h = 1e-6;
            let fd =
                (Stribeck::kinetic(&p, v + h)[0] - Stribeck::kinetic(&p, v - h)[0]) / (2.0 * h);
            assert!(
                (df - fd).abs() < 1e-6 * (1.0 + df.abs()),
                "{v}: {df} vs {fd}"
            );
            assert!(f.is_finite());
        }
    }

    #[test]
    fn shooting_finds_a_periodic_state_that_the_integration_returns_to() {
        let p = Params::default();
        let integ = Integrator::<Stribeck>::new(p, 1e-11).unwrap();
        let rest = State {
            phase: 0.0,
            x: 0.0,
            v: 0.0,
            side: Side::Below,
        };
        let after = integ.run(rest, 200.0 * TAU, |_| {}).unwrap();
        let periodic = integ.shoot(after, 1, 1e-9).unwrap();
        let again = integ.period_map(periodic, 1).unwrap();
        assert!(
            (again.x - periodic.x).abs() < 1e-8 && (again.v - periodic.v).abs() < 1e-8,
            "{periodic:?} {again:?}"
        );
    }
}
