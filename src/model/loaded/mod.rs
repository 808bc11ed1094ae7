//! Models loaded at run time: a model file compiled to machine code by the
//! generator's run-time back end (`stickslip_codegen::jit`), behind the same
//! traits as the compiled-in models, so that every analysis runs on it
//! unchanged.
//!
//! A loaded model is one type per kind: [`Loaded`] (a [`Model`]) and
//! [`LoadedSmooth`] (a [`SmoothModel`]). Which model it is travels in its
//! parameter set: a [`LoadedParams`] is a `&'static` handle to the compiled
//! model (its machine code and its leaked [`ModelInfo`]) and a
//! fixed-capacity array of values, `Copy` like a compiled-in model's
//! `Params`, so that the hot paths allocate nothing. [`load_file`] and
//! [`load_source`] return the model's base parameter set (its defaults),
//! which the lookup (`crate::models::lookup`) hands to the analyses.
//!
//! * [`routines`] — the `sin`, `cos`, `exp`, `ln` and `Ec`/`Es` the machine
//!   code calls: the compiled-in models' own, behind `extern "C"`;
//! * `describe` — the leaked [`ModelInfo`] / [`SmoothInfo`];
//! * `intern` — loading, once per distinct text.

mod describe;
mod intern;
pub mod routines;

use std::fmt;

use nalgebra::{Matrix2, Vector2};
use stickslip_codegen::jit::{FnId, Machine, PiecewiseCode, SmoothCode};

pub use intern::{content_hash, load_file, load_source, LoadError, LoadedModel};
pub use stickslip_codegen::jit::CAPACITY;

use super::info::{Identity, ModelInfo};
use super::oscillator::{Coefficients, FrictionOscillator, Oscillator};
use super::param::{check_derived, check_values, ParamError, ParamSet};
use super::piecewise::{MappingEval, Model, Phase, StickForces};
use super::smooth::{SmoothInfo, SmoothModel};

/// A loaded piecewise-linear model: its code and description.
pub struct PiecewiseHandle {
    info: &'static ModelInfo,
    names: &'static [&'static str],
    code: PiecewiseCode,
}

/// A loaded smooth-law model: its code and description.
pub struct SmoothHandle {
    info: &'static SmoothInfo,
    names: &'static [&'static str],
    code: SmoothCode,
}

/// What a parameter set needs of its model.
pub trait Handle: Send + Sync + 'static {
    /// Name, doc and parameters.
    fn identity(&self) -> &'static Identity;
    /// The free parameters' names, in order.
    fn names(&self) -> &'static [&'static str];
    /// The model's conditions on `p` (after the values' own bounds).
    fn conditions(&self, p: &[f64]) -> Result<(), ParamError>;
}

/// The parameter set of a loaded model: the model (a handle to its code and
/// description) and the values of its free parameters. `Copy`, of fixed
/// size ([`CAPACITY`] values).
pub struct Values<H: 'static> {
    model: &'static H,
    len: usize,
    values: [f64; CAPACITY],
}

impl<H> Clone for Values<H> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<H> Copy for Values<H> {}

/// The parameter set of a [`Loaded`] model.
pub type LoadedParams = Values<PiecewiseHandle>;
/// The parameter set of a [`LoadedSmooth`] model.
pub type LoadedSmoothParams = Values<SmoothHandle>;

impl<H: Handle> Values<H> {
    /// The defaults of `model` (as its identity declares them).
    fn defaults(model: &'static H, identity: &Identity) -> Self {
        let mut values = [f64::NAN; CAPACITY];
        let len = identity.free.len().min(CAPACITY);
        for (v, &i) in values.iter_mut().zip(identity.free) {
            *v = identity.params[i].default;
        }
        Self { model, len, values }
    }

    /// The number of free parameters.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the model has no free parameter.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The values, in the order of [`ParamSet::names`].
    pub fn values(&self) -> &[f64] {
        &self.values[..self.len]
    }
}

impl<H: Handle> PartialEq for Values<H> {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.model, other.model) && self.values() == other.values()
    }
}

