//! Models with a smooth (nonlinear) kinetic friction law (issue 5): the law
//! itself, integrated numerically, and the piecewise-linear models built from
//! it at build time.
//!
//! A model file with a `law { ... }` item generates a type implementing
//! [`SmoothModel`]; each of its scenes with `pieces: N` generates an ordinary
//! piecewise-linear [`crate::Model`] that interpolates the law.

use super::oscillator::Oscillator;
use super::param::ParamSet;

/// Static description of a smooth-law model.
#[derive(Clone, Copy, Debug)]
pub struct SmoothInfo {
    /// Model name.
    pub name: &'static str,
    /// Doc comment.
    pub doc: &'static str,
    /// Every parameter of the model.
    pub params: &'static [crate::ParamInfo],
    /// Indices into `params` of the free ones.
    pub free: &'static [usize],
    /// The law as written in the model file.
    pub law: &'static str,
    /// `|v - V|` covered by the piecewise-linear models' breakpoints.
    pub range: f64,
}

/// A friction oscillator whose kinetic friction is a smooth function of the
/// velocity on each side of the belt speed, with static friction at the belt
/// speed: `x'' + 2 d x' + c x = A0 cos(W t) − f(x')` for `x' ≠ V`, stick at `x' = V`.
pub trait SmoothModel: Copy + Default + Send + Sync + 'static {
    /// Run-time parameters.
    type Params: ParamSet;
    /// Static description.
    const INFO: &'static SmoothInfo;
    /// The linear part of the oscillator.
    fn oscillator(p: &Self::Params) -> Oscillator;
    /// The belt speed `V` (the stick velocity).
    fn belt(p: &Self::Params) -> f64;
    /// The static friction bound `as` per unit mass.
    fn static_bound(p: &Self::Params) -> f64;
    /// `[f(v), f'(v)]`, kinetic friction per unit mass and its slope, for `v ≠ V`.
    fn kinetic(p: &Self::Params, v: f64) -> [f64; 2];
}

/// Something to do with a smooth-law model chosen at run time by name
/// (see [`crate::models::visit_smooth`]).
pub trait SmoothVisitor {
    /// What it returns.
    type Output;
    /// Do it with model `M`.
    fn visit<M: SmoothModel>(self) -> Self::Output;
}
