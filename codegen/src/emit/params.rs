//! The `Params` struct of a generated type and its `ParamSet` impl: field
//! access by index, and `check`, which tests the values and the model's
//! conditions at run time.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::expression::{doc, literal, straight_line};
use crate::equations::Conditions;
use crate::expand::ParamDecl;
use crate::expr::{Graph, Id};
use crate::parse::BoundOp;

/// The free parameters' field names, in order (`Param(k)` is the `k`-th).
pub(super) fn free_idents(params: &[ParamDecl], free: &[usize]) -> Vec<Ident> {
    free.iter().map(|&i| params[i].ident.clone()).collect()
}

/// `Params`, its `Default`, and `ParamSet` with the given `check` method.
pub(super) fn params_items(
    params: &[ParamDecl],
    free: &[usize],
    params_doc: &TokenStream,
    check_fn: &TokenStream,
) -> TokenStream {
    let free: Vec<&ParamDecl> = free.iter().map(|&i| &params[i]).collect();
    let fields = free.iter().map(|p| {
        let name = &p.ident;
        let mut lines = p.docs.clone();
        lines.push(format!("Default: `{}`.", p.default));
        let d = doc(&lines);
        quote!(#d pub #name: f64,)
    });
    let defaults = free.iter().map(|p| {
        let name = &p.ident;
        let (v, _) = literal(p.default);
        quote!(#name: #v,)
    });
    let names_lit = free.iter().map(|p| &p.name);
    let get_arms = free.iter().enumerate().map(|(k, p)| {
        let name = &p.ident;
        quote!(#k => self.#name,)
    });
    let set_arms = free.iter().enumerate().map(|(k, p)| {
        let name = &p.ident;
        quote!(#k => self.#name = value,)
    });
    quote! {
        #params_doc
        #[derive(Clone, Copy, Debug, PartialEq)]
        #[allow(non_snake_case)]
        pub struct Params { #(#fields)* }

        impl ::core::default::Default for Params {
            fn default() -> Self { Self { #(#defaults)* } }
        }

        impl Params {
            /// Names of the fields, in order.
            pub const NAMES: &'static [&'static str] = &[#(#names_lit),*];
            /// Index of a field by name.
            pub fn index_of(name: &str) -> ::core::option::Option<usize> {
                Self::NAMES.iter().position(|n| *n == name)
            }
            /// The defaults with the given values set, checked; `info` names the model in errors.
            pub fn from_pairs(
                info: &::stickslip::Identity,
                pairs: &[(&str, f64)],
            ) -> ::core::result::Result<Self, ::stickslip::ParamError> {
                ::stickslip::ParamSet::with_pairs(Self::default(), info, pairs)
            }
        }

        impl ::stickslip::ParamSet for Params {
            fn names(&self) -> &'static [&'static str] { Self::NAMES }
            fn get(&self, index: usize) -> f64 {
                match index { #(#get_arms)* _ => f64::NAN }
            }
            fn set(&mut self, index: usize, value: f64) {
                match index { #(#set_arms)* _ => {} }
            }
            #check_fn
        }
    }
}

/// `ParamInfo` of every parameter, and the indices of the free ones.
pub(super) fn param_infos(
    params: &[ParamDecl],
    free: &[usize],
) -> (Vec<TokenStream>, Vec<TokenStream>) {
    let infos = params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let name = &p.name;
            let (def, _) = literal(p.default);
            let bounds = p.bounds.iter().map(|(op, b)| {
                let op = bound_tokens(*op);
                let (b, _) = literal(*b);
                quote!((#op, #b))
            });
            let docs = p.docs.join(" ");
            let is_free = free.contains(&i);
            quote!(::stickslip::ParamInfo { name: #name, default: #def, bounds: &[#(#bounds),*], doc: #docs, free: #is_free },)
        })
        .collect();
    let free_idx = free.iter().map(|&i| quote!(#i,)).collect();
    (infos, free_idx)
}

fn bound_tokens(op: BoundOp) -> TokenStream {
    match op {
        BoundOp::Gt => quote!(::stickslip::Bound::Gt),
        BoundOp::Ge => quote!(::stickslip::Bound::Ge),
        BoundOp::Lt => quote!(::stickslip::Bound::Lt),
        BoundOp::Le => quote!(::stickslip::Bound::Le),
    }
}

/// `ParamSet::check` of a model: the values against their bounds, then
/// mass, stiffness, frequency, boundary velocities and the stick condition.
pub(super) fn check_fn(g: &Graph, pnames: &[Ident], c: &Conditions) -> TokenStream {
    let mut outputs = vec![c.mass, c.stiffness, c.frequency];
    outputs.extend(&c.velocities);
    outputs.extend(c.stick.iter().flatten());
    let (stmts, outs) = straight_line(g, pnames, &[], &outputs);
    let (mass, stiffness, frequency) = (&outs[0], &outs[1], &outs[2]);
    let n = c.velocities.len();
    let velocities = &outs[3..3 + n];
    let stick = match &outs[3 + n..] {
        [a, b, c] => quote!(Some((#a, #b, #c))),
        _ => quote!(None),
    };
    check_tokens(
        stmts,
        [mass, stiffness, frequency],
        quote!(INFO.boundaries),
        quote!(&[#(#velocities),*]),
        stick,
    )
}

/// `ParamSet::check` of a smooth model: its conditions are `[m, c, W, as,
/// f(V + eps), f(V - eps)]`.
pub(super) fn smooth_check_fn(g: &Graph, pnames: &[Ident], conditions: &[Id; 6]) -> TokenStream {
    let (stmts, outs) = straight_line(g, pnames, &[], conditions);
    let (st, fa, fb) = (&outs[3], &outs[4], &outs[5]);
    check_tokens(
        stmts,
        [&outs[0], &outs[1], &outs[2]],
        quote!(&[]),
        quote!(&[]),
        quote!(Some((#st, #fa, #fb))),
    )
}

fn check_tokens(
    stmts: TokenStream,
    [mass, stiffness, frequency]: [&TokenStream; 3],
    boundaries: TokenStream,
    velocities: TokenStream,
    stick: TokenStream,
) -> TokenStream {
    quote! {
        fn check(&self) -> ::core::result::Result<(), ::stickslip::ParamError> {
            let p = self;
            ::stickslip::model::param::check_values(self, &INFO.identity)?;
            #stmts
            ::stickslip::model::param::check_conditions(#boundaries, ::stickslip::model::param::Conditions {
                mass: #mass,
                stiffness: #stiffness,
                frequency: #frequency,
                velocities: #velocities,
                stick: #stick,
            })
        }
    }
}
