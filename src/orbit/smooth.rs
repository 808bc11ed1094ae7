//! A smooth law's motions, by the integrator ([`crate::dynamics::integrate`]):
//! what a simulation of the unforced oscillator settles to (steady sliding
//! or a self-excited cycle), and the cycle itself by shooting, with its
//! period, stick duration and Floquet multiplier; with the forcing on,
//! the periodic motion a simulation settles to ([`settle_forced`]), by
//! shooting on the stroboscopic map.
//!
//! **The Poincaré section** is `v = 0` crossed downwards: the cycle's
//! largest displacement. Every cycle of the unforced oscillator crosses it
//! exactly once (at its largest `x`, where `v` turns from positive to
//! negative; there `v' = −c (x − x*) < 0`, so the half-line `x > x*` is a
//! transversal), whether it sticks or not, as long as the belt moves
//! (`V ≠ 0`). The return map `P(x)` on it is one-dimensional; a cycle is a
//! fixed point, found by secant steps on `P(x) − x`, and the nontrivial
//! Floquet multiplier is `P'(x)` (the trivial one, 1, along the flow, is
//! removed by the section). A stick collapses the section onto one point
//! (every motion that sticks leaves the stick at the same state), so a
//! stick-slip cycle's multiplier is exactly 0; a slip cycle's is `P'(x)`
//! by central differences on the integrated map.

use nalgebra::Matrix2;
use serde::Serialize;

use crate::dynamics::integrate::{BeltEvent, IntegrateError, Integrator, Side, State};
use crate::model::oscillator::FrictionOscillator;
use crate::model::smooth::SmoothModel;
use crate::orbit::equilibrium::{steady_sliding_smooth, Equilibrium, EquilibriumError, Verdict};

/// Limits and tolerances of [`settle`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothOptions {
    /// Relative tolerance of the integrator's steps.
    pub rtol: f64,
    /// Returns to the section simulated at most before giving up.
    pub max_returns: u32,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-12,
            max_returns: 3000,
        }
    }
}

/// A self-excited cycle of a smooth law.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SmoothCycle {
    /// The cycle's point on the section `v = 0`: its largest displacement.
    pub x: f64,
    /// The period `T`.
    pub period: f64,
    /// Time stuck to the belt per period (0 for a slip cycle).
    pub stick: f64,
    /// The nontrivial Floquet multiplier (0 when the cycle sticks).
    pub multiplier: f64,
    /// Stable when `|multiplier| < 1`.
    pub verdict: Verdict,
    /// The events at the belt speed in one period, their phases counted
    /// from the section.
    pub events: Vec<BeltEvent>,
}

/// What the motion settles to.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SmoothSettled {
    /// With the forcing on: a periodic motion.
    Periodic(SmoothPeriodic),
    /// At rest on steady sliding.
    SteadySliding {
        /// The equilibrium, with its eigenvalues.
        equilibrium: Equilibrium,
        /// Returns to the section before it was within tolerance.
        returns: u32,
    },
    /// On a self-excited cycle.
    Cycle {
        /// The cycle.
        cycle: SmoothCycle,
        /// Returns to the section before it was refined.
        returns: u32,
    },
}

/// Why no settled motion was found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SmoothError {
    /// The integrator failed.
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// No steady sliding (forced, no spring, or the belt at rest).
    #[error(transparent)]
    Equilibrium(#[from] EquilibriumError),
    /// The motion never reached the section.
    #[error("the motion did not reach the section v = 0 within a time of {time:.6e} from x = {x}: it neither oscillates nor rests; check the parameters")]
    NoReturn {
        /// Where it started.
        x: f64,
        /// The time allowed.
        time: f64,
    },
    /// The forced motion repeated after no `q ≤ 8` periods.
    #[error("no periodic motion of up to 8 forcing periods within {periods} forcing periods of the smooth law: the motion may be quasi-periodic or chaotic; study a piecewise scene of the law (`--scene`) with `lyapunov` or `orbit-diagram`, or allow more with --periods")]
    NoPeriodic {
        /// Forcing periods simulated.
        periods: u32,
    },
    /// Neither rest nor a cycle within the returns allowed.
    #[error("the motion settled neither to steady sliding nor to a cycle within {returns} returns to the section v = 0 (last two: x = {last:.12}, {previous:.12}); allow more with --periods")]
    NotSettled {
        /// Returns simulated.
        returns: u32,
        /// The last section point.
        last: f64,
        /// The one before.
        previous: f64,
    },
}

