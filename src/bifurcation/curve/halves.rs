//! A fold curve of a motion `T T` of two equal halves (a period-2 motion
//! born at `T`'s period doubling) whose two halves merge as the curve runs
//! on: the period-2 motions' fold meets `T`'s period-doubling curve there,
//! at a degenerate period doubling (the flip's cubic coefficient vanishes:
//! on one side of it the period doubling is supercritical, on the other
//! subcritical, and the fold of the period-2 motions born subcritically
//! starts at it). `T T` doubled from `T` solves the motion's equations all
//! along `T`'s period-doubling curve (a branch point of `T T`'s system), so
//! the curve's own system turns singular there and the corrector stalls
//! short of the point.
//!
//! Along the fold curve the halves' difference `a` goes to zero and the
//! parameters go as an even function of it, `p(a) = p₀ + c a² + O(a⁴)`:
//! `p₀` is extrapolated in `s = |a|²` from three traced points (a
//! quadratic in `s`, error `O(s³)`), and the end is solved exactly on `T`'s
//! period-doubling curve across the curve's last tangent through that
//! estimate, then doubled. There `det(I − DP_{TT}) = det(I − DP_T)
//! det(I + DP_T) = 0`: the end holds the curve's own condition and `T`'s
//! period doubling to rounding; its place along `T`'s period-doubling curve
//! is as good as the extrapolation (the linear and the quadratic estimate
//! are compared, and the end is refused where they differ by more than
//! [`AGREE`] of the box).

use crate::bifurcation::bordered::Correction;
use crate::bifurcation::TransitionKind;
use crate::model::Model;

use super::start::{system, to_point};
use super::stop::PAIR_ITERATIONS;
use super::trace::{Sample, Tracer, HOLDS_TO};
use super::Condition;

/// The halves' difference (squared, over the points) must have fallen to
/// less than this fraction of itself over the traced points used.
const MERGING: f64 = 0.25;

/// The extrapolations in `s` (linear from the last two points, quadratic
/// from three) agree to this in the plane (each parameter over its span),
/// or the end is refused.
const AGREE: f64 = 1e-4;

/// `|a|²`: the squared difference of the two halves of `x` (displacements
/// and phases, the second half's phases less half the cycle `shift`).
fn halves_apart(x: &[f64], shift: f64) -> f64 {
    let m = (x.len() - 2) / 2;
    let h = m / 2;
    (0..h)
        .map(|i| {
            let dx = x[2 * (i + h)] - x[2 * i];
            let dp = x[2 * (i + h) + 1] - x[2 * i + 1] - 0.5 * shift;
            dx * dx + dp * dp
        })
        .sum()
}

/// The value at `s = 0` of the polynomial through `(s_k, v_k)`.
fn at_zero(s: &[f64], v: &[f64]) -> f64 {
    (0..s.len())
        .map(|k| {
            let w: f64 = (0..s.len())
                .filter(|&j| j != k)
                .map(|j| s[j] / (s[j] - s[k]))
                .product();
            w * v[k]
        })
        .sum()
}

impl<M: Model> Tracer<'_, M> {
    /// Where a fold curve of `T T` ends as its halves merge (see the
    /// module), from the traced `points` (the last is `prev`): solved on
    /// `T` with its period-doubling test function, accepted where it
    /// converges, lies in the box ahead of `prev`, holds to [`HOLDS_TO`] of
    /// its scale, and every other condition of `T` holds there to
    /// [`SAME_EVENT`]. Returned in the curve's unknowns (`T` doubled).
    pub(super) fn halves_point(&mut self, points: &[Sample], prev: &Sample) -> Option<Sample> {
        if self.sys.eval.condition != Condition::Eigen(TransitionKind::Fold) {
            return None;
        }
        let t = self.sys.eval.structure.as_ref()?.half()?;
        let (h, shift) = (t.len(), self.sys.eval.shift);
        let n = prev.x.len();
        // Three points with distinct `s`: `prev` and the last two before it
        // with at least twice and four times its `s`.
        let s_prev = halves_apart(&prev.x, shift);
        let mut chosen = vec![(s_prev, prev)];
        for q in points.iter().rev() {
            let s = halves_apart(&q.x, shift);
            if chosen.len() < 3 && s >= 2.0 * chosen[chosen.len() - 1].0 {
                chosen.push((s, q));
            }
        }
        // (NaN fails every comparison.)
        let merging = s_prev <= MERGING * chosen.get(2).map_or(f64::NAN, |c| c.0);
        if !merging {
            return None;
        }
        let s: Vec<f64> = chosen.iter().map(|c| c.0).collect();
        let spans = self.sys.spans();
        let mut estimate = [0.0; 2];
        let mut linear = [0.0; 2];
        for (a, (e, l)) in estimate.iter_mut().zip(linear.iter_mut()).enumerate() {
            let v: Vec<f64> = chosen.iter().map(|c| c.1.x[n - 2 + a]).collect();
            *e = at_zero(&s, &v);
            *l = at_zero(&s[..2], &v[..2]);
        }
        let disagree =
            ((estimate[0] - linear[0]) / spans[0]).hypot((estimate[1] - linear[1]) / spans[1]);
        if disagree.is_nan() || disagree > AGREE {
            return None;
        }
        // `T` from the first half of `prev`, on the hyperplane through the
        // estimate across the curve's last tangent.
        let mut z: Vec<f64> = prev.x[..2 * h].to_vec();
        z.extend_from_slice(&estimate);
        let pd = Condition::Eigen(TransitionKind::PeriodDoubling);
        let mut sys =
            system::<M>(self.sys.base(), &self.plane, Some(&t), &to_point(&z), pd).ok()?;
        let anchor = z.clone();
        let mut border = vec![0.0; 2 * h + 2];
        border[2 * h] = prev.t[n - 2];
        border[2 * h + 1] = prev.t[n - 1];
        let done = sys.correct(
            &mut z,
            &border,
            &anchor,
            self.opts.tolerance,
            PAIR_ITERATIONS,
        );
        if !matches!(done, Correction::Converged { .. })
            || self.out_of_box(&z)
            || sys.held(&z) > HOLDS_TO
        {
            return None;
        }
        let reach = self.plane_distance(&estimate, &prev.x[n - 2..]);
        // Ahead along the chosen points' trend, not `prev`'s tangent: the
        // corrector may crawl on into the singular neighbourhood, its
        // tangent turning back and forth (s8box's period-2 fold at W ≈
        // 2.48567, once its test function was free of the arrival's time).
        let back = &chosen[chosen.len() - 1].1.x;
        let trend = [prev.x[n - 2] - back[n - 2], prev.x[n - 1] - back[n - 1]];
        let bound = 4.0 * reach + 16.0 * self.opts.min_step;
        if !self.ahead_along(&prev.x[n - 2..], &trend, &z, bound) {
            return None;
        }
        let z = self.holding_on(sys, z)?;
        // `T` doubled: the second half one cycle of `T` later.
        let mut x = z[..2 * h].to_vec();
        for i in 0..h {
            x.extend([z[2 * i], z[2 * i + 1] + 0.5 * shift]);
        }
        x.extend_from_slice(&z[2 * h..]);
        self.examine(x, prev.t.clone()).ok()
    }
}
