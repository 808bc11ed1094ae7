//! Pass 1: tokens → syntax tree of a model file (`.ssm`).
//!
//! The language is made of Rust tokens, so it is parsed with `syn`; every
//! node keeps the span it came from. A syntax error in one item does not stop
//! the parse: the parser skips to the end of that item and goes on, so all
//! the file's errors are reported at once.

use proc_macro2::{Delimiter, Group, Spacing, Span, TokenStream, TokenTree};
use syn::parse::ParseStream;
use syn::{braced, Attribute, Expr, Ident, LitInt, LitStr, Token};

use crate::diagnostic::Diagnostics;

mod kw {
    syn::custom_keyword!(model);
    syn::custom_keyword!(param);
    syn::custom_keyword!(oscillator);
    syn::custom_keyword!(boundary);
    syn::custom_keyword!(domain);
    syn::custom_keyword!(scene);
    syn::custom_keyword!(stick);
    syn::custom_keyword!(v);
    syn::custom_keyword!(free);
    syn::custom_keyword!(structures);
    syn::custom_keyword!(law);
    syn::custom_keyword!(pieces);
}

/// A whole model file.
#[derive(Debug)]
pub struct ModelAst {
    /// Doc comments on the model.
    pub docs: Vec<String>,
    /// `model NAME`.
    pub name: Ident,
    /// Items in source order.
    pub items: Vec<Item>,
}

/// One item of the model body.
#[derive(Debug)]
pub enum Item {
    /// `param NAME = VALUE [, > LO] [, < HI];`
    Param(ParamAst),
    /// `let NAME = EXPR;`
    Let(LetAst),
    /// `oscillator { key: EXPR, ... }`
    Oscillator(OscillatorAst),
    /// `boundary LABEL: v = EXPR [, stick EXPR];`
    Boundary(BoundaryAst),
    /// `domain N: BAND => EXPR;`
    Domain(DomainAst),
    /// `law { belt: .., stick: .., range: .., kinetic: .. }`: a smooth kinetic friction law.
    Law(OscillatorAst),
    /// `scene NAME { free: ...; structures: ...; }`
    Scene(SceneAst),
}

/// A comparison bound on a parameter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BoundOp {
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `<`
    Lt,
    /// `<=`
    Le,
}

/// `param NAME = VALUE, bounds...;`
#[derive(Debug)]
pub struct ParamAst {
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The name.
    pub name: Ident,
    /// The default value's expression (a number).
    pub default: Expr,
    /// The bounds as written, each with its place.
    pub bounds: Vec<(BoundOp, Expr, Span)>,
}

/// `let NAME = EXPR;`
#[derive(Debug)]
pub struct LetAst {
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The name.
    pub name: Ident,
    /// The expression.
    pub value: Expr,
}

/// `oscillator { mass: .., damping: .., stiffness: .., forcing: .., frequency: .. }`
#[derive(Debug)]
pub struct OscillatorAst {
    /// Where it is written, for diagnostics.
    pub span: Span,
    /// The fields as written, each `name: expression`.
    pub fields: Vec<(Ident, Expr)>,
}

/// `boundary LABEL: v = EXPR [, stick EXPR];`
#[derive(Debug)]
pub struct BoundaryAst {
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The label (`Sigma1`, or the domain's number).
    pub label: Ident,
    /// The boundary's velocity, `v = EXPR`.
    pub velocity: Expr,
    /// The static bound, on the stick boundary.
    pub stick: Option<Expr>,
}

/// The velocity band of a domain, by boundary labels.
#[derive(Debug)]
pub struct BandAst {
    /// Lower boundary (`None`: unbounded below).
    pub lower: Option<Ident>,
    /// Upper boundary (`None`: unbounded above).
    pub upper: Option<Ident>,
    /// Where it is written, for diagnostics.
    pub span: Span,
}

/// `domain N: BAND => LAW;`
#[derive(Debug)]
pub struct DomainAst {
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The label (`Sigma1`, or the domain's number).
    pub label: LitInt,
    /// The velocity band.
    pub band: BandAst,
    /// The kinetic friction law per unit mass.
    pub law: Expr,
}

/// `scene NAME { free: A, B; structures: "..", ".."; }`
#[derive(Debug)]
pub struct SceneAst {
    /// The `///` doc comments, one line each.
    pub docs: Vec<String>,
    /// The name.
    pub name: Ident,
    /// The parameters left free, as written.
    pub free: Vec<Ident>,
    /// The structures to study, as string literals.
    pub structures: Vec<LitStr>,
    /// `pieces: N;` (models with a `law`): build an N-piece model.
    pub pieces: Option<LitInt>,
}

fn docs_of(attrs: &[Attribute], diags: &mut Diagnostics) -> Vec<String> {
    let mut out = Vec::new();
    for attr in attrs {
        if attr.path().is_ident("doc") {
            if let syn::Meta::NameValue(nv) = &attr.meta {
                if let Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Str(s),
                    ..
                }) = &nv.value
                {
                    out.push(s.value().trim().to_string());
                    continue;
                }
            }
        }
        diags.error(
            attr.pound_token.span,
            "only doc comments (`///`) may annotate a model item",
        );
    }
    out
}

