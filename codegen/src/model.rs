//! The checked model: what the model file means, independent of its syntax.
//!
//! Produced by [`crate::check`]; consumed by [`crate::lower`] (expressions per
//! instance) and [`crate::emit`]. Boundaries are stored from the lowest
//! velocity to the highest, domains from the lowest band to the highest.

use proc_macro2::Span;
use syn::Expr;

pub use crate::parse::BoundOp;

/// A named parameter with its default value.
#[derive(Clone, Debug)]
pub struct Param {
    /// The name as written.
    pub name: String,
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The default value.
    pub default: f64,
    /// Bounds a run-time value must satisfy (besides being finite).
    pub bounds: Vec<(BoundOp, f64)>,
    /// Where it is written, for diagnostics.
    pub span: Span,
}

/// A derived quantity, `let NAME = EXPR;`.
#[derive(Clone, Debug)]
pub struct Derived {
    /// The name as written.
    pub name: String,
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The expression.
    pub value: Expr,
}

/// The oscillator's linear part: `x'' + 2 damping x' + stiffness x = forcing cos(frequency t) - f(x')`.
#[derive(Clone, Debug)]
pub struct Oscillator {
    /// The mass `m`.
    pub mass: Expr,
    /// The viscous damping per unit mass `d` (the equation has `2 d x'`).
    pub damping: Expr,
    /// The stiffness per unit mass `c`.
    pub stiffness: Expr,
    /// The forcing amplitude per unit mass `A0`.
    pub forcing: Expr,
    /// The forcing frequency `W`.
    pub frequency: Expr,
}

/// A velocity boundary `v = V_k` between two domains.
#[derive(Clone, Debug)]
pub struct Boundary {
    /// The label as written (`Sigma1`).
    pub label: String,
    /// The number in the label (`1`), used in mapping names.
    pub number: u32,
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The boundary's velocity.
    pub velocity: Expr,
    /// The static friction bound per unit mass, for the stick boundary.
    pub stick: Option<Expr>,
    /// Where it is written, for diagnostics.
    pub span: Span,
}

/// A domain: a velocity band with an affine kinetic friction law `f(v)`.
#[derive(Clone, Debug)]
pub struct Domain {
    /// The label as written (`1`).
    pub label: u32,
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// Index into [`Model::boundaries`] of the lower edge (`None`: unbounded).
    pub lower: Option<usize>,
    /// Index into [`Model::boundaries`] of the upper edge (`None`: unbounded).
    pub upper: Option<usize>,
    /// Friction per unit mass as a function of `v`.
    pub law: Expr,
    /// Where it is written, for diagnostics.
    pub span: Span,
}

/// A domain's place in the topology: its label and edges.
#[derive(Clone, Copy, Debug)]
pub struct Band {
    /// The domain's label.
    pub label: u32,
    /// Index of the lower edge (`None`: unbounded).
    pub lower: Option<usize>,
    /// Index of the upper edge (`None`: unbounded).
    pub upper: Option<usize>,
}

/// Kind of a mapping (SPEC §5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MappingKind {
    /// Leaves a boundary and returns to it (Eq. 34).
    Local,
    /// Crosses a domain from one boundary to the other (Eq. 35).
    Global,
    /// Sticks on the stick boundary (Eq. 36).
    Stick,
}

/// A mapping `P_{j βα}`: in domain `j`, from boundary `α` to boundary `β`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mapping {
    /// `j_βα`, e.g. `3_31`; `0_11` for the stick mapping.
    pub name: String,
    /// Index into [`Model::domains`]; `None` for the stick mapping.
    pub domain: Option<usize>,
    /// Boundary index it starts on (α).
    pub from: usize,
    /// Boundary index it ends on (β).
    pub to: usize,
    /// Local, global or stick.
    pub kind: MappingKind,
}

/// A scene: which parameters stay free, which structures are studied.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The name as written.
    pub name: String,
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// Indices into [`Model::params`].
    pub free: Vec<usize>,
    /// Each structure as mapping indices in the order written (applied right to left).
    pub structures: Vec<Vec<usize>>,
    /// The structures as written.
    pub structure_text: Vec<String>,
    /// For a model with a smooth law: build an N-piece model.
    pub pieces: Option<u32>,
}

