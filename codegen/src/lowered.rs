//! A model lowered into one expression graph: the model's quantities as
//! nodes, with a chosen set of parameters left free (run-time inputs) and
//! the others folded to their default values (SPEC §1: the effective
//! coefficients `d_j, c_j, b_j` of every domain).
//!
//! [`crate::check`] lowers a model to check it; [`crate::expand`] lowers
//! every generated type (the model, each scene, each piecewise-linear model
//! of a smooth law).

use std::collections::HashMap;

use crate::diagnostic::Diagnostics;
use crate::expr::{Graph, Id};
use crate::lower::{lower, Scope, Velocity};
use crate::model::Model;

/// The variable that stands for `v` in a friction law.
pub const LAW_V: u32 = 1000;

/// Per-domain quantities (SPEC Eq. A.1: `x'' + 2 d_j x' + c_j x = A0 cos(W t) - b_j`).
#[derive(Clone, Copy, Debug)]
pub struct DomainNodes {
    /// `f_j(v)`, friction per unit mass, in terms of [`LAW_V`].
    pub law: Id,
    /// `s_j = df_j/dv`.
    pub slope: Id,
    /// `b_j = f_j(0)`.
    pub b: Id,
    /// `d_j = d + s_j / 2`.
    pub d: Id,
    /// `c_j = c`.
    pub c: Id,
}

/// A lowered model.
#[derive(Clone, Debug)]
pub struct Lowered {
    /// Indices of the free parameters, in order; `Param(k)` is `free[k]`.
    pub free: Vec<usize>,
    /// The expression graph holding every node below.
    pub graph: Graph,
    /// `m`.
    pub mass: Id,
    /// `d` (the oscillator's `2 d x'` term).
    pub damping: Id,
    /// `c`.
    pub stiffness: Id,
    /// `A0`.
    pub forcing: Id,
    /// `W`.
    pub frequency: Id,
    /// Velocity of each boundary, in the model's (sorted) order.
    pub boundary_velocity: Vec<Id>,
    /// Static bound of the stick boundary (`as`).
    pub static_bound: Option<Id>,
    /// Per domain, in the model's order.
    pub domains: Vec<DomainNodes>,
    /// Node of every parameter and derived quantity, by name.
    pub names: HashMap<String, Id>,
}

/// Lower `model` with parameters `free` left symbolic. Errors (unknown names,
/// division by zero, ...) go to `diags`.
pub fn lower_instance(model: &Model, free: &[usize], diags: &mut Diagnostics) -> Lowered {
    let mut inst = lower_oscillator(model, free, diags);
    for b in &model.boundaries {
        let ctx = format!("the velocity of {}", b.label);
        let velocity = inst.lower(&b.velocity, &ctx, None, diags);
        let stick = b.stick.as_ref().map(|s| {
            let ctx = format!("the static bound of {}", b.label);
            inst.lower(s, &ctx, None, diags)
        });
        inst.push_boundary(velocity, stick);
    }
    let v = inst.graph.var(LAW_V);
    for dm in &model.domains {
        let ctx = format!("the friction law of domain {}", dm.label);
        let law = inst.lower(&dm.law, &ctx, Some(Velocity::Node(v)), diags);
        inst.push_domain(law);
    }
    inst
}

/// The parameters, derived quantities and oscillator of `model` lowered
/// with parameters `free` left symbolic; no boundaries or domains yet
/// ([`Lowered::push_boundary`], [`Lowered::push_domain`]).
pub fn lower_oscillator(model: &Model, free: &[usize], diags: &mut Diagnostics) -> Lowered {
    let mut graph = Graph::new();
    // Every node knows its value at the defaults, so that lowering reports a
    // non-finite number at the subexpression that makes it.
    graph.set_param_values(free.iter().map(|&i| model.params[i].default).collect());
    let mut names = HashMap::new();
    for (i, p) in model.params.iter().enumerate() {
        let id = match free.iter().position(|&f| f == i) {
            Some(k) => graph.param(k as u32),
            None => graph.constant(p.default),
        };
        names.insert(p.name.clone(), id);
    }
    for d in &model.derived {
        let context = format!("derived quantity `{}`", d.name);
        let id = lower_in(&mut graph, &names, &d.value, &context, None, diags);
        names.insert(d.name.clone(), id);
    }
    let o = &model.oscillator;
    let mut one =
        |e: &syn::Expr, context: &str| lower_in(&mut graph, &names, e, context, None, diags);
    let mass = one(&o.mass, "the mass");
    let damping = one(&o.damping, "the damping");
    let stiffness = one(&o.stiffness, "the stiffness");
    let forcing = one(&o.forcing, "the forcing amplitude");
    let frequency = one(&o.frequency, "the forcing frequency");
    Lowered {
        free: free.to_vec(),
        graph,
        mass,
        damping,
        stiffness,
        forcing,
        frequency,
        boundary_velocity: Vec::new(),
        static_bound: None,
        domains: Vec::new(),
        names,
    }
}

fn lower_in(
    graph: &mut Graph,
    names: &HashMap<String, Id>,
    e: &syn::Expr,
    context: &str,
    velocity: Option<Velocity>,
    diags: &mut Diagnostics,
) -> Id {
    let scope = Scope {
        names,
        velocity,
        context,
    };
    lower(graph, e, &scope, diags)
}

impl Lowered {
    /// Lower one model expression into the graph, with the names known so far.
    pub fn lower(
        &mut self,
        e: &syn::Expr,
        context: &str,
        velocity: Option<Velocity>,
        diags: &mut Diagnostics,
    ) -> Id {
        lower_in(&mut self.graph, &self.names, e, context, velocity, diags)
    }

    /// The next boundary (in sorted order): its velocity and, for the stick
    /// boundary, its static bound.
    pub fn push_boundary(&mut self, velocity: Id, stick: Option<Id>) {
        self.boundary_velocity.push(velocity);
        if stick.is_some() {
            self.static_bound = stick;
        }
    }

    /// The next domain (in sorted order), from its friction law in [`LAW_V`].
    pub fn push_domain(&mut self, law: Id) {
        let graph = &mut self.graph;
        // A non-affine law is reported by the checker; here the slope is
        // taken at v = 0 so that lowering can go on.
        let slope_v = graph
            .diff(law, LAW_V)
            .unwrap_or_else(|_| graph.constant(0.0));
        let zero = graph.constant(0.0);
        let slope = graph.substitute(slope_v, LAW_V, zero);
        let b = graph.substitute(law, LAW_V, zero);
        let half = graph.constant(0.5);
        let hs = graph.mul(half, slope);
        let d = graph.add(self.damping, hs);
        self.domains.push(DomainNodes {
            law,
            slope,
            b,
            d,
            c: self.stiffness,
        });
    }

    /// Value of a node at the default parameters (free ones at their defaults too).
    pub fn at_defaults(&self, model: &Model, id: Id) -> f64 {
        let params: Vec<f64> = self.free.iter().map(|&i| model.params[i].default).collect();
        self.graph.eval(id, &params, &[])
    }
}
