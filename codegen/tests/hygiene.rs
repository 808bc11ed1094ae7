//! Hygiene of the generated code, at generator level: renaming every
//! identifier of the paper model (its name, parameters, let, scenes) to
//! hostile names — Rust keywords, the generator's own names (`p`, `x0`,
//! `t3`, `INFO`, `Params`), prelude and primitive names, Unicode in NFC and
//! NFD, names whose camel case collides — either is rejected with a message
//! located at one of the renamed names, or generates exactly the code of the
//! model with plain names, token for token, up to the renaming (so the
//! arithmetic is the same), and that code parses as Rust.
//!
//! Whether a renaming must be rejected is decided here independently of the
//! generator, from the rules in the README: two parameters or lets with one
//! name after NFC and `r#` removal, a parameter or let named `v`, two scenes
//! with one name, or a scene named `Params`, like the model's type, or like a
//! primitive type.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{Delimiter, Group, Ident, Literal, Span, TokenStream, TokenTree};
use proptest::prelude::*;
use stickslip_codegen::{generate_source, names};
use unicode_normalization::UnicodeNormalization;

/// The paper model with its identifiers as placeholders: `@m` the model,
/// `@pNN` the 15 parameters, `@l00` the let, `@sNN` the two scenes.
const TEMPLATE: &str = r#"model @m {
    param @p00 = 5.0, > 0;
    param @p01 = 0.1, >= 0;
    param @p02 = 30.0, > 0;
    param @p03 = 3.0;
    param @p04 = 4.5;
    param @p05 = 1.5;
    param @p06 = 0.5, >= 0;
    param @p07 = 0.4, >= 0;
    param @p08 = 0.1;
    param @p09 = 0.5;
    param @p10 = 0.1;
    param @p11 = 0.5;
    param @p12 = 9.8, > 0;
    param @p13 = 70.0;
    param @p14 = 3.0, > 0;
    let @l00 = @p00 * @p12;
    oscillator {
        mass: @p00,
        damping: @p01,
        stiffness: @p02,
        forcing: @p13 / @p00,
        frequency: @p14,
    }
    boundary Sigma1: v = @p03, stick @p06 * @l00 / @p00;
    boundary Sigma2: v = @p04;
    boundary Sigma3: v = @p05;
    domain 2: v > Sigma2 => (@p08 * (v - @p04) - @p09 * (@p04 - @p03) + @l00 * @p07) / @p00;
    domain 1: Sigma1 < v < Sigma2 => (-@p09 * (v - @p03) + @l00 * @p07) / @p00;
    domain 3: Sigma3 < v < Sigma1 => (-@p10 * (v - @p03) - @l00 * @p07) / @p00;
    domain 4: v < Sigma3 => (@p11 * (v - @p05) - @p10 * (@p05 - @p03) - @l00 * @p07) / @p00;
    scene @s00 {
        free: @p14;
    }
    scene @s01 {
        free: @p14, @p13;
        structures: "3_33 4_33", "3_31 0_11 3_13 4_33";
    }
}
"#;

const PARAMS: usize = 15;

/// Placeholders in the order of [`Renaming::names`].
fn placeholders() -> Vec<String> {
    let mut out = vec!["@m".to_string()];
    out.extend((0..PARAMS).map(|i| format!("@p{i:02}")));
    out.push("@l00".into());
    out.extend((0..2).map(|i| format!("@s{i:02}")));
    out
}

/// Hostile names: keywords (raw), 2024's `gen`, the generator's own locals,
/// items and prelude names, primitive types, language keywords, Unicode
/// (NFC `é` and its NFD spelling), names with no camel case (`_1`, `__`),
/// needless raw (`r#mu` is `mu`), camel-case twins (`sweep_w`, `sweepW`,
/// `SweepW`), and `v`.
const POOL: &[&str] = &[
    "r#fn",
    "r#type",
    "r#match",
    "r#loop",
    "r#async",
    "r#try",
    "r#dyn",
    "r#yield",
    "r#abstract",
    "r#struct",
    "gen",
    "r#gen",
    "p",
    "x",
    "y",
    "phi",
    "x0",
    "x1",
    "v0",
    "phi0",
    "phi1",
    "t0",
    "t1",
    "t3",
    "t20",
    "ec0",
    "es0",
    "value",
    "index",
    "self_",
    "INFO",
    "SMOOTH_INFO",
    "Params",
    "ParamSet",
    "Default",
    "Some",
    "None",
    "Option",
    "f64",
    "usize",
    "str",
    "core",
    "stickslip",
    "oscillator",
    "static_bound",
    "stick_forces",
    "boundary_velocities",
    "flow_1",
    "mapping_3_33",
    "residual_3_33",
    "coefficients_1",
    "Paper",
    "params",
    "info",
    "model",
    "param",
    "scene",
    "free",
    "domain",
    "boundary",
    "stick",
    "mass",
    "law",
    "pieces",
    "μs",
    "ω",
    "Ω1",
    "é",
    "e\u{301}",
    "ǅ",
    "中文",
    "_1",
    "__",
    "___",
    "_x",
    "r#mu",
    "mu",
    "sweep_w",
    "sweepW",
    "SweepW",
    "v",
];

