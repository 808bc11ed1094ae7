//! The extended system of a curve: the motion's mapping equations, the
//! condition and one border row, with both parameters free, solved by a
//! dense LU on a preallocated workspace (no allocation after construction).
//!
//! Unknowns `X = (x_0, W t_0, …, x_{m−1}, W t_{m−1}, λx, λy)` (`n = 2m + 2`;
//! periodicity substituted as in [`crate::bifurcation::bordered`]).
//! Equations: the `2m` mapping residuals `f_k(u_k, u_{k+1}, λ) = 0`, the
//! condition `g(u, λ) = 0` and the border row `⟨b, X − A⟩ = 0` (the
//! pseudo-arclength hyperplane, or one parameter fixed). `∂f/∂u` are the
//! exact generated blocks; `∂f/∂λ` and the whole gradient `∇g` are central
//! differences (step `1e-6` times the unknown's scale: the motion's length
//! scale `L` for displacements, 1 for phases, `max(1, |λ|)` for the
//! parameters). They enter only the Newton direction and the tangent, never
//! the residuals, so the points solve the equations exactly.
//!
//! The metric (inner products, distances, step sizes) is that of
//! [`crate::bifurcation::bordered`]: displacements over `L`, phases in
//! radians, each switching point weighted `1/m`, each parameter over its
//! range's span. A dense LU costs `O(n³)`, nothing for the small `m` of a
//! motion next to the `4n` evaluations of `g` that `∇g` takes.
//!
//! The corrector stops when the Newton step is below the tolerance, or
//! when it has stopped contracting within `1e3` times it (rounding,
//! amplified by the conditioning, as where an arrival before a stick turns
//! tangential). `Extended::correct_pair` (`extended/pair.rs`) replaces
//! the border row by a second condition: a codimension-two point, solved
//! directly where the curve's own system turns singular at it.
//!
//! On a symmetric motion every event has its mirror image half a cycle
//! later. Where the curve's own event is a tangential arrival before a
//! stick (a passable onset with `as > ak`), its mirror's velocity equation
//! `f2` has a double root in the arrival's phase all along the curve, and
//! the stick's start is free to first order. That row is replaced by the
//! arrival's normal field `F_j = 0` (`Extended::pin_tangent_arrivals`,
//! `extended/mirror.rs`), regular there; the dropped `f2` is checked after
//! each correction.

use crate::bifurcation::bordered::Correction;
use crate::model::{Model, ParamSet};
use crate::orbit::periodic::SwitchingPoint;

use super::condition::{condition_scale, Evaluator};
use super::{Condition, Plane};

mod mirror;
mod pair;
mod symmetric;

/// The equations hold to rounding when each residual is below this times
/// its row's largest derivative ([`Extended::correct`]). Measured: at the
/// rounding floor of the cascade's curves `<= 7e-15`; iterations still
/// converging slowly on Fig. 11's curves `6e-12` (median) up to `4e-10`.
const HOLDS: f64 = 1e-13;

/// A Newton step that has stopped contracting, from a point whose equations
/// hold to rounding ([`HOLDS`]), is rounding stirred up by the conditioning
/// if it is below this times the corrector's tolerance
/// ([`Extended::correct`]); the point is then as exact as the equations
/// allow. The sweep's corrector accepts such a point with no bound at all
/// ([`crate::bifurcation::bordered`]). Measured: on the paper model's
/// grazing curves of 36- to 40-mapping motions (`W=5:8 × Q0=20:60`,
/// `--max-mappings 40`) the arrival before a stick turns nearly tangential
/// as the curve nears a passable onset; the stick's start phase
/// then moves by 1e-10…3e-9 from one iteration to the next while every
/// residual stays below 1.2e-14 of its row's gradient. With the bound at
/// `1e3` those four curves crawled at steps of 1e-9 and ended as corrector
/// failures 5e-4…2.1e-2 in `W` short of their codimension-two points
/// (grazing meeting passable onset).
const ROUNDING_STEP: f64 = 1e5;

/// How far above its estimated rounding floor an eigenvalue test function
/// may lie and still hold ([`Extended::at_rounding_floor`]): the estimate
/// leaves out the rounding of `DP`'s product itself. Measured on
/// `stribeck::pl4`'s fold and period-doubling curves of 10 to 24 mappings:
/// the value over the floor ranged 0.16 to 9.1 over ten points where the
/// curves used to end, and wandered within 10 times the floor over further
/// Newton iterations.
const FLOOR_FACTOR: f64 = 16.0;

