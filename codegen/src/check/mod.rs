//! Pass 2: syntax tree → checked [`Model`], with every error located.
//!
//! What is checked, and how:
//! * names: duplicates, unknown names (each use located), `v` outside a law;
//! * parameter defaults and bounds are numbers; defaults satisfy the bounds;
//! * the oscillator has mass, damping, stiffness, forcing and frequency, with
//!   positive mass, stiffness and frequency at the defaults;
//! * boundaries have distinct velocities at the defaults; at most one carries stick;
//! * the domains' bands tile the velocity axis: no overlap, no gap, no band
//!   that spans a boundary;
//! * every friction law is affine in `v`: its second derivative in `v`,
//!   taken symbolically with every parameter symbolic, must fold to 0; if
//!   not, the smallest offending term is named;
//! * kinetic friction is continuous across every boundary that is not the
//!   stick boundary: symbolically (the jump folds to 0 with all parameters
//!   symbolic), else numerically at the defaults and at 16 random
//!   perturbations of all parameters (a jump that vanishes only for special
//!   parameter values is reported);
//! * the static bound is at least the kinetic level on both sides of the stick boundary;
//! * division by a constant zero (in any instance, scenes included);
//! * scenes free existing parameters, and their structures name mappings the
//!   topology allows, each ending where the next begins.

use std::collections::HashMap;

use proc_macro2::Span;
use quote::ToTokens;
use syn::spanned::Spanned;
use syn::Expr;

use crate::diagnostic::{num, Diagnostics};
use crate::expr::Graph;
use crate::lower::{lower, Scope};
use crate::lowered::{lower_instance, Lowered, LAW_V};
use crate::model::{BoundOp, Boundary, Derived, Domain, Model, Oscillator, Param};
use crate::parse::{Item, ModelAst};

mod continuity;
mod scene;

use continuity::{check_continuity, check_static_bound};
pub use continuity::{check_pieces, Edge, Piecewise};
use scene::check_scene;
pub use scene::parse_structure;

