//! `stickslip::model!`: a thin proc-macro over `stickslip-codegen`, whose
//! [`expand`](stickslip_codegen::expand) module does the work.
//!
//! * `model! { model NAME { ... } }` — an inline model; errors point at its tokens.
//! * `model!(file = "models/NAME.ssm")` — a model file, relative to the
//!   invoking crate's `Cargo.toml`; errors point at the path literal and name
//!   `file:line:col` in the message.
//!
//! Both expand to `pub mod NAME { ... }`, the same module `build.rs` writes.
#![forbid(unsafe_code)]

use proc_macro::TokenStream;

/// Generate a model: `model!(file = "models/x.ssm")` or `model! { model x { ... } }`.
#[proc_macro]
pub fn model(input: TokenStream) -> TokenStream {
    stickslip_codegen::invocation::model(input.into()).into()
}

/// The generated source text of a model, as a string literal (for tests
/// comparing the macro path with the `build.rs` path).
#[doc(hidden)]
#[proc_macro]
pub fn model_source(input: TokenStream) -> TokenStream {
    stickslip_codegen::invocation::model_source(input.into()).into()
}
