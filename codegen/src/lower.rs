//! Model expressions (`syn::Expr`) → nodes of the expression graph.
//!
//! The language of expressions: numbers, names of parameters and derived
//! quantities, `v` inside a friction law, `+ - * /`, unary `-`, parentheses,
//! and the functions `exp ln sqrt sin cos abs` and `powi(x, n)`.

use std::collections::HashMap;

use quote::ToTokens;
use syn::spanned::Spanned;
use syn::{BinOp, Expr, Lit, UnOp};

use crate::diagnostic::Diagnostics;
use crate::expr::{Graph, Id};

/// What names mean while lowering.
pub struct Scope<'a> {
    /// Names of parameters and derived quantities.
    pub names: &'a HashMap<String, Id>,
    /// What `v` stands for, inside a friction law.
    pub velocity: Option<Velocity>,
    /// What the expression is, for messages ("a parameter default").
    pub context: &'a str,
}

/// What `v` stands for while lowering a friction law.
#[derive(Clone, Copy, Debug)]
pub enum Velocity {
    /// A node (usually the variable [`crate::lowered::LAW_V`]).
    Node(Id),
    /// `base + offset` (`base - |offset|` for a negative one), made where `v`
    /// is met: the law evaluated at a shifted velocity such as a breakpoint
    /// `V ± u` of a piecewise-linear model.
    Offset {
        /// The node shifted (the belt speed).
        base: Id,
        /// The shift, a number.
        offset: f64,
    },
}

impl Velocity {
    /// The node `v` stands for, made in `graph` if it is not there yet.
    pub fn node(self, graph: &mut Graph) -> Id {
        match self {
            Velocity::Node(id) => id,
            Velocity::Offset { base, offset } if offset < 0.0 => {
                let u = graph.constant(-offset);
                graph.sub(base, u)
            }
            Velocity::Offset { base, offset } => {
                let u = graph.constant(offset);
                graph.add(base, u)
            }
        }
    }
}

/// Lower `expr` into `graph`. Errors go to `diags`; the result is then a
/// placeholder zero so that checking can go on.
///
/// Every literal and every operation is checked where it is made: a value
/// that is not finite (with the parameters at the graph's
/// [`Graph::set_param_values`], usually the defaults) while its operands are
/// finite is reported at that subexpression, with the values of the names in
/// it. A subnormal number is fine as long as what is made of it is finite.
pub fn lower(graph: &mut Graph, expr: &Expr, scope: &Scope, diags: &mut Diagnostics) -> Id {
    if let Some(attr) = expr_attrs(expr).first() {
        diags.error(
            attr.pound_token.span,
            format!(
                "attributes are not allowed inside an expression (in {}); only doc comments, and only on items",
                scope.context
            ),
        );
        return graph.constant(0.0);
    }
    let mut operands = Vec::new();
    let id = lower_node(graph, expr, scope, diags, &mut operands);
    let value = graph.value(id);
    let unknown = matches!(
        graph.node(id),
        crate::expr::Node::Var(_) | crate::expr::Node::Param(_)
    );
    if !unknown && !value.is_finite() && operands.iter().all(|&o| graph.value(o).is_finite()) {
        diags.error(expr.span(), not_finite(graph, expr, value, scope));
    }
    id
}

/// The message for a subexpression that is not a finite number.
fn not_finite(graph: &Graph, expr: &Expr, value: f64, scope: &Scope) -> String {
    let text = short(&expr.to_token_stream().to_string());
    if let Expr::Lit(_) = expr {
        return format!(
            "the number `{text}` in {} is out of range: it would be {value} as an f64",
            scope.context
        );
    }
    let mut names: Vec<String> = Vec::new();
    for tt in expr.to_token_stream() {
        collect_names(tt, &mut names);
    }
    let with: Vec<String> = names
        .iter()
        .filter_map(|n| {
            let id = scope.names.get(n)?;
            let x = graph.value(*id);
            (!x.is_nan() || graph.as_const(*id).is_some())
                .then(|| format!("{n} = {}", crate::diagnostic::num(x)))
        })
        .collect();
    let at = if scope.names.is_empty() {
        String::new()
    } else if with.is_empty() {
        " at the defaults".to_string()
    } else {
        format!(" at the defaults, with {}", with.join(", "))
    };
    format!(
        "{}: `{text}` evaluates to {value}{at}",
        capitalize_context(scope.context)
    )
}