/// Check a parsed model. Returns `None` when any error was found.
pub fn check(ast: ModelAst, diags: &mut Diagnostics) -> Option<Model> {
    let errors_before = diags.len();
    let mut params: Vec<Param> = Vec::new();
    let mut derived: Vec<Derived> = Vec::new();
    let mut seen: HashMap<String, Span> = HashMap::new();
    let mut oscillator = None;
    let mut law_ast: Option<crate::parse::OscillatorAst> = None;
    let mut boundaries: Vec<Boundary> = Vec::new();
    let mut domain_asts = Vec::new();
    let mut scene_asts = Vec::new();
    let empty = HashMap::new();
    // Whether every default is a number, and every boundary was accepted:
    // the checks at the defaults (signs, order of the boundaries, bands,
    // static bound) would report nonsense otherwise.
    let mut defaults_ok = true;
    let mut boundaries_ok = true;

    let mut declare = |name: &syn::Ident, diags: &mut Diagnostics| -> bool {
        let s = name.to_string();
        if s == "v" {
            diags.error(name.span(), "`v` is the velocity and cannot be redefined");
            return false;
        }
        if let Some(first) = seen.get(&s) {
            let l = first.start();
            diags.error(
                name.span(),
                format!(
                    "`{s}` is defined twice (first at line {}, column {})",
                    l.line,
                    l.column + 1
                ),
            );
            return false;
        }
        seen.insert(s, name.span());
        true
    };

    for item in ast.items {
        match item {
            Item::Param(p) => {
                if !declare(&p.name, diags) {
                    continue;
                }
                let ctx = format!("the default of `{}`", p.name);
                let default = constant(&p.default, &empty, &ctx, diags);
                defaults_ok &= default.is_some();
                let mut bounds = Vec::new();
                for (op, e, span) in &p.bounds {
                    let ctx = format!("a bound of `{}`", p.name);
                    let b = constant(e, &empty, &ctx, diags);
                    if let (Some(d), Some(b)) = (default, b) {
                        if !satisfies(d, *op, b) {
                            diags.error(
                                *span,
                                format!(
                                    "the default {} of `{}` violates its bound {} {}",
                                    num(d),
                                    p.name,
                                    op_str(*op),
                                    num(b)
                                ),
                            );
                        }
                        bounds.push((*op, b));
                    }
                }
                params.push(Param {
                    name: p.name.to_string(),
                    docs: p.docs,
                    default: default.unwrap_or(0.0),
                    bounds,
                    span: p.name.span(),
                });
            }
            Item::Let(l) => {
                if declare(&l.name, diags) {
                    derived.push(Derived {
                        name: l.name.to_string(),
                        docs: l.docs,
                        value: l.value,
                    });
                }
            }
            Item::Oscillator(o) => {
                if oscillator.is_some() {
                    diags.error(o.span, "the oscillator is declared twice");
                    continue;
                }
                oscillator = Some(check_oscillator(o, diags));
            }
            Item::Boundary(b) => {
                let label = b.label.to_string();
                let digits: String = label
                    .chars()
                    .rev()
                    .take_while(|c| c.is_ascii_digit())
                    .collect();
                let digits: String = digits.chars().rev().collect();
                let Ok(number) = digits.parse::<u32>() else {
                    boundaries_ok = false;
                    diags.error(
                        b.label.span(),
                        format!("boundary label `{label}` must end in its number, e.g. `Sigma1`"),
                    );
                    continue;
                };
                if let Some(other) = boundaries.iter().find(|o| o.number == number) {
                    boundaries_ok = false;
                    diags.error(
                        b.label.span(),
                        format!(
                            "boundary number {number} is used twice (`{}` and `{label}`)",
                            other.label
                        ),
                    );
                    // Kept, so that domains naming it get no second error.
                }
                if let Some(first) = boundaries.iter().find(|o| o.stick.is_some()) {
                    if b.stick.is_some() {
                        boundaries_ok = false;
                        diags.error(
                            b.label.span(),
                            format!(
                                "only one boundary can carry static friction; `{}` already does",
                                first.label
                            ),
                        );
                        // Kept, so that domains naming it get no second error.
                    }
                }
                boundaries.push(Boundary {
                    label,
                    number,
                    docs: b.docs,
                    velocity: b.velocity,
                    stick: b.stick,
                    span: b.label.span(),
                });
            }
            Item::Domain(d) => domain_asts.push(d),
            Item::Scene(s) => scene_asts.push(s),
            Item::Law(l) => {
                if law_ast.is_some() {
                    diags.error(l.span, "the law is declared twice");
                } else {
                    law_ast = Some(l);
                }
            }
        }
    }

    let Some(oscillator) = oscillator.flatten() else {
        if diags.len() == errors_before {
            diags.error(
                ast.name.span(),
                "the model has no `oscillator { mass, damping, stiffness, forcing, frequency }`",
            );
        }
        return None;
    };
    if let Some(l) = law_ast {
        if let Some(b) = boundaries.first() {
            diags.error(b.span, "a model with a smooth `law` gets its boundaries and domains from its `pieces` scenes");
        }
        for d in &domain_asts {
            diags.error(d.label.span(), "a model with a smooth `law` gets its boundaries and domains from its `pieces` scenes");
        }
        let law = check_law(l, diags)?;
        let mut model = Model {
            name: ast.name.to_string(),
            docs: ast.docs,
            params,
            derived,
            oscillator,
            boundaries: Vec::new(),
            domains: Vec::new(),
            scenes: Vec::new(),
            mappings: Vec::new(),
            law: Some(law),
        };
        if diags.len() > errors_before {
            return None;
        }
        crate::law::check_smooth(&model, diags);
        model.scenes = scene_asts
            .into_iter()
            .filter_map(|s| check_scene(&model, s, diags))
            .collect();
        return (diags.len() == errors_before).then_some(model);
    }
    if boundaries.is_empty() {
        diags.error(
            ast.name.span(),
            "the model has no boundary: declare at least one `boundary SigmaN: v = ...;`",
        );
        return None;
    }

    // Domains refer to boundaries by label.
    let by_label: HashMap<String, usize> = boundaries
        .iter()
        .enumerate()
        .map(|(i, b)| (b.label.clone(), i))
        .collect();
    let declared_domains = domain_asts.len();
    let mut domains: Vec<Domain> = Vec::new();
    for d in domain_asts {
        let label = match d.label.base10_parse::<u32>() {
            Ok(l) if l >= 1 => l,
            _ => {
                diags.error(
                    d.label.span(),
                    "a domain label is a positive integer (0 is the stick mapping's)",
                );
                continue;
            }
        };
        if domains.iter().any(|o| o.label == label) {
            diags.error(d.label.span(), format!("domain {label} is declared twice"));
            continue;
        }
        let mut resolve = |id: &Option<syn::Ident>| -> Result<Option<usize>, ()> {
            match id {
                None => Ok(None),
                Some(i) => match by_label.get(&i.to_string()) {
                    Some(&k) => Ok(Some(k)),
                    None => {
                        diags.error(i.span(), format!("unknown boundary `{i}`"));
                        Err(())
                    }
                },
            }
        };
        let (Ok(lower_b), Ok(upper_b)) = (resolve(&d.band.lower), resolve(&d.band.upper)) else {
            continue;
        };
        domains.push(Domain {
            label,
            docs: d.docs,
            lower: lower_b,
            upper: upper_b,
            law: d.law,
            span: d.band.span,
        });
    }

    let mut model = Model {
        name: ast.name.to_string(),
        docs: ast.docs,
        params,
        derived,
        oscillator,
        boundaries,
        domains,
        scenes: Vec::new(),
        mappings: Vec::new(),
        law: None,
    };
    // From here on every check runs even when an earlier one failed, so that
    // all of a file's errors are reported at once; a check is skipped only
    // where an earlier error would make it report nonsense.
    let domains_complete = model.domains.len() == declared_domains;

    // Lower everything once with all parameters symbolic: this reports unknown
    // names and divisions by zero, and gives the symbolic checks their graph.
    let all: Vec<usize> = (0..model.params.len()).collect();
    let before_lowering = diags.len();
    let symbolic = lower_instance(&model, &all, diags);
    let lowered = diags.len() == before_lowering;

    if lowered && defaults_ok {
        check_positive(&model, &symbolic, diags);
    }
    let before_affine = diags.len();
    for (j, dm) in model.domains.iter().enumerate() {
        check_affine(&symbolic, dm, j, diags);
    }
    let affine = diags.len() == before_affine;

    // The order of the boundaries is that of their velocities at the defaults.
    let ordered = lowered && defaults_ok && boundaries_ok;
    let before_bands = diags.len();
    if ordered {
        sort_boundaries(&mut model, &symbolic, diags);
    }
    if ordered && domains_complete && diags.len() == before_bands {
        check_bands(&mut model, ast.name.span(), diags);
    }
    let tiled = ordered && domains_complete && diags.len() == before_bands;
    if !tiled {
        return None;
    }
    if lowered && affine {
        // Boundaries and domains are now sorted: lower again in that order.
        let symbolic = lower_instance(&model, &all, &mut Diagnostics::new());
        let view = Piecewise::of(&model);
        check_continuity(&view, &symbolic, diags);
        check_static_bound(&view, &symbolic, diags);
    }

    model.mappings = model.all_mappings();
    model.scenes = scene_asts
        .into_iter()
        .filter_map(|s| check_scene(&model, s, diags))
        .collect();
    if lowered {
        for scene in &model.scenes {
            let mut scratch = Diagnostics::new();
            lower_instance(&model, &scene.free, &mut scratch);
            for d in scratch.iter() {
                diags.error(
                    d.span,
                    format!(
                        "with the parameters of scene `{}` fixed: {}",
                        scene.name, d.message
                    ),
                );
            }
        }
    }
    if diags.len() > errors_before {
        return None;
    }
    Some(model)
}

