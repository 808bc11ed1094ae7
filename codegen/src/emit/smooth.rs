//! The type of a model with a smooth law: its `Params`, a static `INFO`
//! (no boundaries: the law is not piecewise) and a type implementing
//! `SmoothModel` whose `kinetic` gives the law and its exact slope.

use proc_macro2::TokenStream;
use quote::quote;

use super::expression::{doc, doc1, literal, straight_line};
use super::model_impl::friction_oscillator_impl;
use super::params::{free_idents, param_infos, params_items, smooth_check_fn};
use crate::equations::SmoothEquations;
use crate::lowered::LAW_V;

/// Every item of the smooth model's own type.
pub(super) fn smooth_items(e: &SmoothEquations) -> TokenStream {
    let s = &e.smooth;
    let free: Vec<usize> = (0..s.params.len()).collect();
    let pnames = free_idents(&s.params, &free);
    let (param_infos, free_idx) = param_infos(&s.params, &free);
    let g = &s.lowered.graph;
    let (kstmts, kouts) = straight_line(g, &pnames, &[(LAW_V, "v")], &e.kinetic);
    let (kf, kd) = (&kouts[0], &kouts[1]);
    let (ostmts, oouts) = straight_line(g, &pnames, &[], &e.oscillator);
    let (om, od, oc, oa, ow) = (&oouts[0], &oouts[1], &oouts[2], &oouts[3], &oouts[4]);
    // Each function computes only what it returns.
    let (bstmts, bouts) = straight_line(g, &pnames, &[], &[s.law.belt]);
    let (sstmts, souts) = straight_line(g, &pnames, &[], &[s.law.stick]);
    let (belt, stick) = (&bouts[0], &souts[0]);
    let (name, type_ident, docs, law_text) = (&s.name, &s.type_ident, &s.docs, &s.law_text);
    let (range_lit, _) = literal(s.range);
    let type_doc = doc(&s.type_doc);
    let params_doc = doc1("Run-time parameters of the smooth model.");
    let check = smooth_check_fn(g, &pnames, &e.conditions);
    let params_items = params_items(&s.params, &free, &params_doc, &check);
    let base = friction_oscillator_impl(
        type_ident,
        quote! {
            #ostmts
            ::stickslip::Oscillator { mass: #om, damping: #od, stiffness: #oc, amplitude: #oa, frequency: #ow }
        },
    );
    quote! {
        #params_items

        /// Static description of the model and its law (no boundaries: the law
        /// is smooth; see the `pieces` scenes).
        pub static INFO: ::stickslip::model::smooth::SmoothInfo = ::stickslip::model::smooth::SmoothInfo {
            identity: ::stickslip::Identity {
                name: #name,
                model: #name,
                scene: None,
                doc: #docs,
                params: &[#(#param_infos)*],
                free: &[#(#free_idx)*],
                source_hash: None,
            },
            law: #law_text,
            range: #range_lit,
        };

        #type_doc
        #[derive(Clone, Copy, Debug, Default)]
        pub struct #type_ident;

        #base

        impl #type_ident {
            /// The static description, [`SmoothModel::info`](::stickslip::SmoothModel::info) at every parameter set.
            pub const INFO: &'static ::stickslip::model::smooth::SmoothInfo = &INFO;
        }

        impl ::stickslip::model::smooth::SmoothModel for #type_ident {
            #[inline]
            fn info(_: &Params) -> &'static ::stickslip::model::smooth::SmoothInfo { &INFO }
            #[inline]
            fn belt(p: &Params) -> f64 {
                #bstmts
                #belt
            }
            #[inline]
            fn static_bound(p: &Params) -> f64 {
                #sstmts
                #stick
            }
            /// The law and its exact derivative in `v`.
            #[inline]
            fn kinetic(p: &Params, v: f64) -> [f64; 2] {
                #kstmts
                [#kf, #kd]
            }
        }
    }
}
