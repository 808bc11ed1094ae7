//! Names of the model in the generated Rust.
//!
//! A model may name its parameters, lets, scenes and itself with any
//! identifier the language accepts; the generated code must compile and
//! compute the same numbers whatever they are. The emitter keeps the model's
//! names out of the generator's own namespace by construction: parameters are
//! only ever read as fields (`p.NAME`), never bound as locals, so no argument
//! (`x0`, `phi1`), temporary (`t3`, `ec0`) or item of the generated module can
//! be shadowed by one. What is left is checked here:
//!
//! * [`canonical_tokens`] spells every identifier as rustc reads it: NFC
//!   normalised (rustc normalises identifiers, so `é` and `e\u{301}` are one
//!   name) and without a needless `r#` (`r#mu` is `mu`); a keyword keeps its
//!   `r#` (`r#fn`). The checker then sees two names as equal exactly when
//!   rustc would.
//! * [`ident`] spells a name as a Rust identifier: raw for a keyword of any
//!   edition (`r#fn`, `r#gen`), plain otherwise.
//! * [`type_name`] turns a model or scene name into its type name
//!   (`sweep_w` → `SweepW`), mangled deterministically when the camel case is
//!   not an identifier or names another item of the module (`_1` → `Scene1`,
//!   `__` → `Scene`, `self_` → `SceneSelf`, `params` → `SceneParams`).
//! * [`check`] rejects, at the scene's name, a scene module that would
//!   collide with an item of the model's module (`Params`, the model's type,
//!   a primitive type such as `f64`) or with another scene.

use std::collections::HashMap;

use proc_macro2::{Group, Ident, Span, TokenStream, TokenTree};
use unicode_normalization::UnicodeNormalization;

use crate::diagnostic::Diagnostics;
use crate::parse::{Item, ModelAst};

/// Keywords of every Rust edition (strict, reserved, and the 2018 and 2024
/// additions): a name equal to one is written raw (`r#fn`) in generated code.
const KEYWORDS: &[&str] = &[
    "_", "abstract", "as", "async", "await", "become", "box", "break", "const", "continue",
    "crate", "do", "dyn", "else", "enum", "extern", "false", "final", "fn", "for", "gen", "if",
    "impl", "in", "let", "loop", "macro", "match", "mod", "move", "mut", "override", "priv", "pub",
    "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "try", "type",
    "typeof", "unsafe", "unsized", "use", "virtual", "where", "while", "yield",
];

/// Keywords that cannot be raw identifiers either.
const NOT_RAW: &[&str] = &["_", "self", "Self", "super", "crate"];

/// Names a generated type (a unit struct, so in both namespaces) must not
/// take: the parameter struct and statics of its module, and the prelude
/// names the generated code uses unqualified (`Some(..)`, `None`).
const RESERVED_TYPES: &[&str] = &[
    "Params",
    "INFO",
    "SMOOTH_INFO",
    "Some",
    "None",
    "Option",
    "Default",
];

/// Primitive types the generated code names (`f64::NAN`, `usize`, `&str`):
/// a scene module of that name would shadow them in the model's module.
const PRIMITIVES: &[&str] = &[
    "bool", "char", "str", "f32", "f64", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16",
    "u32", "u64", "u128", "usize",
];

/// A name without its `r#` (what the user reads: `fn` for `r#fn`).
pub fn bare(name: &str) -> &str {
    name.strip_prefix("r#").unwrap_or(name)
}

/// Whether `s` is an identifier by its characters (keywords included).
fn is_ident_chars(s: &str) -> bool {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) if c == '_' || unicode_ident::is_xid_start(c) => {
            s != "_" && chars.all(unicode_ident::is_xid_continue)
        }
        _ => false,
    }
}

