//! A loaded model's description, [`ModelInfo`] or [`SmoothInfo`], from the
//! generator's declarations: what the Rust back end writes as a `static
//! INFO`, made once per loaded model and leaked (a loaded model lives as
//! long as the process; see [`super::intern`]).

use stickslip_codegen::equations::Regime as BuildRegime;
use stickslip_codegen::expand::{Instance, ParamDecl, Route, Smooth};
use stickslip_codegen::model::MappingKind as BuildKind;
use stickslip_codegen::parse::BoundOp;

use crate::model::info::{
    Bound, BoundaryInfo, DomainInfo, Identity, MappingInfo, MappingKind, ModelInfo, ParamInfo, Side,
};
use crate::model::oscillator::Regime;
use crate::model::smooth::SmoothInfo;

fn leak_str(s: &str) -> &'static str {
    Box::leak(s.to_owned().into_boxed_str())
}

fn leak<T>(v: Vec<T>) -> &'static [T] {
    Box::leak(v.into_boxed_slice())
}

fn bound(op: BoundOp) -> Bound {
    match op {
        BoundOp::Gt => Bound::Gt,
        BoundOp::Ge => Bound::Ge,
        BoundOp::Lt => Bound::Lt,
        BoundOp::Le => Bound::Le,
    }
}

fn params(decls: &[ParamDecl], free: &[usize]) -> &'static [ParamInfo] {
    leak(
        decls
            .iter()
            .enumerate()
            .map(|(i, p)| ParamInfo {
                name: leak_str(&p.name),
                default: p.default,
                bounds: leak(p.bounds.iter().map(|&(op, b)| (bound(op), b)).collect()),
                doc: leak_str(&p.docs.join(" ")),
                free: free.contains(&i),
            })
            .collect(),
    )
}

/// The identity of a loaded model or scene.
fn identity(
    (name, model, scene, doc): (&str, &str, Option<&str>, &str),
    decls: &[ParamDecl],
    free: &[usize],
    source_hash: u64,
) -> Identity {
    Identity {
        name: leak_str(name),
        model: leak_str(model),
        scene: scene.map(leak_str),
        doc: leak_str(doc),
        params: params(decls, free),
        free: leak(free.to_vec()),
        source_hash: Some(source_hash),
    }
}

/// The description of a piecewise-linear instance whose domains have the
/// damping regimes `regimes` (where fixed by the file).
pub(super) fn piecewise(
    inst: &Instance,
    regimes: &[Option<BuildRegime>],
    source_hash: u64,
) -> &'static ModelInfo {
    let names = (
        inst.display_name.as_str(),
        inst.model_name.as_str(),
        inst.scene_name.as_deref(),
        inst.model_docs.as_str(),
    );
    let boundaries = inst
        .boundaries
        .iter()
        .map(|b| BoundaryInfo {
            label: leak_str(&b.label),
            number: b.number,
            stick: b.stick,
            doc: leak_str(&b.docs.join(" ")),
        })
        .collect();
    let domains = inst
        .domains
        .iter()
        .zip(regimes)
        .map(|(d, regime)| DomainInfo {
            label: d.label,
            lower: d.lower,
            upper: d.upper,
            fixed_regime: regime.map(|r| match r {
                BuildRegime::Underdamped => Regime::Underdamped,
                BuildRegime::Overdamped => Regime::Overdamped,
                BuildRegime::Critical => Regime::Critical,
            }),
            doc: leak_str(&d.docs.join(" ")),
        })
        .collect();
    let mappings = inst
        .mappings
        .iter()
        .map(|m| {
            let (domain, exit) = match m.route {
                Route::Flow { domain } => (Some(domain), None),
                Route::Stick { above: true } => (None, Some(Side::Above)),
                Route::Stick { above: false } => (None, Some(Side::Below)),
            };
            MappingInfo {
                name: leak_str(&m.name),
                domain,
                from: m.from,
                to: m.to,
                kind: match m.kind {
                    BuildKind::Local => MappingKind::Local,
                    BuildKind::Global => MappingKind::Global,
                    BuildKind::Stick => MappingKind::Stick,
                },
                exit,
            }
        })
        .collect();
    Box::leak(Box::new(ModelInfo {
        identity: identity(names, &inst.params, &inst.free, source_hash),
        boundaries: leak(boundaries),
        domains: leak(domains),
        mappings: leak(mappings),
        structures: leak(inst.structures.iter().map(|s| leak_str(s)).collect()),
    }))
}

/// The description of a smooth-law model (every parameter free).
pub(super) fn smooth(s: &Smooth, source_hash: u64) -> &'static SmoothInfo {
    let free: Vec<usize> = (0..s.params.len()).collect();
    let names = (s.name.as_str(), s.name.as_str(), None, s.docs.as_str());
    Box::leak(Box::new(SmoothInfo {
        identity: identity(names, &s.params, &free, source_hash),
        law: leak_str(&s.law_text),
        range: s.range,
    }))
}

/// The names of the free parameters, in order (the `Params` fields).
pub(super) fn names(identity: &Identity) -> &'static [&'static str] {
    leak(
        identity
            .free
            .iter()
            .map(|&i| identity.params[i].name)
            .collect(),
    )
}