/// A smooth kinetic friction law (`law { ... }`).
#[derive(Clone, Debug)]
pub struct Law {
    /// The belt speed: where the law jumps and the mass can stick.
    pub belt: Expr,
    /// The static friction bound per unit mass.
    pub stick: Expr,
    /// `|v - V|` covered by the breakpoints of the piecewise-linear models.
    pub range: Expr,
    /// Kinetic friction per unit mass, any expression in `v`.
    pub kinetic: Expr,
    /// Where it is written, for diagnostics.
    pub span: Span,
}

/// A checked model.
#[derive(Clone, Debug)]
pub struct Model {
    /// The name as written.
    pub name: String,
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The parameters, in declaration order.
    pub params: Vec<Param>,
    /// The `let`s, in declaration order.
    pub derived: Vec<Derived>,
    /// The linear part.
    pub oscillator: Oscillator,
    /// From the lowest velocity to the highest.
    pub boundaries: Vec<Boundary>,
    /// From the lowest band to the highest.
    pub domains: Vec<Domain>,
    /// The scenes, in declaration order.
    pub scenes: Vec<Scene>,
    /// Every mapping the topology allows.
    pub mappings: Vec<Mapping>,
    /// A smooth law instead of affine pieces (then no boundaries or domains:
    /// its scenes build piecewise-linear models from it).
    pub law: Option<Law>,
}

impl Model {
    /// The index of the stick boundary, if any.
    pub fn stick_boundary(&self) -> Option<usize> {
        self.boundaries.iter().position(|b| b.stick.is_some())
    }

    /// Every mapping this model's topology allows.
    pub fn all_mappings(&self) -> Vec<Mapping> {
        let numbers: Vec<u32> = self.boundaries.iter().map(|b| b.number).collect();
        let bands: Vec<Band> = self
            .domains
            .iter()
            .map(|d| Band {
                label: d.label,
                lower: d.lower,
                upper: d.upper,
            })
            .collect();
        Self::topology_mappings(&numbers, self.stick_boundary(), &bands)
    }

    /// The domain just above boundary `k` and just below it.
    pub fn sides(&self, k: usize) -> (usize, usize) {
        // Domains are sorted; domain i lies between boundaries i-1 and i.
        (k + 1, k)
    }

    /// Mapping name for domain label `j` from boundary number `a` to `b`:
    /// `j_ba` when both numbers have one digit, `j_b_a` otherwise.
    pub fn mapping_name(j: u32, to: u32, from: u32) -> String {
        if to < 10 && from < 10 {
            format!("{j}_{to}{from}")
        } else {
            format!("{j}_{to}_{from}")
        }
    }

    /// Every mapping the topology allows: per domain, the local mappings on
    /// each of its edges and the global mappings across it; the stick mapping
    /// on the stick boundary. `numbers` are the boundaries' numbers, `stick`
    /// the stick boundary's index, `bands` each domain's label, lower and
    /// upper edge.
    pub fn topology_mappings(
        numbers: &[u32],
        stick: Option<usize>,
        bands: &[Band],
    ) -> Vec<Mapping> {
        let mut out = Vec::new();
        let mut order: Vec<usize> = (0..bands.len()).collect();
        order.sort_by_key(|&i| bands[i].label);
        for i in order {
            let d = &bands[i];
            let num = |k: usize| numbers[k];
            let mut push = |from: usize, to: usize, kind| {
                out.push(Mapping {
                    name: Self::mapping_name(d.label, num(to), num(from)),
                    domain: Some(i),
                    from,
                    to,
                    kind,
                })
            };
            if let Some(lo) = d.lower {
                push(lo, lo, MappingKind::Local);
            }
            if let Some(hi) = d.upper {
                push(hi, hi, MappingKind::Local);
            }
            if let (Some(lo), Some(hi)) = (d.lower, d.upper) {
                push(lo, hi, MappingKind::Global);
                push(hi, lo, MappingKind::Global);
            }
        }
        if let Some(s) = stick {
            let n = numbers[s];
            out.push(Mapping {
                name: Self::mapping_name(0, n, n),
                domain: None,
                from: s,
                to: s,
                kind: MappingKind::Stick,
            });
        }
        out
    }
}
