//! A generated type implementing `stickslip::Model`: the unit struct and
//! the trait impl that dispatches to the free functions by index.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::expression::doc;
use super::flow::Functions;

/// `pub struct T;` and `impl Model for T`.
pub(super) fn model_impl(type_ident: &Ident, type_doc: &[String], f: &Functions) -> TokenStream {
    let type_doc = doc(type_doc);
    let nan2 = quote!([f64::NAN, f64::NAN]);
    let Functions {
        coefficients,
        flow,
        field,
        residual,
        mapping,
        stick_forces,
        static_bound,
        ..
    } = f;
    let base = friction_oscillator_impl(type_ident, quote!(oscillator(p)));
    quote! {
        #type_doc
        #[derive(Clone, Copy, Debug, Default)]
        pub struct #type_ident;

        #base

        impl #type_ident {
            /// The static description, [`Model::info`](::stickslip::Model::info) at every parameter set.
            pub const INFO: &'static ::stickslip::ModelInfo = &INFO;
        }

        impl ::stickslip::Model for #type_ident {
            #[inline]
            fn info(_: &Params) -> &'static ::stickslip::ModelInfo { &INFO }
            #[inline]
            fn coefficients(p: &Params, domain: usize) -> ::stickslip::Coefficients {
                match domain { #coefficients _ => ::stickslip::Coefficients::NAN }
            }
            #[inline]
            fn boundary_velocity(p: &Params, boundary: usize) -> f64 {
                boundary_velocities(p).get(boundary).copied().unwrap_or(f64::NAN)
            }
            #[inline]
            fn static_bound(p: &Params) -> ::core::option::Option<f64> { #static_bound }
            #[inline]
            fn flow(p: &Params, domain: usize, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2] {
                match domain { #flow _ => #nan2 }
            }
            #[inline]
            fn normal_field(p: &Params, domain: usize, x: f64, y: f64, phi: f64) -> [f64; 2] {
                match domain { #field _ => #nan2 }
            }
            #[inline]
            fn stick_forces(p: &Params, x: f64, phi: f64) -> ::core::option::Option<::stickslip::StickForces> { #stick_forces }
            #[inline]
            fn residual_at(p: &Params, mapping: usize, x0: f64, a: ::stickslip::Phase, x1: f64, b: ::stickslip::Phase) -> ::stickslip::nalgebra::Vector2<f64> {
                match mapping { #residual _ => ::stickslip::nalgebra::Vector2::repeat(f64::NAN) }
            }
            #[inline]
            fn mapping_at(p: &Params, mapping: usize, x0: f64, a: ::stickslip::Phase, x1: f64, b: ::stickslip::Phase) -> ::stickslip::MappingEval {
                match mapping { #mapping _ => ::stickslip::MappingEval::NAN }
            }
        }
    }
}

/// `impl FrictionOscillator`, the base trait of every generated model: its
/// `Params`, its identity (in `INFO`) and `oscillator`, whose body is given.
pub(super) fn friction_oscillator_impl(type_ident: &Ident, oscillator: TokenStream) -> TokenStream {
    quote! {
        impl ::stickslip::FrictionOscillator for #type_ident {
            type Params = Params;
            #[inline]
            fn identity(_: &Params) -> &'static ::stickslip::Identity { &INFO.identity }
            #[inline]
            fn oscillator(p: &Params) -> ::stickslip::Oscillator { #oscillator }
        }
    }
}
