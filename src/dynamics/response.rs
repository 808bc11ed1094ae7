//! The closed-form motion of one segment in one domain, with everything that
//! does not depend on the phase computed once (SPEC §4, Appendix A).
//!
//! In domain `j` the motion solves `x'' + 2 d_j x' + c_j x = A0 cos(W t) − b_j`
//! (the domain's [`Coefficients`]). It is the forced response
//! `x_p(φ) = −b_j / c_j + P cos φ + Q sin φ`
//! ([`Coefficients::forced_response`]), plus the
//! homogeneous motion from the start's deviation `(X, Y) = (x0 − x_p, v0 − v_p)`
//! at `φ0`: `x = x_p + Ec X + Es (Y + d_j X)`, `v = v_p + Ec Y − Es (c_j X + d_j Y)`,
//! `(Ec, Es)` of [`homogeneous::general`] at the elapsed time `(φ − φ0) / W`.
//! This is the formula the generated `flow_j` functions evaluate; they
//! recompute the forced response at the start on every call, which the event
//! search, evaluating one segment at many phases, need not do. One evaluation
//! costs one `sincos` of the phase and one homogeneous solution, and gives the
//! acceleration and its rate with it (the generated `normal_field_j` takes
//! another `sincos`).

use crate::model::homogeneous;
use crate::model::{Coefficients, ForcedResponse, Oscillator};

/// The motion of a segment in one domain, ready to be evaluated at any phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Response {
    d: f64,
    two_d: f64,
    c: f64,
    b: f64,
    amplitude: f64,
    w: f64,
    offset: f64,
    p: f64,
    q: f64,
    dev_x: f64,
    dev_v: f64,
    phi0: f64,
}

/// The state, acceleration and its rate at one phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    /// Displacement.
    pub x: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration `A0 cos φ − b_j − 2 d_j v − c_j x`.
    pub a: f64,
    /// Its rate in time, `−A0 W sin φ − 2 d_j a − c_j v`.
    pub da: f64,
}

impl Response {
    /// The motion from `(x0, v0)` at phase `phi0` in the domain with
    /// coefficients `co`; `None` where the forced response does not exist in
    /// this form (`c_j = 0`, or undamped resonance `c_j = W²`, `d_j = 0`) or is
    /// not finite: the caller then evaluates the generated flow.
    pub fn new(co: Coefficients, osc: Oscillator, x0: f64, v0: f64, phi0: f64) -> Option<Self> {
        let w = osc.frequency;
        let ForcedResponse {
            cos: p,
            sin: q,
            offset,
        } = co.forced_response(&osc);
        let (s0, c0) = libm::sincos(phi0);
        let dev_x = x0 - (offset + (p * c0 + q * s0));
        let dev_v = v0 - w * (q * c0 - p * s0);
        let r = Self {
            d: 0.5 * co.two_d,
            two_d: co.two_d,
            c: co.c,
            b: co.b,
            amplitude: osc.amplitude,
            w,
            offset,
            p,
            q,
            dev_x,
            dev_v,
            phi0,
        };
        (co.c != 0.0 && [p, q, offset, dev_x, dev_v].iter().all(|z| z.is_finite())).then_some(r)
    }

    /// The state at phase `phi`. Allocates nothing.
    #[inline]
    pub fn at(&self, phi: f64) -> State {
        let (s, c) = libm::sincos(phi);
        let tau = (phi - self.phi0) / self.w;
        let (ec, es) = homogeneous::general(self.d, self.c, tau);
        let (dx, dv) = (self.dev_x, self.dev_v);
        let x = self.offset + (self.p * c + self.q * s) + (dx * ec + es * (dv + self.d * dx));
        let v = self.w * (self.q * c - self.p * s) + (dv * ec - es * (self.c * dx + self.d * dv));
        let a = self.amplitude * c - self.b - self.two_d * v - self.c * x;
        let da = -self.amplitude * self.w * s - self.two_d * a - self.c * v;
        State { x, v, a, da }
    }
}