/// Parse a model from tokens, collecting every syntax error.
pub fn parse_model(tokens: TokenStream, diags: &mut Diagnostics) -> Option<ModelAst> {
    // Names as rustc reads them (NFC, no needless `r#`): see `crate::names`.
    let tokens = crate::names::canonical_tokens(tokens);
    let parser = |input: ParseStream| parse_model_stream(input, diags);
    match syn::parse::Parser::parse2(parser, tokens) {
        Ok(m) => m,
        Err(e) => {
            diags.push_syn(e);
            None
        }
    }
}

fn parse_model_stream(
    input: ParseStream,
    diags: &mut Diagnostics,
) -> syn::Result<Option<ModelAst>> {
    let mut inner = input.call(Attribute::parse_inner)?;
    inner.extend(input.call(Attribute::parse_outer)?);
    let docs = docs_of(&inner, diags);
    input.parse::<kw::model>().map_err(|e| {
        syn::Error::new(
            e.span(),
            "expected `model NAME { ... }` (a model file holds one model)",
        )
    })?;
    let name: Ident = input.parse()?;
    let body;
    braced!(body in input);
    let mut items = Vec::new();
    while !body.is_empty() {
        match parse_item(&body, diags) {
            Ok(Some(item)) => items.push(item),
            Ok(None) => {} // an error inside the item's braces, already recorded
            Err(e) => {
                diags.push_syn(e);
                skip_item(&body);
            }
        }
    }
    if !input.is_empty() {
        return Err(input.error("unexpected tokens after the model's closing brace"));
    }
    Ok(Some(ModelAst { docs, name, items }))
}

/// Run `f` on the inside of an item's braces. On error, the rest of the
/// braces is dropped: syn would otherwise report the leftover tokens again
/// ("unexpected token, expected `}`"), and the item ends at its closing
/// brace, so the caller must not skip anything more.
fn braced_body<T>(
    body: ParseStream,
    f: impl FnOnce(ParseStream) -> syn::Result<T>,
) -> syn::Result<T> {
    let result = f(body);
    if result.is_err() {
        let _ = body.step(|cursor| {
            let mut rest = *cursor;
            while let Some((_, next)) = rest.token_tree() {
                rest = next;
            }
            Ok(((), rest))
        });
    }
    result
}

/// Error recovery: drop tokens up to and including the next `;` or braced
/// group at this level, so the next item can be parsed.
fn skip_item(input: ParseStream) {
    let _ = input.step(|cursor| {
        let mut rest = *cursor;
        while let Some((tt, next)) = rest.token_tree() {
            rest = next;
            match tt {
                TokenTree::Punct(p) if p.as_char() == ';' => break,
                TokenTree::Group(g) if g.delimiter() == proc_macro2::Delimiter::Brace => break,
                _ => {}
            }
        }
        Ok(((), rest))
    });
}

