//! What every generated model is, a [`FrictionOscillator`]; its linear part
//! ([`Oscillator`]) and the effective coefficients of a domain, with its
//! damping regime (SPEC §1, Eq. A.1).

use std::sync::atomic::{AtomicBool, Ordering};

use serde::Serialize;

use super::info::Identity;
use super::param::ParamSet;

/// A periodically forced oscillator with friction, `x'' + 2 d x' + c x =
/// A0 cos(W t) − f(x')`: what every generated model is, whatever the form of
/// its friction law. [`Model`](super::Model) (piecewise-linear, solved in
/// closed form) and [`SmoothModel`](super::smooth::SmoothModel) (a smooth
/// law, integrated) add the law.
///
/// A model is described through its parameter set, which is the model
/// instance: a compiled-in model's description is static (its type's
/// `INFO`), a loaded model's is reached through a handle in its `Params`.
pub trait FrictionOscillator: Copy + Send + Sync + 'static {
    /// The run-time parameters.
    type Params: ParamSet;
    /// Name, doc and parameters, as the model file declares them.
    fn identity(p: &Self::Params) -> &'static Identity;
    /// The oscillator's linear part.
    fn oscillator(p: &Self::Params) -> Oscillator;
}

/// Effective coefficients of one domain: `x'' + two_d x' + c x = A0 cos(W t) - b` (SPEC Eq. A.1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Coefficients {
    /// `2 d_j = 2 d + f_j'(v)`: effective damping (may be negative).
    pub two_d: f64,
    /// `c_j`.
    pub c: f64,
    /// `b_j = f_j(0)`, the constant part of the friction law.
    pub b: f64,
}

impl Coefficients {
    /// Returned for an out-of-range domain index.
    pub const NAN: Self = Self {
        two_d: f64::NAN,
        c: f64::NAN,
        b: f64::NAN,
    };

    /// Damping regime at these coefficients.
    pub fn regime(&self) -> Regime {
        Regime::classify(self.two_d, self.c)
    }

    /// The forced (particular) response of this domain's equation under the
    /// oscillator's forcing, `x_p(φ) = cos · cos φ + sin · sin φ + offset`
    /// with `(cos, sin) = A0 (c_j − W², 2 d_j W) / ((c_j − W²)² + (2 d_j W)²)`
    /// and `offset = −b_j / c_j` (SPEC Appendix A). Not finite where it does
    /// not exist (`c_j = 0`, undamped resonance).
    pub fn forced_response(&self, osc: &Oscillator) -> ForcedResponse {
        let w = osc.frequency;
        let detuning = self.c - w * w;
        let damping = self.two_d * w;
        let den = detuning * detuning + damping * damping;
        let (cos, sin) = match forced_rounding() {
            ForcedRounding::Quotient => (
                osc.amplitude * detuning / den,
                damping * osc.amplitude / den,
            ),
            ForcedRounding::Reciprocal => {
                let scale = 1.0 / den;
                (
                    osc.amplitude * detuning * scale,
                    damping * osc.amplitude * scale,
                )
            }
        };
        ForcedResponse {
            cos,
            sin,
            offset: -self.b / self.c,
        }
    }
}

/// How [`Coefficients::forced_response`] rounds its quotients: `x / den`
/// (the default, as the generated flows do) or `x · (1 / den)`. The two
/// differ in the last bit. No result of the library may depend on which:
/// the perturbation check (`tests/perturbation.rs`) runs the sweep, curve
/// and map cases both ways and with every parameter moved by a few ulps,
/// and requires the same structures, transitions and curves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForcedRounding {
    /// `x / den`.
    Quotient,
    /// `x · (1 / den)`.
    Reciprocal,
}

static RECIPROCAL: AtomicBool = AtomicBool::new(false);

/// The process-wide [`ForcedRounding`] (for the perturbation check; the
/// default is [`ForcedRounding::Quotient`]).
pub fn set_forced_rounding(r: ForcedRounding) {
    RECIPROCAL.store(r == ForcedRounding::Reciprocal, Ordering::Relaxed);
}

/// The process-wide [`ForcedRounding`].
pub fn forced_rounding() -> ForcedRounding {
    if RECIPROCAL.load(Ordering::Relaxed) {
        ForcedRounding::Reciprocal
    } else {
        ForcedRounding::Quotient
    }
}

/// The forced response of a domain ([`Coefficients::forced_response`]):
/// `x_p(φ) = cos · cos φ + sin · sin φ + offset`, `φ = W t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForcedResponse {
    /// The cosine coefficient.
    pub cos: f64,
    /// The sine coefficient.
    pub sin: f64,
    /// The constant part, `−b_j / c_j`.
    pub offset: f64,
}

/// The linear part of the oscillator: `x'' + 2 damping x' + stiffness x = amplitude cos(frequency t) - f(x')`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Oscillator {
    /// `m`.
    pub mass: f64,
    /// `d`.
    pub damping: f64,
    /// `c`.
    pub stiffness: f64,
    /// `A0 = Q0 / m`.
    pub amplitude: f64,
    /// `W`.
    pub frequency: f64,
}

/// Damping regime of a domain (sign of `d_j² - c_j`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Regime {
    /// `d_j² < c_j`: damped oscillation (or growing, for negative damping).
    Underdamped,
    /// `d_j² = c_j`.
    Critical,
    /// `d_j² > c_j`: two real exponents.
    Overdamped,
}

impl Regime {
    /// The regime of `x'' + two_d x' + c x = 0`.
    pub fn classify(two_d: f64, c: f64) -> Self {
        let d = 0.5 * two_d;
        let w2 = d * d - c;
        if w2 < 0.0 {
            Regime::Underdamped
        } else if w2 > 0.0 {
            Regime::Overdamped
        } else {
            Regime::Critical
        }
    }

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Regime::Underdamped => "underdamped",
            Regime::Critical => "critical",
            Regime::Overdamped => "overdamped",
        }
    }
}
