//! Neutral families: periodic motions whose Poincaré map has the eigenvalue
//! `+1` (e.g. the undamped Coulomb oscillator at `W = sqrt(c) / (2 n)`,
//! Csernák, Stépán & Shaw 2007). There `I − DP` is singular and Newton's
//! cycle solve breaks down (a singular or huge step), although a solution
//! exists at every point of a curve. A minimum-norm Newton step (the
//! pseudo-inverse of `I − DP`, its null direction dropped) converges to the
//! member nearest the guess; the caller decides by `DP`'s eigenvalues whether
//! that is a family member.

use nalgebra::{Matrix2, Vector2};

use crate::model::Model;
use crate::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};

/// Singular values of `I − DP` below this fraction of the largest are
/// treated as zero (the null direction of the family).
const RCOND: f64 = 1e-7;

/// Minimum-norm Newton for the structure of `solver` from `points`
/// (modified in place only on success). Returns `(iterations, residual)` when
/// the residual reached `opts.tolerance` (or stagnated within `1e3` of it),
/// `None` otherwise. The step solves the cycle equation `(I − DP) δu_0 = G`
/// by the pseudo-inverse, so a singular `I − DP` is not an obstacle.
pub fn solve_min_norm<M: Model>(
    solver: &PeriodicSolver<M>,
    p: &M::Params,
    points: &mut [SwitchingPoint],
    opts: NewtonOptions,
) -> Option<(usize, f64)> {
    let m = points.len();
    let mut work = points.to_vec();
    let mut trial = points.to_vec();
    let mut a = vec![Matrix2::zeros(); m];
    let mut g = vec![Vector2::zeros(); m];
    let mut delta = vec![Vector2::zeros(); m];
    let mut r = solver.residual(p, &work);
    if !r.is_finite() {
        return None;
    }
    for it in 0..opts.max_iterations {
        if r <= opts.tolerance {
            points.copy_from_slice(&work);
            return Some((it, r));
        }
        let mut product = Matrix2::identity();
        let mut acc = Vector2::zeros();
        for k in 0..m {
            let e = solver.evaluate(p, &work, k);
            let inv = e.d_next.try_inverse()?;
            a[k] = -(inv * e.d_prev);
            g[k] = -(inv * e.residual);
            if !(a[k].iter().all(|v| v.is_finite()) && g[k].iter().all(|v| v.is_finite())) {
                return None;
            }
            product = a[k] * product;
            acc = a[k] * acc + g[k];
        }
        let svd = (Matrix2::identity() - product).svd(true, true);
        let top = svd.singular_values.max();
        let pinv = svd
            .pseudo_inverse(RCOND * top.max(f64::MIN_POSITIVE))
            .ok()?;
        delta[0] = pinv * acc;
        for k in 0..m - 1 {
            delta[k + 1] = a[k] * delta[k] + g[k];
        }
        let mut lambda = 1.0;
        let mut accepted = None;
        while lambda >= 1e-3 {
            for ((t, pt), d) in trial.iter_mut().zip(&work).zip(&delta) {
                *t = SwitchingPoint {
                    x: pt.x + lambda * d[0],
                    phase: pt.phase + lambda * d[1],
                };
            }
            let rl = solver.residual(p, &trial);
            if rl < r {
                accepted = Some(rl);
                break;
            }
            lambda *= 0.5;
        }
        match accepted {
            Some(rl) => {
                work.copy_from_slice(&trial);
                r = rl;
            }
            None if r <= 1e3 * opts.tolerance => {
                points.copy_from_slice(&work);
                return Some((it + 1, r));
            }
            None => return None,
        }
    }
    (r <= opts.tolerance).then(|| {
        points.copy_from_slice(&work);
        (opts.max_iterations, r)
    })
}