fn capitalize_context(c: &str) -> String {
    if c.is_empty() {
        return "this expression".to_string();
    }
    c.to_string()
}

fn short(text: &str) -> String {
    if text.chars().count() <= 60 {
        return text.to_string();
    }
    let head: String = text.chars().take(57).collect();
    format!("{head}...")
}

fn collect_names(tt: proc_macro2::TokenTree, out: &mut Vec<String>) {
    match tt {
        proc_macro2::TokenTree::Ident(i) => {
            let n = i.to_string();
            if !out.contains(&n) {
                out.push(n);
            }
        }
        proc_macro2::TokenTree::Group(g) => {
            for t in g.stream() {
                collect_names(t, out);
            }
        }
        _ => {}
    }
}

fn expr_attrs(expr: &Expr) -> &[syn::Attribute] {
    match expr {
        Expr::Lit(e) => &e.attrs,
        Expr::Path(e) => &e.attrs,
        Expr::Paren(e) => &e.attrs,
        Expr::Group(e) => &e.attrs,
        Expr::Unary(e) => &e.attrs,
        Expr::Binary(e) => &e.attrs,
        Expr::Call(e) => &e.attrs,
        _ => &[],
    }
}

/// The node for `expr`; the nodes of its operands go to `operands`.
fn lower_node(
    graph: &mut Graph,
    expr: &Expr,
    scope: &Scope,
    diags: &mut Diagnostics,
    operands: &mut Vec<Id>,
) -> Id {
    match expr {
        Expr::Lit(lit) => match &lit.lit {
            Lit::Float(f) => match f.base10_parse::<f64>() {
                Ok(x) => graph.constant(x),
                Err(e) => fail(graph, diags, e),
            },
            Lit::Int(i) => match i.base10_parse::<f64>() {
                Ok(x) => graph.constant(x),
                Err(e) => fail(graph, diags, e),
            },
            other => {
                diags.error(
                    other.span(),
                    format!("expected a number in {}", scope.context),
                );
                graph.constant(0.0)
            }
        },
        Expr::Path(p) => {
            let Some(ident) = p.path.get_ident() else {
                diags.error(p.span(), "expected a name, not a path");
                return graph.constant(0.0);
            };
            let name = ident.to_string();
            if name == "v" {
                if let Some(v) = scope.velocity {
                    return v.node(graph);
                }
                diags.error(
                    ident.span(),
                    format!(
                        "`v` (the velocity) is only defined inside a friction law, not in {}",
                        scope.context
                    ),
                );
                return graph.constant(0.0);
            }
            match scope.names.get(&name) {
                Some(&id) => id,
                None => {
                    let what = if scope.names.is_empty() {
                        format!(
                            "{} must be a number; it cannot refer to `{}`",
                            scope.context, name
                        )
                    } else {
                        format!("unknown name `{}` in {}", name, scope.context)
                    };
                    diags.error(ident.span(), what);
                    graph.constant(0.0)
                }
            }
        }
        Expr::Paren(p) => operand(graph, &p.expr, scope, diags, operands),
        Expr::Group(g) => operand(graph, &g.expr, scope, diags, operands),
        Expr::Unary(u) => match u.op {
            UnOp::Neg(_) => {
                let a = operand(graph, &u.expr, scope, diags, operands);
                graph.neg(a)
            }
            _ => {
                diags.error(u.op.span(), "only unary `-` is allowed");
                graph.constant(0.0)
            }
        },
        Expr::Binary(b) => {
            let l = operand(graph, &b.left, scope, diags, operands);
            let r = operand(graph, &b.right, scope, diags, operands);
            match b.op {
                BinOp::Add(_) => graph.add(l, r),
                BinOp::Sub(_) => graph.sub(l, r),
                BinOp::Mul(_) => graph.mul(l, r),
                BinOp::Div(_) => {
                    if graph.as_const(r) == Some(0.0) {
                        diags.error(
                            b.right.span(),
                            format!(
                                "division by zero: `{}` is the constant 0 in {}",
                                b.right.to_token_stream(),
                                scope.context
                            ),
                        );
                        return graph.constant(0.0);
                    }
                    graph.div(l, r)
                }
                _ => {
                    diags.error(
                        b.op.span(),
                        format!(
                            "operator `{}` is not allowed; use + - * / and powi(x, n)",
                            b.op.to_token_stream()
                        ),
                    );
                    graph.constant(0.0)
                }
            }
        }
        Expr::Call(call) => {
            let name = match &*call.func {
                Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                _ => None,
            };
            let Some(name) = name else {
                diags.error(call.func.span(), "expected a function name");
                return graph.constant(0.0);
            };
            let args: Vec<&Expr> = call.args.iter().collect();
            let unary: Option<fn(&mut Graph, Id) -> Id> = match name.as_str() {
                "exp" => Some(Graph::exp),
                "ln" => Some(Graph::ln),
                "sqrt" => Some(Graph::sqrt),
                "sin" => Some(Graph::sin),
                "cos" => Some(Graph::cos),
                "abs" => Some(Graph::abs),
                "sign" => Some(Graph::sign),
                _ => None,
            };
            if let Some(f) = unary {
                if args.len() != 1 {
                    diags.error(call.span(), format!("`{name}` takes one argument"));
                    return graph.constant(0.0);
                }
                let a = operand(graph, args[0], scope, diags, operands);
                return f(graph, a);
            }
            if name == "powi" {
                // The exponent as written, in i64 (or `None` when it is not
                // an integer literal); beyond i32 it is reported as such.
                let wide = match args.get(1) {
                    Some(Expr::Lit(syn::ExprLit {
                        lit: Lit::Int(i), ..
                    })) => Some(i.base10_parse::<i64>().map_err(|_| i.span())),
                    Some(Expr::Unary(syn::ExprUnary {
                        op: UnOp::Neg(_),
                        expr,
                        ..
                    })) => match &**expr {
                        Expr::Lit(syn::ExprLit {
                            lit: Lit::Int(i), ..
                        }) => Some(i.base10_parse::<i64>().map(|n| -n).map_err(|_| i.span())),
                        _ => None,
                    },
                    _ => None,
                };
                let n = match wide {
                    Some(Ok(n)) => match i32::try_from(n) {
                        Ok(n) => Some(n),
                        Err(_) => {
                            diags.error(
                                args[1].span(),
                                format!(
                                    "the exponent {n} of `powi` is out of range: it must fit in an i32 (|n| <= {})",
                                    i32::MAX
                                ),
                            );
                            return graph.constant(0.0);
                        }
                    },
                    Some(Err(span)) => {
                        diags.error(
                            span,
                            "the exponent of `powi` is out of range: it must fit in an i32",
                        );
                        return graph.constant(0.0);
                    }
                    None => None,
                };
                match (args.len(), n) {
                    (2, Some(n)) => {
                        let a = operand(graph, args[0], scope, diags, operands);
                        if n < 0 && graph.as_const(a) == Some(0.0) {
                            diags.error(
                                args[0].span(),
                                format!(
                                    "division by zero: negative power of 0 in {}",
                                    scope.context
                                ),
                            );
                            return graph.constant(0.0);
                        }
                        return graph.powi(a, n);
                    }
                    _ => {
                        diags.error(
                            call.span(),
                            "`powi(x, n)` takes an expression and an integer literal",
                        );
                        return graph.constant(0.0);
                    }
                }
            }
            diags.error(
                call.func.span(),
                format!("unknown function `{name}`; available: exp, ln, sqrt, sin, cos, abs, sign, powi"),
            );
            graph.constant(0.0)
        }
        other => {
            diags.error(
                other.span(),
                format!("this expression is not allowed in {}: use numbers, names, + - * /, and functions", scope.context),
            );
            graph.constant(0.0)
        }
    }
}

fn operand(
    graph: &mut Graph,
    expr: &Expr,
    scope: &Scope,
    diags: &mut Diagnostics,
    operands: &mut Vec<Id>,
) -> Id {
    let id = lower(graph, expr, scope, diags);
    operands.push(id);
    id
}

fn fail(graph: &mut Graph, diags: &mut Diagnostics, e: syn::Error) -> Id {
    diags.push_syn(e);
    graph.constant(0.0)
}