/// The central differences of the condition's row and of the mapping
/// equations' parameter columns step this far in each unknown's natural
/// unit (displacements over `L`, phases in radians, parameters relative).
/// Their truncation error, not rounding, limited the corrector near
/// strongly expanding motions: on `stribeck8`'s grazing curve of
/// `7_76 6_65 5_51 0_11 5_15 6_56 7_67 8_77` at W = 0.9765 (`|λ| = 817`)
/// a step of `1e-6` left the Jacobian 5 % off, Newton contracted by only
/// 0.05 per iteration, and the step control (more than 5 iterations:
/// shorter) crept along at 6.5e-8 of the box to the point limit; the two
/// fold curves of `T'T` near W = 1.93 did the same. At `1e-7` the
/// truncation error is 100 times smaller and the rounding error (about
/// `1e-16 / 1e-7` of the condition's terms) still far below it.
const FD_STEP: f64 = 1e-7;

/// The extended system of one curve, with its workspace.
#[derive(Clone, Debug)]
pub struct Extended<M: Model> {
    base: M::Params,
    plane: Plane,
    m: usize,
    n: usize,
    /// Length scale `L` of displacements.
    pub length: f64,
    spans: [f64; 2],
    metric: Vec<f64>,
    pub(super) eval: Evaluator<M>,
    /// A second condition that vanishes with the curve's own at a
    /// codimension-two point, for [`Self::correct_pair`].
    pub(super) pair: Option<Evaluator<M>>,
    jac: Vec<f64>,
    rhs: Vec<f64>,
    delta: Vec<f64>,
    pts: Vec<SwitchingPoint>,
    trial: Vec<f64>,
    /// The flow segments whose arrival (before a stick) is tangential all
    /// along the curve: their velocity row is the arrival's normal field
    /// ([`Self::pin_tangent_arrivals`]).
    pins: Vec<usize>,
}

impl<M: Model> Extended<M> {
    pub(super) fn new(base: M::Params, plane: Plane, length: f64, eval: Evaluator<M>) -> Self {
        let m = eval.steps.len();
        let n = 2 * m + 2;
        let spans = [
            plane.x_range[1] - plane.x_range[0],
            plane.y_range[1] - plane.y_range[0],
        ];
        let mut metric = vec![0.0; n];
        let w = if m > 0 { 1.0 / m as f64 } else { 0.0 };
        for k in 0..m {
            metric[2 * k] = w / (length * length);
            metric[2 * k + 1] = w;
        }
        metric[n - 2] = 1.0 / (spans[0] * spans[0]);
        metric[n - 1] = 1.0 / (spans[1] * spans[1]);
        Self {
            base,
            plane,
            m,
            n,
            length,
            spans,
            metric,
            eval,
            pair: None,
            jac: vec![0.0; n * n],
            rhs: vec![0.0; n],
            delta: vec![0.0; n],
            pts: vec![SwitchingPoint { phase: 0.0, x: 0.0 }; m],
            trial: vec![0.0; n],
            pins: Vec::new(),
        }
    }

    /// The parameters the plane's two are set in.
    pub(super) fn base(&self) -> &M::Params {
        &self.base
    }

    /// The number of unknowns `2m + 2`.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Never empty (the two parameters are unknowns).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The parameters at `x` (a copy of the base with both set).
    pub fn params(&self, x: &[f64]) -> M::Params {
        let mut p = self.base;
        p.set(self.plane.x, x[self.n - 2]);
        p.set(self.plane.y, x[self.n - 1]);
        p
    }

    /// The switching points of `x` into `out`.
    pub fn points_into(x: &[f64], out: &mut [SwitchingPoint]) {
        for (k, q) in out.iter_mut().enumerate() {
            *q = SwitchingPoint {
                x: x[2 * k],
                phase: x[2 * k + 1],
            };
        }
    }

    fn load(&mut self, x: &[f64]) {
        Self::points_into(x, &mut self.pts);
    }

    /// The spans of the two parameters' ranges.
    pub fn spans(&self) -> [f64; 2] {
        self.spans
    }

