//! Third pass: a checked model → the checked instances it generates, one
//! per generated type.
//!
//! * the model itself, every parameter free ([`Instance`]), or for a model
//!   with a smooth law its [`Smooth`] type;
//! * each scene: the parameters it frees, the mappings its structures use;
//! * each `pieces: N` scene of a smooth model: an N-piece model of the law,
//!   built on the expression graph ([`pieces`]) and checked here.
//!
//! Every fact the emitter needs is established here: Rust spellings of the
//! names, which mappings exist and on which side a stick mapping leaves,
//! the lowered graph. After this pass nothing can fail but an internal
//! derivative ([`crate::equations`]).

pub mod pieces;

use proc_macro2::{Ident, Span};

use crate::diagnostic::Diagnostics;
use crate::law::{lower_law, LawNodes};
use crate::lowered::{lower_instance, Lowered};
use crate::model::{Mapping, MappingKind, Model, Scene};
use crate::names;
use crate::parse::BoundOp;

/// Everything one model file generates.
pub struct Expanded {
    /// What the `@generated` header says about the model.
    pub header: Header,
    /// The model's own type.
    pub main: Main,
    /// One module per scene, in the order written.
    pub scenes: Vec<SceneModule>,
}

/// The model's own type: piecewise (affine domains) or a smooth law.
pub enum Main {
    /// A model of affine domains.
    Piecewise(Box<Instance>),
    /// A model with a smooth kinetic law.
    Smooth(Box<Smooth>),
}

/// The counts the `@generated` header states.
pub struct Header {
    /// The model's name, without `r#`.
    pub name: String,
    /// Numbers of domains, boundaries, mappings and scenes of the model.
    pub domains: usize,
    /// See `domains`.
    pub boundaries: usize,
    /// See `domains`.
    pub mappings: usize,
    /// See `domains`.
    pub scenes: usize,
}

/// A scene's module.
pub struct SceneModule {
    /// The module's name.
    pub module: Ident,
    /// Its one-line doc.
    pub doc: String,
    /// The scene's type.
    pub instance: Instance,
}

/// A parameter as the generated code declares it.
#[derive(Clone, Debug)]
pub struct ParamDecl {
    /// The field name (`r#fn` for `fn`).
    pub ident: Ident,
    /// The name as the user wrote it, without `r#`.
    pub name: String,
    /// Doc comment lines.
    pub docs: Vec<String>,
    /// Default value.
    pub default: f64,
    /// Bounds a run-time value must satisfy.
    pub bounds: Vec<(BoundOp, f64)>,
}

/// A boundary of a generated type.
#[derive(Clone, Debug)]
pub struct BoundaryDecl {
    /// `Sigma1`.
    pub label: String,
    /// `1`.
    pub number: u32,
    /// Doc comment lines.
    pub docs: Vec<String>,
    /// Whether the mass can stick here.
    pub stick: bool,
}

/// A domain of a generated type.
#[derive(Clone, Debug)]
pub struct DomainDecl {
    /// `1`.
    pub label: u32,
    /// Doc comment lines.
    pub docs: Vec<String>,
    /// Index of the lower boundary.
    pub lower: Option<usize>,
    /// Index of the upper boundary.
    pub upper: Option<usize>,
}

/// A generated mapping: the stick mapping is generated twice (leaving up,
/// leaving down).
#[derive(Clone, Debug)]
pub struct MappingDecl {
    /// Suffix of its functions (`3_31`, `0_11_above`).
    pub fn_name: String,
    /// The mapping's name (`3_31`, `0_11`).
    pub name: String,
    /// Boundary it starts on.
    pub from: usize,
    /// Boundary it ends on.
    pub to: usize,
    /// Local, global or stick.
    pub kind: MappingKind,
    /// Where the motion goes.
    pub route: Route,
}

/// How a mapping moves.
#[derive(Clone, Copy, Debug)]
pub enum Route {
    /// Through domain `domain`.
    Flow {
        /// Index of the domain.
        domain: usize,
    },
    /// Sticking on `from`, then leaving above or below it.
    Stick {
        /// Whether it leaves to the domain above.
        above: bool,
    },
}