/// `Ok(None)`: an error inside the item's braces, recorded in `diags`.
fn parse_item(input: ParseStream, diags: &mut Diagnostics) -> syn::Result<Option<Item>> {
    let attrs = input.call(Attribute::parse_outer)?;
    let docs = docs_of(&attrs, diags);
    let la = input.lookahead1();
    if la.peek(kw::param) {
        input.parse::<kw::param>()?;
        let name: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let default = expr(input)?;
        let mut bounds = Vec::new();
        while input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
            let span = input.span();
            let op = if input.peek(Token![>=]) {
                input.parse::<Token![>=]>()?;
                BoundOp::Ge
            } else if input.peek(Token![<=]) {
                input.parse::<Token![<=]>()?;
                BoundOp::Le
            } else if input.peek(Token![>]) {
                input.parse::<Token![>]>()?;
                BoundOp::Gt
            } else if input.peek(Token![<]) {
                input.parse::<Token![<]>()?;
                BoundOp::Lt
            } else {
                return Err(
                    input.error("expected a bound: `> value`, `>= value`, `< value` or `<= value`")
                );
            };
            let value = expr(input)?;
            bounds.push((op, value, span));
        }
        input.parse::<Token![;]>()?;
        Ok(Some(Item::Param(ParamAst {
            docs,
            name,
            default,
            bounds,
        })))
    } else if la.peek(Token![let]) {
        input.parse::<Token![let]>()?;
        let name: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value = expr(input)?;
        input.parse::<Token![;]>()?;
        Ok(Some(Item::Let(LetAst { docs, name, value })))
    } else if la.peek(kw::oscillator) || la.peek(kw::law) {
        let is_law = input.peek(kw::law);
        let span = if is_law {
            input.parse::<kw::law>()?.span
        } else {
            input.parse::<kw::oscillator>()?.span
        };
        let body;
        braced!(body in input);
        let fields = braced_body(&body, |body| {
            let mut fields = Vec::new();
            while !body.is_empty() {
                let key: Ident = body.parse()?;
                body.parse::<Token![:]>()?;
                let value = expr(body)?;
                fields.push((key, value));
                if body.is_empty() {
                    break;
                }
                body.parse::<Token![,]>()?;
            }
            Ok(fields)
        });
        let fields = match fields {
            Ok(f) => f,
            Err(e) => {
                diags.push_syn(e);
                return Ok(None);
            }
        };
        let ast = OscillatorAst { span, fields };
        Ok(Some(if is_law {
            Item::Law(ast)
        } else {
            Item::Oscillator(ast)
        }))
    } else if la.peek(kw::boundary) {
        input.parse::<kw::boundary>()?;
        let label: Ident = input.parse()?;
        input.parse::<Token![:]>()?;
        input.parse::<kw::v>()?;
        input.parse::<Token![=]>()?;
        let velocity = expr(input)?;
        let mut stick = None;
        if input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
            input.parse::<kw::stick>().map_err(|e| {
                syn::Error::new(
                    e.span(),
                    "expected `stick BOUND` (the static friction bound per unit mass)",
                )
            })?;
            stick = Some(expr(input)?);
        }
        input.parse::<Token![;]>()?;
        Ok(Some(Item::Boundary(BoundaryAst {
            docs,
            label,
            velocity,
            stick,
        })))
    } else if la.peek(kw::domain) {
        input.parse::<kw::domain>()?;
        let label: LitInt = input.parse()?;
        input.parse::<Token![:]>()?;
        let band = parse_band(input)?;
        input.parse::<Token![=>]>()?;
        let law = expr(input)?;
        input.parse::<Token![;]>()?;
        Ok(Some(Item::Domain(DomainAst {
            docs,
            label,
            band,
            law,
        })))
    } else if la.peek(kw::scene) {
        input.parse::<kw::scene>()?;
        let name: Ident = input.parse()?;
        let body;
        braced!(body in input);
        let parsed = braced_body(&body, |body| {
            let mut free = Vec::new();
            let mut structures = Vec::new();
            let mut pieces = None;
            while !body.is_empty() {
                if body.peek(kw::pieces) {
                    body.parse::<kw::pieces>()?;
                    body.parse::<Token![:]>()?;
                    pieces = Some(body.parse::<LitInt>()?);
                    body.parse::<Token![;]>()?;
                    continue;
                }
                if body.peek(kw::free) {
                    body.parse::<kw::free>()?;
                    body.parse::<Token![:]>()?;
                    loop {
                        free.push(body.parse::<Ident>()?);
                        if !body.peek(Token![,]) {
                            break;
                        }
                        body.parse::<Token![,]>()?;
                    }
                } else if body.peek(kw::structures) {
                    body.parse::<kw::structures>()?;
                    body.parse::<Token![:]>()?;
                    loop {
                        structures.push(body.parse::<LitStr>()?);
                        if !body.peek(Token![,]) {
                            break;
                        }
                        body.parse::<Token![,]>()?;
                    }
                } else {
                    return Err(body.error(
                        "expected `free: NAMES;`, `structures: \"..\", ..;` or `pieces: N;` in a scene",
                    ));
                }
                body.parse::<Token![;]>()?;
            }
            Ok((free, structures, pieces))
        });
        let (free, structures, pieces) = match parsed {
            Ok(p) => p,
            Err(e) => {
                diags.push_syn(e);
                return Ok(None);
            }
        };
        Ok(Some(Item::Scene(SceneAst {
            docs,
            name,
            free,
            structures,
            pieces,
        })))
    } else {
        Err(la.error())
    }
}

