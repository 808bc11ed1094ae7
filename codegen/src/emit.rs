//! Last pass: instance graphs → formatted, straight-line Rust.
//!
//! Each generated function is one walk over the nodes its outputs reach:
//! a node used more than once becomes `let tN = …;` (common-subexpression
//! elimination falls out of the hash-consed graph), a node used once is
//! written inline, and the pair `Ec, Es` of one `(d, w2, tau)` is computed by
//! one call whose form depends on the damping regime when it is known at
//! build time.

use std::collections::{BTreeMap, HashMap};

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use crate::diagnostic::Diagnostics;
use crate::equations;
use crate::expr::{children, Graph, Hom, Id, Node};
use crate::instance::lower_instance;
use crate::model::{MappingKind, Model};
use crate::names;
use crate::parse::BoundOp;

/// Options of one generation run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Where the model came from, for the `@generated` header (e.g. `models/paper.ssm`).
    pub origin: String,
}

/// Operator precedence of an emitted expression, lowest first.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Add,
    Mul,
    Unary,
    Atom,
}

struct Writer<'g> {
    g: &'g Graph,
    params: &'g [Ident],
    vars: HashMap<u32, Ident>,
    bound: HashMap<Id, Ident>,
}

fn literal(x: f64) -> (TokenStream, Prec) {
    if x.is_nan() {
        (quote!(f64::NAN), Prec::Atom)
    } else if x == f64::INFINITY {
        (quote!(f64::INFINITY), Prec::Atom)
    } else if x == f64::NEG_INFINITY {
        (quote!(f64::NEG_INFINITY), Prec::Atom)
    } else if x < 0.0 {
        let l = syn::LitFloat::new(&format!("{:?}", -x), Span::call_site());
        (quote!(-#l), Prec::Unary)
    } else {
        let l = syn::LitFloat::new(&format!("{x:?}"), Span::call_site());
        (quote!(#l), Prec::Atom)
    }
}

fn paren(e: (TokenStream, Prec), min: Prec) -> TokenStream {
    let (t, p) = e;
    if p >= min {
        t
    } else {
        quote!((#t))
    }
}

impl Writer<'_> {
    fn expr(&self, id: Id) -> (TokenStream, Prec) {
        if let Some(name) = self.bound.get(&id) {
            return (quote!(#name), Prec::Atom);
        }
        let g = self.g;
        match g.node(id) {
            Node::Const(bits) => literal(f64::from_bits(bits)),
            Node::Param(k) => {
                // Parameters are only ever read as fields of `p`: no local of
                // the generated code can shadow them, nor they a local.
                let name = &self.params[k as usize];
                (quote!(p.#name), Prec::Atom)
            }
            Node::Var(k) => {
                let name = &self.vars[&k];
                (quote!(#name), Prec::Atom)
            }
            Node::Add(a, b) => {
                let l = paren(self.expr(a), Prec::Add);
                if let Node::Neg(nb) = g.node(b) {
                    if !self.bound.contains_key(&b) {
                        let r = paren(self.expr(nb), Prec::Mul);
                        return (quote!(#l - #r), Prec::Add);
                    }
                }
                let r = paren(self.expr(b), Prec::Mul);
                (quote!(#l + #r), Prec::Add)
            }
            Node::Mul(a, b) => {
                let l = paren(self.expr(a), Prec::Mul);
                if let Node::Recip(rb) = g.node(b) {
                    if !self.bound.contains_key(&b) {
                        let r = paren(self.expr(rb), Prec::Unary);
                        return (quote!(#l / #r), Prec::Mul);
                    }
                }
                let r = paren(self.expr(b), Prec::Unary);
                (quote!(#l * #r), Prec::Mul)
            }
            Node::Neg(a) => {
                let a = paren(self.expr(a), Prec::Unary);
                (quote!(-#a), Prec::Unary)
            }
            Node::Recip(a) => {
                let a = paren(self.expr(a), Prec::Unary);
                (quote!(1.0 / #a), Prec::Mul)
            }
            Node::Powi(a, n) => {
                let a = paren(self.expr(a), Prec::Atom);
                let n = proc_macro2::Literal::i32_unsuffixed(n);
                (quote!(#a.powi(#n)), Prec::Atom)
            }
            Node::Sqrt(a) => self.method(a, "sqrt"),
            Node::Exp(a) => self.method(a, "exp"),
            Node::Ln(a) => self.method(a, "ln"),
            Node::Sin(a) => self.method(a, "sin"),
            Node::Cos(a) => self.method(a, "cos"),
            Node::Abs(a) => self.method(a, "abs"),
            Node::Sign(a) => self.method(a, "signum"),
            Node::Hom(..) => unreachable!("homogeneous pairs are always bound"),
        }
    }

    fn method(&self, a: Id, name: &str) -> (TokenStream, Prec) {
        let a = paren(self.expr(a), Prec::Atom);
        let m = format_ident!("{}", name);
        (quote!(#a.#m()), Prec::Atom)
    }

    /// The call computing `(Ec, Es)` for `(d, w2, tau)`, specialized when the
    /// regime is known at build time.
    fn hom_call(&self, d: Id, c: Id, tau: Id) -> TokenStream {
        let dt = self.expr(d).0;
        let tt = self.expr(tau).0;
        match (self.g.as_const(d), self.g.as_const(c)) {
            (Some(dv), Some(cv)) if dv * dv < cv => {
                let (om, _) = literal((cv - dv * dv).sqrt());
                quote!(::stickslip::model::homogeneous::underdamped(#dt, #om, #tt))
            }
            (Some(dv), Some(cv)) if dv * dv > cv => {
                let ct = self.expr(c).0;
                quote!(::stickslip::model::homogeneous::overdamped(#dt, #ct, #tt))
            }
            (Some(_), Some(_)) => quote!(::stickslip::model::homogeneous::critical(#dt, #tt)),
            _ => {
                let ct = self.expr(c).0;
                quote!(::stickslip::model::homogeneous::general(#dt, #ct, #tt))
            }
        }
    }
}

/// Straight-line code computing `outputs`: the statements and one
/// expression per output.
fn straight_line(
    g: &Graph,
    params: &[Ident],
    vars: &[(u32, &str)],
    outputs: &[Id],
) -> (TokenStream, Vec<TokenStream>) {
    let n = outputs.iter().map(|o| o.0 as usize + 1).max().unwrap_or(0);
    let mut reach = vec![false; n];
    let mut uses = vec![0u32; n];
    let mut stack: Vec<Id> = outputs.to_vec();
    for o in outputs {
        uses[o.0 as usize] += 1;
    }
    while let Some(id) = stack.pop() {
        if reach[id.0 as usize] {
            continue;
        }
        reach[id.0 as usize] = true;
        for c in children(g.node(id)) {
            uses[c.0 as usize] += 1;
            stack.push(c);
        }
    }
    let mut w = Writer {
        g,
        params,
        vars: vars
            .iter()
            .map(|(k, name)| (*k, format_ident!("{}", name)))
            .collect(),
        bound: HashMap::new(),
    };
    let mut stmts = TokenStream::new();
    let reads_params = (0..n)
        .filter(|&i| reach[i])
        .any(|i| matches!(g.node(Id(i as u32)), Node::Param(_)));
    if !reads_params {
        // Every parameter this function reads was folded at build time.
        stmts.extend(quote!(let _ = p;));
    }
    let mut homs: BTreeMap<(Id, Id, Id), (Ident, Ident)> = BTreeMap::new();
    let mut counter = 0usize;
    for i in 0..n {
        if !reach[i] {
            continue;
        }
        let id = Id(i as u32);
        let node = g.node(id);
        match node {
            Node::Const(_) | Node::Param(_) | Node::Var(_) => continue,
            Node::Hom(kind, d, c, tau) => {
                let key = (d, c, tau);
                if let std::collections::btree_map::Entry::Vacant(slot) = homs.entry(key) {
                    let (ec, es) = (
                        format_ident!("ec{}", counter),
                        format_ident!("es{}", counter),
                    );
                    counter += 1;
                    let call = w.hom_call(d, c, tau);
                    stmts.extend(quote!(let (#ec, #es) = #call;));
                    slot.insert((ec, es));
                }
                let (ec, es) = &homs[&key];
                let name = match kind {
                    Hom::Ec => ec.clone(),
                    Hom::Es => es.clone(),
                };
                w.bound.insert(id, name);
            }
            _ if uses[i] >= 2 => {
                let e = w.expr(id).0;
                let name = format_ident!("t{}", counter);
                counter += 1;
                stmts.extend(quote!(let #name = #e;));
                w.bound.insert(id, name);
            }
            _ => {}
        }
    }
    let outs = outputs.iter().map(|&o| w.expr(o).0).collect();
    (stmts, outs)
}

fn doc(lines: &[String]) -> TokenStream {
    let mut t = TokenStream::new();
    for l in lines {
        let l = format!(" {l}");
        t.extend(quote!(#[doc = #l]));
    }
    t
}

fn doc1(s: &str) -> TokenStream {
    let s = format!(" {s}");
    quote!(#[doc = #s])
}

/// A parameter or scene name as a Rust identifier (`r#fn` for `fn`). Every
/// name was checked by [`emit`] first; a name without a spelling (never
/// produced by the parser) becomes one that cannot clash with anything.
fn param_ident(name: &str) -> Ident {
    names::ident(name).unwrap_or_else(|| Ident::new("__stickslip_unnamed", Span::call_site()))
}

fn param_idents(model: &Model, free: &[usize]) -> Vec<Ident> {
    free.iter()
        .map(|&i| param_ident(&model.params[i].name))
        .collect()
}

/// The type of a model (`prefix = "Model"`) or scene (`"Scene"`).
fn type_ident(name: &str, prefix: &str) -> Ident {
    param_ident(&names::type_name(name, prefix))
}

fn bound_tokens(op: BoundOp) -> TokenStream {
    match op {
        BoundOp::Gt => quote!(::stickslip::Bound::Gt),
        BoundOp::Ge => quote!(::stickslip::Bound::Ge),
        BoundOp::Lt => quote!(::stickslip::Bound::Lt),
        BoundOp::Le => quote!(::stickslip::Bound::Le),
    }
}

/// The pieces of a `Params` struct over the free parameters `free`.
struct ParamsCode {
    names_lit: Vec<String>,
    get_arms: Vec<TokenStream>,
    set_arms: Vec<TokenStream>,
    fields: Vec<TokenStream>,
    defaults: Vec<TokenStream>,
    param_infos: Vec<TokenStream>,
    free_idx: Vec<TokenStream>,
}

impl ParamsCode {
    /// `Params`, its `Default`, and `ParamSet` with the given `check` method.
    fn items(&self, params_doc: &TokenStream, check_fn: &TokenStream) -> TokenStream {
        let ParamsCode {
            names_lit,
            get_arms,
            set_arms,
            fields,
            defaults,
            ..
        } = self;
        quote! {
            #params_doc
            #[derive(Clone, Copy, Debug, PartialEq)]
            #[allow(non_snake_case)]
            pub struct Params { #(#fields)* }

            impl ::core::default::Default for Params {
                fn default() -> Self { Self { #(#defaults)* } }
            }

            impl ::stickslip::ParamSet for Params {
                const NAMES: &'static [&'static str] = &[#(#names_lit),*];
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
}

fn params_code(model: &Model, free: &[usize]) -> ParamsCode {
    let fields = free
        .iter()
        .map(|&i| {
            let p = &model.params[i];
            let name = param_ident(&p.name);
            let mut lines = p.docs.clone();
            lines.push(format!("Default: `{}`.", p.default));
            let d = doc(&lines);
            quote!(#d pub #name: f64,)
        })
        .collect();
    let defaults = free
        .iter()
        .map(|&i| {
            let p = &model.params[i];
            let name = param_ident(&p.name);
            let (v, _) = literal(p.default);
            quote!(#name: #v,)
        })
        .collect();
    let names_lit = free
        .iter()
        .map(|&i| names::bare(&model.params[i].name).to_string())
        .collect();
    let get_arms = free
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let name = param_ident(&model.params[i].name);
            quote!(#k => self.#name,)
        })
        .collect();
    let set_arms = free
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let name = param_ident(&model.params[i].name);
            quote!(#k => self.#name = value,)
        })
        .collect();
    let param_infos = model
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let name = names::bare(&p.name);
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
    ParamsCode {
        names_lit,
        get_arms,
        set_arms,
        fields,
        defaults,
        param_infos,
        free_idx,
    }
}

/// Items of a model with a smooth law: its `Params`, a static `INFO` (a
/// `SmoothInfo`: no boundaries, the law is not piecewise) and a type
/// implementing `FrictionOscillator` and `SmoothModel`, whose `kinetic`
/// gives the law and its exact slope.
fn smooth_items(model: &Model, diags: &mut Diagnostics) -> TokenStream {
    let law = model.law.as_ref().expect("a smooth model");
    let free: Vec<usize> = (0..model.params.len()).collect();
    let mut inst = lower_instance(model, &free, diags);
    let nodes = crate::pieces::lower_law(&mut inst, law, diags);
    let pnames = param_idents(model, &free);
    let code = params_code(model, &free);
    let (param_infos, free_idx) = (&code.param_infos, &code.free_idx);
    let g = &mut inst.graph;
    let slope = g
        .diff(nodes.kinetic, crate::instance::LAW_V)
        .unwrap_or_else(|_| g.constant(f64::NAN));
    let eps = g.constant(1e-12);
    let range_eps = g.mul(nodes.range, eps);
    let above = g.add(nodes.belt, range_eps);
    let below = g.sub(nodes.belt, range_eps);
    let f_above = g.substitute(nodes.kinetic, crate::instance::LAW_V, above);
    let f_below = g.substitute(nodes.kinetic, crate::instance::LAW_V, below);
    let (kstmts, kouts) = straight_line(
        &inst.graph,
        &pnames,
        &[(crate::instance::LAW_V, "v")],
        &[nodes.kinetic, slope],
    );
    let (kf, kd) = (&kouts[0], &kouts[1]);
    let osc = [
        inst.mass,
        inst.damping,
        inst.stiffness,
        inst.forcing,
        inst.frequency,
    ];
    let (ostmts, oouts) = straight_line(&inst.graph, &pnames, &[], &osc);
    let (om, od, oc, oa, ow) = (&oouts[0], &oouts[1], &oouts[2], &oouts[3], &oouts[4]);
    // Each function computes only what it returns.
    let (bstmts, bouts) = straight_line(&inst.graph, &pnames, &[], &[nodes.belt]);
    let (sstmts, souts) = straight_line(&inst.graph, &pnames, &[], &[nodes.stick]);
    let (belt, stick) = (&bouts[0], &souts[0]);
    let cond = [
        inst.mass,
        inst.stiffness,
        inst.frequency,
        nodes.stick,
        f_above,
        f_below,
    ];
    let (cstmts, couts) = straight_line(&inst.graph, &pnames, &[], &cond);
    let (cm, cs, cw, cst, cfa, cfb) = (
        &couts[0], &couts[1], &couts[2], &couts[3], &couts[4], &couts[5],
    );
    let name = names::bare(&model.name);
    let type_ident = type_ident(&model.name, "Model");
    let docs = model.docs.join("\n");
    let law_text = quote::ToTokens::to_token_stream(&law.kinetic).to_string();
    let range_val = {
        let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
        inst.graph.eval(nodes.range, &defaults, &[])
    };
    let (range_lit, _) = literal(range_val);
    let mut lines = model.docs.clone();
    lines.push(format!(
        "Model `{}` with a smooth kinetic law: `{law_text}`.",
        model.name
    ));
    let type_doc = doc(&lines);
    let params_doc = doc1("Run-time parameters of the smooth model.");
    let smooth_check = quote! {
            fn check(&self) -> ::core::result::Result<(), ::stickslip::ParamError> {
                let p = self;
                ::stickslip::model::param::check_values(self, &INFO.identity)?;
                #cstmts
                ::stickslip::model::param::check_conditions(&[], ::stickslip::model::param::Conditions {
                    mass: #cm,
                    stiffness: #cs,
                    frequency: #cw,
                    velocities: &[],
                    stick: Some((#cst, #cfa, #cfb)),
                })
            }
    };
    let params_items = code.items(&params_doc, &smooth_check);
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
            },
            law: #law_text,
            range: #range_lit,
        };

        #type_doc
        #[derive(Clone, Copy, Debug, Default)]
        pub struct #type_ident;

        impl ::stickslip::FrictionOscillator for #type_ident {
            type Params = Params;
            const IDENTITY: &'static ::stickslip::Identity = &INFO.identity;
            #[inline]
            fn oscillator(p: &Params) -> ::stickslip::Oscillator {
                #ostmts
                ::stickslip::Oscillator { mass: #om, damping: #od, stiffness: #oc, amplitude: #oa, frequency: #ow }
            }
        }

        impl ::stickslip::model::smooth::SmoothModel for #type_ident {
            const INFO: &'static ::stickslip::model::smooth::SmoothInfo = &INFO;
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

/// Items of one instance: the full model (`scene = None`) or a scene.
fn instance_items(model: &Model, scene: Option<usize>, diags: &mut Diagnostics) -> TokenStream {
    let (free, mapping_filter, type_name, display_name): (
        Vec<usize>,
        Option<Vec<usize>>,
        Ident,
        String,
    ) = match scene {
        None => (
            (0..model.params.len()).collect(),
            None,
            type_ident(&model.name, "Model"),
            names::bare(&model.name).to_string(),
        ),
        Some(s) => {
            let sc = &model.scenes[s];
            let mut used: Vec<usize> = sc.structures.iter().flatten().copied().collect();
            used.sort_unstable();
            used.dedup();
            let filter = if sc.structures.is_empty() {
                None
            } else {
                Some(used)
            };
            (
                sc.free.clone(),
                filter,
                type_ident(&sc.name, "Scene"),
                format!("{}::{}", names::bare(&model.name), names::bare(&sc.name)),
            )
        }
    };
    let mut inst = lower_instance(model, &free, diags);
    let pnames = param_idents(model, &free);
    let type_ident = type_name;

    // --- Params ---------------------------------------------------------
    let code = params_code(model, &free);
    let (param_infos, free_idx) = (&code.param_infos, &code.free_idx);

    // --- Conditions checked at run time ---------------------------------
    let vel: Vec<Id> = inst.boundary_velocity.clone();
    let levels = model
        .stick_boundary()
        .map(|k| equations::kinetic_levels(&mut inst, k));
    let mut cond_outputs = vec![inst.mass, inst.stiffness, inst.frequency];
    cond_outputs.extend(&vel);
    if let (Some(sb), Some((la, lb))) = (inst.static_bound, levels) {
        cond_outputs.extend([sb, la, lb]);
    }
    let (cstmts, couts) = straight_line(&inst.graph, &pnames, &[], &cond_outputs);
    let (mass_t, stiff_t, freq_t) = (&couts[0], &couts[1], &couts[2]);
    let vel_t = &couts[3..3 + vel.len()];
    let stick_t = if inst.static_bound.is_some() {
        let s = &couts[3 + vel.len()..];
        let (a, b, c) = (&s[0], &s[1], &s[2]);
        quote!(Some((#a, #b, #c)))
    } else {
        quote!(None)
    };
    let check_fn = quote! {
        fn check(&self) -> ::core::result::Result<(), ::stickslip::ParamError> {
            let p = self;
            ::stickslip::model::param::check_values(self, &INFO.identity)?;
            #cstmts
            ::stickslip::model::param::check_conditions(INFO.boundaries, ::stickslip::model::param::Conditions {
                mass: #mass_t,
                stiffness: #stiff_t,
                frequency: #freq_t,
                velocities: &[#(#vel_t),*],
                stick: #stick_t,
            })
        }
    };

    // --- Static description --------------------------------------------
    let boundary_infos = model.boundaries.iter().map(|b| {
        let label = &b.label;
        let number = b.number;
        let stick = b.stick.is_some();
        let d = b.docs.join(" ");
        quote!(::stickslip::BoundaryInfo { label: #label, number: #number, stick: #stick, doc: #d },)
    });
    let domain_infos = model.domains.iter().enumerate().map(|(j, d)| {
        let label = d.label;
        let lo = match d.lower {
            Some(k) => quote!(Some(#k)),
            None => quote!(None),
        };
        let hi = match d.upper {
            Some(k) => quote!(Some(#k)),
            None => quote!(None),
        };
        let dn = inst.domains[j];
        let g = &mut inst.graph;
        let d2 = g.powi(dn.d, 2);
        let w2 = g.sub(d2, dn.c);
        let regime = match g.as_const(w2) {
            Some(w) if w < 0.0 => quote!(Some(::stickslip::Regime::Underdamped)),
            Some(w) if w > 0.0 => quote!(Some(::stickslip::Regime::Overdamped)),
            Some(_) => quote!(Some(::stickslip::Regime::Critical)),
            None => quote!(None),
        };
        let docs = d.docs.join(" ");
        quote!(::stickslip::DomainInfo { label: #label, lower: #lo, upper: #hi, fixed_regime: #regime, doc: #docs },)
    }).collect::<Vec<_>>();

    // Mappings generated: all, or those the scene's structures use; the
    // stick mapping twice (leaving up, leaving down).
    struct Gen {
        fn_name: String,
        name: String,
        domain: Option<usize>,
        from: usize,
        to: usize,
        kind: MappingKind,
        exit: Option<f64>,
    }
    let mut gens = Vec::new();
    for (i, m) in model.mappings.iter().enumerate() {
        if let Some(f) = &mapping_filter {
            if !f.contains(&i) {
                continue;
            }
        }
        let base = m.name.replace('.', "_");
        if m.kind == MappingKind::Stick {
            for (sfx, s) in [("above", 1.0), ("below", -1.0)] {
                gens.push(Gen {
                    fn_name: format!("{base}_{sfx}"),
                    name: m.name.clone(),
                    domain: None,
                    from: m.from,
                    to: m.to,
                    kind: m.kind,
                    exit: Some(s),
                });
            }
        } else {
            gens.push(Gen {
                fn_name: base,
                name: m.name.clone(),
                domain: m.domain,
                from: m.from,
                to: m.to,
                kind: m.kind,
                exit: None,
            });
        }
    }
    let mapping_infos = gens.iter().map(|m| {
        let name = &m.name;
        let (from, to) = (m.from, m.to);
        let dom = match m.domain {
            Some(j) => quote!(Some(#j)),
            None => quote!(None),
        };
        let kind = match m.kind {
            MappingKind::Local => quote!(::stickslip::MappingKind::Local),
            MappingKind::Global => quote!(::stickslip::MappingKind::Global),
            MappingKind::Stick => quote!(::stickslip::MappingKind::Stick),
        };
        let exit = match m.exit {
            Some(s) if s > 0.0 => quote!(Some(::stickslip::Side::Above)),
            Some(_) => quote!(Some(::stickslip::Side::Below)),
            None => quote!(None),
        };
        quote!(::stickslip::MappingInfo { name: #name, domain: #dom, from: #from, to: #to, kind: #kind, exit: #exit },)
    });
    let structures: Vec<String> = match scene {
        Some(s) => model.scenes[s].structure_text.clone(),
        None => Vec::new(),
    };
    let model_docs = model.docs.join("\n");
    let scene_name = match scene {
        Some(s) => {
            let n = names::bare(&model.scenes[s].name);
            quote!(Some(#n))
        }
        None => quote!(None),
    };
    let model_name = names::bare(&model.name);

    // --- Functions -------------------------------------------------------
    let mut fns = TokenStream::new();
    let mut coeff_arms = TokenStream::new();
    let mut flow_arms = TokenStream::new();
    let mut field_arms = TokenStream::new();
    let flow_vars: [(u32, &str); 4] = [(0, "x0"), (1, "v0"), (2, "phi0"), (3, "phi1")];
    for (j, d) in model.domains.iter().enumerate() {
        let label = d.label;
        let dn = inst.domains[j];
        let g = &mut inst.graph;
        let two = g.constant(2.0);
        let two_d = g.mul(two, dn.d);
        let (stmts, outs) = straight_line(&inst.graph, &pnames, &[], &[two_d, dn.c, dn.b]);
        let (a, b, c) = (&outs[0], &outs[1], &outs[2]);
        let f = format_ident!("coefficients_{}", label);
        let dc = doc1(&format!(
            "Effective coefficients of domain {label} (SPEC Eq. A.1): `x'' + 2 d_j x' + c_j x = A0 cos(W t) - b_j`."
        ));
        fns.extend(quote! {
            #dc
            #[inline]
            pub fn #f(p: &Params) -> ::stickslip::Coefficients {
                #stmts
                ::stickslip::Coefficients { two_d: #a, c: #b, b: #c }
            }
        });
        coeff_arms.extend(quote!(#j => #f(p),));

        let vars = [0, 1, 2, 3].map(|k| inst.graph.var(k));
        let (x, v) = equations::flow(&mut inst, j, vars[0], vars[1], vars[2], vars[3]);
        let (stmts, outs) = straight_line(&inst.graph, &pnames, &flow_vars, &[x, v]);
        let (xo, vo) = (&outs[0], &outs[1]);
        let f = format_ident!("flow_{}", label);
        let dc = doc(&[
            format!("Closed-form flow in domain {label} (SPEC §4, Appendix A): the state `[x, v]` at phase"),
            "`phi1 = W t` of the motion that starts at `(x0, v0)` at phase `phi0`; exact in".into(),
            "every damping regime, written in the elapsed time `(phi1 - phi0) / W`.".into(),
        ]);
        fns.extend(quote! {
            #dc
            #[inline]
            pub fn #f(p: &Params, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2] {
                #stmts
                [#xo, #vo]
            }
        });
        flow_arms.extend(quote!(#j => #f(p, x0, v0, phi0, phi1),));

        let vars = [0, 1, 2].map(|k| inst.graph.var(k));
        let (field, rate) = equations::normal_field(&mut inst, j, vars);
        let (stmts, outs) = straight_line(
            &inst.graph,
            &pnames,
            &[(0, "x"), (1, "y"), (2, "phi")],
            &[field, rate],
        );
        let (fo, ro) = (&outs[0], &outs[1]);
        let f = format_ident!("normal_field_{}", label);
        let dc = doc(&[
            format!("Normal vector field of domain {label} (Eq. 10), `F = A0 cos(phi) - f(y) - 2 d y - c x`,"),
            "and its rate along the flow `DF = F_x y + F_y F + F_phi W` (Eqs. 21–23): `[F, DF]`.".into(),
        ]);
        fns.extend(quote! {
            #dc
            #[inline]
            pub fn #f(p: &Params, x: f64, y: f64, phi: f64) -> [f64; 2] {
                #stmts
                [#fo, #ro]
            }
        });
        field_arms.extend(quote!(#j => #f(p, x, y, phi),));
    }

    let mapping_vars: [(u32, &str); 4] = [(0, "x0"), (1, "phi0"), (2, "x1"), (3, "phi1")];
    let mut residual_arms = TokenStream::new();
    let mut mapping_arms = TokenStream::new();
    for (idx, m) in gens.iter().enumerate() {
        let vars = [0, 1, 2, 3].map(|k| inst.graph.var(k));
        let f = match (m.domain, m.exit) {
            (Some(j), _) => equations::flow_mapping(&mut inst, j, m.from, m.to, vars),
            (None, Some(s)) => equations::stick_mapping(&mut inst, m.from, s, vars),
            (None, None) => unreachable!("stick mappings have an exit side"),
        };
        let mut jac = Vec::new();
        for fi in f {
            for k in 0..4u32 {
                match inst.graph.diff(fi, k) {
                    Ok(d) => jac.push(d),
                    Err(e) => {
                        diags.error(
                            Span::call_site(),
                            format!("internal: cannot differentiate mapping {}: {e:?}", m.name),
                        );
                        return TokenStream::new();
                    }
                }
            }
        }
        let what = match (m.kind, m.exit) {
            (MappingKind::Stick, Some(s)) => format!(
                "Stick mapping `{}` on {} leaving {} (Eq. 37): `f1 = x_i + V (t_{{i+1}} - t_i) - x_{{i+1}}`, \
                 `f2 = Fnf(x_{{i+1}}, t_{{i+1}}) {} as`.",
                m.name,
                model.boundaries[m.from].label,
                if s > 0.0 { "upwards" } else { "downwards" },
                if s > 0.0 { "-" } else { "+" }
            ),
            _ => format!(
                "{} mapping `{}` in domain {} from {} to {} (Eq. 38): `f1 = x_j(t_{{i+1}}) - x_{{i+1}}`, `f2 = v_j(t_{{i+1}}) - V_β`.",
                if m.kind == MappingKind::Local { "Local" } else { "Global" },
                m.name,
                model.domains[m.domain.expect("flow mapping")].label,
                model.boundaries[m.from].label,
                model.boundaries[m.to].label
            ),
        };
        let (stmts, outs) = straight_line(&inst.graph, &pnames, &mapping_vars, &f);
        let (f1, f2) = (&outs[0], &outs[1]);
        let rf = format_ident!("residual_{}", m.fn_name);
        let dc = doc(&[what.clone(), "Residual `f` only.".into()]);
        fns.extend(quote! {
            #dc
            #[inline]
            pub fn #rf(p: &Params, x0: f64, phi0: f64, x1: f64, phi1: f64) -> ::stickslip::nalgebra::Vector2<f64> {
                #stmts
                ::stickslip::nalgebra::Vector2::new(#f1, #f2)
            }
        });
        residual_arms.extend(quote!(#idx => #rf(p, x0, phi0, x1, phi1),));

        let mut outputs = f.to_vec();
        outputs.extend(&jac);
        let (stmts, outs) = straight_line(&inst.graph, &pnames, &mapping_vars, &outputs);
        let (f1, f2) = (&outs[0], &outs[1]);
        let j = &outs[2..];
        let (a00, a01, b00, b01) = (&j[0], &j[1], &j[2], &j[3]);
        let (a10, a11, b10, b11) = (&j[4], &j[5], &j[6], &j[7]);
        let mf = format_ident!("mapping_{}", m.fn_name);
        let dc = doc(&[
            what,
            "Residual and its exact Jacobian blocks `∂f/∂(x_i, W t_i)` and `∂f/∂(x_{i+1}, W t_{i+1})`.".into(),
        ]);
        fns.extend(quote! {
            #dc
            #[inline]
            pub fn #mf(p: &Params, x0: f64, phi0: f64, x1: f64, phi1: f64) -> ::stickslip::MappingEval {
                #stmts
                ::stickslip::MappingEval {
                    residual: ::stickslip::nalgebra::Vector2::new(#f1, #f2),
                    d_prev: ::stickslip::nalgebra::Matrix2::new(#a00, #a01, #a10, #a11),
                    d_next: ::stickslip::nalgebra::Matrix2::new(#b00, #b01, #b10, #b11),
                }
            }
        });
        mapping_arms.extend(quote!(#idx => #mf(p, x0, phi0, x1, phi1),));
    }

    // Boundaries, oscillator and stick forces.
    let (stmts, outs) = straight_line(&inst.graph, &pnames, &[], &vel);
    let nb = vel.len();
    fns.extend(quote! {
        /// Velocities of the boundaries, lowest first.
        #[inline]
        pub fn boundary_velocities(p: &Params) -> [f64; #nb] {
            #stmts
            [#(#outs),*]
        }
    });
    let osc = [
        inst.mass,
        inst.damping,
        inst.stiffness,
        inst.forcing,
        inst.frequency,
    ];
    let (stmts, outs) = straight_line(&inst.graph, &pnames, &[], &osc);
    let (om, od, oc, oa, ow) = (&outs[0], &outs[1], &outs[2], &outs[3], &outs[4]);
    fns.extend(quote! {
        /// The oscillator: `x'' + 2 d x' + c x = A0 cos(W t) - f(x')` (Eq. 5).
        #[inline]
        pub fn oscillator(p: &Params) -> ::stickslip::Oscillator {
            #stmts
            ::stickslip::Oscillator { mass: #om, damping: #od, stiffness: #oc, amplitude: #oa, frequency: #ow }
        }
    });
    let (stick_forces_body, static_bound_body) = match model.stick_boundary() {
        Some(k) => {
            let vars = [0, 1].map(|i| inst.graph.var(i));
            let forces = equations::stick_forces(&mut inst, k, vars);
            let (stmts, outs) =
                straight_line(&inst.graph, &pnames, &[(0, "x"), (1, "phi")], &forces);
            let (a, b, c, d, e) = (&outs[0], &outs[1], &outs[2], &outs[3], &outs[4]);
            let label = format!(
                "Forces on the stick boundary {} at `(x, W t)` (Eqs. 2, 24–25).",
                model.boundaries[k].label
            );
            let dc = doc1(&label);
            fns.extend(quote! {
                #dc
                #[inline]
                pub fn stick_forces(p: &Params, x: f64, phi: f64) -> ::stickslip::StickForces {
                    #stmts
                    ::stickslip::StickForces { non_friction: #a, input_above: #b, input_below: #c, output_above: #d, output_below: #e }
                }
            });
            let (stmts, outs) = straight_line(
                &inst.graph,
                &pnames,
                &[],
                &[inst.static_bound.expect("stick")],
            );
            let o = &outs[0];
            fns.extend(quote! {
                /// The static friction bound `as` per unit mass on the stick boundary.
                #[inline]
                pub fn static_bound(p: &Params) -> f64 {
                    #stmts
                    #o
                }
            });
            (
                quote!(Some(stick_forces(p, x, phi))),
                quote!(Some(static_bound(p))),
            )
        }
        None => (
            quote!({
                let _ = (p, x, phi);
                None
            }),
            quote!({
                let _ = p;
                None
            }),
        ),
    };

    let nan2 = quote!([f64::NAN, f64::NAN]);
    let info_doc = doc1(&format!("Static description of `{display_name}`."));
    let type_doc = if let Some(s) = scene {
        let sc = &model.scenes[s];
        let mut lines = sc.docs.clone();
        lines.push(format!(
            "Scene `{}` of model `{}`: free parameters {}; the others are folded into constants.",
            names::bare(&sc.name),
            names::bare(&model.name),
            free.iter()
                .map(|&i| format!("`{}`", names::bare(&model.params[i].name)))
                .collect::<Vec<_>>()
                .join(", ")
        ));
        doc(&lines)
    } else {
        let mut lines = model.docs.clone();
        lines.push(format!(
            "Model `{}`, every parameter free.",
            names::bare(&model.name)
        ));
        doc(&lines)
    };
    let params_doc = doc1(&format!("Run-time parameters of `{display_name}`."));
    let params_items = code.items(&params_doc, &check_fn);
    quote! {
        #params_items

        #info_doc
        pub static INFO: ::stickslip::ModelInfo = ::stickslip::ModelInfo {
            identity: ::stickslip::Identity {
                name: #display_name,
                model: #model_name,
                scene: #scene_name,
                doc: #model_docs,
                params: &[#(#param_infos)*],
                free: &[#(#free_idx)*],
            },
            boundaries: &[#(#boundary_infos)*],
            domains: &[#(#domain_infos)*],
            mappings: &[#(#mapping_infos)*],
            structures: &[#(#structures),*],
        };

        #type_doc
        #[derive(Clone, Copy, Debug, Default)]
        pub struct #type_ident;

        impl ::stickslip::FrictionOscillator for #type_ident {
            type Params = Params;
            const IDENTITY: &'static ::stickslip::Identity = &INFO.identity;
            #[inline]
            fn oscillator(p: &Params) -> ::stickslip::Oscillator { oscillator(p) }
        }

        impl ::stickslip::Model for #type_ident {
            const INFO: &'static ::stickslip::ModelInfo = &INFO;
            #[inline]
            fn coefficients(p: &Params, domain: usize) -> ::stickslip::Coefficients {
                match domain { #coeff_arms _ => ::stickslip::Coefficients::NAN }
            }
            #[inline]
            fn boundary_velocity(p: &Params, boundary: usize) -> f64 {
                boundary_velocities(p).get(boundary).copied().unwrap_or(f64::NAN)
            }
            #[inline]
            fn static_bound(p: &Params) -> ::core::option::Option<f64> { #static_bound_body }
            #[inline]
            fn flow(p: &Params, domain: usize, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2] {
                match domain { #flow_arms _ => #nan2 }
            }
            #[inline]
            fn normal_field(p: &Params, domain: usize, x: f64, y: f64, phi: f64) -> [f64; 2] {
                match domain { #field_arms _ => #nan2 }
            }
            #[inline]
            fn stick_forces(p: &Params, x: f64, phi: f64) -> ::core::option::Option<::stickslip::StickForces> { #stick_forces_body }
            #[inline]
            fn residual(p: &Params, mapping: usize, x0: f64, phi0: f64, x1: f64, phi1: f64) -> ::stickslip::nalgebra::Vector2<f64> {
                match mapping { #residual_arms _ => ::stickslip::nalgebra::Vector2::repeat(f64::NAN) }
            }
            #[inline]
            fn mapping(p: &Params, mapping: usize, x0: f64, phi0: f64, x1: f64, phi1: f64) -> ::stickslip::MappingEval {
                match mapping { #mapping_arms _ => ::stickslip::MappingEval::NAN }
            }
        }

        #fns
    }
}

/// The module body for a checked model: the full instance, then one
/// submodule per scene. Returns formatted source with the `@generated` header.
pub fn emit(model: &Model, options: &Options, diags: &mut Diagnostics) -> Option<String> {
    // The parser only accepts identifiers, so every name has a Rust spelling;
    // say so rather than emit code that does not compile, should one not.
    let scene_names = model.scenes.iter().map(|s| &s.name);
    for n in std::iter::once(&model.name)
        .chain(model.params.iter().map(|p| &p.name))
        .chain(scene_names)
    {
        if names::ident(n).is_none() {
            diags.error(
                Span::call_site(),
                format!("internal: `{n}` has no spelling as a Rust identifier"),
            );
        }
    }
    if !diags.is_empty() {
        return None;
    }
    let mut items = if model.law.is_some() {
        smooth_items(model, diags)
    } else {
        instance_items(model, None, diags)
    };
    for (s, sc) in model.scenes.iter().enumerate() {
        let body = match sc.pieces {
            Some(n) => {
                // A piecewise-linear model of the law, as its own instance.
                let pl = crate::pieces::build(model, sc, n);
                let mut check = Diagnostics::new();
                let all: Vec<usize> = (0..pl.params.len()).collect();
                let inst = lower_instance(&pl, &all, &mut check);
                crate::check::check_pieces(&pl, &inst, &mut check);
                for d in check.iter() {
                    diags.error(
                        d.span,
                        format!(
                            "in the {n}-piece model of scene `{}`: {}",
                            sc.name, d.message
                        ),
                    );
                }
                instance_items(&pl, Some(0), diags)
            }
            None => instance_items(model, Some(s), diags),
        };
        let m = param_ident(&sc.name);
        let d = doc1(&format!(
            "Scene `{}` of model `{}`.",
            names::bare(&sc.name),
            names::bare(&model.name)
        ));
        items.extend(quote! {
            #d
            pub mod #m {
                #body
            }
        });
    }
    if !diags.is_empty() {
        return None;
    }
    let file: syn::File = match syn::parse2(items) {
        Ok(f) => f,
        Err(e) => {
            diags.error(
                Span::call_site(),
                format!("internal: generated code does not parse: {e}"),
            );
            return None;
        }
    };
    let header = format!(
        "// @generated by stickslip-codegen from `{}`: do not edit.\n\
         // Model `{}`: {} domains, {} boundaries, {} mappings, {} scenes.\n\n",
        options.origin,
        names::bare(&model.name),
        model.domains.len(),
        model.boundaries.len(),
        model.mappings.len(),
        model.scenes.len()
    );
    Some(header + &prettyplease::unparse(&file))
}