impl<H: Handle> fmt::Debug for Values<H> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut s = f.debug_struct(self.model.identity().name);
        for (name, value) in self.model.names().iter().zip(self.values()) {
            s.field(name, value);
        }
        s.finish()
    }
}

impl<H: Handle> ParamSet for Values<H> {
    fn names(&self) -> &'static [&'static str] {
        self.model.names()
    }
    fn get(&self, index: usize) -> f64 {
        self.values().get(index).copied().unwrap_or(f64::NAN)
    }
    fn set(&mut self, index: usize, value: f64) {
        if index < self.len {
            self.values[index] = value;
        }
    }
    fn check(&self) -> Result<(), ParamError> {
        check_values(self, self.model.identity())?;
        self.model.conditions(&self.values)
    }
}

/// `f(params)` into `O` values.
#[inline]
fn eval<const A: usize, const O: usize>(
    machine: &Machine,
    f: FnId<A, O>,
    p: &[f64],
    args: [f64; A],
) -> [f64; O] {
    let mut out = [0.0; O];
    machine.call(f, p, &args, &mut out);
    out
}

fn oscillator(o: [f64; 5]) -> Oscillator {
    Oscillator {
        mass: o[0],
        damping: o[1],
        stiffness: o[2],
        amplitude: o[3],
        frequency: o[4],
    }
}

impl Handle for PiecewiseHandle {
    fn identity(&self) -> &'static Identity {
        &self.info.identity
    }
    fn names(&self) -> &'static [&'static str] {
        self.names
    }
    fn conditions(&self, p: &[f64]) -> Result<(), ParamError> {
        let c = &self.code;
        let m = &c.machine;
        let stick = c.stick.map(|s| {
            let [a, above, below] = eval(m, s.levels, p, []);
            (a, above, below)
        });
        check_derived(
            self.info.boundaries,
            eval(m, c.conditions, p, []),
            c.velocities.len(),
            |k| eval(m, c.velocities[k], p, [])[0],
            stick,
        )
    }
}

impl Handle for SmoothHandle {
    fn identity(&self) -> &'static Identity {
        &self.info.identity
    }
    fn names(&self) -> &'static [&'static str] {
        self.names
    }
    fn conditions(&self, p: &[f64]) -> Result<(), ParamError> {
        let [m, c, w, bound, above, below] = eval(&self.code.machine, self.code.conditions, p, []);
        check_derived(&[], [m, c, w], 0, |_| f64::NAN, Some((bound, above, below)))
    }
}

/// A piecewise-linear model loaded at run time ([`load_file`],
/// [`load_source`]); which one is in its [`LoadedParams`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Loaded;

impl FrictionOscillator for Loaded {
    type Params = LoadedParams;
    #[inline]
    fn identity(p: &LoadedParams) -> &'static Identity {
        &p.model.info.identity
    }
    #[inline]
    fn oscillator(p: &LoadedParams) -> Oscillator {
        let c = &p.model.code;
        oscillator(eval(&c.machine, c.oscillator, &p.values, []))
    }
}

