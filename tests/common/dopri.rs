//! Dormand–Prince 5(4) as data: the Butcher tableau of Dormand & Prince
//! (1980), the embedded 4th-order weights, and the continuous extension of
//! Hairer, Nørsett & Wanner (Solving ODEs I, §II.6, the `dopri5` dense
//! output), driven by one generic explicit Runge–Kutta stepper.
//!
//! Written for the tests from the textbook, not copied from `src/`: the
//! library's integrator (`src/dynamics/integrate.rs`) keeps its own decimal
//! copy of the tableau with the error weights `b − b̂` precomputed, and
//! locates events on a cubic Hermite interpolant; this one takes every
//! coefficient from the published rationals, forms `b − b̂` from both
//! weight rows, and interpolates with the tableau's own 4th-order dense
//! output (`tests/references.rs` checks the orders against a closed form).

/// Stages of the method (the seventh is the first of the next step: FSAL).
pub const STAGES: usize = 7;

/// The rational `n / d` as an `f64` (the tableau is published in rationals).
const fn q(n: i64, d: i64) -> f64 {
    n as f64 / d as f64
}

/// Nodes `c_i`.
pub const C: [f64; STAGES] = [0.0, q(1, 5), q(3, 10), q(4, 5), q(8, 9), 1.0, 1.0];

/// Stage coefficients `a_ij` (strictly lower triangular; the last row is
/// the 5th-order weights, so that the last stage is at the new solution).
#[rustfmt::skip]
pub const A: [[f64; STAGES]; STAGES] = [
    [0.0; STAGES],
    [q(1, 5), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [q(3, 40), q(9, 40), 0.0, 0.0, 0.0, 0.0, 0.0],
    [q(44, 45), q(-56, 15), q(32, 9), 0.0, 0.0, 0.0, 0.0],
    [q(19372, 6561), q(-25360, 2187), q(64448, 6561), q(-212, 729), 0.0, 0.0, 0.0],
    [q(9017, 3168), q(-355, 33), q(46732, 5247), q(49, 176), q(-5103, 18656), 0.0, 0.0],
    B,
];

/// 5th-order weights `b_i` (the propagated solution).
#[rustfmt::skip]
pub const B: [f64; STAGES] = [
    q(35, 384), 0.0, q(500, 1113), q(125, 192), q(-2187, 6784), q(11, 84), 0.0,
];

/// Embedded 4th-order weights `b̂_i` (the error estimate is `y5 − y4`).
#[rustfmt::skip]
pub const B_HAT: [f64; STAGES] = [
    q(5179, 57600), 0.0, q(7571, 16695), q(393, 640), q(-92097, 339200), q(187, 2100), q(1, 40),
];

/// Weights of the 5th dense-output coefficient (Hairer's `d_i`).
#[rustfmt::skip]
pub const DENSE: [f64; STAGES] = [
    q(-12715105075, 11282082432), 0.0, q(87487479700, 32700410799), q(-10690763975, 1880347072),
    q(701980252875, 199316789632), q(-1453857185, 822651844), q(69997945, 29380423),
];

/// One step of length `h` from `(t, y)`: the stages and the results.
#[derive(Clone, Copy, Debug)]
pub struct Step<const N: usize> {
    pub h: f64,
    pub y0: [f64; N],
    /// The 5th-order solution at `t + h`.
    pub y: [f64; N],
    /// The error estimate `y5 − y4`.
    pub err: [f64; N],
    k: [[f64; N]; STAGES],
}

/// `y + h Σ w_i k_i`.
fn combine<const N: usize>(y: &[f64; N], h: f64, w: &[f64], k: &[[f64; N]]) -> [f64; N] {
    let mut out = *y;
    for (wi, ki) in w.iter().zip(k) {
        for n in 0..N {
            out[n] += h * wi * ki[n];
        }
    }
    out
}

/// One Dormand–Prince step of `y' = f(t, y)`.
pub fn step<const N: usize>(
    f: impl Fn(f64, &[f64; N]) -> [f64; N],
    t: f64,
    y: [f64; N],
    h: f64,
) -> Step<N> {
    let mut k = [[0.0; N]; STAGES];
    for i in 0..STAGES {
        let yi = combine(&y, h, &A[i][..i], &k[..i]);
        k[i] = f(t + C[i] * h, &yi);
    }
    let y5 = combine(&y, h, &B, &k);
    let mut diff = [0.0; STAGES];
    for i in 0..STAGES {
        diff[i] = B[i] - B_HAT[i];
    }
    let err = combine(&[0.0; N], h, &diff, &k);
    Step {
        h,
        y0: y,
        y: y5,
        err,
        k,
    }
}

impl<const N: usize> Step<N> {
    /// The continuous extension at `t + θ h`, `θ ∈ [0, 1]` (4th order).
    pub fn dense(&self, theta: f64) -> [f64; N] {
        let h = self.h;
        let r5 = combine(&[0.0; N], h, &DENSE, &self.k);
        let mut out = [0.0; N];
        for n in 0..N {
            let dy = self.y[n] - self.y0[n];
            let r3 = h * self.k[0][n] - dy;
            let r4 = dy - h * self.k[STAGES - 1][n] - r3;
            let t1 = 1.0 - theta;
            out[n] = self.y0[n] + theta * (dy + t1 * (r3 + theta * (r4 + t1 * r5[n])));
        }
        out
    }

    /// The largest error component relative to `rtol (1 + |y|)`: a step
    /// with a value above 1 is rejected.
    pub fn error_norm(&self, rtol: f64) -> f64 {
        (0..N).fold(0.0f64, |m, n| {
            let scale = rtol * (1.0 + self.y0[n].abs().max(self.y[n].abs()));
            m.max((self.err[n] / scale).abs())
        })
    }
}
