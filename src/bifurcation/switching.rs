//! Branch switching: the starts of the branches born at a bifurcation.
//!
//! At a branch point the kernel of `F_u` is `φ = (φ_0, …, φ_{m−1})`: the
//! eigenvector of `DP` for `+1`, propagated around the cycle by the blocks
//! `A_k` of the bordered system (`φ_{k+1} = A_k φ_k`). The new branch leaves
//! along `(φ, 0)` made orthogonal to the old branch's tangent (scaled
//! metric); both halves, `±`, are followed away from the branch point. The
//! first corrector step lies on the hyperplane normal to that direction,
//! which the old branch meets only far away, and a step whose correction is
//! larger than half the step is rejected and halved (so the corrector cannot
//! fall back onto the old branch).
//!
//! At a period doubling the doubled structure (`structure.repeated(2)`, the
//! motion continued twice) has a branch point: the eigenvalue `−1` of `DP`
//! is `+1` of `DP²`, with kernel `(φ, −φ)` (`φ` for the `−1` eigenvector),
//! orthogonal to the old branch's `(t_u, t_u, t_λ)` exactly. Its two halves
//! are the same motion one forcing cycle apart, so there is one start.

use nalgebra::{Matrix2, Vector2};

use crate::bifurcation::bordered::{State, Vector};
use crate::bifurcation::branch::{Bifurcation, Branch};
use crate::bifurcation::continuation::{system, to_direction, ContinuationOptions, Start};
use crate::bifurcation::TransitionKind;
use crate::model::Model;
use crate::orbit::periodic::SwitchingPoint;

/// An eigenvector of the 2×2 matrix `a` for its real eigenvalue `mu`.
fn eigenvector(a: &Matrix2<f64>, mu: f64) -> Vector2<f64> {
    let b = a - Matrix2::identity() * mu;
    // Each row r of b gives the kernel vector (-r1, r0); take the larger.
    let v0 = Vector2::new(-b[(0, 1)], b[(0, 0)]);
    let v1 = Vector2::new(-b[(1, 1)], b[(1, 0)]);
    let v = if v0.norm() >= v1.norm() { v0 } else { v1 };
    if v.norm() > 0.0 {
        v / v.norm()
    } else {
        Vector2::new(1.0, 0.0)
    }
}

/// The starts of the branches born at `bif` on `branch` (parameter `index`
/// of `base`): two at a branch point, one (on the doubled structure) at a
/// period doubling, none at a fold or a Neimark–Sacker point.
pub fn born<M: Model>(
    base: &M::Params,
    index: usize,
    branch: &Branch,
    bif: &Bifurcation,
    opts: &ContinuationOptions,
) -> Vec<Start> {
    let mu = match bif.kind {
        TransitionKind::BranchPoint => 1.0,
        TransitionKind::PeriodDoubling => -1.0,
        _ => return Vec::new(),
    };
    let at = &bif.at;
    let m = at.points.len();
    let mut sys = system::<M>(base, index, &branch.structure, at.value, &at.points, opts);
    let x = State {
        points: at.points.clone(),
        value: at.value,
    };
    // The old branch's tangent, oriented by its neighbours (the secant).
    let i = bif.index.min(branch.points.len().saturating_sub(1));
    let (lo, hi) = (i.saturating_sub(1), (i + 1).min(branch.points.len() - 1));
    let mut secant = Vector::zeros(m);
    if lo != hi {
        let (a, b) = (&branch.points[lo], &branch.points[hi]);
        for ((d, p), q) in secant.du.iter_mut().zip(&b.points).zip(&a.points) {
            *d = Vector2::new(p.x - q.x, p.phase - q.phase);
        }
        secant.dl = b.value - a.value;
    } else {
        secant.dl = 1.0;
    }
    sys.normalize(&mut secant);
    // The blocks A_k at the point, left in the workspace by a tangent solve
    // (stored before its 3×3 solve, which at a branch point is singular:
    // its solution is not the old branch's tangent, so the secant through
    // the neighbours serves as that).
    let mut scratch = secant.clone();
    let _ = sys.tangent(&x, &secant, &mut scratch);
    let tangent = secant;
    let blocks: Vec<Matrix2<f64>> = sys.blocks().to_vec();
    let dp = blocks.iter().fold(Matrix2::identity(), |acc, a| a * acc);
    // The real eigenvalue of DP nearest mu.
    let (tr, det) = (dp.trace(), dp.determinant());
    let disc = (0.25 * tr * tr - det).max(0.0).sqrt();
    let ev = [0.5 * tr + disc, 0.5 * tr - disc];
    let lambda = if (ev[0] - mu).abs() <= (ev[1] - mu).abs() {
        ev[0]
    } else {
        ev[1]
    };
    let mut phi = Vec::with_capacity(m);
    let mut v = eigenvector(&dp, lambda);
    for a in &blocks {
        phi.push(v);
        v = a * v;
    }
    match bif.kind {
        TransitionKind::BranchPoint => {
            let mut d = Vector { du: phi, dl: 0.0 };
            let along = sys.dot(&d, &tangent);
            for (x, t) in d.du.iter_mut().zip(&tangent.du) {
                *x -= along * t;
            }
            d.dl -= along * tangent.dl;
            sys.normalize(&mut d);
            [d.clone(), d.neg()]
                .into_iter()
                .map(|d| Start {
                    structure: branch.structure.clone(),
                    value: at.value,
                    points: at.points.clone(),
                    direction: Some(to_direction(&d)),
                })
                .collect()
        }
        _ => {
            let doubled = branch.structure.repeated(2);
            let shift = std::f64::consts::TAU * branch.structure.periods() as f64;
            let mut points = at.points.clone();
            points.extend(at.points.iter().map(|q| SwitchingPoint {
                phase: q.phase + shift,
                x: q.x,
            }));
            let mut du = phi.clone();
            du.extend(phi.iter().map(|v| -v));
            let d = Vector { du, dl: 0.0 };
            vec![Start {
                structure: doubled,
                value: at.value,
                points,
                direction: Some(to_direction(&d)),
            }]
        }
    }
}
