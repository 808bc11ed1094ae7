//! A model instance: the model's quantities as nodes of one expression
//! graph, with a chosen set of parameters left free (run-time inputs) and
//! the others folded to their default values (SPEC §1: the effective
//! coefficients `d_j, c_j, b_j` of every domain).

use std::collections::HashMap;

use crate::diagnostic::Diagnostics;
use crate::expr::{Graph, Id};
use crate::lower::{lower, Scope};
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
pub struct Instance {
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
pub fn lower_instance(model: &Model, free: &[usize], diags: &mut Diagnostics) -> Instance {
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
        let id = lower(
            &mut graph,
            &d.value,
            &Scope {
                names: &names,
                velocity: None,
                context: &context,
            },
            diags,
        );
        names.insert(d.name.clone(), id);
    }
    let mut expr = |graph: &mut Graph, e: &syn::Expr, context: &str, velocity: Option<Id>| {
        lower(
            graph,
            e,
            &Scope {
                names: &names,
                velocity,
                context,
            },
            diags,
        )
    };
    let o = &model.oscillator;
    let mass = expr(&mut graph, &o.mass, "the mass", None);
    let damping = expr(&mut graph, &o.damping, "the damping", None);
    let stiffness = expr(&mut graph, &o.stiffness, "the stiffness", None);
    let forcing = expr(&mut graph, &o.forcing, "the forcing amplitude", None);
    let frequency = expr(&mut graph, &o.frequency, "the forcing frequency", None);
    let mut boundary_velocity = Vec::new();
    let mut static_bound = None;
    for b in &model.boundaries {
        let ctx = format!("the velocity of {}", b.label);
        boundary_velocity.push(expr(&mut graph, &b.velocity, &ctx, None));
        if let Some(s) = &b.stick {
            let ctx = format!("the static bound of {}", b.label);
            static_bound = Some(expr(&mut graph, s, &ctx, None));
        }
    }
    let v = graph.var(LAW_V);
    let mut domains = Vec::new();
    for dm in &model.domains {
        let ctx = format!("the friction law of domain {}", dm.label);
        let law = expr(&mut graph, &dm.law, &ctx, Some(v));
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
        let d = graph.add(damping, hs);
        domains.push(DomainNodes {
            law,
            slope,
            b,
            d,
            c: stiffness,
        });
    }
    Instance {
        free: free.to_vec(),
        graph,
        mass,
        damping,
        stiffness,
        forcing,
        frequency,
        boundary_velocity,
        static_bound,
        domains,
        names,
    }
}

impl Instance {
    /// Value of a node at the default parameters (free ones at their defaults too).
    pub fn at_defaults(&self, model: &Model, id: Id) -> f64 {
        let params: Vec<f64> = self.free.iter().map(|&i| model.params[i].default).collect();
        self.graph.eval(id, &params, &[])
    }
}
