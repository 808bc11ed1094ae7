//! The registry of compiled-in models: the entries of [`crate::models::ALL`],
//! each saying which kind of model it describes, and the [`ModelVisitor`]
//! that [`crate::models::visit`] runs with a model chosen at run time by name.
//!
//! The catalogue itself is generated (`stickslip-codegen`'s `registry`);
//! these are the types it is written in.

use super::info::{Identity, ModelInfo};
use super::piecewise::Model;
use super::smooth::{SmoothInfo, SmoothModel};

/// A compiled-in model or scene, by kind.
#[derive(Clone, Copy, Debug)]
pub enum Entry {
    /// A piecewise-linear model or scene (a [`Model`]).
    Piecewise(&'static ModelInfo),
    /// A model with a smooth friction law (a [`SmoothModel`]).
    Smooth(&'static SmoothInfo),
}

impl Entry {
    /// What every kind declares: name, doc, parameters.
    pub fn identity(&self) -> &'static Identity {
        match *self {
            Entry::Piecewise(info) => &info.identity,
            Entry::Smooth(info) => &info.identity,
        }
    }

    /// `paper`, `paper::sweep_w`, `stribeck`.
    pub fn name(&self) -> &'static str {
        self.identity().name
    }

    /// The description of a piecewise-linear model, else `None`.
    pub fn piecewise(&self) -> Option<&'static ModelInfo> {
        match *self {
            Entry::Piecewise(info) => Some(info),
            Entry::Smooth(_) => None,
        }
    }

    /// The description of a smooth-law model, else `None`.
    pub fn smooth(&self) -> Option<&'static SmoothInfo> {
        match *self {
            Entry::Smooth(info) => Some(info),
            Entry::Piecewise(_) => None,
        }
    }
}

/// Something to do with a model chosen at run time (see
/// [`crate::models::visit`] and [`crate::models::lookup`]): one method per
/// kind of model, each handed the model's base parameter set (its declared
/// defaults), which for a loaded model also carries the model itself. A
/// visitor implements the kinds it takes; the others return `None`, as for
/// a name that is not compiled in.
pub trait ModelVisitor: Sized {
    /// What it returns.
    type Output;

    /// Do it with the piecewise-linear model `M`, whose defaults are `base`.
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        let _ = base;
        None
    }

    /// Do it with the smooth-law model `M`, whose defaults are `base`.
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        let _ = base;
        None
    }
}