/// `v > B`, `A < v < B` or `v < A`.
fn parse_band(input: ParseStream) -> syn::Result<BandAst> {
    let span = input.span();
    let expected = "expected a velocity band: `v > SigmaA`, `SigmaA < v < SigmaB` or `v < SigmaA`";
    if input.peek(kw::v) {
        input.parse::<kw::v>()?;
        if input.peek(Token![>]) {
            input.parse::<Token![>]>()?;
            let lower: Ident = input.parse()?;
            Ok(BandAst {
                lower: Some(lower),
                upper: None,
                span,
            })
        } else if input.peek(Token![<]) {
            input.parse::<Token![<]>()?;
            let upper: Ident = input.parse()?;
            Ok(BandAst {
                lower: None,
                upper: Some(upper),
                span,
            })
        } else {
            Err(input.error(expected))
        }
    } else if input.peek(Ident) {
        let lower: Ident = input.parse()?;
        input
            .parse::<Token![<]>()
            .map_err(|e| syn::Error::new(e.span(), expected))?;
        input
            .parse::<kw::v>()
            .map_err(|e| syn::Error::new(e.span(), expected))?;
        input
            .parse::<Token![<]>()
            .map_err(|e| syn::Error::new(e.span(), expected))?;
        let upper: Ident = input.parse()?;
        Ok(BandAst {
            lower: Some(lower),
            upper: Some(upper),
            span,
        })
    } else {
        Err(input.error(expected))
    }
}

/// How deep an expression may nest: parentheses, calls and unary operators
/// together. `syn` parses nesting by recursion, so a limit (with a located
/// error) is what keeps a model with thousands of nested parentheses from
/// overflowing the stack of the build script or the compiler.
pub const MAX_NESTING: usize = 64;

/// Terms a sum may have at one level before it is grouped: a flat sum
/// `a + b + c + ...` is a left-deep tree, as deep as it is long, and every
/// pass over it (parser, checker, emitter, rustc) would recurse that deep.
pub const MAX_FLAT_TERMS: usize = 64;

/// One expression: the tokens up to the next `,` or `;` at this level (or
/// the end), checked for depth, long sums grouped, then parsed by `syn`.
fn expr(input: ParseStream) -> syn::Result<Expr> {
    if input.is_empty() || input.peek(Token![,]) || input.peek(Token![;]) {
        return Err(input.error("expected an expression"));
    }
    let tokens = input.step(|cursor| {
        let mut rest = *cursor;
        let mut out = Vec::new();
        while let Some((tt, next)) = rest.token_tree() {
            // The expression ends before a `,` or `;`, and before an operand
            // that directly follows one (`3.0 3.0`, `3.0 param ..`: the item's
            // `;` is then reported missing there); a name followed by
            // parentheses is a call.
            let ends = match (&tt, out.last()) {
                (TokenTree::Punct(p), _) => p.as_char() == ',' || p.as_char() == ';',
                (TokenTree::Group(g), Some(TokenTree::Ident(_))) => {
                    g.delimiter() != Delimiter::Parenthesis
                }
                // `#[..]` (an attribute, rejected with its own message) is no operand.
                (_, Some(TokenTree::Group(g))) if g.delimiter() == Delimiter::Bracket => false,
                (_, Some(prev)) => is_operand(prev),
                (_, None) => false,
            };
            if ends {
                break;
            }
            out.push(tt);
            rest = next;
        }
        Ok((out, rest))
    })?;
    check_nesting(&tokens)?;
    let grouped = group_long_sums(tokens);
    syn::parse2(grouped.into_iter().collect())
}

/// Whether `tt` ends an operand (so that a `+` or `-` after it is binary).
fn is_operand(tt: &TokenTree) -> bool {
    !matches!(tt, TokenTree::Punct(_))
}

