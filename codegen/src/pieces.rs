//! Smooth friction laws and the piecewise-linear models built from them at
//! build time (issue 5, SPEC §12).
//!
//! **Breakpoint rule.** On each side of the belt speed the law is
//! interpolated linearly between breakpoints `|v − V| = 0 < u_1 < … < u_{k−1} < R`
//! (`k = N/2` pieces per side; the outermost piece interpolates on
//! `[u_{k−1}, R]` and continues beyond `R`). Linear interpolation on a piece
//! of width `h` errs by about `|f''| h² / 8`, so the breakpoints equidistribute
//! `∫ sqrt|f''(V ± u)| du` over `[0, R]` (de Boor's rule): every piece then
//! carries the same interpolation error, and the error falls as `N^-2`. The
//! second derivative is the law's exact symbolic derivative, evaluated at the
//! default parameters; the pieces' values are the law itself (symbolic in
//! the parameters), so a piecewise model interpolates the law at any
//! parameter values, at breakpoints placed for the defaults.

use proc_macro2::{Delimiter, Group, Span, TokenStream, TokenTree};
use quote::quote;
use syn::spanned::Spanned;
use syn::Expr;

use crate::diagnostic::{num, Diagnostics};
use crate::expr::{Graph, Id, Node};
use crate::instance::{lower_instance, Instance, LAW_V};
use crate::lower::{lower, Scope};
use crate::model::{Boundary, Domain, Law, Model, Scene};

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
pub fn lower_law(inst: &mut Instance, law: &Law, diags: &mut Diagnostics) -> LawNodes {
    let names = inst.names.clone();
    let v = inst.graph.var(LAW_V);
    let mut one = |e: &Expr, ctx: &str, velocity: Option<Id>| {
        lower(
            &mut inst.graph,
            e,
            &Scope {
                names: &names,
                velocity,
                context: ctx,
            },
            diags,
        )
    };
    LawNodes {
        belt: one(&law.belt, "the belt speed", None),
        stick: one(&law.stick, "the static bound", None),
        range: one(&law.range, "the range of the pieces", None),
        kinetic: one(&law.kinetic, "the kinetic friction law", Some(v)),
    }
}