/// One generated type implementing `Model`: the model or one scene.
pub struct Instance {
    /// Every parameter of the model.
    pub params: Vec<ParamDecl>,
    /// Indices of the free ones (the others are folded).
    pub free: Vec<usize>,
    /// `Paper`, `SweepW`.
    pub type_ident: Ident,
    /// The type's doc comment lines.
    pub type_doc: Vec<String>,
    /// `paper` or `paper::sweep_w`.
    pub display_name: String,
    /// `paper`.
    pub model_name: String,
    /// `sweep_w`, for a scene.
    pub scene_name: Option<String>,
    /// The model's doc comment.
    pub model_docs: String,
    /// The scene's structures as written.
    pub structures: Vec<String>,
    /// Boundaries, lowest first.
    pub boundaries: Vec<BoundaryDecl>,
    /// Domains, lowest first.
    pub domains: Vec<DomainDecl>,
    /// The mappings generated.
    pub mappings: Vec<MappingDecl>,
    /// The lowered graph (free parameters symbolic).
    pub lowered: Lowered,
}

impl Instance {
    /// The index of the stick boundary and its static bound, if any.
    pub fn stick(&self) -> Option<(usize, crate::expr::Id)> {
        let k = self.boundaries.iter().position(|b| b.stick)?;
        Some((k, self.lowered.static_bound?))
    }
}

/// The type of a model with a smooth law (implements `SmoothModel`).
pub struct Smooth {
    /// Every parameter (all free).
    pub params: Vec<ParamDecl>,
    /// `Stribeck`.
    pub type_ident: Ident,
    /// The model's name without `r#`.
    pub name: String,
    /// The type's doc comment lines.
    pub type_doc: Vec<String>,
    /// The model's doc comment.
    pub docs: String,
    /// The kinetic law as written.
    pub law_text: String,
    /// The range of the pieces at the defaults.
    pub range: f64,
    /// The lowered graph.
    pub lowered: Lowered,
    /// The law's nodes.
    pub law: LawNodes,
}

/// Expand a checked model into its instances. Errors here are those of
/// the generated piecewise-linear models (and internal ones).
pub fn expand(model: &Model) -> Result<Expanded, Diagnostics> {
    let mut diags = Diagnostics::new();
    let spelled = |n: &str, diags: &mut Diagnostics| -> Ident {
        // The parser only accepts identifiers, so every name has a Rust
        // spelling; say so rather than emit code that does not compile.
        names::ident(n).unwrap_or_else(|| {
            diags.error(
                Span::call_site(),
                format!("internal: `{n}` has no spelling as a Rust identifier"),
            );
            Ident::new("__stickslip_unnamed", Span::call_site())
        })
    };
    let _ = spelled(&model.name, &mut diags);
    let params: Vec<ParamDecl> = model
        .params
        .iter()
        .map(|p| ParamDecl {
            ident: spelled(&p.name, &mut diags),
            name: names::bare(&p.name).to_string(),
            docs: p.docs.clone(),
            default: p.default,
            bounds: p.bounds.clone(),
        })
        .collect();
    let modules: Vec<Ident> = model
        .scenes
        .iter()
        .map(|s| spelled(&s.name, &mut diags))
        .collect();
    if !diags.is_empty() {
        return Err(diags);
    }
    let main = match &model.law {
        Some(law) => Main::Smooth(Box::new(smooth(model, law, params.clone(), &mut diags))),
        None => Main::Piecewise(Box::new(piecewise(model, None, &params, &mut diags))),
    };
    let mut scenes = Vec::new();
    for ((s, sc), module) in model.scenes.iter().enumerate().zip(modules) {
        let instance = match (sc.pieces, &model.law) {
            (Some(n), Some(law)) => pieces::instance(model, law, sc, n, &params, &mut diags),
            _ => piecewise(model, Some(s), &params, &mut diags),
        };
        let doc = format!(
            "Scene `{}` of model `{}`.",
            names::bare(&sc.name),
            names::bare(&model.name)
        );
        scenes.push(SceneModule {
            module,
            doc,
            instance,
        });
    }
    if !diags.is_empty() {
        return Err(diags);
    }
    let header = Header {
        name: names::bare(&model.name).to_string(),
        domains: model.domains.len(),
        boundaries: model.boundaries.len(),
        mappings: model.mappings.len(),
        scenes: model.scenes.len(),
    };
    Ok(Expanded {
        header,
        main,
        scenes,
    })
}

/// The smooth model's own type.
fn smooth(
    model: &Model,
    law: &crate::model::Law,
    params: Vec<ParamDecl>,
    diags: &mut Diagnostics,
) -> Smooth {
    let all: Vec<usize> = (0..model.params.len()).collect();
    let mut lowered = lower_instance(model, &all, diags);
    let nodes = lower_law(&mut lowered, law, diags);
    let law_text = quote::ToTokens::to_token_stream(&law.kinetic).to_string();
    let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
    let range = lowered.graph.eval(nodes.range, &defaults, &[]);
    let mut type_doc = model.docs.clone();
    type_doc.push(format!(
        "Model `{}` with a smooth kinetic law: `{law_text}`.",
        model.name
    ));
    Smooth {
        params,
        type_ident: type_ident(&model.name, "Model"),
        name: names::bare(&model.name).to_string(),
        type_doc,
        docs: model.docs.join("\n"),
        law_text,
        range,
        lowered,
        law: nodes,
    }
}

