//! Graph nodes → straight-line Rust.
//!
//! Each generated function is one walk over the nodes its outputs reach:
//! a node used more than once becomes `let tN = …;` (common-subexpression
//! elimination falls out of the hash-consed graph), a node used once is
//! written inline, and the pair `Ec, Es` of one `(d, w2, tau)` is computed by
//! one call whose form depends on the damping regime when it is known at
//! build time.

use std::collections::{BTreeMap, HashMap};

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use crate::expr::{Graph, Hom, Id, Node, Schedule};

/// Operator precedence of an emitted expression, lowest first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Prec {
    Add,
    Mul,
    Unary,
    Atom,
}

struct Writer<'g> {
    g: &'g Graph,
    params: &'g [Ident],
    vars: HashMap<u32, Ident>,
    /// Variables passed as a `::stickslip::Phase`: read as `a.phi()`, and
    /// their `cos`, `sin` as `a.cos()`, `a.sin()` (computed once by the caller).
    phases: HashMap<u32, Ident>,
    bound: HashMap<Id, Ident>,
}

pub(super) fn literal(x: f64) -> (TokenStream, Prec) {
    if x.is_nan() {
        (quote!(f64::NAN), Prec::Atom)
    } else if x == f64::INFINITY {
        (quote!(f64::INFINITY), Prec::Atom)
    } else if x == f64::NEG_INFINITY {
        (quote!(f64::NEG_INFINITY), Prec::Atom)
    } else if x < 0.0 {
        let l = syn::LitFloat::new(&format!("{:?}", -x), Span::call_site());
        (quote!(-#l), Prec::Unary)
    } else {
        let l = syn::LitFloat::new(&format!("{x:?}"), Span::call_site());
        (quote!(#l), Prec::Atom)
    }
}

fn paren(e: (TokenStream, Prec), min: Prec) -> TokenStream {
    let (t, p) = e;
    if p >= min {
        t
    } else {
        quote!((#t))
    }
}

impl Writer<'_> {
    fn expr(&self, id: Id) -> (TokenStream, Prec) {
        if let Some(name) = self.bound.get(&id) {
            return (quote!(#name), Prec::Atom);
        }
        let g = self.g;
        match g.node(id) {
            Node::Const(bits) => literal(f64::from_bits(bits)),
            Node::Param(k) => {
                // Parameters are only ever read as fields of `p`: no local of
                // the generated code can shadow them, nor they a local.
                let name = &self.params[k as usize];
                (quote!(p.#name), Prec::Atom)
            }
            Node::Var(k) => {
                if let Some(phase) = self.phases.get(&k) {
                    return (quote!(#phase.phi()), Prec::Atom);
                }
                let name = &self.vars[&k];
                (quote!(#name), Prec::Atom)
            }
            Node::Add(a, b) => {
                let l = paren(self.expr(a), Prec::Add);
                if let Node::Neg(nb) = g.node(b) {
                    if !self.bound.contains_key(&b) {
                        let r = paren(self.expr(nb), Prec::Mul);
                        return (quote!(#l - #r), Prec::Add);
                    }
                }
                let r = paren(self.expr(b), Prec::Mul);
                (quote!(#l + #r), Prec::Add)
            }
            Node::Mul(a, b) => {
                let l = paren(self.expr(a), Prec::Mul);
                if let Node::Recip(rb) = g.node(b) {
                    if !self.bound.contains_key(&b) {
                        let r = paren(self.expr(rb), Prec::Unary);
                        return (quote!(#l / #r), Prec::Mul);
                    }
                }
                let r = paren(self.expr(b), Prec::Unary);
                (quote!(#l * #r), Prec::Mul)
            }
            Node::Neg(a) => {
                let a = paren(self.expr(a), Prec::Unary);
                (quote!(-#a), Prec::Unary)
            }
            Node::Recip(a) => {
                let a = paren(self.expr(a), Prec::Unary);
                (quote!(1.0 / #a), Prec::Mul)
            }
            Node::Powi(a, n) => {
                let a = paren(self.expr(a), Prec::Atom);
                let n = proc_macro2::Literal::i32_unsuffixed(n);
                (quote!(#a.powi(#n)), Prec::Atom)
            }
            Node::Sqrt(a) => self.method(a, "sqrt"),
            Node::Exp(a) => self.method(a, "exp"),
            Node::Ln(a) => self.method(a, "ln"),
            Node::Sin(a) => self.trig(a, "sin"),
            Node::Cos(a) => self.trig(a, "cos"),
            Node::Abs(a) => self.method(a, "abs"),
            Node::Sign(a) => self.method(a, "signum"),
            Node::Hom(..) => unreachable!("homogeneous pairs are always bound"),
        }
    }

    /// `sin`/`cos` of `a`: the caller's value when `a` is a phase variable.
    fn trig(&self, a: Id, name: &str) -> (TokenStream, Prec) {
        if let Node::Var(k) = self.g.node(a) {
            if let Some(phase) = self.phases.get(&k) {
                let m = format_ident!("{}", name);
                return (quote!(#phase.#m()), Prec::Atom);
            }
        }
        self.method(a, name)
    }

    fn method(&self, a: Id, name: &str) -> (TokenStream, Prec) {
        let a = paren(self.expr(a), Prec::Atom);
        let m = format_ident!("{}", name);
        (quote!(#a.#m()), Prec::Atom)
    }

    /// The call computing `(Ec, Es)` for `(d, w2, tau)`, specialized when the
    /// regime is known at build time.
    fn hom_call(&self, d: Id, c: Id, tau: Id) -> TokenStream {
        let dt = self.expr(d).0;
        let tt = self.expr(tau).0;
        match (self.g.as_const(d), self.g.as_const(c)) {
            (Some(dv), Some(cv)) if dv * dv < cv => {
                let (om, _) = literal((cv - dv * dv).sqrt());
                quote!(::stickslip::model::homogeneous::underdamped(#dt, #om, #tt))
            }
            (Some(dv), Some(cv)) if dv * dv > cv => {
                let ct = self.expr(c).0;
                quote!(::stickslip::model::homogeneous::overdamped(#dt, #ct, #tt))
            }
            (Some(_), Some(_)) => quote!(::stickslip::model::homogeneous::critical(#dt, #tt)),
            _ => {
                let ct = self.expr(c).0;
                quote!(::stickslip::model::homogeneous::general(#dt, #ct, #tt))
            }
        }
    }
}

/// Straight-line code computing `outputs`: the statements and one
/// expression per output.
pub(super) fn straight_line(
    g: &Graph,
    params: &[Ident],
    vars: &[(u32, &str)],
    outputs: &[Id],
) -> (TokenStream, Vec<TokenStream>) {
    straight_line_with_phases(g, params, vars, &[], outputs)
}

/// [`straight_line`] where the variables `phases` are `::stickslip::Phase`
/// arguments: their `cos` and `sin` come with them instead of being computed.
pub(super) fn straight_line_with_phases(
    g: &Graph,
    params: &[Ident],
    vars: &[(u32, &str)],
    phases: &[(u32, &str)],
    outputs: &[Id],
) -> (TokenStream, Vec<TokenStream>) {
    let schedule = Schedule::new(g, outputs);
    let mut w = Writer {
        g,
        params,
        vars: vars
            .iter()
            .map(|(k, name)| (*k, format_ident!("{}", name)))
            .collect(),
        phases: phases
            .iter()
            .map(|(k, name)| (*k, format_ident!("{}", name)))
            .collect(),
        bound: HashMap::new(),
    };
    let mut stmts = TokenStream::new();
    let reads_params = schedule
        .nodes()
        .any(|id| matches!(g.node(id), Node::Param(_)));
    if !reads_params {
        // Every parameter this function reads was folded at build time.
        stmts.extend(quote!(let _ = p;));
    }
    let mut homs: BTreeMap<(Id, Id, Id), (Ident, Ident)> = BTreeMap::new();
    let mut counter = 0usize;
    for id in schedule.nodes() {
        if !schedule.is_bound(g, id) {
            continue;
        }
        match g.node(id) {
            Node::Hom(kind, d, c, tau) => {
                let key = (d, c, tau);
                if let std::collections::btree_map::Entry::Vacant(slot) = homs.entry(key) {
                    let (ec, es) = (
                        format_ident!("ec{}", counter),
                        format_ident!("es{}", counter),
                    );
                    counter += 1;
                    let call = w.hom_call(d, c, tau);
                    stmts.extend(quote!(let (#ec, #es) = #call;));
                    slot.insert((ec, es));
                }
                let (ec, es) = &homs[&key];
                let name = match kind {
                    Hom::Ec => ec.clone(),
                    Hom::Es => es.clone(),
                };
                w.bound.insert(id, name);
            }
            _ => {
                let e = w.expr(id).0;
                let name = format_ident!("t{}", counter);
                counter += 1;
                stmts.extend(quote!(let #name = #e;));
                w.bound.insert(id, name);
            }
        }
    }
    let outs = outputs.iter().map(|&o| w.expr(o).0).collect();
    (stmts, outs)
}

pub(super) fn doc(lines: &[String]) -> TokenStream {
    let mut t = TokenStream::new();
    for l in lines {
        let l = format!(" {l}");
        t.extend(quote!(#[doc = #l]));
    }
    t
}

pub(super) fn doc1(s: &str) -> TokenStream {
    let s = format!(" {s}");
    quote!(#[doc = #s])
}