/// Where a start at velocity `v` is: slipping above or below the belt
/// speed, or stuck on it.
fn side_of(v: f64, belt: f64) -> Side {
    if v > belt {
        Side::Above
    } else if v < belt {
        Side::Below
    } else {
        Side::Stick
    }
}

/// Stable inside the unit circle, unstable outside, neutral on it: by the
/// largest multiplier's modulus.
fn verdict_of_modulus(largest: f64) -> Verdict {
    if largest < 1.0 {
        Verdict::Stable
    } else if largest > 1.0 {
        Verdict::Unstable
    } else {
        Verdict::Neutral
    }
}

/// One return to the section: the state, the time stuck and the events.
struct Return {
    state: State,
    stick: f64,
    events: Vec<BeltEvent>,
}

/// The unforced smooth-law oscillator at fixed parameters, with its
/// return map on the section `v = 0`.
pub struct ReturnMap<M: SmoothModel> {
    integrator: Integrator<M>,
    frequency: f64,
    belt: f64,
    /// The rest position `x*` (the section's end: a cycle of no amplitude).
    rest: f64,
    /// Where every stick ends: `−2 d V − c x = ∓ as` (carried along by the belt).
    stick_end: f64,
    /// The natural frequency `sqrt(c)`.
    omega: f64,
    /// The longest time allowed between two returns.
    horizon: f64,
}

impl<M: SmoothModel> ReturnMap<M> {
    /// The return map at `p`, integrated at relative tolerance `rtol`.
    pub fn new(p: M::Params, rtol: f64) -> Result<Self, SmoothError> {
        let rest = steady_sliding_smooth::<M>(&p)?.x;
        let osc = <M as FrictionOscillator>::oscillator(&p);
        let integrator = Integrator::<M>::new(p, rtol)?;
        let belt = integrator.belt();
        let omega = osc.stiffness.abs().sqrt().max(1e-300);
        let bound = M::static_bound(&p);
        let stick_end = (bound * belt.signum() - 2.0 * osc.damping * belt) / osc.stiffness;
        Ok(Self {
            integrator,
            frequency: osc.frequency,
            belt,
            rest,
            stick_end,
            omega,
            horizon: 1e4 * std::f64::consts::TAU / omega,
        })
    }

    fn side(&self, v: f64) -> Side {
        side_of(v, self.belt)
    }

    /// From `start` to the next downward crossing of `v = 0`, or the state
    /// at the horizon if there is none.
    fn next(&self, start: State) -> Result<Result<Return, State>, SmoothError> {
        let mut events = Vec::new();
        let mut stick = 0.0;
        let mut since: Option<f64> = (start.side == Side::Stick).then_some(start.phase);
        let end = start.phase + self.horizon * self.frequency;
        let (state, hit) = self.integrator.to_section(start, 0.0, end, |e| {
            if e.after == Side::Stick {
                since = Some(e.phase);
            } else if e.before == Side::Stick {
                if let Some(s) = since.take() {
                    stick += e.phase - s;
                }
            }
            events.push(*e);
        })?;
        if !hit {
            return Ok(Err(state));
        }
        for e in &mut events {
            e.phase -= start.phase;
        }
        Ok(Ok(Return {
            state,
            stick: stick / self.frequency,
            events,
        }))
    }

    /// The rest position `x*`: the section is the half-line `x > x*`.
    pub fn rest(&self) -> f64 {
        self.rest
    }

    /// `P(x)`: the next section point after `(x, v = 0)`, with the time it
    /// took and the time stuck on the way.
    fn apply(&self, x: f64) -> Result<(Return, f64), SmoothError> {
        let start = State {
            phase: 0.0,
            x,
            v: 0.0,
            side: self.side(0.0),
        };
        match self.next(start)? {
            Ok(r) => {
                let period = r.state.phase / self.frequency;
                Ok((r, period))
            }
            Err(_) => Err(SmoothError::NoReturn {
                x,
                time: self.horizon,
            }),
        }
    }

    /// The return map `P(x)` on the section `v = 0`.
    pub fn map(&self, x: f64) -> Result<f64, SmoothError> {
        Ok(self.apply(x)?.0.state.x)
    }