/// The type of a model or scene (`prefix` `"Model"` or `"Scene"`).
fn type_ident(name: &str, prefix: &str) -> Ident {
    names::ident(&names::type_name(name, prefix))
        .unwrap_or_else(|| Ident::new("__stickslip_unnamed", Span::call_site()))
}

/// The model (`scene = None`) or one of its scenes, of a piecewise model.
fn piecewise(
    model: &Model,
    scene: Option<usize>,
    params: &[ParamDecl],
    diags: &mut Diagnostics,
) -> Instance {
    let boundaries = model
        .boundaries
        .iter()
        .map(|b| BoundaryDecl {
            label: b.label.clone(),
            number: b.number,
            docs: b.docs.clone(),
            stick: b.stick.is_some(),
        })
        .collect();
    let domains = model
        .domains
        .iter()
        .map(|d| DomainDecl {
            label: d.label,
            docs: d.docs.clone(),
            lower: d.lower,
            upper: d.upper,
        })
        .collect();
    let sc = scene.map(|s| &model.scenes[s]);
    let free: Vec<usize> = match sc {
        Some(sc) => sc.free.clone(),
        None => (0..model.params.len()).collect(),
    };
    let parts = Parts {
        boundaries,
        domains,
        mappings: &model.mappings,
        lowered: lower_instance(model, &free, diags),
    };
    assemble(model, sc, params, parts)
}

/// The topology and graph of a generated type.
pub(crate) struct Parts<'a> {
    pub boundaries: Vec<BoundaryDecl>,
    pub domains: Vec<DomainDecl>,
    /// Every mapping the topology allows.
    pub mappings: &'a [Mapping],
    pub lowered: Lowered,
}

/// The instance of `model` (`scene = None`) or of a scene, from its parts.
pub(crate) fn assemble(
    model: &Model,
    sc: Option<&Scene>,
    params: &[ParamDecl],
    parts: Parts,
) -> Instance {
    let free = parts.lowered.free.clone();
    Instance {
        params: params.to_vec(),
        mappings: mapping_decls(parts.mappings, sc),
        type_doc: type_doc(model, sc, &free),
        type_ident: match sc {
            Some(sc) => type_ident(&sc.name, "Scene"),
            None => type_ident(&model.name, "Model"),
        },
        display_name: match sc {
            Some(sc) => format!("{}::{}", names::bare(&model.name), names::bare(&sc.name)),
            None => names::bare(&model.name).to_string(),
        },
        model_name: names::bare(&model.name).to_string(),
        scene_name: sc.map(|sc| names::bare(&sc.name).to_string()),
        model_docs: model.docs.join("\n"),
        structures: sc.map(|sc| sc.structure_text.clone()).unwrap_or_default(),
        free,
        boundaries: parts.boundaries,
        domains: parts.domains,
        lowered: parts.lowered,
    }
}

/// The doc comment of a model's or scene's type.
fn type_doc(model: &Model, scene: Option<&Scene>, free: &[usize]) -> Vec<String> {
    match scene {
        Some(sc) => {
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
            lines
        }
        None => {
            let mut lines = model.docs.clone();
            lines.push(format!(
                "Model `{}`, every parameter free.",
                names::bare(&model.name)
            ));
            lines
        }
    }
}

/// The mappings generated: all, or those the scene's structures use; the
/// stick mapping twice (leaving up, leaving down).
fn mapping_decls(mappings: &[Mapping], scene: Option<&Scene>) -> Vec<MappingDecl> {
    let used: Option<Vec<usize>> = scene
        .filter(|sc| !sc.structures.is_empty())
        .map(|sc| sc.structures.iter().flatten().copied().collect());
    let mut out = Vec::new();
    for (i, m) in mappings.iter().enumerate() {
        if used.as_ref().is_some_and(|u| !u.contains(&i)) {
            continue;
        }
        let base = m.name.replace('.', "_");
        let decl = |fn_name: String, route| MappingDecl {
            fn_name,
            name: m.name.clone(),
            from: m.from,
            to: m.to,
            kind: m.kind,
            route,
        };
        match m.domain {
            Some(domain) => out.push(decl(base, Route::Flow { domain })),
            None => {
                for (sfx, above) in [("above", true), ("below", false)] {
                    out.push(decl(format!("{base}_{sfx}"), Route::Stick { above }));
                }
            }
        }
    }
    out
}
