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
    /// The node standing for `v`, inside a friction law.
    pub velocity: Option<Id>,
    /// What the expression is, for messages ("a parameter default").
    pub context: &'a str,
}

/// Lower `expr` into `graph`. Errors go to `diags`; the result is then a
/// placeholder zero so that checking can go on.
pub fn lower(graph: &mut Graph, expr: &Expr, scope: &Scope, diags: &mut Diagnostics) -> Id {
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
                    return v;
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
        Expr::Paren(p) => lower(graph, &p.expr, scope, diags),
        Expr::Group(g) => lower(graph, &g.expr, scope, diags),
        Expr::Unary(u) => match u.op {
            UnOp::Neg(_) => {
                let a = lower(graph, &u.expr, scope, diags);
                graph.neg(a)
            }
            _ => {
                diags.error(u.op.span(), "only unary `-` is allowed");
                graph.constant(0.0)
            }
        },
        Expr::Binary(b) => {
            let l = lower(graph, &b.left, scope, diags);
            let r = lower(graph, &b.right, scope, diags);
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
                let a = lower(graph, args[0], scope, diags);
                return f(graph, a);
            }
            if name == "powi" {
                let n = match args.get(1) {
                    Some(Expr::Lit(syn::ExprLit {
                        lit: Lit::Int(i), ..
                    })) => i.base10_parse::<i32>().ok(),
                    Some(Expr::Unary(syn::ExprUnary {
                        op: UnOp::Neg(_),
                        expr,
                        ..
                    })) => match &**expr {
                        Expr::Lit(syn::ExprLit {
                            lit: Lit::Int(i), ..
                        }) => i.base10_parse::<i32>().ok().map(|n| -n),
                        _ => None,
                    },
                    _ => None,
                };
                match (args.len(), n) {
                    (2, Some(n)) => {
                        let a = lower(graph, args[0], scope, diags);
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

fn fail(graph: &mut Graph, diags: &mut Diagnostics, e: syn::Error) -> Id {
    diags.push_syn(e);
    graph.constant(0.0)
}