    /// The cycle through the section near `x`, by secant steps on
    /// `P(x) − x` from `x` and `P(x)`; `None` if they do not converge.
    pub fn cycle(&self, x: f64) -> Result<Option<SmoothCycle>, SmoothError> {
        let scale = |x: f64| 1.0 + x.abs();
        let (mut a, mut fa) = (x, self.map(x)? - x);
        let mut b = a + fa;
        if fa == 0.0 {
            b = a;
        }
        let mut fb = if b == a { fa } else { self.map(b)? - b };
        for _ in 0..40 {
            if fb.abs() <= 1e-13 * scale(b) {
                break;
            }
            if fb == fa {
                return Ok(None);
            }
            let c = b - fb * (b - a) / (fb - fa);
            if !c.is_finite() {
                return Ok(None);
            }
            (a, fa) = (b, fb);
            b = c;
            fb = self.map(b)? - b;
        }
        // Not converged, or converged onto the equilibrium (the section's
        // end point, where `P(x*) = x*` with no cycle).
        if fb.abs() > 1e-10 * scale(b) || b - self.rest <= 1e-6 * scale(b) {
            return Ok(None);
        }
        self.finish(b).map(Some)
    }

    /// The cycle through the section point `x` (a fixed point of `P`): its
    /// period, stick, events and multiplier.
    fn finish(&self, x: f64) -> Result<SmoothCycle, SmoothError> {
        let (r, period) = self.apply(x)?;
        let multiplier = if r.stick > 0.0 {
            0.0
        } else {
            // Differences inside the section (x > x*).
            let h = (1e-5 * (1.0 + x.abs())).min(0.1 * (x - self.rest));
            (self.map(x + h)? - self.map(x - h)?) / (2.0 * h)
        };
        let verdict = verdict_of_modulus(multiplier.abs());
        Ok(SmoothCycle {
            x,
            period,
            stick: r.stick,
            multiplier,
            verdict,
            events: r.events,
        })
    }

    /// The stick-slip cycle, if there is one. In one degree of freedom
    /// every stick ends at the same state (`v = V`, the spring and damper
    /// at the static bound), so a stick-slip cycle passes through it and
    /// crosses the section once: it exists exactly when the motion from the
    /// stick's end sticks again before its second return to the section.
    pub fn stick_slip(&self) -> Result<Option<SmoothCycle>, SmoothError> {
        // Just before the end of a stick: the integrator ends it exactly.
        let start = State {
            phase: 0.0,
            x: self.stick_end - 1e-9 * self.belt.signum() * (1.0 + self.stick_end.abs()),
            v: self.belt,
            side: Side::Stick,
        };
        let first = match self.next(start)? {
            Ok(r) => r.state.x,
            Err(_) => return Ok(None),
        };
        let (r, _) = match self.apply(first) {
            Ok(r) => r,
            Err(SmoothError::NoReturn { .. }) => return Ok(None),
            Err(e) => return Err(e),
        };
        if r.stick == 0.0 {
            return Ok(None);
        }
        // After the stick the path is the one from `first`: `P` is constant.
        self.finish(r.state.x).map(Some)
    }

