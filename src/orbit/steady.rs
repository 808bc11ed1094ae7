//! The steady forced response of one domain: the particular solution of
//! its linear equation under the harmonic forcing, in closed form. It is
//! the no-motion regime (SPEC: the motion that never reaches a boundary)
//! when it stays inside the domain's band.

use crate::model::Model;

/// The steady forced response of domain `j` (its particular solution):
/// `x(φ) = a cos φ + b sin φ + offset`, `v(φ) = W (−a sin φ + b cos φ)`
/// with `φ = W t`, so that its velocity ranges over `±W √(a² + b²)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteadyResponse {
    /// The cosine coefficient.
    pub a: f64,
    /// The sine coefficient.
    pub b: f64,
    /// The constant part, `−b_j / c_j`.
    pub offset: f64,
    /// The largest velocity, `W √(a² + b²)` (the smallest is its negative).
    pub max_v: f64,
}

/// The steady forced response of domain `j` at `p` (closed form), or
/// `None` if the domain is not damped (`2d <= 0` or NaN: no steady response
/// attracts).
pub fn steady_response<M: Model>(p: &M::Params, j: usize) -> Option<SteadyResponse> {
    let co = M::coefficients(p, j);
    let osc = M::oscillator(p);
    let d = 0.5 * co.two_d;
    if d.is_nan() || d <= 0.0 {
        return None;
    }
    let f = co.forced_response(&osc);
    Some(SteadyResponse {
        a: f.cos,
        b: f.sin,
        offset: f.offset,
        max_v: osc.frequency * f.cos.hypot(f.sin),
    })
}