/// `name` (bare or raw) as a Rust identifier token: raw for a keyword of any
/// edition. `None` when it cannot be one (`self`, `_`, not an identifier).
pub fn ident(name: &str) -> Option<Ident> {
    let b = bare(name);
    if NOT_RAW.contains(&b) || !is_ident_chars(b) {
        return None;
    }
    Some(if KEYWORDS.contains(&b) {
        Ident::new_raw(b, Span::call_site())
    } else {
        Ident::new(b, Span::call_site())
    })
}

/// The text of [`ident`] (`r#fn`, `mu`).
pub fn ident_text(name: &str) -> Option<String> {
    ident(name).map(|i| i.to_string())
}

/// `sweep_w` → `SweepW`: each `_`-separated part capitalised, then NFC.
fn camel(name: &str) -> String {
    bare(name)
        .split('_')
        .filter(|s| !s.is_empty())
        .map(|s| {
            let mut c = s.chars();
            match c.next() {
                Some(f) => f.to_uppercase().collect::<String>() + c.as_str(),
                None => String::new(),
            }
        })
        .collect::<String>()
        .nfc()
        .collect()
}

/// The type name of a model (`prefix = "Model"`) or scene (`"Scene"`):
/// the camel case of its name, or `prefix` + it when that is not a plain
/// identifier (empty, a leading digit, `Self`, another keyword) or is the
/// name of another item of its module (`params` → `SceneParams`).
pub fn type_name(name: &str, prefix: &str) -> String {
    let c = camel(name);
    if is_ident_chars(&c)
        && !KEYWORDS.contains(&c.as_str())
        && !RESERVED_TYPES.contains(&c.as_str())
    {
        c
    } else {
        format!("{prefix}{c}")
    }
}

/// Every identifier of `tokens` spelled as rustc reads it: NFC normalised,
/// `r#` kept only where the bare name is a keyword the parser would refuse.
/// Spans are kept, so messages still point at the name as written.
pub fn canonical_tokens(tokens: TokenStream) -> TokenStream {
    // An explicit stack, not recursion: a model may nest groups thousands
    // deep (the depth limit is checked later, on the canonical tokens).
    struct Frame {
        rest: proc_macro2::token_stream::IntoIter,
        out: Vec<TokenTree>,
        group: Option<Group>,
    }
    let mut stack = vec![Frame {
        rest: tokens.into_iter(),
        out: Vec::new(),
        group: None,
    }];
    loop {
        let top = stack
            .last_mut()
            .expect("the outermost frame is never popped");
        match top.rest.next() {
            Some(TokenTree::Group(g)) => stack.push(Frame {
                rest: g.stream().into_iter(),
                out: Vec::new(),
                group: Some(g),
            }),
            Some(TokenTree::Ident(i)) => top.out.push(TokenTree::Ident(canonical_ident(i))),
            Some(other) => top.out.push(other),
            None => {
                let done = stack.pop().expect("a frame is on the stack");
                let stream: TokenStream = done.out.into_iter().collect();
                match (done.group, stack.last_mut()) {
                    (Some(g), Some(parent)) => {
                        let mut ng = Group::new(g.delimiter(), stream);
                        ng.set_span(g.span());
                        parent.out.push(TokenTree::Group(ng));
                    }
                    _ => return stream,
                }
            }
        }
    }
}

fn canonical_ident(i: Ident) -> Ident {
    let s = i.to_string();
    let raw = s.starts_with("r#");
    let b = bare(&s);
    let n: String = b.nfc().collect();
    if !raw && n == b {
        return i;
    }
    if !is_ident_chars(&n) || NOT_RAW.contains(&n.as_str()) {
        return i;
    }
    // The parser refuses a keyword unless it is raw: keep those raw.
    let keyword = syn::parse_str::<syn::Ident>(&n).is_err();
    if keyword {
        if raw && n == b {
            return i;
        }
        Ident::new_raw(&n, i.span())
    } else {
        Ident::new(&n, i.span())
    }
}