fn op_str(op: BoundOp) -> &'static str {
    match op {
        BoundOp::Gt => ">",
        BoundOp::Ge => ">=",
        BoundOp::Lt => "<",
        BoundOp::Le => "<=",
    }
}

/// Whether `value OP bound` holds.
pub fn satisfies(value: f64, op: BoundOp, bound: f64) -> bool {
    match op {
        BoundOp::Gt => value > bound,
        BoundOp::Ge => value >= bound,
        BoundOp::Lt => value < bound,
        BoundOp::Le => value <= bound,
    }
}

/// Lower an expression that must be a finite number.
fn constant(
    e: &Expr,
    names: &HashMap<String, crate::expr::Id>,
    ctx: &str,
    diags: &mut Diagnostics,
) -> Option<f64> {
    let mut g = Graph::new();
    let before = diags.len();
    let id = lower(
        &mut g,
        e,
        &Scope {
            names,
            velocity: None,
            context: ctx,
        },
        diags,
    );
    if diags.len() > before {
        return None;
    }
    match g.as_const(id) {
        Some(x) if x.is_finite() => Some(x),
        Some(x) => {
            diags.error(
                e.span(),
                format!("{ctx} is {}, not a finite number", num(x)),
            );
            None
        }
        None => {
            diags.error(e.span(), format!("{ctx} must be a number"));
            None
        }
    }
}

fn check_law(l: crate::parse::OscillatorAst, diags: &mut Diagnostics) -> Option<crate::model::Law> {
    let span = l.span;
    let [belt, stick, range, kinetic] =
        fields(l, ["belt", "stick", "range", "kinetic"], "law", diags)?;
    Some(crate::model::Law {
        belt,
        stick,
        range,
        kinetic,
        span,
    })
}

