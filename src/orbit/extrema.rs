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
//!
//! On a monotone piece `|a'| ≥ μ = |a'_m| − r max|a''| > 0`, so the signs of
//! `a` at its ends follow from the same Taylor bound where it is decisive
//! (no evaluation), and an iterate `t` with acceleration `a` is within
//! `|a| / μ` (in time) of the zero and its velocity within `a² / μ` of the
//! extremum's: a caller that needs only to know that the extremum is clear
//! of a boundary can stop the refinement as soon as that is proven
//! (`Zero`, the `enough` of `SegmentFlow::acceleration_zeros`).

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

/// A zero of the acceleration as the search hands it over: its phase and
/// the state there, with bounds on how far both are from the exact zero's
/// (zero when refined until Newton's correction is below the phase's
/// rounding).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Zero {
    /// The phase.
    pub phase: f64,
    /// The state there.
    pub state: FlowState,
    /// `|phase − exact zero's phase|` is at most this.
    pub phase_err: f64,
    /// `|state.v − v at the exact zero|` is at most this.
    pub v_err: f64,
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

    /// The forcing frequency `W` (phase per unit time).
    pub fn frequency(&self) -> f64 {
        self.w
    }

    /// The state at phase `phi`.
    #[inline]
    pub fn at(&self, phi: f64) -> FlowState {
        self.response.at(phi)
    }

    /// Every zero of the acceleration on `[lo, hi]` (phases), in increasing
    /// order, each passed to `on_zero` ([`Zero`]): refined until Newton's
    /// correction is below the rounding of the phase, or until `enough`
    /// accepts it with its error bounds (`|_| false`: always to rounding).
    /// Returns the number of evaluations made.
    pub fn acceleration_zeros(
        &self,
        lo: f64,
        hi: f64,
        enough: impl Fn(&Zero) -> bool,
        mut on_zero: impl FnMut(&Zero),
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
            if monotone && j.is_finite() && snap.is_finite() {
                // `|a'| ≥ mu` on the piece; the ends' signs from Taylor
                // where it decides them, else evaluated.
                let mu = m.da.abs() - snap * r;
                let slack = 0.5 * snap * r * r;
                let sign = |end: f64, at: f64, evals: &mut usize| {
                    let taylor = m.a + m.da * end;
                    if taylor.abs() > slack {
                        taylor > 0.0
                    } else {
                        *evals += 1;
                        self.at(at).a > 0.0
                    }
                };
                let (a0, a1) = (sign(-r, p0, &mut evals), sign(r, p1, &mut evals));
                if a0 != a1 {
                    let (z, n) = self.refine(p0, p1, a0, m, mid, mu, &enough);
                    evals += n;
                    on_zero(&z);
                }
                continue;
            }
            // Not proven monotone with finite bounds: at the deepest halving
            // or where the bounds overflow, the ends' signs decide.
            if depth >= MAX_DEPTH || !(j.is_finite() && snap.is_finite()) {
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
                    let (z, n) = self.refine(p0, p1, s0.a > 0.0, m, mid, 0.0, &|_| false);
                    evals += n;
                    on_zero(&z);
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

    /// The zero of `a` in `[lo, hi]` (where it changes sign, `a(lo) > 0`
    /// is `lo_positive`) by Newton safeguarded with bisection, from `start`
    /// (state `s`). `mu > 0`: a lower bound of `|a'|` on the bracket, which
    /// bounds each iterate's errors for `enough` (0: no bound, refined to
    /// rounding).
    #[allow(clippy::too_many_arguments)]
    fn refine(
        &self,
        mut lo: f64,
        mut hi: f64,
        lo_positive: bool,
        mut s: FlowState,
        start: f64,
        mu: f64,
        enough: &impl Fn(&Zero) -> bool,
    ) -> (Zero, usize) {
        let mut t = start;
        let mut evals = 0;
        for _ in 0..60 {
            if (s.a > 0.0) == lo_positive {
                lo = t;
            } else {
                hi = t;
            }
            if mu > 0.0 {
                let dt = s.a.abs() / mu;
                let z = Zero {
                    phase: t,
                    state: s,
                    phase_err: dt * self.w,
                    v_err: s.a.abs() * dt,
                };
                if enough(&z) {
                    return (z, evals);
                }
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
        let z = Zero {
            phase: t,
            state: s,
            phase_err: 0.0,
            v_err: 0.0,
        };
        (z, evals)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::simulate::{SimOptions, Simulator};
    use crate::models::paper::{Paper, Params};

    /// A flow of the paper model at W = 5, Q0 = 70 in domain `j` over two
    /// forcing periods (several extrema of `v`).
    fn flow(j: usize) -> SegmentFlow {
        let p = Params {
            W: 5.0,
            Q0: 70.0,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("params");
        SegmentFlow::new(sim.oscillator(), sim.coefficients(j), 0.5, 2.0, 0.3).expect("a flow")
    }

    /// A zero accepted early by `enough` is within its stated bounds of the
    /// zero refined to rounding, and costs fewer evaluations.
    #[test]
    fn an_early_zero_is_within_its_bounds_of_the_refined_one() {
        for j in 0..4 {
            let f = flow(j);
            let (lo, hi) = (0.3, 0.3 + 4.0 * std::f64::consts::PI);
            let mut full = Vec::new();
            let n_full = f.acceleration_zeros(lo, hi, |_| false, |z| full.push(*z));
            let mut early = Vec::new();
            let n_early = f.acceleration_zeros(lo, hi, |z| z.v_err < 1e-2, |z| early.push(*z));
            assert!(full.len() >= 2, "domain {j}: {} zeros", full.len());
            assert_eq!(full.len(), early.len(), "domain {j}");
            assert!(full.iter().all(|z| z.phase_err == 0.0 && z.v_err == 0.0));
            assert!(
                early.iter().any(|z| z.phase_err > 0.0),
                "domain {j}: no zero accepted early"
            );
            assert!(
                n_early < n_full,
                "domain {j}: {n_early} vs {n_full} evaluations"
            );
            for (e, z) in early.iter().zip(&full) {
                // The bounds hold (and the refined zero is a zero).
                assert!(z.state.a.abs() <= 1e-9 * (1.0 + z.state.da.abs()), "{z:?}");
                assert!(
                    (e.phase - z.phase).abs() <= e.phase_err + 1e-12,
                    "domain {j}: {e:?} vs {z:?}"
                );
                assert!(
                    (e.state.v - z.state.v).abs() <= e.v_err + 1e-12,
                    "domain {j}: {e:?} vs {z:?}"
                );
            }
        }
    }
}