/// A message for a tokenizer error at `span` that is a raw identifier which
/// cannot be one (`r#self`, `r#Self`, `r#super`, `r#crate`, `r#_`).
pub fn tokenize_hint(source: &str, span: Span) -> Option<String> {
    let start = span.start();
    let line = source.lines().nth(start.line.checked_sub(1)?)?;
    let rest: String = line.chars().skip(start.column).collect();
    let word: String = rest
        .strip_prefix("r#")?
        .chars()
        .take_while(|&c| c == '_' || unicode_ident::is_xid_continue(c))
        .collect();
    NOT_RAW.contains(&word.as_str()).then(|| {
        format!(
            "`r#{word}` is not an identifier: `self`, `Self`, `super`, `crate` and `_` cannot be written raw, \
             nor name anything in a model"
        )
    })
}

fn at(span: Span) -> String {
    let l = span.start();
    format!("line {}, column {}", l.line, l.column + 1)
}

/// Collisions between a scene's module and the other items of the model's
/// module, each reported at the scene's name.
pub fn check(ast: &ModelAst, diags: &mut Diagnostics) {
    let model = ast.name.to_string();
    let model_type = type_name(&model, "Model");
    let mut seen: HashMap<String, Span> = HashMap::new();
    for item in &ast.items {
        let Item::Scene(s) = item else { continue };
        let name = s.name.to_string();
        let span = s.name.span();
        let shown = bare(&name);
        if let Some(first) = seen.get(&name) {
            diags.error(
                span,
                format!("scene `{shown}` is defined twice (first at {})", at(*first)),
            );
            continue;
        }
        seen.insert(name.clone(), span);
        let clash = if shown == "Params" {
            Some("the parameter struct `Params`".to_string())
        } else if shown == model_type {
            Some(format!(
                "the type `{model_type}` of model `{}`",
                bare(&model)
            ))
        } else if PRIMITIVES.contains(&shown) {
            Some(format!("the primitive type `{shown}`"))
        } else {
            None
        };
        if let Some(clash) = clash {
            diags.error(
                span,
                format!(
                    "scene `{shown}` would generate a module `{shown}` that clashes with {clash} \
                     in the generated code; rename the scene"
                ),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers_are_raw_exactly_for_keywords() {
        assert_eq!(ident_text("fn").as_deref(), Some("r#fn"));
        assert_eq!(ident_text("r#fn").as_deref(), Some("r#fn"));
        assert_eq!(ident_text("gen").as_deref(), Some("r#gen"));
        assert_eq!(ident_text("mu").as_deref(), Some("mu"));
        assert_eq!(ident_text("μs").as_deref(), Some("μs"));
        assert_eq!(ident_text("__").as_deref(), Some("__"));
        assert_eq!(ident_text("_1").as_deref(), Some("_1"));
        for bad in ["self", "Self", "super", "crate", "_", "1a", ""] {
            assert_eq!(ident_text(bad), None, "{bad}");
        }
    }

    #[test]
    fn type_names_are_identifiers_and_deterministic() {
        assert_eq!(type_name("sweep_w", "Scene"), "SweepW");
        assert_eq!(type_name("_1", "Scene"), "Scene1");
        assert_eq!(type_name("__", "Scene"), "Scene");
        assert_eq!(type_name("self_", "Scene"), "SceneSelf");
        assert_eq!(type_name("r#fn", "Scene"), "Fn");
        assert_eq!(type_name("ω", "Scene"), "Ω");
        assert_eq!(type_name("params", "Scene"), "SceneParams");
        assert_eq!(type_name("INFO", "Model"), "ModelINFO");
        assert_eq!(type_name("some", "Scene"), "SceneSome");
    }

    #[test]
    fn canonical_identifiers_are_nfc_and_raw_only_for_keywords() {
        let t: TokenStream = "r#mu e\u{301} r#fn (r#gen)".parse().expect("tokens");
        let out = canonical_tokens(t).to_string();
        assert_eq!(out, "mu \u{e9} r#fn (gen)");
    }
}
