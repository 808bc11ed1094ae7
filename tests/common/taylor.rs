//! A Taylor-series integrator of one domain's ODE
//! `x'' + 2 d x' + c x = a0 cos(W t) − b` (order 30, steps short enough that
//! `|λ| h ≤ 1/4` for every exponent, so that each series is well
//! conditioned), its variational equations, and for two real exponents the
//! modal form. Written for the tests from the series recurrence of the ODE;
//! it knows nothing of the closed forms in `src/` or the generated code.

use stickslip::Model;

/// One domain's ODE as data: `x'' + 2 d x' + c x = a0 cos(W t) − b`.
#[derive(Clone, Copy, Debug)]
pub struct Ode {
    pub d: f64,
    pub c: f64,
    pub b: f64,
    pub a0: f64,
    pub w: f64,
}

impl Ode {
    /// Domain `j` of `M` at `p`, read from the model's coefficients.
    pub fn of<M: Model>(p: &M::Params, j: usize) -> Self {
        let co = M::coefficients(p, j);
        let osc = M::oscillator(p);
        Self {
            d: 0.5 * co.two_d,
            c: co.c,
            b: co.b,
            a0: osc.amplitude,
            w: osc.frequency,
        }
    }

    /// The homogeneous equation (for the variational equations).
    pub fn homogeneous(self) -> Self {
        Self {
            b: 0.0,
            a0: 0.0,
            ..self
        }
    }

    /// `x''` at a state.
    pub fn accel(&self, x: f64, v: f64, phase: f64) -> f64 {
        self.a0 * phase.cos() - self.b - 2.0 * self.d * v - self.c * x
    }

    /// Largest rate in the problem: bounds every exponent and the forcing frequency.
    pub fn rate(&self) -> f64 {
        2.0 * self.d.abs() + self.c.abs().sqrt() + self.w
    }

    /// `(x, v)` after the elapsed time `tau` from `(x0, v0)` at phase `phi0`:
    /// Taylor series of order 30 in steps `h` with `rate · h ≤ 1/4`.
    pub fn taylor(&self, x0: f64, v0: f64, phi0: f64, tau: f64) -> (f64, f64) {
        let steps = ((tau.abs() * self.rate() * 4.0).ceil() as usize).max(16);
        self.taylor_in(steps, x0, v0, phi0, tau)
    }

    /// [`Ode::taylor`] in a given number of equal steps.
    pub fn taylor_in(&self, steps: usize, x0: f64, v0: f64, phi0: f64, tau: f64) -> (f64, f64) {
        const ORDER: usize = 30;
        let h = tau / steps as f64;
        let (mut x, mut v) = (x0, v0);
        for k in 0..steps {
            let phase = phi0 + self.w * (k as f64 * h);
            let (sn, cs) = phase.sin_cos();
            // d^n/dt^n cos(phase + W t) at 0 cycles through cos, -sin, -cos, sin.
            let cycle = [cs, -sn, -cs, sn];
            let mut a = [0.0f64; ORDER + 2];
            a[0] = x;
            a[1] = v;
            let mut wn = 1.0; // W^n / n!
            for n in 0..ORDER {
                if n > 0 {
                    wn *= self.w / n as f64;
                }
                let mut g = self.a0 * wn * cycle[n % 4];
                if n == 0 {
                    g -= self.b;
                }
                let n1 = (n + 1) as f64;
                a[n + 2] =
                    (g - 2.0 * self.d * n1 * a[n + 1] - self.c * a[n]) / (n1 * (n + 2) as f64);
            }
            let (mut xs, mut vs) = (0.0, 0.0);
            for n in (0..=ORDER).rev() {
                xs = xs * h + a[n];
                vs = vs * h + (n + 1) as f64 * a[n + 1];
            }
            x = xs;
            v = vs;
        }
        (x, v)
    }

    /// The state-transition matrix `Φ(τ)` of the homogeneous equation
    /// (columns: from `(1, 0)` and from `(0, 1)`), by the Taylor integrator.
    pub fn transition(&self, tau: f64) -> [[f64; 2]; 2] {
        let h = self.homogeneous();
        let (x1, v1) = h.taylor(1.0, 0.0, 0.0, tau);
        let (x2, v2) = h.taylor(0.0, 1.0, 0.0, tau);
        [[x1, x2], [v1, v2]]
    }

    /// The two real exponents `(slow, fast)` when `d² > c`, without cancellation.
    pub fn exponents(&self) -> (f64, f64) {
        let om = (self.d * self.d - self.c).sqrt();
        let big = -(self.d + om.copysign(self.d));
        (self.c / big, big)
    }

    /// The slowest decay rate of the homogeneous solution (`d` when under-damped).
    pub fn exponents_or_damping(&self) -> f64 {
        if self.d * self.d > self.c {
            -self.exponents().0
        } else {
            self.d
        }
    }

    /// Steady (forced) response `(x, v)` at `phase` (SPEC §4, from the complex amplitude).
    pub fn forced(&self, phase: f64) -> (f64, f64) {
        // x_p = Re(X e^{i phase}), X = a0 / (c − W² + 2 i d W).
        let (re, im) = (self.c - self.w * self.w, 2.0 * self.d * self.w);
        let den = re * re + im * im;
        let (xr, xi) = (self.a0 * re / den, -self.a0 * im / den);
        let (s, c) = phase.sin_cos();
        (
            xr * c - xi * s - self.b / self.c,
            self.w * (-xr * s - xi * c),
        )
    }

    /// `(x, v)` after `tau` by the modal form (two real exponents only):
    /// `x_h = k1 e^{λ1 τ} + k2 e^{λ2 τ}` fitted to the start.
    pub fn modal(&self, x0: f64, v0: f64, phi0: f64, tau: f64) -> (f64, f64) {
        let (l1, l2) = self.exponents();
        let (xp0, vp0) = self.forced(phi0);
        let (xh, vh) = (x0 - xp0, v0 - vp0);
        // xh = k1 + k2, vh = l1 k1 + l2 k2.
        let k1 = (vh - l2 * xh) / (l1 - l2);
        let k2 = (l1 * xh - vh) / (l1 - l2);
        let (e1, e2) = ((l1 * tau).exp(), (l2 * tau).exp());
        let (xp, vp) = self.forced(phi0 + self.w * tau);
        (xp + k1 * e1 + k2 * e2, vp + l1 * k1 * e1 + l2 * k2 * e2)
    }
}