    /// Every cycle through the section: the stick-slip cycle, and the
    /// slip cycles between the equilibrium and it (or, without it, out to
    /// a few times the stick's end from the rest position), from the sign
    /// changes of `P(x) − x` on a grid that crowds towards both ends (where
    /// cycles are born at a Hopf point and meet at a fold), each refined by
    /// bracketed secant steps. Sorted by `x`.
    pub fn cycles(&self) -> Result<Vec<SmoothCycle>, SmoothError> {
        let outer = self.stick_slip()?;
        let rest = self.rest;
        let top = match &outer {
            Some(c) => c.x,
            None => rest + 4.0 * ((self.stick_end - rest).abs() + self.belt.abs() / self.omega),
        };
        let span = top - rest;
        let mut fractions: Vec<f64> = Vec::new();
        for k in (1..=8).rev() {
            fractions.push(10f64.powf(-(k as f64) / 2.0));
        }
        fractions.extend((1..20).map(|i| 0.05 * i as f64));
        for k in 2..=8 {
            fractions.push(1.0 - 10f64.powf(-(k as f64) / 2.0));
        }
        let mut samples: Vec<(f64, f64)> = Vec::new();
        for f in fractions {
            let x = rest + f * span;
            match self.map(x) {
                Ok(p) => samples.push((x, p - x)),
                Err(SmoothError::NoReturn { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        let mut found: Vec<SmoothCycle> = Vec::new();
        for w in samples.windows(2) {
            let ((a, fa), (b, fb)) = (w[0], w[1]);
            if fa.signum() == fb.signum() || fa == 0.0 || fb == 0.0 {
                continue;
            }
            if let Some(x) = self.root(a, fa, b, fb)? {
                found.push(self.finish(x)?);
            }
        }
        if let Some(c) = outer {
            let scale = 1.0 + c.x.abs();
            found.retain(|s| (s.x - c.x).abs() > 1e-8 * scale);
            found.push(c);
        }
        found.sort_by(|a, b| a.x.total_cmp(&b.x));
        // A root on a sample point ends two brackets: one cycle.
        found.dedup_by(|a, b| (a.x - b.x).abs() <= 1e-8 * (1.0 + b.x.abs()));
        Ok(found)
    }

    /// The root of `P(x) − x` in `[a, b]` (values `fa`, `fb` of opposite
    /// signs) by regula falsi (Illinois); `None` if the map fails inside.
    fn root(
        &self,
        mut a: f64,
        mut fa: f64,
        mut b: f64,
        mut fb: f64,
    ) -> Result<Option<f64>, SmoothError> {
        let mut last = 0i32;
        for _ in 0..100 {
            let c = (a * fb - b * fa) / (fb - fa);
            let c = if c > a.min(b) && c < a.max(b) {
                c
            } else {
                0.5 * (a + b)
            };
            let fc = match self.map(c) {
                Ok(p) => p - c,
                Err(SmoothError::NoReturn { .. }) => return Ok(None),
                Err(e) => return Err(e),
            };
            if fc == 0.0 || (b - a).abs() <= 1e-14 * (1.0 + c.abs()) {
                return Ok(Some(c));
            }
            if fc.signum() == fa.signum() {
                (a, fa) = (c, fc);
                if last == 1 {
                    fb *= 0.5;
                }
                last = 1;
            } else {
                (b, fb) = (c, fc);
                if last == -1 {
                    fa *= 0.5;
                }
                last = -1;
            }
        }
        Ok(Some(0.5 * (a + b)))
    }
}

/// What the smooth-law oscillator at `p` settles to from `(x, v, W t)`:
/// [`settle`] when it is unforced (the phase is then only a clock),
/// [`settle_forced`] when the forcing is on.
pub fn simulate<M: SmoothModel>(
    p: M::Params,
    (x, v, phase): (f64, f64, f64),
    options: SmoothOptions,
) -> Result<SmoothSettled, SmoothError> {
    if <M as FrictionOscillator>::oscillator(&p).amplitude != 0.0 {
        settle_forced::<M>(p, (x, v, phase), options).map(SmoothSettled::Periodic)
    } else {
        settle::<M>(p, (x, v), options)
    }
}

/// What the unforced smooth-law oscillator at `p` settles to from
/// `(x, v)`: steady sliding, or a stable cycle (refined by shooting on the
/// section `v = 0`).
pub fn settle<M: SmoothModel>(
    p: M::Params,
    (x, v): (f64, f64),
    options: SmoothOptions,
) -> Result<SmoothSettled, SmoothError> {
    let equilibrium = steady_sliding_smooth::<M>(&p)?;
    let map = ReturnMap::<M>::new(p, options.rtol)?;
    let scale = |s: f64| 1.0 + s.abs() + equilibrium.x.abs();
    let resting = |s: &State| {
        (s.x - equilibrium.x).abs() <= 1e-8 * scale(s.x) && s.v.abs() <= 1e-8 * scale(s.x)
    };
    let mut state = State {
        phase: 0.0,
        x,
        v,
        side: map.side(v),
    };
    let mut previous = f64::NAN;
    for returns in 0..=options.max_returns {
        let r = match map.next(state)? {
            Ok(r) => r,
            // No more turning points: a node, or already at rest.
            Err(end) if resting(&end) => {
                return Ok(SmoothSettled::SteadySliding {
                    equilibrium,
                    returns,
                })
            }
            Err(_) => {
                return Err(SmoothError::NoReturn {
                    x: state.x,
                    time: map.horizon,
                })
            }
        };
        let (current, next) = (state.x, r.state.x);
        if (next - equilibrium.x).abs() <= 1e-8 * scale(next)
            && equilibrium.verdict != Verdict::Unstable
        {
            return Ok(SmoothSettled::SteadySliding {
                equilibrium,
                returns,
            });
        }
        // Settled on the section, or converging slowly (every 50 returns):
        // refine, and keep it if it is the attractor.
        let on_section = returns > 0;
        let step = (next - current).abs();
        if on_section
            && (step <= 1e-7 * scale(current)
                || (returns % 50 == 0 && step <= 1e-2 * scale(current)))
        {
            if let Some(cycle) = map.cycle(next)? {
                if cycle.verdict == Verdict::Stable {
                    return Ok(SmoothSettled::Cycle { cycle, returns });
                }
            }
        }
        previous = current;
        state = State {
            phase: 0.0,
            ..r.state
        };
    }
    Err(SmoothError::NotSettled {
        returns: options.max_returns,
        last: state.x,
        previous,
    })
}

/// A periodic motion of the forced smooth-law oscillator.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SmoothPeriodic {
    /// Its period in forcing periods.
    pub periods: u32,
    /// The stroboscopic section's phase `W t` (mod 2π).
    pub phase: f64,
    /// Displacement there.
    pub x: f64,
    /// Velocity there.
    pub v: f64,
    /// Whether it sticks to the belt in a period.
    pub sticks: bool,
    /// The Floquet multipliers `[re, im]`, from central differences on the
    /// integrated stroboscopic map (a stick makes one of them 0).
    pub multipliers: [[f64; 2]; 2],
    /// Stable when both lie inside the unit circle.
    pub verdict: Verdict,
    /// The events at the belt speed in one period, phases from the section.
    pub events: Vec<BeltEvent>,
    /// Forcing periods simulated before it was refined.
    pub transient: u32,
}

/// The periodic motion the forced smooth-law oscillator at `p` settles to
/// from `(x, v, W t)`: simulated period by period until the stroboscopic
/// state repeats after some `q ≤ 8` periods, then refined by shooting.
pub fn settle_forced<M: SmoothModel>(
    p: M::Params,
    (x, v, phase): (f64, f64, f64),
    options: SmoothOptions,
) -> Result<SmoothPeriodic, SmoothError> {
    const LONGEST: usize = 8;
    let integrator = Integrator::<M>::new(p, options.rtol)?;
    let side = side_of(v, integrator.belt());
    let mut seen: Vec<State> = vec![State { phase, x, v, side }];
    let scale = |s: &State| 1.0 + s.x.abs().max(s.v.abs());
    let close = |a: &State, b: &State| {
        (a.x - b.x).abs().max((a.v - b.v).abs()) <= 1e-7 * scale(a) && a.side == b.side
    };
    for k in 1..=options.max_returns {
        let next = integrator.period_map(*seen.last().expect("a state"), 1)?;
        let found = (1..=LONGEST.min(seen.len())).find(|&q| close(&next, &seen[seen.len() - q]));
        if seen.len() > LONGEST {
            seen.remove(0);
        }
        seen.push(next);
        let Some(q) = found else { continue };
        let q = q as u32;
        let Ok(state) = integrator.shoot(next, q, 1e-11) else {
            continue;
        };
        let mut events = Vec::new();
        integrator.run(state, state.phase + q as f64 * std::f64::consts::TAU, |e| {
            let mut e = *e;
            e.phase -= state.phase;
            events.push(e);
        })?;
        let sticks = events.iter().any(|e| e.after == Side::Stick);
        let h = 1e-6 * scale(&state);
        let mut jac = Matrix2::zeros();
        for (col, (dx, dv)) in [(h, 0.0), (0.0, h)].into_iter().enumerate() {
            let at = |sign: f64| {
                integrator.period_map(
                    State {
                        x: state.x + sign * dx,
                        v: state.v + sign * dv,
                        ..state
                    },
                    q,
                )
            };
            let (plus, minus) = (at(1.0)?, at(-1.0)?);
            jac[(0, col)] = (plus.x - minus.x) / (2.0 * h);
            jac[(1, col)] = (plus.v - minus.v) / (2.0 * h);
        }
        // A stick collapses the map to a curve: one multiplier is exactly
        // 0 and the other the trace.
        let multipliers = if sticks {
            [[jac.trace(), 0.0], [0.0, 0.0]]
        } else {
            let eig = jac.complex_eigenvalues();
            [[eig[0].re, eig[0].im], [eig[1].re, eig[1].im]]
        };
        let norm = |m: [f64; 2]| m[0].hypot(m[1]);
        let verdict = verdict_of_modulus(norm(multipliers[0]).max(norm(multipliers[1])));
        return Ok(SmoothPeriodic {
            periods: q,
            phase: state.phase.rem_euclid(std::f64::consts::TAU),
            x: state.x,
            v: state.v,
            sticks,
            multipliers,
            verdict,
            events,
            transient: k,
        });
    }
    Err(SmoothError::NoPeriodic {
        periods: options.max_returns,
    })
}
