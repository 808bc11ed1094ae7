//! The pitchfork of a symmetric motion (see the parent module): where the
//! symmetric motion's asymmetric pair branches off, the whole cycle's
//! system is singular all along the curve, and the curve is solved on the
//! symmetric motions alone, as the mirrored half-cycle map's eigenvalue
//! `−1`.

use crate::bifurcation::TransitionKind;
use crate::model::Model;

use super::super::condition::mirrored_half_map;
use super::super::Condition;
use super::Extended;

/// How nearly a branch point's start must mirror its first half to be
/// taken for a symmetric motion's pitchfork ([`Extended::restrict_to_symmetric`]),
/// relative to the motion's length scale and in radians. Looser than the
/// pin's (`mirror.rs`): a sweep locates a pitchfork on the singular whole
/// system, and its point is asymmetric by about the square root of its
/// tolerance (3.7e-5 on Shaw's `P_{0_11 1_11 0_11 2_11}` at W = 0.408).
/// The mirror rows make the first correction symmetric; whether the
/// oscillator is symmetric is checked after every correction
/// ([`Extended::mirror_residual`]).
const NEARLY_MIRRORED: f64 = 1e-3;

impl<M: Model> Extended<M> {
    /// Solve a branch-point curve on the symmetric motions alone where it
    /// is a symmetric motion's pitchfork: `x` (a point near the curve)
    /// nearly a symmetric motion (point `k + m/2` is point `k` mirrored,
    /// `N π` later, `N` odd), and its eigenvalue `+1` of `DP = (R DG)²`
    /// that of the mirrored half-cycle map `R DG` at `−1`, not at `+1`.
    ///
    /// Why: at a symmetry-breaking branch point the mapping equations'
    /// Jacobian has an antisymmetric null vector, and their derivatives in
    /// the parameters are symmetric, so in its range: the whole system
    /// `{F = 0, det(I − DP) = 0}` is singular all along the curve (on
    /// Shaw's oscillator a singular value 2.7e-10 of the largest 13.1),
    /// and no start converges. Restricted to the symmetric motions (the
    /// second half's equations replaced by the mirror, rows
    /// [`Self::mirror_rows`]) with the test function `det(I + R DG)`, it
    /// is regular. The second half's mapping equations, dropped, still
    /// hold on every accepted point ([`Self::mirror_residual`]). Returns
    /// whether the system is so restricted.
    pub(in crate::bifurcation::curve) fn restrict_to_symmetric(&mut self, x: &[f64]) -> bool {
        self.eval.half = 0;
        let m = self.m;
        let odd = self
            .eval
            .structure
            .as_ref()
            .is_some_and(|s| s.periods() % 2 == 1);
        if self.eval.condition != Condition::Eigen(TransitionKind::BranchPoint)
            || m == 0
            || m % 2 != 0
            || !odd
            || !self.mirrored_within(x, NEARLY_MIRRORED)
        {
            return false;
        }
        let p = self.params(x);
        self.load(x);
        let Ok(rdg) =
            mirrored_half_map::<M>(&p, &self.eval.steps, m / 2, self.eval.shift, &self.pts)
        else {
            return false;
        };
        let (tr, det) = (rdg.trace(), rdg.determinant());
        // `R DG` at +1 is a fold of the symmetric motions themselves:
        // regular in the whole system.
        if (1.0 + tr + det).abs() < (1.0 - tr + det).abs() {
            self.eval.half = m / 2;
        }
        self.restricted()
    }

    /// Whether the system is solved on the symmetric motions alone.
    pub(in crate::bifurcation::curve) fn restricted(&self) -> bool {
        self.eval.half > 0
    }

    /// The whole cycle's system again.
    pub(in crate::bifurcation::curve) fn unrestrict(&mut self) {
        self.eval.half = 0;
    }

    /// Rows `2k`, `2k + 1` (`k` in the second half, `j = k − m/2`): point
    /// `k` is point `j` mirrored half a cycle later, `x_k + x_j = 0` and
    /// `W t_k − W t_j − N π = 0`.
    pub(super) fn mirror_rows(&mut self, x: &[f64], k: usize) {
        let n = self.n;
        let j = k - self.eval.half;
        let (rx, rt) = (2 * k * n, (2 * k + 1) * n);
        self.jac[rx + 2 * k] = 1.0;
        self.jac[rx + 2 * j] = 1.0;
        self.rhs[2 * k] = -(x[2 * k] + x[2 * j]);
        self.jac[rt + 2 * k + 1] = 1.0;
        self.jac[rt + 2 * j + 1] = -1.0;
        self.rhs[2 * k + 1] = -(x[2 * k + 1] - x[2 * j + 1] - 0.5 * self.eval.shift);
    }

    /// The largest mapping equation of the second half at `x`, each over
    /// its row's largest derivative (0 unrestricted): the mirror rows stand
    /// in for them, and they hold only where the oscillator is symmetric.
    pub(super) fn mirror_residual(&self, x: &[f64]) -> f64 {
        if !self.restricted() {
            return 0.0;
        }
        (self.eval.half..self.m)
            .flat_map(|k| [(k, 0), (k, 1)])
            .fold(0.0f64, |worst, (k, row)| {
                worst.max(self.row_residual(x, k, row))
            })
    }

    /// `|R DG|`'s scale `1 + |tr| + |det|` at `x` (restricted systems;
    /// `None` unrestricted or where an arrival is tangential).
    pub(super) fn half_scale(&self, p: &M::Params) -> Option<f64> {
        if !self.restricted() {
            return None;
        }
        mirrored_half_map::<M>(
            p,
            &self.eval.steps,
            self.eval.half,
            self.eval.shift,
            &self.pts,
        )
        .ok()
        .map(|rdg| 1.0 + rdg.trace().abs() + rdg.determinant().abs())
    }
}
