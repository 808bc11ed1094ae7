//! Run-time parameters: the generated `Params` structs implement [`ParamSet`];
//! their validating checks report a typed [`ParamError`].

use super::info::{BoundaryInfo, Identity};

/// Why a parameter set was rejected.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// NaN or infinite.
    #[error("parameter `{name}` is {value}: it must be a finite number")]
    NotFinite {
        /// Parameter name.
        name: String,
        /// The rejected value.
        value: f64,
    },
    /// Violates a bound declared in the model file.
    #[error("parameter `{name}` = {value} violates its bound `{name} {op} {bound}`")]
    OutOfRange {
        /// Parameter name.
        name: String,
        /// The rejected value.
        value: f64,
        /// The operator.
        op: &'static str,
        /// The bound.
        bound: f64,
    },
    /// Not a parameter of the model.
    #[error("`{name}` is not a parameter of `{model}` (its parameters: {known})")]
    Unknown {
        /// The name asked for.
        name: String,
        /// Model (or scene) name.
        model: String,
        /// The names it has.
        known: String,
    },
    /// A parameter the scene folded into a constant at build time.
    #[error(
        "`{name}` is fixed to {value} in `{model}` (free: {free}); to vary it, add `{name}` to the scene's `free:` list in the model file"
    )]
    Fixed {
        /// Parameter name.
        name: String,
        /// Model and scene.
        model: String,
        /// Its build-time value.
        value: f64,
        /// The free parameters.
        free: String,
    },
    /// Mass, stiffness or frequency not positive.
    #[error("the {what} is {value}; it must be positive")]
    NotPositive {
        /// `mass`, `stiffness` or `forcing frequency`.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// Boundaries out of order (the domains would overlap).
    #[error("boundary `{lower}` (v = {lower_v}) must lie below `{upper}` (v = {upper_v})")]
    BoundaryOrder {
        /// The boundary that should be lower.
        lower: &'static str,
        /// Its velocity.
        lower_v: f64,
        /// The boundary that should be higher.
        upper: &'static str,
        /// Its velocity.
        upper_v: f64,
    },
    /// Static bound below the kinetic level.
    #[error("the static friction bound {bound} is below the kinetic friction level {kinetic} {side} the stick boundary")]
    StaticBelowKinetic {
        /// `as`.
        bound: f64,
        /// The kinetic level.
        kinetic: f64,
        /// `above` or `below`.
        side: &'static str,
    },
}

/// A set of run-time parameters, as generated for a model or scene: the model
/// instance every analysis is handed. A compiled-in model's `Params` is a
/// struct of named fields (with `NAMES`, `index_of` and `from_pairs` as
/// inherent items); a loaded model's holds a handle to the compiled model
/// and its values.
pub trait ParamSet: Copy + std::fmt::Debug + PartialEq + Send + Sync + 'static {
    /// Names of the fields, in order.
    fn names(&self) -> &'static [&'static str];
    /// Field `index` (NaN when out of range).
    fn get(&self, index: usize) -> f64;
    /// Set field `index` without checking (see [`check`](Self::check)).
    fn set(&mut self, index: usize, value: f64);
    /// Every value finite and within its declared bounds, and the model's
    /// conditions hold: positive mass, stiffness and frequency, boundaries in
    /// order, static bound at least the kinetic levels.
    fn check(&self) -> Result<(), ParamError>;

    /// Index of a field by name.
    fn index_of(&self, name: &str) -> Option<usize> {
        self.names().iter().position(|n| *n == name)
    }

    /// These values with the given ones set, checked; `info` names the
    /// model in errors.
    fn with_pairs(mut self, info: &Identity, pairs: &[(&str, f64)]) -> Result<Self, ParamError> {
        for &(name, value) in pairs {
            match self.index_of(name) {
                Some(i) => self.set(i, value),
                None => return Err(ParamError::not_free(info, name)),
            }
        }
        self.check()?;
        Ok(self)
    }
}

impl ParamError {
    /// `name` is not a free parameter of `info`'s model or scene: fixed by
    /// the scene ([`ParamError::Fixed`]) or unknown ([`ParamError::Unknown`]),
    /// each listing the free parameters.
    pub fn not_free(info: &Identity, name: &str) -> Self {
        unknown_or_fixed(info, name)
    }
}