const PRIMITIVES: &[&str] = &[
    "bool", "char", "str", "f32", "f64", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16",
    "u32", "u64", "u128", "usize",
];

/// A model name, its parameters and let, its scenes.
#[derive(Clone, Debug)]
struct Renaming {
    names: Vec<String>,
}

/// The canonical name (what rustc and the checker compare): NFC, no `r#`.
fn canonical(name: &str) -> String {
    names::bare(name).nfc().collect()
}

impl Renaming {
    fn plain() -> Self {
        let mut names = vec!["zqm".to_string()];
        names.extend((0..PARAMS).map(|i| format!("zqp{i:02}")));
        names.push("zql00".into());
        names.extend((0..2).map(|i| format!("zqs{i:02}")));
        Renaming { names }
    }

    fn source(&self) -> String {
        let mut s = TEMPLATE.to_string();
        // Longest placeholders first: `@m` is a prefix of none, but be safe.
        let mut pairs: Vec<(String, &String)> =
            placeholders().into_iter().zip(&self.names).collect();
        pairs.sort_by_key(|(p, _)| std::cmp::Reverse(p.len()));
        for (p, n) in pairs {
            s = s.replace(&p, n);
        }
        s
    }

    fn model(&self) -> &str {
        &self.names[0]
    }
    fn values(&self) -> &[String] {
        &self.names[1..=PARAMS + 1]
    }
    fn scenes(&self) -> &[String] {
        &self.names[PARAMS + 2..]
    }

    /// Whether the language rejects this renaming (decided from the rules).
    fn must_reject(&self) -> bool {
        let vals: Vec<String> = self.values().iter().map(|n| canonical(n)).collect();
        let distinct: BTreeSet<&String> = vals.iter().collect();
        if distinct.len() < vals.len() || vals.iter().any(|n| n == "v") {
            return true;
        }
        let scenes: Vec<String> = self.scenes().iter().map(|n| canonical(n)).collect();
        if scenes[0] == scenes[1] {
            return true;
        }
        let model_type = names::type_name(&canonical(self.model()), "Model");
        scenes
            .iter()
            .any(|s| s == "Params" || *s == model_type || PRIMITIVES.contains(&s.as_str()))
    }
}

/// Start `(line, column)` (1-based, columns in characters) of every
/// occurrence of a placeholder in the template, as it lands in `source`
/// after renaming.
fn name_positions(r: &Renaming) -> BTreeSet<(usize, usize)> {
    let mut out = BTreeSet::new();
    let ph = placeholders();
    for (ln, line) in TEMPLATE.lines().enumerate() {
        // Walk the template line, tracking the column in the renamed line.
        let mut col = 1;
        let mut rest = line;
        'outer: while !rest.is_empty() {
            if rest.starts_with('@') {
                for (k, p) in ph.iter().enumerate() {
                    let next = &rest[p.len().min(rest.len())..];
                    let ends = next
                        .chars()
                        .next()
                        .is_none_or(|c| !c.is_alphanumeric() && c != '_');
                    if rest.starts_with(p.as_str()) && ends {
                        out.insert((ln + 1, col));
                        col += r.names[k].chars().count();
                        rest = next;
                        continue 'outer;
                    }
                }
            }
            let c = rest.chars().next().expect("non-empty");
            col += 1;
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// `file:line:col` of every error in a rendered report.
fn error_positions(report: &str) -> Vec<(usize, usize)> {
    report
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("--> test.ssm:"))
        .filter_map(|rest| {
            let mut it = rest.split(':');
            Some((it.next()?.parse().ok()?, it.next()?.parse().ok()?))
        })
        .collect()
}

/// The tokens of `code` with the plain names of `from` replaced by the
/// names of `to`: identifiers by their Rust spelling (types by their type
/// names), string literals by substring on the bare names.
fn rename_tokens(code: TokenStream, map: &Maps) -> TokenStream {
    code.into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) => {
                let mut ng = Group::new(g.delimiter(), rename_tokens(g.stream(), map));
                ng.set_span(g.span());
                TokenTree::Group(ng)
            }
            TokenTree::Ident(i) => {
                let s = i.to_string();
                match map.idents.get(&s) {
                    Some(n) => TokenTree::Ident(ident(n)),
                    None => TokenTree::Ident(i),
                }
            }
            TokenTree::Literal(l) => {
                let s = l.to_string();
                match syn::parse_str::<syn::LitStr>(&s) {
                    Ok(lit) if s.starts_with('"') => {
                        let mut v = lit.value();
                        for (from, to) in &map.strings {
                            v = v.replace(from, to);
                        }
                        TokenTree::Literal(Literal::string(&v))
                    }
                    _ => TokenTree::Literal(l),
                }
            }
            other => other,
        })
        .collect()
}