impl Model for Loaded {
    #[inline]
    fn info(p: &LoadedParams) -> &'static ModelInfo {
        p.model.info
    }
    #[inline]
    fn coefficients(p: &LoadedParams, domain: usize) -> Coefficients {
        let c = &p.model.code;
        match c.coefficients.get(domain) {
            Some(&f) => {
                let [two_d, cj, b] = eval(&c.machine, f, &p.values, []);
                Coefficients { two_d, c: cj, b }
            }
            None => Coefficients::NAN,
        }
    }
    #[inline]
    fn boundary_velocity(p: &LoadedParams, boundary: usize) -> f64 {
        let c = &p.model.code;
        match c.velocities.get(boundary) {
            Some(&f) => eval(&c.machine, f, &p.values, [])[0],
            None => f64::NAN,
        }
    }
    #[inline]
    fn static_bound(p: &LoadedParams) -> Option<f64> {
        let c = &p.model.code;
        c.stick.map(|s| eval(&c.machine, s.bound, &p.values, [])[0])
    }
    #[inline]
    fn flow(p: &LoadedParams, domain: usize, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2] {
        let c = &p.model.code;
        match c.flows.get(domain) {
            Some(&f) => eval(&c.machine, f, &p.values, [x0, v0, phi0, phi1]),
            None => [f64::NAN; 2],
        }
    }
    #[inline]
    fn normal_field(p: &LoadedParams, domain: usize, x: f64, y: f64, phi: f64) -> [f64; 2] {
        let c = &p.model.code;
        match c.fields.get(domain) {
            Some(&f) => eval(&c.machine, f, &p.values, [x, y, phi]),
            None => [f64::NAN; 2],
        }
    }
    #[inline]
    fn stick_forces(p: &LoadedParams, x: f64, phi: f64) -> Option<StickForces> {
        let c = &p.model.code;
        c.stick.map(|s| {
            let [f, ia, ib, oa, ob] = eval(&c.machine, s.forces, &p.values, [x, phi]);
            StickForces {
                non_friction: f,
                input_above: ia,
                input_below: ib,
                output_above: oa,
                output_below: ob,
            }
        })
    }
    #[inline]
    fn residual_at(
        p: &LoadedParams,
        mapping: usize,
        x0: f64,
        a: Phase,
        x1: f64,
        b: Phase,
    ) -> Vector2<f64> {
        let c = &p.model.code;
        match c.residuals.get(mapping) {
            Some(&f) => {
                let args = [x0, a.phi(), a.cos(), a.sin(), x1, b.phi(), b.cos(), b.sin()];
                let [f1, f2] = eval(&c.machine, f, &p.values, args);
                Vector2::new(f1, f2)
            }
            None => Vector2::repeat(f64::NAN),
        }
    }
    #[inline]
    fn mapping_at(
        p: &LoadedParams,
        mapping: usize,
        x0: f64,
        a: Phase,
        x1: f64,
        b: Phase,
    ) -> MappingEval {
        let c = &p.model.code;
        match c.mappings.get(mapping) {
            Some(&f) => {
                let args = [x0, a.phi(), a.cos(), a.sin(), x1, b.phi(), b.cos(), b.sin()];
                // `[f1, f2]`, then `∂f_i/∂(x0, phi0, x1, phi1)` row by row.
                let o = eval(&c.machine, f, &p.values, args);
                MappingEval {
                    residual: Vector2::new(o[0], o[1]),
                    d_prev: Matrix2::new(o[2], o[3], o[6], o[7]),
                    d_next: Matrix2::new(o[4], o[5], o[8], o[9]),
                }
            }
            None => MappingEval::NAN,
        }
    }
}

/// A smooth-law model loaded at run time; which one is in its
/// [`LoadedSmoothParams`].
#[derive(Clone, Copy, Debug, Default)]
pub struct LoadedSmooth;

impl FrictionOscillator for LoadedSmooth {
    type Params = LoadedSmoothParams;
    #[inline]
    fn identity(p: &LoadedSmoothParams) -> &'static Identity {
        &p.model.info.identity
    }
    #[inline]
    fn oscillator(p: &LoadedSmoothParams) -> Oscillator {
        let c = &p.model.code;
        oscillator(eval(&c.machine, c.oscillator, &p.values, []))
    }
}

impl SmoothModel for LoadedSmooth {
    #[inline]
    fn info(p: &LoadedSmoothParams) -> &'static SmoothInfo {
        p.model.info
    }
    #[inline]
    fn belt(p: &LoadedSmoothParams) -> f64 {
        let c = &p.model.code;
        eval(&c.machine, c.belt, &p.values, [])[0]
    }
    #[inline]
    fn static_bound(p: &LoadedSmoothParams) -> f64 {
        let c = &p.model.code;
        eval(&c.machine, c.bound, &p.values, [])[0]
    }
    #[inline]
    fn kinetic(p: &LoadedSmoothParams, v: f64) -> [f64; 2] {
        let c = &p.model.code;
        eval(&c.machine, c.kinetic, &p.values, [v])
    }
}