fn unknown_or_fixed(info: &Identity, name: &str) -> ParamError {
    let free: Vec<&str> = info.free.iter().map(|&i| info.params[i].name).collect();
    match info.params.iter().find(|p| p.name == name) {
        Some(p) => ParamError::Fixed {
            name: name.to_string(),
            model: info.name.to_string(),
            value: p.default,
            free: free.join(", "),
        },
        None => ParamError::Unknown {
            name: name.to_string(),
            model: info.name.to_string(),
            known: free.join(", "),
        },
    }
}

/// Finite values within their declared bounds (called by generated `check`).
pub fn check_values<P: ParamSet>(p: &P, info: &Identity) -> Result<(), ParamError> {
    for (k, &i) in info.free.iter().enumerate() {
        let pi = &info.params[i];
        let value = p.get(k);
        if !value.is_finite() {
            return Err(ParamError::NotFinite {
                name: pi.name.to_string(),
                value,
            });
        }
        for &(op, bound) in pi.bounds {
            if !op.holds(value, bound) {
                return Err(ParamError::OutOfRange {
                    name: pi.name.to_string(),
                    value,
                    op: op.symbol(),
                    bound,
                });
            }
        }
    }
    Ok(())
}

/// Values derived from the parameters that the model needs to make sense.
#[derive(Clone, Copy, Debug)]
pub struct Conditions<'a> {
    /// `m`.
    pub mass: f64,
    /// `c`.
    pub stiffness: f64,
    /// `W`.
    pub frequency: f64,
    /// Boundary velocities, in the model's order (lowest first).
    pub velocities: &'a [f64],
    /// `(as, f_above(V), f_below(V))` on the stick boundary.
    pub stick: Option<(f64, f64, f64)>,
}

/// The static bound may fall short of the kinetic level by this much
/// relative to `1 + level` ([`check_conditions`]): rounding.
const SAME_LEVEL: f64 = 1e-12;

/// Check [`Conditions`] (called by generated `check`); `boundaries` are the
/// model's, to name those out of order.
pub fn check_conditions(boundaries: &[BoundaryInfo], c: Conditions) -> Result<(), ParamError> {
    check_derived(
        boundaries,
        [c.mass, c.stiffness, c.frequency],
        c.velocities.len(),
        |k| c.velocities[k],
        c.stick,
    )
}

/// [`check_conditions`] with the `count` boundary velocities given by
/// `velocity(k)`, evaluated where they are compared (a loaded model's check
/// stores none: it allocates nothing).
pub fn check_derived(
    boundaries: &[BoundaryInfo],
    [mass, stiffness, frequency]: [f64; 3],
    count: usize,
    velocity: impl Fn(usize) -> f64,
    stick: Option<(f64, f64, f64)>,
) -> Result<(), ParamError> {
    for (what, value) in [
        ("mass", mass),
        ("stiffness", stiffness),
        ("forcing frequency", frequency),
    ] {
        if !value.is_finite() || value <= 0.0 {
            return Err(ParamError::NotPositive { what, value });
        }
    }
    for k in 0..count.saturating_sub(1) {
        let (lower, upper) = (velocity(k), velocity(k + 1));
        if lower.partial_cmp(&upper) != Some(std::cmp::Ordering::Less) {
            return Err(ParamError::BoundaryOrder {
                lower: boundaries[k].label,
                lower_v: lower,
                upper: boundaries[k + 1].label,
                upper_v: upper,
            });
        }
    }
    if let Some((bound, above, below)) = stick {
        for (kinetic, side) in [(above.abs(), "above"), (below.abs(), "below")] {
            // Equal up to rounding counts as equal: a smooth law's N-piece
            // model has `as = ak` at the belt speed, its kinetic level
            // evaluated from the pieces a few ulps either side of `as`
            // (the build's check allows the same).
            if bound.is_nan() || bound < kinetic - SAME_LEVEL * (1.0 + kinetic) {
                return Err(ParamError::StaticBelowKinetic {
                    bound,
                    kinetic,
                    side,
                });
            }
        }
    }
    Ok(())
}
