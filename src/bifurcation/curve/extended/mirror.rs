//! The mirror arrival of a symmetric motion (see the parent module): where
//! the curve's own event is a tangential arrival before a stick, its mirror
//! image half a cycle later is tangential too, all along the curve, and its
//! velocity equation has a double root in the arrival's phase. That row is
//! solved as the arrival's normal field instead, and the dropped equation
//! checked after every correction.

use crate::bifurcation::bordered::Correction;
use crate::model::{MappingKind, Model};
use crate::orbit::admissible::SAME_EVENT;

use super::super::condition::field_at_end;
use super::super::trace::HOLDS_TO;
use super::super::Condition;
use super::Extended;

/// How nearly a motion's second half must mirror its first to be taken for
/// a symmetric motion ([`Extended::pin_tangent_arrivals`]), relative to the
/// motion's length scale and in radians: the start of a curve, located by
/// a sweep, is symmetric to about its location tolerance; a motion of an
/// oscillator without the symmetry is not symmetric at all.
const MIRRORED: f64 = 1e-6;

impl<M: Model> Extended<M> {
    /// Pin the mirror image of the curve's own arrival before a stick
    /// where it is tangential with it all along the curve: `x` (a point of
    /// the curve) a symmetric motion ([`Self::mirrored`]: point `k + m/2` is
    /// point `k` mirrored, half a cycle later), the curve's condition a
    /// margin at segment `s` and the arrival of segment `s + m/2`, before a
    /// stick, tangential (normal field within [`SAME_EVENT`] of zero).
    /// That arrival's velocity equation has a double root in its phase
    /// (Newton halves the error per iteration, and the point is located
    /// only to the square root of rounding), so the system solves `F_j = 0`
    /// there instead. Shaw's oscillator (`coulomb` with `V = 0`) at W ≈
    /// 0.41: the passable onset of
    /// `P_{0_11 2_11 1_11 2_11 1_11 0_11 1_11 2_11 1_11 2_11}^3` at one
    /// stick is its mirror's at the other; without the pin the system's
    /// Jacobian has a singular value 2e-10 of its largest. An arrival that
    /// is nearly tangential by coincidence (the paper model's period-adding
    /// cascade) is not pinned: there the dropped velocity equation, only
    /// quadratic in the arrival's phase, would hardly see the point leave
    /// the curve. Returns how many arrivals are pinned (0 or 1).
    pub(in crate::bifurcation::curve) fn pin_tangent_arrivals(&mut self, x: &[f64]) -> usize {
        self.pins.clear();
        let Condition::Margin { segment: own, .. } = self.eval.condition else {
            return 0;
        };
        let m = self.m;
        if m % 2 != 0 || own >= m || !self.mirrored(x) {
            return 0;
        }
        let k = (own + m / 2) % m;
        let info = self.eval.sim.info();
        let step = self.eval.steps[k];
        let next = self.eval.steps[(k + 1) % m];
        if info.mappings[step].kind == MappingKind::Stick
            || info.mappings[next].kind != MappingKind::Stick
        {
            return 0;
        }
        let (_, b) = self.ends(x, k);
        if field_at_end::<M>(&self.params(x), step, b, true, false).abs() <= SAME_EVENT {
            self.pins.push(k);
        }
        self.pins.len()
    }

    /// Whether the switching points of `x` are a symmetric motion: point
    /// `k + m/2` is point `k` mirrored (`−x`, within [`MIRRORED`] of `L`)
    /// half a cycle later (`N π`, within [`MIRRORED`] radians).
    fn mirrored(&self, x: &[f64]) -> bool {
        self.mirrored_within(x, MIRRORED)
    }

    /// [`Self::mirrored`] within `tol` (of `L`, and radians).
    pub(super) fn mirrored_within(&self, x: &[f64], tol: f64) -> bool {
        let half = self.m / 2;
        let shift = 0.5 * self.eval.shift;
        (0..half).all(|k| {
            let (a, b) = (2 * k, 2 * (k + half));
            (x[a] + x[b]).abs() <= tol * self.length && (x[b + 1] - x[a + 1] - shift).abs() <= tol
        })
    }

    /// How many arrivals are pinned.
    pub(in crate::bifurcation::curve) fn pinned(&self) -> usize {
        self.pins.len()
    }

    /// Every arrival's velocity equation back in the system.
    pub(in crate::bifurcation::curve) fn unpin(&mut self) {
        self.pins.clear();
    }

    /// The largest dropped velocity equation `f2` of a pinned arrival at
    /// `x`, over its row's largest derivative (0 with none pinned).
    fn dropped_residual(&self, x: &[f64]) -> f64 {
        self.pins
            .iter()
            .fold(0.0f64, |worst, &k| worst.max(self.row_residual(x, k, 1)))
    }

    /// Mapping `k`'s equation `row` at `x` over its row's largest
    /// derivative (NaN counts as infinite).
    pub(super) fn row_residual(&self, x: &[f64], k: usize, row: usize) -> f64 {
        let p = self.params(x);
        let (a, b) = self.ends(x, k);
        let ev = M::mapping(&p, self.eval.steps[k], a.x, a.phase, b.x, b.phase);
        let scale = (0..2).fold(0.0f64, |s, c| {
            s.max(ev.d_prev[(row, c)].abs())
                .max(ev.d_next[(row, c)].abs())
        });
        let r = (ev.residual[row] / scale).abs();
        if r.is_nan() {
            f64::INFINITY
        } else {
            r
        }
    }

    /// Row `2k + 1` (segment `k`'s velocity equation) replaced by its
    /// arrival's normal field and that field's central differences in the
    /// arrival point and the two parameters.
    pub(super) fn pin_row(&mut self, x: &[f64], k: usize) {
        let (n, m) = (self.n, self.m);
        let step = self.eval.steps[k];
        let next = (k + 1) % m;
        let row = 2 * k + 1;
        let field = |s: &Self, at: &[f64]| {
            let (_, b) = s.ends(at, k);
            field_at_end::<M>(&s.params(at), step, b, true, false)
        };
        self.jac[row * n..(row + 1) * n]
            .iter_mut()
            .for_each(|c| *c = 0.0);
        self.rhs[row] = -field(self, x);
        let mut trial = std::mem::take(&mut self.trial);
        trial.copy_from_slice(x);
        for i in [2 * next, 2 * next + 1, n - 2, n - 1] {
            let h = self.fd_step(x, i);
            trial[i] = x[i] + h;
            let fp = field(self, &trial);
            trial[i] = x[i] - h;
            let fm = field(self, &trial);
            trial[i] = x[i];
            self.jac[row * n + i] = (fp - fm) / (2.0 * h);
        }
        self.trial = trial;
    }

    /// A converged correction stands only if the velocity equations
    /// dropped for pinned arrivals ([`Self::pin_tangent_arrivals`]), and
    /// the second half's mapping equations of a system restricted to the
    /// symmetric motions ([`Self::restrict_to_symmetric`]), hold to
    /// [`HOLDS_TO`] of their rows' largest derivatives.
    pub(super) fn check_dropped(&self, x: &[f64], c: Correction) -> Correction {
        if !matches!(c, Correction::Converged { .. }) {
            return c;
        }
        let r = self.mirror_residual(x);
        if r > HOLDS_TO {
            return Correction::Failed(format!(
                "the motion's second half is not its first mirrored (its mapping equations hold to {r:.1e} only)"
            ));
        }
        let r = self.dropped_residual(x);
        if r <= HOLDS_TO {
            return c;
        }
        Correction::Failed(format!(
            "a pinned arrival is no longer tangential (its velocity equation holds to {r:.1e} only)"
        ))
    }
}