fn ident(text: &str) -> Ident {
    match text.strip_prefix("r#") {
        Some(b) => Ident::new_raw(b, Span::call_site()),
        None => Ident::new(text, Span::call_site()),
    }
}

struct Maps {
    idents: BTreeMap<String, String>,
    strings: Vec<(String, String)>,
}

fn maps(plain: &Renaming, hostile: &Renaming) -> Maps {
    let mut idents = BTreeMap::new();
    let mut strings = Vec::new();
    for (k, (a, b)) in plain.names.iter().zip(&hostile.names).enumerate() {
        let b = canonical(b);
        let rust = names::ident_text(&b).expect("a hostile name has a Rust spelling");
        idents.insert(a.clone(), rust);
        strings.push((a.clone(), b.clone()));
        let prefix = match k {
            0 => Some("Model"),
            k if k > PARAMS + 1 => Some("Scene"),
            _ => None,
        };
        if let Some(prefix) = prefix {
            idents.insert(names::type_name(a, prefix), names::type_name(&b, prefix));
        }
    }
    Maps { idents, strings }
}

/// The tokens of a generated file, without the trailing commas the
/// formatter adds when it breaks a long list (their presence depends on the
/// length of the names).
fn tokens_of(code: &str) -> TokenStream {
    let file = syn::parse_file(code).expect("generated code parses as Rust");
    strip_trailing_commas(quote::ToTokens::into_token_stream(file))
}

fn strip_trailing_commas(t: TokenStream) -> TokenStream {
    let mut out: Vec<TokenTree> = t
        .into_iter()
        .map(|tt| match tt {
            TokenTree::Group(g) => {
                let mut ng = Group::new(g.delimiter(), strip_trailing_commas(g.stream()));
                ng.set_span(g.span());
                TokenTree::Group(ng)
            }
            other => other,
        })
        .collect();
    if matches!(out.last(), Some(TokenTree::Punct(p)) if p.as_char() == ',') {
        out.pop();
    }
    out.into_iter().collect()
}

/// The generated code of the plain model, as tokens (generated once).
fn plain_tokens() -> TokenStream {
    static CODE: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    let code = CODE.get_or_init(|| {
        generate_source(&Renaming::plain().source(), "test.ssm")
            .expect("the plain model generates")
            .code
    });
    tokens_of(code)
}

fn check_renaming(hostile: &Renaming) -> Result<(), TestCaseError> {
    let src = hostile.source();
    let result = generate_source(&src, "test.ssm");
    if hostile.must_reject() {
        let report = match result {
            Err(r) => r,
            Ok(_) => return Err(TestCaseError::fail(format!("accepted:\n{src}"))),
        };
        // Every error is located; the first is at one of the renamed names
        // (later ones may follow from it: a law that is no longer affine
        // once a parameter is called `v`).
        let at = error_positions(&report);
        let errors = report.lines().filter(|l| l.starts_with("error:")).count();
        prop_assert!(
            !at.is_empty() && at.len() == errors,
            "unlocated errors in\n{report}"
        );
        prop_assert!(
            name_positions(hostile).contains(&at[0]),
            "first error at {:?} is not at a name:\n{report}\n{src}",
            at[0]
        );
        return Ok(());
    }
    let generated = match result {
        Ok(g) => g,
        Err(r) => return Err(TestCaseError::fail(format!("rejected:\n{r}\n{src}"))),
    };
    let plain = Renaming::plain();
    let expected = rename_tokens(plain_tokens(), &maps(&plain, hostile)).to_string();
    let got = tokens_of(&generated.code).to_string();
    if expected != got {
        let at = expected
            .char_indices()
            .zip(got.chars())
            .find(|((_, a), b)| a != b)
            .map_or(expected.len().min(got.len()), |((i, _), _)| i);
        let lo = at.saturating_sub(200);
        let ctx = |s: &str| s.get(lo..(at + 200).min(s.len())).unwrap_or("").to_string();
        return Err(TestCaseError::fail(format!(
            "generated code differs beyond the renaming:\n expected …{}…\n got      …{}…\n{src}",
            ctx(&expected),
            ctx(&got)
        )));
    }
    prop_assert_eq!(generated.name, canonical(hostile.model()));
    Ok(())
}

