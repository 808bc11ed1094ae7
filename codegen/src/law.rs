//! Smooth friction laws (SPEC §12): the law's quantities as graph
//! nodes, and the checks of a smooth model at its defaults. The
//! piecewise-linear models built from a law are [`crate::expand::pieces`].

use syn::spanned::Spanned;

use crate::diagnostic::{num, Diagnostics};
use crate::expr::{Graph, Id, Node};
use crate::lower::Velocity;
use crate::lowered::{lower_instance, Lowered, LAW_V};
use crate::model::{Law, Model};

/// The law's quantities as nodes of an instance's graph.
#[derive(Clone, Copy, Debug)]
pub struct LawNodes {
    /// `V`.
    pub belt: Id,
    /// `as`.
    pub stick: Id,
    /// `R`.
    pub range: Id,
    /// `f(v)` in terms of [`LAW_V`].
    pub kinetic: Id,
}

/// Lower the law's expressions into `inst`.
pub fn lower_law(inst: &mut Lowered, law: &Law, diags: &mut Diagnostics) -> LawNodes {
    let v = Velocity::Node(inst.graph.var(LAW_V));
    LawNodes {
        belt: inst.lower(&law.belt, "the belt speed", None, diags),
        stick: inst.lower(&law.stick, "the static bound", None, diags),
        range: inst.lower(&law.range, "the range of the pieces", None, diags),
        kinetic: inst.lower(&law.kinetic, "the kinetic friction law", Some(v), diags),
    }
}

/// A small offset from the belt speed where the law's one-sided limits are taken.
pub fn side_offset(range: f64) -> f64 {
    1e-12 * range.max(1.0)
}

/// Check a smooth model at its defaults: finite belt speed, positive range,
/// a finite law, static bound at least the kinetic level on both sides.
pub fn check_smooth(model: &Model, diags: &mut Diagnostics) {
    let Some(law) = &model.law else { return };
    let all: Vec<usize> = (0..model.params.len()).collect();
    let before = diags.len();
    let mut inst = lower_instance(model, &all, diags);
    let nodes = lower_law(&mut inst, law, diags);
    if diags.len() > before {
        return;
    }
    let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
    let g = &inst.graph;
    let (belt, range, stick) = (
        g.eval(nodes.belt, &defaults, &[]),
        g.eval(nodes.range, &defaults, &[]),
        g.eval(nodes.stick, &defaults, &[]),
    );
    if !belt.is_finite() {
        diags.error(
            law.belt.span(),
            format!("the belt speed is {} at the defaults", num(belt)),
        );
    }
    if !(range.is_finite() && range > 0.0) {
        diags.error(
            law.range.span(),
            format!(
                "the range of the pieces must be positive; it is {} at the defaults",
                num(range)
            ),
        );
        return;
    }
    let f = |v: f64| eval_law(g, nodes.kinetic, &defaults, v);
    let delta = side_offset(range);
    for (side, v) in [("above", belt + delta), ("below", belt - delta)] {
        let level = f(v);
        if !level.is_finite() {
            diags.error(
                law.kinetic.span(),
                format!(
                    "the kinetic law is {} just {side} the belt speed",
                    num(level)
                ),
            );
        } else if stick.is_nan() || stick < level.abs() - 1e-12 * (1.0 + level.abs()) {
            diags.error(
                law.stick.span(),
                format!(
                    "the static bound {} is below the kinetic friction level {} just {side} the belt speed",
                    num(stick),
                    num(level.abs())
                ),
            );
        }
    }
    check_law_finite(&mut inst.graph, nodes, law, &defaults, belt, range, diags);
}

/// Samples per side of the belt speed where the law and its first two
/// derivatives must be finite: the grid on which the breakpoints are placed.
const SAMPLES: usize = 4000;

/// The law must be finite on its declared range `V ± R` (the belt speed
/// itself excluded: the law jumps there), and so must its first and second
/// derivatives, which place the breakpoints. What is guaranteed:
/// * finite at every point of the breakpoint grid (`SAMPLES + 1` points on
///   each side, both ends included) — the points where the build evaluates it;
/// * no pole inside the range from a `1 / a`, `ln(a)` or negative power of
///   an `a` that is affine in `v`: its root is computed exactly, so a pole
///   between grid points is found too.
///
/// A pole of a non-affine argument that falls between grid points is not
/// found here; the pieces then still hold finite values at their breakpoints
/// (checked again when they are built).
fn check_law_finite(
    g: &mut Graph,
    nodes: LawNodes,
    law: &Law,
    defaults: &[f64],
    belt: f64,
    range: f64,
    diags: &mut Diagnostics,
) {
    let f0 = nodes.kinetic;
    let f1 = g.diff(f0, LAW_V).unwrap_or(f0);
    let f2 = g.diff(f1, LAW_V).unwrap_or(f1);
    let delta = side_offset(range);
    let what = [
        "the kinetic law",
        "the kinetic law's first derivative",
        "the kinetic law's second derivative (which places the breakpoints)",
    ];
    for sign in [1.0, -1.0] {
        for i in 0..=SAMPLES {
            let u = (range * i as f64 / SAMPLES as f64).max(delta);
            let v = belt + sign * u;
            for (k, f) in [f0, f1, f2].into_iter().enumerate() {
                let y = eval_law(g, f, defaults, v);
                if !y.is_finite() {
                    diags.error(
                        law.kinetic.span(),
                        format!(
                            "{} is {y} at v = {} (the belt speed {} {} {}), inside the law's range: \
                             a smooth law must be finite on V ± range",
                            what[k],
                            num(v),
                            num(belt),
                            if sign > 0.0 { "+" } else { "-" },
                            num(u)
                        ),
                    );
                    return;
                }
            }
        }
    }
    // Exact poles of affine arguments.
    let mut stack = vec![f0, f1, f2];
    let mut seen = std::collections::HashSet::new();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        let node = g.node(id);
        stack.extend(crate::expr::children(node));
        let arg = match node {
            Node::Recip(a) | Node::Ln(a) => a,
            Node::Powi(a, n) if n < 0 => a,
            _ => continue,
        };
        if !g.depends_on(arg, LAW_V) {
            continue;
        }
        let Ok(da) = g.diff(arg, LAW_V) else { continue };
        if g.depends_on(da, LAW_V) {
            continue; // not affine: left to the sampling
        }
        let slope = eval_law(g, da, defaults, 0.0);
        let at_belt = eval_law(g, arg, defaults, belt);
        if slope == 0.0 || !slope.is_finite() || !at_belt.is_finite() {
            continue;
        }
        let root = belt - at_belt / slope;
        let off = (root - belt).abs();
        if off > 0.0 && off <= range {
            diags.error(
                law.kinetic.span(),
                format!(
                    "the kinetic law has a pole at v = {} (the belt speed {} {} {}), inside the law's range: \
                     a smooth law must be finite on V ± range",
                    num(root),
                    num(belt),
                    if root > belt { "+" } else { "-" },
                    num(off)
                ),
            );
            return;
        }
    }
}

/// The law `law` at `v`, the parameters at `params`.
pub fn eval_law(g: &Graph, law: Id, params: &[f64], v: f64) -> f64 {
    let mut vars = vec![0.0; LAW_V as usize + 1];
    vars[LAW_V as usize] = v;
    g.eval(law, params, &vars)
}