fn check_oscillator(o: crate::parse::OscillatorAst, diags: &mut Diagnostics) -> Option<Oscillator> {
    const KEYS: [&str; 5] = ["mass", "damping", "stiffness", "forcing", "frequency"];
    let [mass, damping, stiffness, forcing, frequency] = fields(o, KEYS, "oscillator", diags)?;
    Some(Oscillator {
        mass,
        damping,
        stiffness,
        forcing,
        frequency,
    })
}

/// The fields `keys` of a `what { key: expr, ... }` block, each exactly
/// once; an unknown, repeated or missing field is an error.
fn fields<const N: usize>(
    block: crate::parse::OscillatorAst,
    keys: [&str; N],
    what: &str,
    diags: &mut Diagnostics,
) -> Option<[Expr; N]> {
    let mut found: [Option<Expr>; N] = std::array::from_fn(|_| None);
    for (key, value) in block.fields {
        let k = key.to_string();
        match keys.iter().position(|&x| x == k) {
            Some(i) if found[i].is_some() => {
                diags.error(key.span(), format!("`{k}` is given twice"))
            }
            Some(i) => found[i] = Some(value),
            None => diags.error(
                key.span(),
                format!("unknown {what} field `{k}`; expected {}", keys.join(", ")),
            ),
        }
    }
    let missing: Vec<&str> = keys
        .iter()
        .zip(&found)
        .filter(|(_, f)| f.is_none())
        .map(|(k, _)| *k)
        .collect();
    if !missing.is_empty() {
        diags.error(
            block.span,
            format!("the {what} lacks {}", missing.join(", ")),
        );
        return None;
    }
    let all: Vec<Expr> = found.into_iter().collect::<Option<_>>()?;
    all.try_into().ok()
}

fn check_positive(model: &Model, inst: &Lowered, diags: &mut Diagnostics) {
    let o = &model.oscillator;
    for (what, id, e) in [
        ("mass", inst.mass, &o.mass),
        ("stiffness", inst.stiffness, &o.stiffness),
        ("forcing frequency", inst.frequency, &o.frequency),
    ] {
        let v = inst.at_defaults(model, id);
        if v.is_nan() || v <= 0.0 {
            diags.error(
                e.span(),
                format!(
                    "the {what} `{}` is {} at the defaults; it must be positive",
                    e.to_token_stream(),
                    num(v)
                ),
            );
        }
    }
}

/// Sort boundaries by velocity at the defaults, and remap the domains.
fn sort_boundaries(model: &mut Model, inst: &Lowered, diags: &mut Diagnostics) {
    let vel: Vec<f64> = inst
        .boundary_velocity
        .iter()
        .map(|&id| inst.at_defaults(model, id))
        .collect();
    let mut order: Vec<usize> = (0..model.boundaries.len()).collect();
    order.sort_by(|&a, &b| vel[a].total_cmp(&vel[b]));
    for w in order.windows(2) {
        if vel[w[0]] == vel[w[1]] {
            let (a, b) = (&model.boundaries[w[0]], &model.boundaries[w[1]]);
            diags.error(
                b.span,
                format!(
                    "`{}` and `{}` have the same velocity {} at the defaults",
                    a.label,
                    b.label,
                    num(vel[w[0]])
                ),
            );
        }
    }
    for &i in &order {
        if !vel[i].is_finite() {
            let b = &model.boundaries[i];
            diags.error(
                b.velocity.span(),
                format!(
                    "the velocity of `{}` is {} at the defaults",
                    b.label,
                    num(vel[i])
                ),
            );
        }
    }
    let mut position = vec![0; order.len()];
    for (k, &i) in order.iter().enumerate() {
        position[i] = k;
    }
    model.boundaries = order.iter().map(|&i| model.boundaries[i].clone()).collect();
    for d in &mut model.domains {
        d.lower = d.lower.map(|i| position[i]);
        d.upper = d.upper.map(|i| position[i]);
    }
}