/// A small offset from the belt speed where the law's one-sided limits are taken.
fn side_offset(range: f64) -> f64 {
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

fn eval_law(g: &Graph, law: Id, params: &[f64], v: f64) -> f64 {
    let mut vars = vec![0.0; LAW_V as usize + 1];
    vars[LAW_V as usize] = v;
    g.eval(law, params, &vars)
}

/// Breakpoint offsets `u_1 < … < u_{k−1}` and the range `R` on one side.
fn side_breakpoints(
    g: &Graph,
    f2: Id,
    defaults: &[f64],
    belt: f64,
    range: f64,
    sign: f64,
    k: usize,
) -> Vec<f64> {
    const M: usize = 4000;
    let density: Vec<f64> = (0..=M)
        .map(|i| {
            let u = range * (i as f64 / M as f64).max(1e-9);
            eval_law(g, f2, defaults, belt + sign * u).abs().sqrt()
        })
        .collect();
    let finite: Vec<f64> = density
        .iter()
        .map(|d| if d.is_finite() { *d } else { 0.0 })
        .collect();
    let mean = finite.iter().sum::<f64>() / finite.len() as f64;
    // A floor keeps pieces finite where the law is locally straight.
    let floor = 1e-3 * mean.max(f64::MIN_POSITIVE);
    let mut cumulative = vec![0.0; M + 1];
    for i in 1..=M {
        let (a, b) = (finite[i - 1].max(floor), finite[i].max(floor));
        cumulative[i] = cumulative[i - 1] + 0.5 * (a + b) * range / M as f64;
    }
    let total = cumulative[M];
    (1..k)
        .map(|j| {
            let target = total * j as f64 / k as f64;
            let i = cumulative.partition_point(|&c| c < target).clamp(1, M);
            let (c0, c1) = (cumulative[i - 1], cumulative[i]);
            let t = if c1 > c0 {
                (target - c0) / (c1 - c0)
            } else {
                0.0
            };
            range * ((i - 1) as f64 + t) / M as f64
        })
        .collect()
}

/// `tokens` with every identifier `v` replaced by `(replacement)`.
fn substitute_v(tokens: TokenStream, replacement: &TokenStream) -> TokenStream {
    tokens
        .into_iter()
        .map(|tt| match tt {
            TokenTree::Ident(ref i) if i == "v" => {
                TokenTree::Group(Group::new(Delimiter::Parenthesis, replacement.clone()))
            }
            TokenTree::Group(g) => {
                let mut ng = Group::new(g.delimiter(), substitute_v(g.stream(), replacement));
                ng.set_span(g.span());
                TokenTree::Group(ng)
            }
            other => other,
        })
        .collect()
}

fn expr(tokens: TokenStream) -> Expr {
    syn::parse2(tokens).expect("generated piece expressions parse")
}

/// The `n`-piece model of scene `scene` of a smooth model: boundaries at the
/// breakpoints (the belt speed carries the stick), one affine domain per piece
/// interpolating the law, and the scene's free parameters.
pub fn build(model: &Model, scene: &Scene, n: u32) -> Model {
    let law = model.law.as_ref().expect("a smooth model");
    let all: Vec<usize> = (0..model.params.len()).collect();
    let mut inst = lower_instance(model, &all, &mut Diagnostics::new());
    let nodes = lower_law(&mut inst, law, &mut Diagnostics::new());
    let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
    let g = &mut inst.graph;
    let f1 = g.diff(nodes.kinetic, LAW_V).unwrap_or(nodes.kinetic);
    let f2 = g.diff(f1, LAW_V).unwrap_or(f1);
    let belt = g.eval(nodes.belt, &defaults, &[]);
    let range = g.eval(nodes.range, &defaults, &[]);
    let k = (n / 2) as usize;
    let delta = side_offset(range);
    let (kinetic, belt_expr) = (&law.kinetic, &law.belt);
    let law_tokens = quote!(#kinetic);
    let belt_tokens = quote!(#belt_expr);
    let value_at = |sign: f64, u: f64| -> TokenStream {
        // The law at v = V ± u (one-sided at the belt speed).
        let u = if u == 0.0 { delta } else { u };
        let op = if sign > 0.0 { quote!(+) } else { quote!(-) };
        let u = syn::LitFloat::new(&format!("{u:?}"), Span::call_site());
        let at = quote!((#belt_tokens) #op #u);
        let sub = substitute_v(law_tokens.clone(), &at);
        quote!((#sub))
    };
    let mut boundaries = vec![Boundary {
        label: "Sigma1".into(),
        number: 1,
        docs: vec!["The belt speed: the law jumps here and the mass can stick.".into()],
        velocity: expr(belt_tokens.clone()),
        stick: Some(law.stick.clone()),
        span: Span::call_site(),
    }];
    let mut sides: Vec<(f64, Vec<f64>)> = Vec::new();
    for sign in [1.0, -1.0] {
        let mut u = side_breakpoints(&inst.graph, f2, &defaults, belt, range, sign, k);
        for &uj in &u {
            let number = boundaries.len() as u32 + 1;
            let lit = syn::LitFloat::new(&format!("{uj:?}"), Span::call_site());
            let op = if sign > 0.0 { quote!(+) } else { quote!(-) };
            boundaries.push(Boundary {
                label: format!("Sigma{number}"),
                number,
                docs: vec![format!("Breakpoint |v - V| = {uj:.6}.")],
                velocity: expr(quote!((#belt_tokens) #op #lit)),
                stick: None,
                span: Span::call_site(),
            });
        }
        u.insert(0, 0.0);
        u.push(range);
        sides.push((sign, u));
    }
    // Boundary indices by velocity, lowest first; domains between them.
    let mut order: Vec<usize> = (0..boundaries.len()).collect();
    let offset = |b: usize| -> f64 {
        if b == 0 {
            0.0
        } else if b < k {
            sides[0].1[b]
        } else {
            -sides[1].1[b - k + 1]
        }
    };
    order.sort_by(|&a, &b| offset(a).total_cmp(&offset(b)));
    let position = |b: usize| {
        order
            .iter()
            .position(|&o| o == b)
            .expect("every boundary is ordered")
    };
    let sorted: Vec<Boundary> = order.iter().map(|&i| boundaries[i].clone()).collect();
    let mut domains: Vec<Domain> = Vec::new();
    for (s, (sign, u)) in sides.iter().enumerate() {
        for piece in 0..k {
            let (ua, ub) = (u[piece], u[piece + 1]);
            let (fa, fb) = (value_at(*sign, ua), value_at(*sign, ub));
            let du = syn::LitFloat::new(&format!("{:?}", ub - ua), Span::call_site());
            let ua_lit = syn::LitFloat::new(&format!("{ua:?}"), Span::call_site());
            // f_a + (f_b − f_a) / (u_b − u_a) · (±(v − V) − u_a)
            let rel = if *sign > 0.0 {
                quote!((v - (#belt_tokens)))
            } else {
                quote!(((#belt_tokens) - v))
            };
            let law_expr = expr(quote!(#fa + (#fb - #fa) / #du * (#rel - #ua_lit)));
            // Boundary indices (unsorted) of this piece's edges.
            let inner = if piece == 0 {
                Some(0)
            } else {
                Some(if s == 0 { piece } else { k - 1 + piece })
            };
            let outer = if piece + 1 < k {
                Some(if s == 0 { piece + 1 } else { k + piece })
            } else {
                None
            };
            let (lower, upper) = if *sign > 0.0 {
                (inner, outer)
            } else {
                (outer, inner)
            };
            domains.push(Domain {
                label: (s * k + piece + 1) as u32,
                docs: vec![format!(
                    "Piece {} {} the belt speed: |v - V| in {}.",
                    piece + 1,
                    if *sign > 0.0 { "above" } else { "below" },
                    if piece + 1 < k {
                        format!("[{ua:.6}, {ub:.6}]")
                    } else {
                        format!("[{ua:.6}, ∞), interpolated up to {ub:.6}")
                    }
                )],
                lower: lower.map(position),
                upper: upper.map(position),
                law: law_expr,
                span: Span::call_site(),
            });
        }
    }
    domains.sort_by_key(|d| d.lower.map_or(-1, |l| l as i64));
    let mappings = Model::topology_mappings(&sorted, &domains);
    Model {
        name: model.name.clone(),
        docs: model.docs.clone(),
        params: model.params.clone(),
        derived: model.derived.clone(),
        oscillator: model.oscillator.clone(),
        boundaries: sorted,
        domains,
        scenes: vec![Scene {
            pieces: None,
            ..scene.clone()
        }],
        mappings,
        law: None,
    }
}
