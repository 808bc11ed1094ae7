//! The codimension-two solve (see the parent module): the mapping
//! equations with the curve's condition and a second one, both parameters
//! free and no border row, where the curve's own system turns singular at
//! the point.

use crate::bifurcation::bordered::Correction;
use crate::model::Model;

use super::super::condition::field_at_end;
use super::Extended;

/// A codimension-two point's equations hold when each residual is below this
/// times its row's largest derivative ([`Extended::correct_pair`]), where
/// the iteration stalls. Measured: the `^7` cascade curve's pair with its
/// segment 21 onset stalls at `2.7e-12`; the test's bar on a curve point's
/// condition is `1e-10`.
const PAIR_MERIT: f64 = 1e-11;

/// [`Extended::correct_pair`] stops after this many iterations without
/// the merit halving, and takes the best iterate.
const PAIR_STALL: usize = 8;

impl<M: Model> Extended<M> {
    /// Newton on the mapping equations, the curve's condition and the
    /// second condition [`Self::pair`] (both parameters free, no border
    /// row): a codimension-two point, from `x` (modified in place).
    /// Converged as [`Self::correct`]. Where an arrival before a stick
    /// turns tangential the curve's own system is singular (the stick's
    /// start is free along the stick to first order); the force criterion
    /// at that arrival pins it, so this system stays regular there.
    pub(in crate::bifurcation::curve) fn correct_pair(
        &mut self,
        x: &mut [f64],
        tol: f64,
        max_iterations: usize,
    ) -> Correction {
        let c = self.pair_newton(x, tol, max_iterations);
        self.check_dropped(x, c)
    }

    /// [`Self::correct_pair`]'s Newton iteration.
    fn pair_newton(&mut self, x: &mut [f64], tol: f64, max_iterations: usize) -> Correction {
        let n = self.n;
        if self.pair.is_none() {
            return Correction::Failed("no second condition".into());
        }
        let ulps = 8.0 * f64::EPSILON / tol.max(f64::MIN_POSITIVE);
        let mut last = f64::INFINITY;
        let mut scale = vec![0.0; n];
        let mut from = x.to_vec();
        // The iterate with the smallest merit, and how many iterations
        // since the merit last halved.
        let mut best = (f64::INFINITY, x.to_vec());
        let mut stalled = 0;
        for it in 0..max_iterations {
            if let Err(why) = self.assemble(x) {
                return Correction::Failed(why);
            }
            let g2 = self.condition_row(x, n - 1, true);
            if !g2.is_finite() || self.jac[(n - 1) * n..].iter().any(|v| !v.is_finite()) {
                return Correction::Failed(format!(
                    "the second condition is not defined here ({g2:e})"
                ));
            }
            // Each row's residual over its largest derivative: the merit
            // of a step, in the units the elimination equilibrates to.
            for (i, sc) in scale.iter_mut().enumerate() {
                *sc = self.jac[i * n..(i + 1) * n]
                    .iter()
                    .fold(0.0f64, |a, v| a.max(v.abs()));
            }
            let merit = self
                .rhs
                .iter()
                .zip(&scale)
                .fold(0.0f64, |a, (r, s)| a.max(r.abs() / s));
            stalled = if merit < 0.5 * best.0 { 0 } else { stalled + 1 };
            if merit < best.0 {
                best.0 = merit;
                best.1.copy_from_slice(x);
            }
            // The merit has reached its rounding floor: where further
            // arrivals before sticks are almost tangential as well (a
            // period-adding cascade's accumulating codimension-two points)
            // their stick starts are nearly free along the sticks, and the
            // steps only stir them at the rounding level times that
            // conditioning.
            if stalled >= PAIR_STALL {
                break;
            }
            if let Err(why) = self.eliminate() {
                return Correction::Failed(why);
            }
            from.copy_from_slice(x);
            let mut size = self.step(x, ulps);
            if size.is_nan() {
                return Correction::Failed("the Newton step is not finite".into());
            }
            // Damped: near a second arrival that is almost tangential the
            // full step overshoots onto the far root of its arrival
            // equation; halve it until the merit falls.
            if size > 1e3 * tol {
                for _ in 0..12 {
                    if self.pair_merit(x, &scale) < merit {
                        break;
                    }
                    for ((xi, a), d) in x.iter_mut().zip(&from).zip(&mut self.delta) {
                        *d *= 0.5;
                        *xi = a + *d;
                    }
                    size *= 0.5;
                }
            }
            if size <= tol || (it >= 1 && size <= 1e3 * tol && size > 0.5 * last) {
                return Correction::Converged { iterations: it + 1 };
            }
            last = size;
        }
        if best.0 <= PAIR_MERIT {
            x.copy_from_slice(&best.1);
            return Correction::Converged {
                iterations: max_iterations,
            };
        }
        Correction::Failed(format!(
            "no convergence in {max_iterations} iterations (smallest scaled residual {:.3e})",
            best.0
        ))
    }

    /// The largest residual of the pair system at `x`, each row over
    /// `scale` (NaN counts as infinite).
    fn pair_merit(&mut self, x: &[f64], scale: &[f64]) -> f64 {
        let n = self.n;
        let p = self.params(x);
        let mut worst = 0.0f64;
        let mut add = |v: f64, s: f64| {
            let r = (v / s).abs();
            worst = if r.is_nan() {
                f64::INFINITY
            } else {
                worst.max(r)
            };
        };
        for k in 0..self.m {
            let (a, b) = self.ends(x, k);
            let step = self.eval.steps[k];
            let f = M::residual(&p, step, a.x, a.phase, b.x, b.phase);
            add(f[0], scale[2 * k]);
            if self.pins.contains(&k) {
                add(
                    field_at_end::<M>(&p, step, b, true, false),
                    scale[2 * k + 1],
                );
            } else {
                add(f[1], scale[2 * k + 1]);
            }
        }
        let g = self.condition(x);
        let g2 = self.pair_condition(x);
        add(g, scale[2 * self.m]);
        add(g2, scale[n - 1]);
        worst
    }
}
