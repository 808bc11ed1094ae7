//! Test functions of the eigenvalue bifurcations along a branch, and which
//! bifurcation a sign change between two points means.
//!
//! * `ψ_fold = t_λ`, the parameter component of the unit tangent;
//! * `ψ_+1 = det(I − DP)`: zero iff `DP` has the eigenvalue `+1`;
//! * `ψ_−1 = det(I + DP)`: zero iff `DP` has the eigenvalue `−1`;
//! * `ψ_NS = det DP − 1`: zero on a complex pair on the unit circle (when
//!   the eigenvalues are complex at one end of the step at least, and at
//!   the located zero).
//!
//! A Neimark–Sacker point need not have complex eigenvalues at both ends
//! of a step: near a 1:2 (or 1:1) resonance the pair crosses the circle
//! and then meets on the real axis within one step, and a step from a
//! complex pair outside the circle to a real pair inside it has crossed
//! the circle as a complex pair (neither `ψ_±1` changes sign: no real
//! eigenvalue crossed). With real eigenvalues at both ends `det DP = 1`
//! within the step is no crossing of the circle by a pair. The zero
//! located is accepted only if the pair is complex there and on the circle
//! ([`is_critical`]): a zero of `det DP − 1` on a real pair (one eigenvalue
//! inside, one outside) is none.
//!
//! `ψ_+1` changing sign is a fold when `t_λ` changes sign with it (the
//! branch turns back), else a branch point (the branch goes on through it
//! and another branch crosses). Of the two usual criteria for a branch
//! point — the sign of `ψ_+1` without a turn, or the sign of the bordered
//! system's determinant — the first is used: both `ψ_+1` and `t_λ` are
//! already computed at every point, exactly (`DP` from the generated
//! blocks), while the bordered determinant would depend on the scaling of
//! the unknowns and on the finite-difference `∂F/∂λ`. It can misclassify
//! only if a fold and a branch point fall within one step, which the step
//! control (eigenvalue moves of at most 0.25 per step) makes unlikely.

use nalgebra::Matrix2;

use crate::bifurcation::TransitionKind;
use crate::orbit::stability::Stability;

/// Test-function values at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tests {
    pub t_lambda: f64,
    pub plus: f64,
    pub minus: f64,
    pub ns: f64,
    pub complex: bool,
}

/// Which test function locates a bifurcation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Psi {
    Plus,
    Minus,
    Ns,
}

/// Below this a test function counts as zero at the start of a step: the
/// start is itself the bifurcation (a branch born there), not a crossing.
const AT_ZERO: f64 = 1e-9;

impl Tests {
    pub fn of(dp: &Matrix2<f64>, t_lambda: f64) -> Self {
        let (tr, det) = (dp.trace(), dp.determinant());
        Self {
            t_lambda,
            plus: 1.0 - tr + det,
            minus: 1.0 + tr + det,
            ns: det - 1.0,
            complex: tr * tr < 4.0 * det,
        }
    }

    pub fn value(&self, which: Psi) -> f64 {
        match which {
            Psi::Plus => self.plus,
            Psi::Minus => self.minus,
            Psi::Ns => self.ns,
        }
    }
}

impl Psi {
    /// The sign of this test function at `a` (so that `sign · ψ > 0` on `a`'s side).
    pub fn sign_from(self, a: &Tests) -> f64 {
        a.value(self).signum()
    }
}

fn changes(a: f64, b: f64) -> bool {
    a.abs() > AT_ZERO && (a > 0.0) != (b > 0.0) && !b.is_nan()
}

/// The bifurcations between two consecutive points of a branch.
pub(crate) fn crossings(a: &Tests, b: &Tests) -> Vec<(TransitionKind, Psi)> {
    let mut out = Vec::new();
    if changes(a.plus, b.plus) {
        let turned = (a.t_lambda > 0.0) != (b.t_lambda > 0.0);
        let kind = if turned {
            TransitionKind::Fold
        } else {
            TransitionKind::BranchPoint
        };
        out.push((kind, Psi::Plus));
    }
    if changes(a.minus, b.minus) {
        out.push((TransitionKind::PeriodDoubling, Psi::Minus));
    }
    if (a.complex || b.complex) && changes(a.ns, b.ns) {
        out.push((TransitionKind::NeimarkSacker, Psi::Ns));
    }
    out
}

