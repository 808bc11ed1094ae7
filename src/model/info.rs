//! The static description of a generated model, as the model file declares
//! it: what every model declares ([`Identity`]: name, doc, parameters) and
//! what a piecewise-linear one adds ([`ModelInfo`]: domains, boundaries,
//! mappings).

use std::ops::Deref;

use serde::Serialize;

use super::oscillator::Regime;

/// A comparison bound declared on a parameter in the model file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// `> b`
    Gt,
    /// `>= b`
    Ge,
    /// `< b`
    Lt,
    /// `<= b`
    Le,
}

impl Bound {
    /// Whether `value` satisfies `OP bound`.
    pub fn holds(self, value: f64, bound: f64) -> bool {
        match self {
            Bound::Gt => value > bound,
            Bound::Ge => value >= bound,
            Bound::Lt => value < bound,
            Bound::Le => value <= bound,
        }
    }

    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            Bound::Gt => ">",
            Bound::Ge => ">=",
            Bound::Lt => "<",
            Bound::Le => "<=",
        }
    }
}

/// Side of a boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Towards higher velocities.
    Above,
    /// Towards lower velocities.
    Below,
}

/// Kind of a mapping (SPEC §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MappingKind {
    /// Leaves a boundary and returns to it (Eq. 34).
    Local,
    /// Crosses a domain (Eq. 35).
    Global,
    /// Sticks on the stick boundary (Eq. 36).
    Stick,
}

/// A parameter as declared in the model file.
#[derive(Clone, Copy, Debug)]
pub struct ParamInfo {
    /// Name.
    pub name: &'static str,
    /// Default value.
    pub default: f64,
    /// Declared bounds.
    pub bounds: &'static [(Bound, f64)],
    /// Doc comment.
    pub doc: &'static str,
    /// Whether this instance takes it at run time (else it is folded into constants).
    pub free: bool,
}

/// A velocity boundary.
#[derive(Clone, Copy, Debug)]
pub struct BoundaryInfo {
    /// Label (`Sigma1`).
    pub label: &'static str,
    /// Its number (`1`), used in mapping names.
    pub number: u32,
    /// Whether static friction acts here.
    pub stick: bool,
    /// Doc comment.
    pub doc: &'static str,
}

/// A domain (velocity band).
#[derive(Clone, Copy, Debug)]
pub struct DomainInfo {
    /// Label (`1`).
    pub label: u32,
    /// Index of the lower boundary (`None`: unbounded).
    pub lower: Option<usize>,
    /// Index of the upper boundary (`None`: unbounded).
    pub upper: Option<usize>,
    /// Regime when fixed at build time (its coefficients do not depend on a free parameter).
    pub fixed_regime: Option<Regime>,
    /// Doc comment.
    pub doc: &'static str,
}

/// A generated mapping.
#[derive(Clone, Copy, Debug)]
pub struct MappingInfo {
    /// `j_βα` (`3_31`; `0_11` for stick).
    pub name: &'static str,
    /// Domain index (`None` for stick).
    pub domain: Option<usize>,
    /// Boundary index it starts on.
    pub from: usize,
    /// Boundary index it ends on.
    pub to: usize,
    /// Local, global or stick.
    pub kind: MappingKind,
    /// For the stick mapping, the side it leaves to.
    pub exit: Option<Side>,
}

/// What every generated model or scene declares, whatever its kind: its
/// name, its model's doc comment and its parameters. [`ModelInfo`] and
/// [`SmoothInfo`](super::smooth::SmoothInfo) hold one and dereference to it
/// (`info.name`, `info.params`).
#[derive(Clone, Copy, Debug)]
pub struct Identity {
    /// `paper`, or `paper::sweep_w` for a scene.
    pub name: &'static str,
    /// The model's name.
    pub model: &'static str,
    /// The scene's name.
    pub scene: Option<&'static str>,
    /// The model's doc comment.
    pub doc: &'static str,
    /// Every parameter of the model.
    pub params: &'static [ParamInfo],
    /// Indices into `params` of the free ones, in the order of the `Params` fields.
    pub free: &'static [usize],
    /// For a model loaded at run time, the content hash of its model file
    /// (`model::loaded::content_hash`); `None` for a compiled-in model.
    pub source_hash: Option<u64>,
}

/// Static description of a generated piecewise-linear model or scene: its
/// [`Identity`] and its domains, boundaries and mappings.
#[derive(Clone, Copy, Debug)]
pub struct ModelInfo {
    /// Name, doc and parameters.
    pub identity: Identity,
    /// Boundaries, lowest velocity first.
    pub boundaries: &'static [BoundaryInfo],
    /// Domains, lowest band first.
    pub domains: &'static [DomainInfo],
    /// The generated mappings (the stick mapping appears once per exit side).
    pub mappings: &'static [MappingInfo],
    /// The structures a scene studies.
    pub structures: &'static [&'static str],
}

impl Deref for ModelInfo {
    type Target = Identity;
    fn deref(&self) -> &Identity {
        &self.identity
    }
}

impl ModelInfo {
    /// Index of the stick boundary.
    pub fn stick_boundary(&self) -> Option<usize> {
        self.boundaries.iter().position(|b| b.stick)
    }

    /// Distinct mapping names, in generation order.
    pub fn mapping_names(&self) -> Vec<&'static str> {
        let mut out: Vec<&'static str> = Vec::new();
        for m in self.mappings {
            if !out.contains(&m.name) {
                out.push(m.name);
            }
        }
        out
    }

    /// Index of the mapping `name`; for the stick mapping, the one leaving to
    /// `exit` (the first of the two when `exit` is `None`).
    pub fn mapping_index(&self, name: &str, exit: Option<Side>) -> Option<usize> {
        self.mappings
            .iter()
            .position(|m| m.name == name && (exit.is_none() || m.exit.is_none() || m.exit == exit))
    }
}
