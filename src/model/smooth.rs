//! Models with a smooth (nonlinear) kinetic friction law: the law
//! itself, integrated numerically, and the piecewise-linear models built from
//! it at build time.
//!
//! A model file with a `law { ... }` item generates a type implementing
//! [`SmoothModel`]; each of its scenes with `pieces: N` generates an ordinary
//! piecewise-linear [`crate::Model`] that interpolates the law.

use std::ops::Deref;

use super::info::Identity;
use super::oscillator::FrictionOscillator;

/// Static description of a smooth-law model: its [`Identity`] (it derefs to
/// it) and its law.
#[derive(Clone, Copy, Debug)]
pub struct SmoothInfo {
    /// Name, doc and parameters.
    pub identity: Identity,
    /// The law as written in the model file.
    pub law: &'static str,
    /// `|v - V|` covered by the piecewise-linear models' breakpoints.
    pub range: f64,
}

impl Deref for SmoothInfo {
    type Target = Identity;
    fn deref(&self) -> &Identity {
        &self.identity
    }
}

/// A friction oscillator whose kinetic friction is a smooth function of the
/// velocity on each side of the belt speed, with static friction at the belt
/// speed: `x'' + 2 d x' + c x = A0 cos(W t) − f(x')` for `x' ≠ V`, stick at `x' = V`.
/// Its parameters and linear part are those of the [`FrictionOscillator`] it is.
pub trait SmoothModel: FrictionOscillator {
    /// The description: the identity and the law.
    fn info(p: &Self::Params) -> &'static SmoothInfo;
    /// The belt speed `V` (the stick velocity).
    fn belt(p: &Self::Params) -> f64;
    /// The static friction bound `as` per unit mass.
    fn static_bound(p: &Self::Params) -> f64;
    /// `[f(v), f'(v)]`, kinetic friction per unit mass and its slope, for `v ≠ V`.
    fn kinetic(p: &Self::Params, v: f64) -> [f64; 2];
}