/// The bands must tile the velocity axis; sorts the domains from low to high.
fn check_bands(model: &mut Model, model_span: Span, diags: &mut Diagnostics) {
    let n = model.boundaries.len();
    // Interval k lies between boundary k-1 and boundary k (k = 0..=n).
    let mut covered: Vec<Option<usize>> = vec![None; n + 1];
    let mut ok = true;
    for (j, d) in model.domains.iter().enumerate() {
        let label = |k: usize| &model.boundaries[k].label;
        let interval = match (d.lower, d.upper) {
            (Some(lo), Some(hi)) if hi <= lo => {
                diags.error(
                    d.span,
                    format!(
                        "empty band in domain {}: `{}` is not below `{}`",
                        d.label,
                        label(lo),
                        label(hi)
                    ),
                );
                ok = false;
                continue;
            }
            (lo, hi) => {
                let first = lo.map_or(0, |l| l + 1);
                let last = hi.unwrap_or(n);
                if last > first {
                    let inside: Vec<&str> = (first..last).map(|k| label(k).as_str()).collect();
                    diags.error(
                        d.span,
                        format!(
                            "domain {}'s band contains the boundary {}: a domain lies between two adjacent boundaries",
                            d.label,
                            inside.join(", ")
                        ),
                    );
                    ok = false;
                    continue;
                }
                first
            }
        };
        if let Some(other) = covered[interval] {
            diags.error(
                d.span,
                format!(
                    "domain {} overlaps domain {}: both cover the same velocity band",
                    d.label, model.domains[other].label
                ),
            );
            ok = false;
        } else {
            covered[interval] = Some(j);
        }
    }
    if !ok {
        return;
    }
    for (k, c) in covered.iter().enumerate() {
        if c.is_none() {
            let band = match k {
                0 => format!("v < {}", model.boundaries[0].label),
                k if k == n => format!("v > {}", model.boundaries[n - 1].label),
                k => format!(
                    "{} < v < {}",
                    model.boundaries[k - 1].label,
                    model.boundaries[k].label
                ),
            };
            let span = if k < n {
                model.boundaries[k].span
            } else {
                model_span
            };
            diags.error(span, format!("gap: no domain covers the band {band}"));
        }
    }
    if covered.iter().all(Option::is_some) {
        model.domains = covered
            .iter()
            .map(|c| model.domains[c.expect("all covered")].clone())
            .collect();
    }
}

fn check_affine(inst: &Lowered, dm: &Domain, j: usize, diags: &mut Diagnostics) {
    let mut g = inst.graph.clone();
    let law = inst.domains[j].law;
    if is_affine(&mut g, law) {
        return;
    }
    let term = offending_term(&mut g.clone(), &inst.names, &dm.law);
    diags.error(
        term.span(),
        format!(
            "the friction law of domain {} is not affine in `v`: the term `{}` is nonlinear in `v`; \
             split the band into affine pieces",
            dm.label,
            term.to_token_stream()
        ),
    );
}

fn is_affine(g: &mut Graph, id: crate::expr::Id) -> bool {
    if has_kink_in_v(g, id) {
        return false;
    }
    match g.diff(id, LAW_V).and_then(|d1| g.diff(d1, LAW_V)) {
        Ok(d2) => g.as_const(d2) == Some(0.0),
        Err(_) => false,
    }
}

/// Whether `id` takes `abs` (or `sign`) of a term that depends on `v`. The
/// second derivative of such a law folds to 0 (that of `sign` is 0), but the
/// law is not one affine function of `v`: the flows, built from its value and
/// slope at `v = 0`, would be wrong on the band.
fn has_kink_in_v(g: &Graph, id: crate::expr::Id) -> bool {
    let mut stack = vec![id];
    let mut seen = std::collections::HashSet::new();
    while let Some(i) = stack.pop() {
        if !seen.insert(i) {
            continue;
        }
        let node = g.node(i);
        if let crate::expr::Node::Abs(a) | crate::expr::Node::Sign(a) = node {
            if g.depends_on(a, LAW_V) {
                return true;
            }
        }
        stack.extend(crate::expr::children(node));
    }
    false
}

/// The smallest subterm of `e` that is not affine in `v`.
fn offending_term<'e>(
    g: &mut Graph,
    names: &HashMap<String, crate::expr::Id>,
    e: &'e Expr,
) -> &'e Expr {
    let v = g.var(LAW_V);
    let affine = |g: &mut Graph, sub: &Expr| {
        let id = lower(
            g,
            sub,
            &Scope {
                names,
                velocity: Some(crate::lower::Velocity::Node(v)),
                context: "",
            },
            &mut Diagnostics::new(),
        );
        is_affine(g, id)
    };
    let children: Vec<&Expr> = match e {
        Expr::Binary(b) => vec![&b.left, &b.right],
        Expr::Unary(u) => vec![&u.expr],
        Expr::Paren(p) => return offending_term(g, names, &p.expr),
        Expr::Call(c) => c.args.iter().collect(),
        _ => vec![],
    };
    for c in children {
        if !affine(g, c) {
            return offending_term(g, names, c);
        }
    }
    e
}
