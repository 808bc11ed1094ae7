//! The velocity extrema of one flow segment, from the closed form (SPEC §4),
//! for the admissibility checks: where the acceleration `a = v'` vanishes
//! between two switching points, proven by bounds, so that a segment on
//! which the acceleration keeps its sign costs one evaluation.
//!
//! In a domain the flow is `x = A cos W t + B sin W t + C + homogeneous(τ)`
//! and the acceleration solves `a'' + 2 d_j a' + c_j a = −A0 W² cos W t`
//! (the equation of motion differentiated twice). By Grönwall in the norm
//! `max(ω̂ |a|, |a'|)`, `ω̂ = sqrt|c_j|` (the rate of the system matrix in it
//! is `ρ = max(ω̂, |c_j| / ω̂ + 2 |d_j|)`), from the state at the middle of a
//! piece of half-length `r` (in time):
//!
//! `|a'| ≤ J = (max(ω̂ |a_m|, |a'_m|) + r A0 W²) e^{ρ r}` on the whole piece,
//! `|a''| ≤ 2 |d_j| J + |c_j| (|a_m| + J r) + A0 W²`.
//!
//! So `|a_m| > J r` proves that `a` has no zero on the piece, and
//! `|a'_m| > r max|a''|` that `a` is monotone there (one zero at most, found
//! by a sign change and refined by safeguarded Newton). Otherwise the piece
//! is halved. The bounds hold in every damping regime (they use the ODE, not
//! the form of its solution).

use crate::dynamics::response::Response;
use crate::model::{Coefficients, Oscillator};

/// State and acceleration of the flow at one phase.
pub(crate) type FlowState = crate::dynamics::response::State;

/// The closed-form flow of one domain from `(x0, v0)` at phase `phi0`
/// ([`Response`]: everything that does not depend on the phase computed
/// once), with the constants of the bounds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SegmentFlow {
    response: Response,
    w: f64,
    two_d: f64,
    c: f64,
    omega: f64,
    rate: f64,
    forcing: f64,
}

/// Deepest halving of a piece before a sign test decides (the piece is then
/// 2^-48 of the segment: a double zero of `a`, a tangency of `v`'s extremum).
const MAX_DEPTH: u32 = 48;

impl SegmentFlow {
    /// The flow in a domain with coefficients `co` from `(x0, v0)` at
    /// `phi0`; `None` where the closed form does not apply (`c_j = 0`) or a
    /// coefficient is not finite.
    pub fn new(osc: Oscillator, co: Coefficients, x0: f64, v0: f64, phi0: f64) -> Option<Self> {
        let w = osc.frequency;
        let omega = match co.c.abs().sqrt() {
            o if o > 0.0 => o,
            _ => 1.0,
        };
        let rate = omega.max(co.c.abs() / omega + co.two_d.abs());
        let forcing = osc.amplitude.abs() * w * w;
        let response = Response::new(co, osc, x0, v0, phi0)?;
        (rate.is_finite() && forcing.is_finite() && w > 0.0).then_some(Self {
            response,
            w,
            two_d: co.two_d,
            c: co.c,
            omega,
            rate,
            forcing,
        })
    }

    /// The state at phase `phi`.
    #[inline]
    pub fn at(&self, phi: f64) -> FlowState {
        self.response.at(phi)
    }

    /// Every zero of the acceleration on `[lo, hi]` (phases), in increasing
    /// order, each passed to `on_zero` with its phase (refined until
    /// Newton's correction is below the rounding of the phase) and the state
    /// there. Returns the number of evaluations made.
    pub fn acceleration_zeros(
        &self,
        lo: f64,
        hi: f64,
        mut on_zero: impl FnMut(f64, &FlowState),
    ) -> usize {
        let mut evals = 0usize;
        // Pieces still to look at, the leftmost on top; (lo, hi, depth).
        let mut stack = [(0.0f64, 0.0f64, 0u32); MAX_DEPTH as usize + 2];
        let mut top = 1usize;
        stack[0] = (lo, hi, 0);
        let mut cached: Option<(f64, FlowState)> = None;
        while top > 0 {
            top -= 1;
            let (p0, p1, depth) = stack[top];
            let mid = 0.5 * (p0 + p1);
            let r = 0.5 * (p1 - p0) / self.w;
            let m = self.at(mid);
            evals += 1;
            let j = ((self.omega * m.a).abs().max(m.da.abs()) + r * self.forcing)
                * (self.rate * r).exp();
            if m.a.abs() > j * r {
                continue;
            }
            let snap = self.two_d.abs() * j + self.c.abs() * (m.a.abs() + j * r) + self.forcing;
            // Taylor with the bound on `a''`: `|a − a_m − a'_m s| ≤ snap s²/2`.
            if m.a.abs() > m.da.abs() * r + 0.5 * snap * r * r {
                continue;
            }
            let monotone = m.da.abs() > snap * r;
            if monotone || depth >= MAX_DEPTH || !(j.is_finite() && snap.is_finite()) {
                // The right end of the piece looked at last is often this one's left end.
                let s0 = match cached {
                    Some((phi, s)) if phi == p0 => s,
                    _ => {
                        evals += 1;
                        self.at(p0)
                    }
                };
                let s1 = self.at(p1);
                evals += 1;
                cached = Some((p1, s1));
                if (s0.a > 0.0) != (s1.a > 0.0) {
                    let (phi, st, n) = self.refine(p0, p1, s0.a, m, mid);
                    evals += n;
                    on_zero(phi, &st);
                }
                continue;
            }
            // Right half below the left one: the left is looked at first.
            stack[top] = (mid, p1, depth + 1);
            stack[top + 1] = (p0, mid, depth + 1);
            top += 2;
        }
        evals
    }

    /// The zero of `a` in `[lo, hi]` (where it changes sign, `a(lo) = a_lo`)
    /// by Newton safeguarded with bisection, from `start` (state `s`).
    fn refine(
        &self,
        mut lo: f64,
        mut hi: f64,
        a_lo: f64,
        mut s: FlowState,
        start: f64,
    ) -> (f64, FlowState, usize) {
        let mut t = start;
        let mut evals = 0;
        for _ in 0..60 {
            if (s.a > 0.0) == (a_lo > 0.0) {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - s.a * self.w / s.da;
            let resolution = 4.0 * f64::EPSILON * t.abs().max(1.0);
            // A correction below the phase's rounding: converged (it would
            // round to the iterate, an end of the bracket).
            if s.da != 0.0 && (newton - t).abs() <= resolution {
                break;
            }
            let next = if s.da != 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let done = (next - t).abs() <= resolution;
            t = next;
            s = self.at(t);
            evals += 1;
            if done {
                break;
            }
        }
        (t, s, evals)
    }
}
