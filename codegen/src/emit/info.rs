//! The static `INFO` table of a generated type: its parameters, boundaries,
//! domains, mappings and structures, as the run time and the CLI read them.

use proc_macro2::TokenStream;
use quote::quote;

use super::expression::doc1;
use super::params::param_infos;
use crate::equations::{Equations, Regime};
use crate::expand::Route;
use crate::model::MappingKind;

/// `pub static INFO: ModelInfo = …;` of one instance.
pub(super) fn info(e: &Equations) -> TokenStream {
    let inst = &e.instance;
    let (params, free) = param_infos(&inst.params, &inst.free);
    let boundaries = inst.boundaries.iter().map(|b| {
        let (label, number, stick) = (&b.label, b.number, b.stick);
        let d = b.docs.join(" ");
        quote!(::stickslip::BoundaryInfo { label: #label, number: #number, stick: #stick, doc: #d },)
    });
    let domains = inst.domains.iter().zip(&e.domains).map(|(d, eq)| {
        let label = d.label;
        let lo = option(d.lower);
        let hi = option(d.upper);
        let regime = match eq.regime {
            Some(Regime::Underdamped) => quote!(Some(::stickslip::Regime::Underdamped)),
            Some(Regime::Overdamped) => quote!(Some(::stickslip::Regime::Overdamped)),
            Some(Regime::Critical) => quote!(Some(::stickslip::Regime::Critical)),
            None => quote!(None),
        };
        let docs = d.docs.join(" ");
        quote!(::stickslip::DomainInfo { label: #label, lower: #lo, upper: #hi, fixed_regime: #regime, doc: #docs },)
    });
    let mappings = inst.mappings.iter().map(|m| {
        let name = &m.name;
        let (from, to) = (m.from, m.to);
        let (dom, exit) = match m.route {
            Route::Flow { domain } => (quote!(Some(#domain)), quote!(None)),
            Route::Stick { above: true } => (quote!(None), quote!(Some(::stickslip::Side::Above))),
            Route::Stick { above: false } => (quote!(None), quote!(Some(::stickslip::Side::Below))),
        };
        let kind = match m.kind {
            MappingKind::Local => quote!(::stickslip::MappingKind::Local),
            MappingKind::Global => quote!(::stickslip::MappingKind::Global),
            MappingKind::Stick => quote!(::stickslip::MappingKind::Stick),
        };
        quote!(::stickslip::MappingInfo { name: #name, domain: #dom, from: #from, to: #to, kind: #kind, exit: #exit },)
    });
    let (display, model, docs) = (&inst.display_name, &inst.model_name, &inst.model_docs);
    let scene = match &inst.scene_name {
        Some(n) => quote!(Some(#n)),
        None => quote!(None),
    };
    let structures = &inst.structures;
    let info_doc = doc1(&format!("Static description of `{display}`."));
    quote! {
        #info_doc
        pub static INFO: ::stickslip::ModelInfo = ::stickslip::ModelInfo {
            identity: ::stickslip::Identity {
                name: #display,
                model: #model,
                scene: #scene,
                doc: #docs,
                params: &[#(#params)*],
                free: &[#(#free)*],
                source_hash: None,
            },
            boundaries: &[#(#boundaries)*],
            domains: &[#(#domains)*],
            mappings: &[#(#mappings)*],
            structures: &[#(#structures),*],
        };
    }
}

fn option(k: Option<usize>) -> TokenStream {
    match k {
        Some(k) => quote!(Some(#k)),
        None => quote!(None),
    }
}