/// Reject nesting deeper than [`MAX_NESTING`], at the token where it gets
/// too deep. Iterative: the depth of the input is what is being checked.
fn check_nesting(tokens: &[TokenTree]) -> syn::Result<()> {
    // (tokens of one level, next index, depth of that level)
    let mut stack: Vec<(Vec<TokenTree>, usize, usize)> = vec![(tokens.to_vec(), 0, 0)];
    while let Some((level, mut i, depth)) = stack.pop() {
        let mut unary = 0;
        while i < level.len() {
            let tt = &level[i];
            i += 1;
            match tt {
                TokenTree::Punct(p)
                    if matches!(p.as_char(), '-' | '!')
                        && (i < 2 || !is_operand(&level[i - 2])) =>
                {
                    unary += 1;
                    if depth + unary > MAX_NESTING {
                        return Err(syn::Error::new(
                            p.span(),
                            format!(
                                "expression nested deeper than {MAX_NESTING} levels (unary operators and parentheses); \
                                 split it with `let`"
                            ),
                        ));
                    }
                }
                TokenTree::Group(g) => {
                    let inner = depth + unary + 1;
                    if inner > MAX_NESTING {
                        return Err(syn::Error::new(
                            g.span_open(),
                            format!(
                                "expression nested deeper than {MAX_NESTING} levels (parentheses, calls and unary operators); \
                                 split it with `let`"
                            ),
                        ));
                    }
                    let child: Vec<TokenTree> = g.stream().into_iter().collect();
                    stack.push((level, i, depth));
                    stack.push((child, 0, inner));
                    break;
                }
                _ => unary = 0,
            }
        }
    }
    Ok(())
}

/// Group a sum of more than [`MAX_FLAT_TERMS`] terms into parenthesized
/// chunks (and chunks of chunks), inside every group too: `t1 + ... + t64 -
/// t65 + t66 ...` becomes `(t1 + ... + t64) - (t65 - t66 ...)`, the signs
/// inside a chunk that follows a `-` flipped. The value is the same sum,
/// added in a different order (rounding may differ in the last bits).
/// Recursion follows the nesting, which [`check_nesting`] has bounded.
fn group_long_sums(tokens: Vec<TokenTree>) -> Vec<TokenTree> {
    let tokens: Vec<TokenTree> = tokens
        .into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) => {
                let inner: TokenStream = group_long_sums(g.stream().into_iter().collect())
                    .into_iter()
                    .collect();
                let mut ng = Group::new(g.delimiter(), inner);
                ng.set_span(g.span());
                TokenTree::Group(ng)
            }
            other => other,
        })
        .collect();
    // Terms, each with the binary operator before it (`None` for the first).
    let mut terms: Vec<(Option<proc_macro2::Punct>, Vec<TokenTree>)> = vec![(None, Vec::new())];
    for (i, tt) in tokens.iter().enumerate() {
        if let TokenTree::Punct(p) = tt {
            if matches!(p.as_char(), '+' | '-')
                && p.spacing() == Spacing::Alone
                && i > 0
                && is_operand(&tokens[i - 1])
            {
                terms.push((Some(p.clone()), Vec::new()));
                continue;
            }
        }
        if let Some(last) = terms.last_mut() {
            last.1.push(tt.clone());
        }
    }
    if terms.len() <= MAX_FLAT_TERMS {
        return tokens;
    }
    while terms.len() > MAX_FLAT_TERMS {
        let mut next = Vec::new();
        for chunk in terms.chunks(MAX_FLAT_TERMS) {
            let lead = chunk[0].0.clone();
            let flip = lead.as_ref().is_some_and(|p| p.as_char() == '-');
            let mut inner: Vec<TokenTree> = Vec::new();
            for (k, (op, term)) in chunk.iter().enumerate() {
                if k > 0 {
                    if let Some(op) = op {
                        let c = match (op.as_char(), flip) {
                            ('+', true) => '-',
                            ('-', true) => '+',
                            (c, _) => c,
                        };
                        let mut p = proc_macro2::Punct::new(c, Spacing::Alone);
                        p.set_span(op.span());
                        inner.push(TokenTree::Punct(p));
                    }
                }
                inner.extend(term.iter().cloned());
            }
            let first = inner.first().map_or_else(Span::call_site, TokenTree::span);
            let last = inner.last().map_or(first, TokenTree::span);
            let mut g = Group::new(Delimiter::Parenthesis, inner.into_iter().collect());
            g.set_span(first.join(last).unwrap_or(first));
            next.push((lead, vec![TokenTree::Group(g)]));
        }
        terms = next;
    }
    let mut out = Vec::new();
    for (op, term) in terms {
        if let Some(op) = op {
            out.push(TokenTree::Punct(op));
        }
        out.extend(term);
    }
    out
}
