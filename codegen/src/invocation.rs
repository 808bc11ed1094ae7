//! What `stickslip::model!` expands to; the proc-macro crate only converts
//! between `proc_macro` and `proc_macro2` tokens.
//!
//! * `model! { model NAME { ... } }` — an inline model; errors point at its tokens.
//! * `model!(file = "models/NAME.ssm")` — a model file, relative to the
//!   invoking crate's `Cargo.toml`; errors point at the path literal and name
//!   `file:line:col` in the message.
//!
//! Both expand to the module [`registry::module`] wraps, the one `build.rs`
//! writes.

use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::parse::{Parse, ParseStream};
use syn::{LitStr, Token};

use crate::emit::registry;
use crate::{GeneratedFile, Options};

enum Input {
    File(LitStr),
    Inline(TokenStream),
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
fn generate(input: TokenStream) -> syn::Result<(GeneratedFile, Option<String>)> {
    match syn::parse2::<Input>(input)? {
        Input::Inline(tokens) => {
            let options = Options {
                origin: "stickslip::model! (inline)".into(),
            };
            crate::generate(tokens, &options)
                .map(|g| (g, None))
                .map_err(|d| d.to_syn_error())
        }
        Input::File(lit) => {
            let dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
            let path = std::path::Path::new(&dir).join(lit.value());
            // The entry point of build.rs and `stickslip check` too, so the
            // report is theirs word for word. Tokens of a file read here have
            // no spans in the caller's source: use proc-macro2's own tokenizer
            // for line/column information, and report at the path literal.
            proc_macro2::fallback::force();
            let result = crate::check_file(&path, &lit.value());
            proc_macro2::fallback::unforce();
            result
                .map(|g| (g, Some(path.display().to_string())))
                .map_err(|report| {
                    syn::Error::new(
                        lit.span(),
                        format!("invalid model file\n{}", report.render()),
                    )
                })
        }
    }
}

/// `model!(..)`: the model's module, or the compile errors.
pub fn model(input: TokenStream) -> TokenStream {
    let (generated, tracked) = match generate(input) {
        Ok(g) => g,
        Err(e) => return e.to_compile_error(),
    };
    let body: TokenStream = match generated.code.parse() {
        Ok(t) => t,
        Err(e) => {
            return syn::Error::new(Span::call_site(), format!("internal: {e}")).to_compile_error()
        }
    };
    // Make the compiler rebuild when the model file changes.
    let track = tracked.map(|p| {
        quote!(
            const _: &[u8] = include_bytes!(#p);
        )
    });
    registry::module(&generated, quote!(#track #body))
}

/// `model_source!(..)`: the generated source text as a string literal (for
/// tests comparing the macro path with the `build.rs` path).
pub fn model_source(input: TokenStream) -> TokenStream {
    match generate(input) {
        Ok((generated, _)) => {
            let code = &generated.code;
            quote!(#code)
        }
        Err(e) => e.to_compile_error(),
    }
}
