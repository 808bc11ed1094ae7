//! `stickslip::model!`: a thin proc-macro over `stickslip-codegen`.
//!
//! * `model! { model NAME { ... } }` — an inline model; errors point at its tokens.
//! * `model!(file = "models/NAME.ssm")` — a model file, relative to the
//!   invoking crate's `Cargo.toml`; errors point at the path literal and name
//!   `file:line:col` in the message.
//!
//! Both expand to `pub mod NAME { ... }`, the same code `build.rs` writes.
#![forbid(unsafe_code)]

use proc_macro::TokenStream;
use proc_macro2::{Span, TokenStream as Tokens};
use quote::{format_ident, quote};
use stickslip_codegen::{GeneratedFile, Options};
use syn::parse::{Parse, ParseStream};
use syn::{LitStr, Token};

enum Input {
    File(LitStr),
    Inline(Tokens),
}

impl Parse for Input {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let fork = input.fork();
        if fork.parse::<syn::Ident>().is_ok_and(|i| i == "file") && fork.peek(Token![=]) {
            input.parse::<syn::Ident>()?;
            input.parse::<Token![=]>()?;
            let lit: LitStr = input.parse()?;
            let _ = input.parse::<Option<Token![,]>>()?;
            return Ok(Input::File(lit));
        }
        Ok(Input::Inline(input.parse()?))
    }
}

/// Generate the code of a model; returns it with the file to track, if any.
fn generate(input: Input) -> syn::Result<(GeneratedFile, Option<String>)> {
    match input {
        Input::Inline(tokens) => {
            let options = Options {
                origin: "stickslip::model! (inline)".into(),
            };
            stickslip_codegen::generate(tokens, &options)
                .map(|g| (g, None))
                .map_err(|d| d.to_syn_error())
        }
        Input::File(lit) => {
            let dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
            let path = std::path::Path::new(&dir).join(lit.value());
            if let Err(e) = std::fs::metadata(&path) {
                return Err(syn::Error::new(
                    lit.span(),
                    format!("cannot read model file {}: {e}", path.display()),
                ));
            }
            // Tokens of a file read here have no spans in the caller's source:
            // use proc-macro2's own tokenizer for line/column information,
            // and report at the path literal. `generate_file` reads the bytes
            // (a non-UTF-8 byte is located) and checks the file's name.
            proc_macro2::fallback::force();
            let result = stickslip_codegen::generate_file(&path, &lit.value());
            proc_macro2::fallback::unforce();
            result
                .map(|g| (g, Some(path.display().to_string())))
                .map_err(|report| {
                    syn::Error::new(lit.span(), format!("invalid model file\n{report}"))
                })
        }
    }
}

fn expand(input: TokenStream, as_source: bool) -> Tokens {
    let input = match syn::parse::<Input>(input) {
        Ok(i) => i,
        Err(e) => return e.to_compile_error(),
    };
    let (generated, tracked) = match generate(input) {
        Ok(g) => g,
        Err(e) => return e.to_compile_error(),
    };
    if as_source {
        let code = &generated.code;
        return quote!(#code);
    }
    let body: Tokens = match generated.code.parse() {
        Ok(t) => t,
        Err(e) => {
            return syn::Error::new(Span::call_site(), format!("internal: {e}")).to_compile_error()
        }
    };
    let name = format_ident!("{}", generated.name);
    // Make the compiler rebuild when the model file changes.
    let track = tracked.map(|p| {
        quote!(
            const _: &[u8] = include_bytes!(#p);
        )
    });
    let lints: Tokens = stickslip_codegen::MODULE_LINTS
        .parse()
        .expect("lint list tokenizes");
    quote! {
        #[allow(#lints)]
        pub mod #name {
            #track
            #body
        }
    }
}

/// Generate a model: `model!(file = "models/x.ssm")` or `model! { model x { ... } }`.
#[proc_macro]
pub fn model(input: TokenStream) -> TokenStream {
    expand(input, false).into()
}

/// The generated source text of a model, as a string literal (for tests
/// comparing the macro path with the `build.rs` path).
#[doc(hidden)]
#[proc_macro]
pub fn model_source(input: TokenStream) -> TokenStream {
    expand(input, true).into()
}
