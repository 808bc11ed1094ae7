//! Scenes: the parameters a scene frees, its `pieces`, and its structures,
//! which must name mappings the topology allows, each ending where the next
//! begins.

use crate::diagnostic::Diagnostics;
use crate::model::{Model, Scene};

/// A scene of `model`: its free parameters exist, each once; its structures parse.
pub(super) fn check_scene(
    model: &Model,
    s: crate::parse::SceneAst,
    diags: &mut Diagnostics,
) -> Option<Scene> {
    let before = diags.len();
    let mut free = Vec::new();
    for name in &s.free {
        let n = name.to_string();
        match model.params.iter().position(|p| p.name == n) {
            Some(i) if free.contains(&i) => {
                diags.error(name.span(), format!("`{n}` is freed twice"))
            }
            Some(i) => free.push(i),
            None if model.derived.iter().any(|d| d.name == n) => diags.error(
                name.span(),
                format!("`{n}` is a derived quantity; free the parameters it is computed from"),
            ),
            None => diags.error(name.span(), format!("unknown parameter `{n}`")),
        }
    }
    free.sort_unstable();
    let mut structures = Vec::new();
    let mut texts = Vec::new();
    for lit in &s.structures {
        match parse_structure(model, &lit.value()) {
            Ok(st) => {
                structures.push(st);
                texts.push(lit.value());
            }
            Err(msg) => diags.error(lit.span(), msg),
        }
    }
    let pieces = match &s.pieces {
        None if model.law.is_some() => {
            diags.error(
                s.name.span(),
                "a scene of a model with a smooth `law` needs `pieces: N;`",
            );
            None
        }
        None => None,
        Some(lit) if model.law.is_none() => {
            diags.error(
                lit.span(),
                "`pieces` builds a piecewise-linear model from a smooth `law`; this model has none",
            );
            None
        }
        Some(lit) => match lit.base10_parse::<u32>() {
            Ok(n) if (2..=128).contains(&n) && n % 2 == 0 => Some(n),
            _ => {
                diags.error(lit.span(), "`pieces` is an even number from 2 to 128 (half on each side of the belt speed)");
                None
            }
        },
    };
    (diags.len() == before).then(|| Scene {
        name: s.name.to_string(),
        docs: s.docs,
        free,
        structures,
        structure_text: texts,
        pieces,
    })
}

/// Parse `P_{3_31 0_11 3_13 4_33}` (or `P{..}`, or the names alone) into
/// mapping indices as written (the last one is applied first), by the
/// grammar the runtime uses ([`crate::structure`]): each mapping ends on the
/// boundary where the next one starts, and a stick mapping is followed by a
/// mapping into a domain.
pub fn parse_structure(model: &Model, text: &str) -> Result<Vec<usize>, String> {
    let views: Vec<crate::structure::MappingView> = model
        .mappings
        .iter()
        .map(|m| crate::structure::MappingView {
            name: &m.name,
            from: m.from,
            to: m.to,
            domain_above_from: m.domain.map(|j| model.domains[j].lower == Some(m.from)),
        })
        .collect();
    let labels: Vec<&str> = model.boundaries.iter().map(|b| b.label.as_str()).collect();
    let applied =
        crate::structure::parse(&model.name, &views, &labels, text).map_err(|e| e.to_string())?;
    Ok(applied.iter().rev().map(|&(i, _)| i).collect())
}