fn hostile() -> impl Strategy<Value = Renaming> {
    prop::collection::vec(prop::sample::select(POOL), PARAMS + 4).prop_map(|v| Renaming {
        names: v.into_iter().map(str::to_string).collect(),
    })
}

/// Distinct names (after canonicalisation), so the model is accepted unless
/// a scene clashes: exercises the generated code more than random picks,
/// which mostly collide.
fn distinct_hostile() -> impl Strategy<Value = Renaming> {
    Just(POOL.to_vec()).prop_shuffle().prop_map(|pool| {
        let mut names: Vec<String> = Vec::new();
        let mut values = BTreeSet::new();
        let mut rest = pool.into_iter().cycle();
        while names.len() < PARAMS + 4 {
            let n = rest.next().expect("a cycle never ends");
            // Parameters and the let: distinct and not `v`; the model and
            // scenes may reuse a parameter's name.
            let k = names.len();
            if (1..=PARAMS + 1).contains(&k)
                && (canonical(n) == "v" || !values.insert(canonical(n)))
            {
                continue;
            }
            names.push(n.to_string());
        }
        Renaming { names }
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn random_hostile_names_are_rejected_at_a_name_or_change_nothing(r in hostile()) {
        check_renaming(&r)?;
    }

    #[test]
    fn distinct_hostile_names_change_nothing_but_the_names(r in distinct_hostile()) {
        check_renaming(&r)?;
    }
}

#[test]
fn the_plain_renaming_is_the_paper_model() {
    // The template is the paper model: same code as models/paper.ssm up to names.
    let plain = Renaming::plain();
    let paper_names = Renaming {
        names: [
            "paper",
            "m",
            "d",
            "c",
            "V",
            "V1",
            "V2",
            "mus",
            "muk",
            "mu1",
            "mu2",
            "mu3",
            "mu4",
            "g",
            "Q0",
            "W",
            "FN",
            "sweep_w",
            "reference",
        ]
        .map(String::from)
        .to_vec(),
    };
    check_renaming(&paper_names).expect("paper names");
    let _ = plain;
}

#[test]
fn every_hostile_name_in_every_role_alone() {
    // Each pool name alone, as the model, the mass `m` (read everywhere) or
    // the first scene in turn (each role takes every third name, so every
    // name is tried once and every role about 27 times; the random tests
    // cover the other roles), the other names plain.
    let plain = Renaming::plain();
    let roles = [0, 1, PARAMS + 2];
    for (i, n) in POOL.iter().enumerate() {
        let k = roles[i % roles.len()];
        let mut r = plain.clone();
        r.names[k] = n.to_string();
        if let Err(e) = check_renaming(&r) {
            panic!("role {k} named {n:?}: {e}");
        }
    }
}

#[test]
fn nfc_twins_and_needless_raw_twins_are_one_name() {
    for (a, b) in [("é", "e\u{301}"), ("mu", "r#mu"), ("gen", "r#gen")] {
        let mut r = Renaming::plain();
        r.names[1] = a.into();
        r.names[2] = b.into();
        let report = generate_source(&r.source(), "test.ssm").expect_err("one name twice");
        assert!(
            report.contains(&format!(
                "`{}` is defined twice (first at line 2, column 11)",
                canonical(a)
            )) && report.contains("--> test.ssm:3:11"),
            "{a} / {b}: {report}"
        );
    }
}

#[test]
fn delimiters_are_kept() {
    // `rename_tokens` keeps groups: a sanity check of the comparison itself.
    let t: TokenStream = "a (b) [c] {d}".parse().expect("tokens");
    let m = Maps {
        idents: [("b".to_string(), "r#fn".to_string())]
            .into_iter()
            .collect(),
        strings: Vec::new(),
    };
    let out = rename_tokens(t, &m);
    assert_eq!(out.to_string(), "a (r#fn) [c] { d }");
    let _ = Delimiter::None;
}