/// How far the eigenvalues move between two points (the larger of the two
/// moves, eigenvalues matched the closer way), relative to their modulus
/// when it exceeds 1: only moves near the unit circle can hide a crossing.
pub(crate) fn eigenvalue_jump(a: &Stability, b: &Stability) -> f64 {
    let d = |x: [f64; 2], y: [f64; 2]| {
        let scale = x[0].hypot(x[1]).min(y[0].hypot(y[1])).max(1.0);
        (x[0] - y[0]).hypot(x[1] - y[1]) / scale
    };
    let [a0, a1] = a.eigenvalues;
    let [b0, b1] = b.eigenvalues;
    let straight = d(a0, b0).max(d(a1, b1));
    let crossed = d(a0, b1).max(d(a1, b0));
    straight.min(crossed)
}

/// The critical eigenvalue of a bifurcation of kind `kind` (`im >= 0`).
/// How far the critical eigenvalue of a located bifurcation may lie from
/// the unit circle's critical point: a test function that changes sign
/// through a pole rather than a zero (the eigenvalues of `DP` jump or blow up
/// at a non-smooth transition: the arrival becomes tangential and `DP` is
/// singular) locates no bifurcation.
pub(crate) const CRITICAL_TOL: f64 = 1e-6;

/// Whether the located point's critical eigenvalue is on the unit circle
/// where `kind` says (within [`CRITICAL_TOL`]).
pub(crate) fn is_critical(kind: TransitionKind, s: &Stability) -> bool {
    let e = critical(kind, s);
    let miss = match kind {
        TransitionKind::PeriodDoubling => (e[0] + 1.0).hypot(e[1]),
        // A real pair with det DP = 1 is no Neimark–Sacker point.
        TransitionKind::NeimarkSacker if s.eigenvalues[0][1] == 0.0 => f64::INFINITY,
        TransitionKind::NeimarkSacker => (e[0].hypot(e[1]) - 1.0).abs(),
        _ => (e[0] - 1.0).hypot(e[1]),
    };
    miss <= CRITICAL_TOL
}

pub(crate) fn critical(kind: TransitionKind, s: &Stability) -> [f64; 2] {
    let target = match kind {
        TransitionKind::PeriodDoubling => -1.0,
        _ => 1.0,
    };
    let score = |e: &[f64; 2]| match kind {
        TransitionKind::NeimarkSacker => (e[0].hypot(e[1]) - 1.0).abs() - e[1].max(0.0) * 1e-12,
        _ => (e[0] - target).hypot(e[1]),
    };
    let e = if score(&s.eigenvalues[0]) <= score(&s.eigenvalues[1]) {
        s.eigenvalues[0]
    } else {
        s.eigenvalues[1]
    };
    [e[0], e[1].abs()]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dp(re: f64, im: f64) -> Matrix2<f64> {
        // A rotation-dilation: the eigenvalues re ± i im.
        Matrix2::new(re, -im, im, re)
    }

    /// A complex pair leaving the unit circle within a step whose end has
    /// real eigenvalues (they met on the real axis after the crossing) is a
    /// Neimark–Sacker crossing; real pairs at both ends are none.
    #[test]
    fn a_pair_crossing_the_circle_is_seen_from_one_complex_end() {
        let inside = Tests::of(&dp(-0.99, 0.05), 1.0);
        let outside = Tests::of(&dp(-0.99, 0.2), 1.0);
        let real_inside = Tests::of(&Matrix2::new(-0.995, 0.0, 0.0, -0.98), 1.0);
        let real_across = Tests::of(&Matrix2::new(0.5, 0.0, 0.0, 3.0), 1.0);
        let ns = |a: &Tests, b: &Tests| {
            crossings(a, b)
                .iter()
                .any(|&(k, _)| k == TransitionKind::NeimarkSacker)
        };
        assert!(ns(&outside, &inside) && ns(&inside, &outside));
        assert!(ns(&outside, &real_inside) && ns(&real_inside, &outside));
        assert!(!ns(&real_inside, &real_across));
    }
}
