//! The checks of a piecewise model that need its sorted topology: kinetic
//! friction continuous across every boundary but the stick boundary, and the
//! static bound at least the kinetic level on both sides of the stick
//! boundary. They run on a checked model ([`Piecewise::of`]) and on every
//! generated N-piece model of a smooth law ([`check_pieces`]).

use proc_macro2::Span;
use quote::ToTokens;
use syn::spanned::Spanned;
use syn::Expr;

use super::satisfies;
use crate::diagnostic::{num, Diagnostics};
use crate::lowered::{Lowered, LAW_V};
use crate::model::{Model, Param};

/// A piecewise model as the continuity and static-bound checks see it:
/// its parameters, its boundaries (sorted) and its domains' labels (sorted;
/// domain `k + 1` lies above boundary `k`).
pub struct Piecewise<'a> {
    /// The model's parameters (defaults and bounds).
    pub params: &'a [crate::model::Param],
    /// Each boundary, lowest first.
    pub edges: Vec<Edge<'a>>,
    /// Each domain's label, lowest first.
    pub domain_labels: Vec<u32>,
}

/// A boundary as [`Piecewise`] sees it.
pub struct Edge<'a> {
    /// `Sigma1`.
    pub label: &'a str,
    /// Where errors about it point.
    pub span: Span,
    /// The static bound, on the stick boundary.
    pub stick: Option<&'a Expr>,
}

impl<'a> Piecewise<'a> {
    /// The view of a checked model.
    pub fn of(model: &'a Model) -> Self {
        Piecewise {
            params: &model.params,
            edges: model
                .boundaries
                .iter()
                .map(|b| Edge {
                    label: &b.label,
                    span: b.span,
                    stick: b.stick.as_ref(),
                })
                .collect(),
            domain_labels: model.domains.iter().map(|d| d.label).collect(),
        }
    }
}

/// The checks of a generated piecewise-linear model (affine by
/// construction): continuity away from the stick boundary, static bound
/// above the kinetic levels. `inst` has every parameter free.
pub fn check_pieces(model: &Piecewise, inst: &Lowered, diags: &mut Diagnostics) {
    check_continuity(model, inst, diags);
    check_static_bound(model, inst, diags);
}

/// Deterministic pseudo-random numbers in [-1, 1] (no dependency needed for 16 draws).
fn perturbations(n: usize, trials: usize) -> Vec<Vec<f64>> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..trials)
        .map(|_| {
            (0..n)
                .map(|_| {
                    state = state
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
                })
                .collect()
        })
        .collect()
}

/// The defaults moved by the draws `t` in [-1, 1], each kept inside its
/// parameter's bounds: a value outside them is pulled back towards the
/// default (which satisfies them) by halving the step. The continuity check
/// must only try valid parameter values: a Stribeck law `exp(-|v - V| / vs)`
/// with `vs` pushed below zero is not a law of the model at all.
fn perturbed(params: &[Param], defaults: &[f64], t: &[f64]) -> Vec<f64> {
    defaults
        .iter()
        .zip(t)
        .zip(params)
        .map(|((&d, &u), p)| {
            let mut step = d * 0.3 * u + 0.1 * u;
            for _ in 0..60 {
                let x = d + step;
                if p.bounds.iter().all(|&(op, b)| satisfies(x, op, b)) {
                    return x;
                }
                step *= 0.5;
            }
            d
        })
        .collect()
}

pub(super) fn check_continuity(model: &Piecewise, inst: &Lowered, diags: &mut Diagnostics) {
    let mut g = inst.graph.clone();
    let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
    let trials = perturbations(defaults.len(), 16);
    for (k, b) in model.edges.iter().enumerate() {
        if b.stick.is_some() {
            continue;
        }
        let (above, below) = (k + 1, k);
        let vk = inst.boundary_velocity[k];
        let fa = g.substitute(inst.domains[above].law, LAW_V, vk);
        let fb = g.substitute(inst.domains[below].law, LAW_V, vk);
        let jump = g.sub(fa, fb);
        if g.as_const(jump) == Some(0.0) {
            continue; // symbolically continuous
        }
        let (la, lb) = (model.domain_labels[above], model.domain_labels[below]);
        let at_defaults = g.eval(jump, &defaults, &[]);
        let scale = 1.0 + g.eval(fa, &defaults, &[]).abs();
        // NaN (a law undefined at the boundary) is a jump too.
        if at_defaults.is_nan() || at_defaults.abs() > 1e-12 * scale {
            diags.error(
                b.span,
                format!(
                    "kinetic friction jumps at `{}` (domain {lb} gives {}, domain {la} gives {}), but `{}` is not a stick boundary: \
                     make the laws meet there or declare `stick BOUND`",
                    b.label,
                    num(g.eval(fb, &defaults, &[])),
                    num(g.eval(fa, &defaults, &[])),
                    b.label
                ),
            );
            continue;
        }
        for t in &trials {
            let p = perturbed(model.params, &defaults, t);
            let jv = g.eval(jump, &p, &[]);
            let sc = 1.0 + g.eval(fa, &p, &[]).abs();
            if jv.abs() > 1e-9 * sc {
                diags.error(
                    b.span,
                    format!(
                        "kinetic friction is continuous at `{}` only for the default parameter values: \
                         domains {lb} and {la} do not meet there for other values",
                        b.label
                    ),
                );
                break;
            }
        }
    }
}

pub(super) fn check_static_bound(model: &Piecewise, inst: &Lowered, diags: &mut Diagnostics) {
    let Some((k, b, e)) = model
        .edges
        .iter()
        .enumerate()
        .find_map(|(k, b)| Some((k, b, b.stick?)))
    else {
        return;
    };
    let Some(bound) = inst.static_bound else {
        return;
    };
    let mut g = inst.graph.clone();
    let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
    let s = g.eval(bound, &defaults, &[]);
    let (above, below) = (k + 1, k);
    let vk = inst.boundary_velocity[k];
    for (j, sign, side) in [(above, 1.0, "above"), (below, -1.0, "below")] {
        let f = g.substitute(inst.domains[j].law, LAW_V, vk);
        let level = sign * g.eval(f, &defaults, &[]);
        if s.is_nan() || s < level.abs() - 1e-12 * (1.0 + level.abs()) {
            diags.error(
                e.span(),
                format!(
                    "the static bound `{}` = {} is below the kinetic friction level {} {side} `{}` (domain {}): \
                     static friction must be at least kinetic",
                    e.to_token_stream(),
                    num(s),
                    num(level.abs()),
                    b.label,
                    model.domain_labels[j]
                ),
            );
        }
    }
}