    /// `⟨a, b⟩` in the scaled metric.
    pub fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .zip(&self.metric)
            .map(|((x, y), w)| w * x * y)
            .sum()
    }

    /// `⟨b, x − y⟩` in the scaled metric.
    pub fn dot_diff(&self, b: &[f64], x: &[f64], y: &[f64]) -> f64 {
        let mut s = 0.0;
        for i in 0..self.n {
            s += self.metric[i] * b[i] * (x[i] - y[i]);
        }
        s
    }

    /// `|x − y|` in the scaled metric.
    pub fn distance(&self, x: &[f64], y: &[f64]) -> f64 {
        let mut s = 0.0;
        for i in 0..self.n {
            s += self.metric[i] * (x[i] - y[i]).powi(2);
        }
        s.sqrt()
    }

    /// Normalize `v` to unit length in the scaled metric.
    pub fn normalize(&self, v: &mut [f64]) {
        let n = self.dot(v, v).sqrt();
        if n > 0.0 && n.is_finite() {
            v.iter_mut().for_each(|c| *c /= n);
        }
    }

    /// The unit vector along parameter `axis` (0: x, 1: y) in the metric.
    pub fn axis(&self, axis: usize, out: &mut [f64]) {
        out.iter_mut().for_each(|c| *c = 0.0);
        out[self.n - 2 + axis] = self.spans[axis];
    }

    /// The condition's value at `x`.
    pub fn condition(&mut self, x: &[f64]) -> f64 {
        let p = self.params(x);
        self.load(x);
        self.eval.value(&p, &self.pts)
    }

    /// `|g| / scale` of the condition at `x` ([`condition_scale`]; NaN
    /// counts as infinite), on the system's own switching-point buffer.
    pub fn held(&mut self, x: &[f64]) -> f64 {
        let g = self.condition(x);
        let p = self.params(x);
        let eval = &self.eval;
        let scale = self.half_scale(&p).unwrap_or_else(|| {
            condition_scale::<M>(&p, eval.condition, eval.structure.as_ref(), &self.pts)
        });
        let r = (g / scale).abs();
        if r.is_nan() {
            f64::INFINITY
        } else {
            r
        }
    }

    /// Whether the condition at `x` is an eigenvalue test function that
    /// holds to its rounding floor: `|g| <= FLOOR_FACTOR · Σ |∂g/∂x_i|
    /// |x_i| ε` (the condition row's central differences). On a long stick
    /// motion `DP`'s entries move by 1e4 to 2e6 per unit of a switching
    /// point, so an ulp of the unknowns moves `det(I ∓ DP)` by more than
    /// 1e-10 of its scale ([`Self::held`]); the eigenvalue is then as
    /// close to ±1 as double precision places it, and the point lies on
    /// the curve to `|g| / |∂g/∂(W, Q0)|`, below 1e-12 in the plane.
    /// Margins are not let through: where a grazing extremum merges with a
    /// tangential departure their gradient grows without bound and points
    /// off the curve pass a floor so made.
    pub fn at_rounding_floor(&mut self, x: &[f64]) -> bool {
        if !matches!(self.eval.condition, Condition::Eigen(_)) || self.assemble(x).is_err() {
            return false;
        }
        let (n, m) = (self.n, self.m);
        let row = &self.jac[2 * m * n..(2 * m + 1) * n];
        let floor: f64 = row
            .iter()
            .zip(x)
            .map(|(d, v)| (d * v).abs() * f64::EPSILON)
            .sum();
        self.rhs[2 * m].abs() <= FLOOR_FACTOR * floor
    }

    /// The second condition's value at `x` (NaN without one).
    fn pair_condition(&mut self, x: &[f64]) -> f64 {
        let p = self.params(x);
        self.load(x);
        match &mut self.pair {
            Some(e) => e.value(&p, &self.pts),
            None => f64::NAN,
        }
    }

    /// The largest mapping residual at `x` (NaN propagates).
    pub fn mapping_residual(&self, x: &[f64]) -> f64 {
        let p = self.params(x);
        let mut r = 0.0f64;
        for k in 0..self.m {
            let (a, b) = self.ends(x, k);
            let f = M::residual(&p, self.eval.steps[k], a.x, a.phase, b.x, b.phase);
            for v in f.iter() {
                if v.is_nan() {
                    return f64::NAN;
                }
                r = r.max(v.abs());
            }
        }
        r
    }

    #[inline]
    fn ends(&self, x: &[f64], k: usize) -> (SwitchingPoint, SwitchingPoint) {
        let a = SwitchingPoint {
            x: x[2 * k],
            phase: x[2 * k + 1],
        };
        let b = if k + 1 < self.m {
            SwitchingPoint {
                x: x[2 * k + 2],
                phase: x[2 * k + 3],
            }
        } else {
            SwitchingPoint {
                x: x[0],
                phase: x[1] + self.eval.shift,
            }
        };
        (a, b)
    }

    /// The finite-difference step of unknown `i` at `x` ([`FD_STEP`] in
    /// the unknown's natural unit).
    fn fd_step(&self, x: &[f64], i: usize) -> f64 {
        if i >= 2 * self.m {
            FD_STEP * x[i].abs().max(1.0)
        } else if i % 2 == 0 {
            FD_STEP * self.length
        } else {
            FD_STEP
        }
    }

    /// The Jacobian of the mapping equations and the condition at `x`
    /// (rows `0..2m+1`, row-major, `n` columns) into the workspace, the
    /// residuals (mapping equations, then the condition) into `rhs`
    /// (negated). Returns the largest mapping residual; `Err` if a value is
    /// not finite.
    fn assemble(&mut self, x: &[f64]) -> Result<f64, String> {
        let (n, m) = (self.n, self.m);
        self.jac.iter_mut().for_each(|c| *c = 0.0);
        let p = self.params(x);
        let mut r = 0.0f64;
        let hl = [self.fd_step(x, n - 2), self.fd_step(x, n - 1)];
        let mut pl = [[p; 2]; 2];
        for (axis, h) in hl.iter().enumerate() {
            let idx = if axis == 0 {
                self.plane.x
            } else {
                self.plane.y
            };
            pl[axis][0].set(idx, x[n - 2 + axis] + h);
            pl[axis][1].set(idx, x[n - 2 + axis] - h);
        }
        for k in 0..m {
            if self.restricted() && k >= self.eval.half {
                self.mirror_rows(x, k);
                continue;
            }
            let (a, b) = self.ends(x, k);
            let step = self.eval.steps[k];
            let ev = M::mapping(&p, step, a.x, a.phase, b.x, b.phase);
            let next = (k + 1) % m;
            for row in 0..2 {
                let ri = (2 * k + row) * n;
                for col in 0..2 {
                    self.jac[ri + 2 * k + col] += ev.d_prev[(row, col)];
                    self.jac[ri + 2 * next + col] += ev.d_next[(row, col)];
                }
                self.rhs[2 * k + row] = -ev.residual[row];
                let v = ev.residual[row];
                r = if v.is_nan() || r.is_nan() {
                    f64::NAN
                } else {
                    r.max(v.abs())
                };
            }
            for axis in 0..2 {
                let fp = M::residual(&pl[axis][0], step, a.x, a.phase, b.x, b.phase);
                let fm = M::residual(&pl[axis][1], step, a.x, a.phase, b.x, b.phase);
                for row in 0..2 {
                    self.jac[(2 * k + row) * n + n - 2 + axis] =
                        (fp[row] - fm[row]) / (2.0 * hl[axis]);
                }
            }
        }
        for i in 0..self.pins.len() {
            self.pin_row(x, self.pins[i]);
        }
        // The condition's row: its value and central differences.
        let g = self.condition_row(x, 2 * m, false);
        if !g.is_finite() {
            return Err(format!("the condition is not finite ({g:e})"));
        }
        if let Some(i) = self.jac[..(2 * m + 1) * n]
            .iter()
            .position(|v| !v.is_finite())
        {
            let (row, col) = (i / n, i % n);
            return Err(if row == 2 * m {
                format!("the condition's derivative in unknown {col} is not finite (the condition is not defined on both sides)")
            } else {
                format!(
                    "mapping {}'s derivative in unknown {col} is not finite",
                    row / 2
                )
            });
        }
        Ok(r)
    }

    /// Row `row` of the Jacobian and `rhs` from a condition (the curve's
    /// own, or the second one with `second`): its value (returned) and its
    /// central differences.
    fn condition_row(&mut self, x: &[f64], row: usize, second: bool) -> f64 {
        let n = self.n;
        let value = |s: &mut Self, at: &[f64]| {
            if second {
                s.pair_condition(at)
            } else {
                s.condition(at)
            }
        };
        let g = value(self, x);
        self.rhs[row] = -g;
        if !g.is_finite() {
            return g;
        }
        let mut trial = std::mem::take(&mut self.trial);
        trial.copy_from_slice(x);
        for i in 0..n {
            // Central differences; where the condition is not defined on
            // one side at this step (a short segment reversed), smaller
            // steps, then a one-sided difference.
            let mut d = f64::NAN;
            let mut h = self.fd_step(x, i);
            for _ in 0..3 {
                trial[i] = x[i] + h;
                let gp = value(self, &trial);
                trial[i] = x[i] - h;
                let gm = value(self, &trial);
                d = if gp.is_finite() && gm.is_finite() {
                    (gp - gm) / (2.0 * h)
                } else if gp.is_finite() {
                    (gp - g) / h
                } else if gm.is_finite() {
                    (g - gm) / h
                } else {
                    f64::NAN
                };
                if gp.is_finite() && gm.is_finite() {
                    break;
                }
                h *= 1e-2;
            }
            trial[i] = x[i];
            self.jac[row * n + i] = d;
        }
        self.trial = trial;
        g
    }

    /// The Jacobian of the mapping equations and the condition at `x`
    /// (`(2m + 1) × n`, row-major): for checks.
    pub fn jacobian(&mut self, x: &[f64]) -> Result<&[f64], String> {
        self.assemble(x)?;
        Ok(&self.jac[..(2 * self.m + 1) * self.n])
    }

    /// The mapping residuals and the condition at `x` into `out` (`2m + 1`).
    pub fn residuals(&mut self, x: &[f64], out: &mut [f64]) {
        let p = self.params(x);
        for k in 0..self.m {
            let (a, b) = self.ends(x, k);
            let f = M::residual(&p, self.eval.steps[k], a.x, a.phase, b.x, b.phase);
            out[2 * k] = f[0];
            out[2 * k + 1] = f[1];
        }
        out[2 * self.m] = self.condition(x);
    }

    /// Set the border row (`⟨border, δX⟩ = rhs` in the metric) and solve
    /// the system in place (row equilibration, partial pivoting); the
    /// solution is left in `self.delta`.
    fn solve(&mut self, border: &[f64], rhs: f64) -> Result<(), String> {
        let n = self.n;
        let last = (n - 1) * n;
        for ((j, w), b) in self.jac[last..].iter_mut().zip(&self.metric).zip(border) {
            *j = w * b;
        }
        self.rhs[n - 1] = rhs;
        self.eliminate()
    }

    /// Solve the assembled square system in place (row equilibration,
    /// partial pivoting) into `self.delta`.
    fn eliminate(&mut self) -> Result<(), String> {
        let n = self.n;
        for i in 0..n {
            let row = &mut self.jac[i * n..(i + 1) * n];
            let s = row.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if !(s > 0.0 && s.is_finite()) {
                return Err(format!("row {i} of the extended system is zero"));
            }
            row.iter_mut().for_each(|v| *v /= s);
            self.rhs[i] /= s;
        }
        for col in 0..n {
            let mut piv = col;
            for i in col + 1..n {
                if self.jac[i * n + col].abs() > self.jac[piv * n + col].abs() {
                    piv = i;
                }
            }
            let pv = self.jac[piv * n + col];
            if pv.abs() <= 1e-14 || !pv.is_finite() {
                return Err("the extended system is singular".into());
            }
            if piv != col {
                for j in 0..n {
                    self.jac.swap(piv * n + j, col * n + j);
                }
                self.rhs.swap(piv, col);
            }
            for i in col + 1..n {
                let f = self.jac[i * n + col] / pv;
                if f != 0.0 {
                    for j in col..n {
                        self.jac[i * n + j] -= f * self.jac[col * n + j];
                    }
                    self.rhs[i] -= f * self.rhs[col];
                }
            }
        }
        for i in (0..n).rev() {
            let mut s = self.rhs[i];
            for j in i + 1..n {
                s -= self.jac[i * n + j] * self.delta[j];
            }
            self.delta[i] = s / self.jac[i * n + i];
        }
        if self.delta.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err("the extended system's solution is not finite".into())
        }
    }

    /// The unit tangent at `x` (mapping equations and condition
    /// linearized, `⟨prev, t⟩ = 1`), oriented so that `⟨t, prev⟩ > 0`,
    /// into `out`. No allocation.
    pub fn tangent(&mut self, x: &[f64], prev: &[f64], out: &mut [f64]) -> Result<(), String> {
        self.assemble(x)?;
        self.rhs.iter_mut().for_each(|c| *c = 0.0);
        self.solve(prev, 1.0)?;
        out.copy_from_slice(&self.delta);
        self.normalize(out);
        if self.dot(out, prev) < 0.0 {
            out.iter_mut().for_each(|c| *c = -*c);
        }
        Ok(())
    }

    /// Add the Newton step `self.delta` to `x`; its size, each unknown in
    /// its natural unit (displacements over `L`, phases in radians but no
    /// finer than `ulps` of their magnitude, parameters over their spans).
    fn step(&self, x: &mut [f64], ulps: f64) -> f64 {
        let n = self.n;
        let mut size = 0.0f64;
        for (i, (xi, &d)) in x.iter_mut().zip(&self.delta).enumerate() {
            let v = if i >= 2 * self.m {
                d.abs() / self.spans[i + 2 - n]
            } else if i % 2 == 0 {
                d.abs() / self.length
            } else {
                d.abs() / (ulps * xi.abs()).max(1.0)
            };
            size = size.max(v);
            *xi += d;
        }
        size
    }

    /// The largest of the first `rows` assembled residuals, each over its
    /// row's largest derivative (NaN counts as infinite).
    fn scaled_residual(&self, rows: usize) -> f64 {
        let n = self.n;
        (0..rows).fold(0.0f64, |a, i| {
            let s = self.jac[i * n..(i + 1) * n]
                .iter()
                .fold(0.0f64, |a, v| a.max(v.abs()));
            let r = (self.rhs[i] / s).abs();
            if r.is_nan() {
                f64::INFINITY
            } else {
                a.max(r)
            }
        })
    }

    /// Newton on the mapping equations, the condition and
    /// `⟨border, X − anchor⟩ = 0`, from `x` (modified in place). Converged
    /// when the Newton step is below `tol` in every unknown in its natural
    /// unit (displacements over `L`, phases in radians, parameters over
    /// their spans). No allocation.
    pub fn correct(
        &mut self,
        x: &mut [f64],
        border: &[f64],
        anchor: &[f64],
        tol: f64,
        max_iterations: usize,
    ) -> Correction {
        let c = self.newton(x, border, anchor, tol, max_iterations);
        self.check_dropped(x, c)
    }

    /// [`Self::correct`]'s Newton iteration.
    fn newton(
        &mut self,
        x: &mut [f64],
        border: &[f64],
        anchor: &[f64],
        tol: f64,
        max_iterations: usize,
    ) -> Correction {
        let ulps = 8.0 * f64::EPSILON / tol.max(f64::MIN_POSITIVE);
        let mut last = f64::INFINITY;
        for it in 0..max_iterations {
            if let Err(why) = self.assemble(x) {
                return Correction::Failed(why);
            }
            let holds = self.scaled_residual(2 * self.m + 1) <= HOLDS;
            let rhs = -self.dot_diff(border, x, anchor);
            if let Err(why) = self.solve(border, rhs) {
                return Correction::Failed(why);
            }
            let size = self.step(x, ulps);
            if size.is_nan() {
                return Correction::Failed("the Newton step is not finite".into());
            }
            if size <= tol {
                return Correction::Converged { iterations: it + 1 };
            }
            // Rounding-limited: the step has stopped contracting at a size
            // within [`ROUNDING_STEP`] `tol`, and the equations held to
            // rounding where it was computed. Near a point where the system
            // turns singular (an arrival turning tangential before a stick
            // leaves the stick's start free along the stick to first order)
            // rounding in the residuals, amplified by the conditioning,
            // keeps the step above `tol`: further iterations only stir the
            // noise. (A slow convergence has residuals well above rounding.)
            if it >= 1 && size <= ROUNDING_STEP * tol && size > 0.5 * last && holds {
                return Correction::Converged { iterations: it + 1 };
            }
            if it >= 3 && size > last && size > 1e3 * tol {
                return Correction::Failed(format!(
                    "the corrector does not converge (Newton step {size:.3e} after {} iterations)",
                    it + 1
                ));
            }
            last = size;
        }
        if last <= 1e3 * tol {
            return Correction::Converged {
                iterations: max_iterations,
            };
        }
        Correction::Failed(format!(
            "no convergence in {max_iterations} iterations (last Newton step {last:.3e})"
        ))
    }
}
