//! The grammar of mapping structures `P_{σm … σ2 σ1}` (SPEC §6), shared by
//! the checker (a scene's `structures: ".."`) and the runtime
//! (`stickslip::structure::Structure::parse`), so that a structure a scene
//! accepts at build time is one the runtime accepts, and the other way round.
//!
//! The grammar: `P_{NAMES}`, `P{NAMES}` or bare `NAMES`, where `NAMES` are
//! mapping names separated by whitespace, written right to left (the last
//! one is applied first). Consecutive mappings (in application order, and
//! the last back to the first) must meet on a boundary; a stick mapping must
//! be followed by a mapping that leaves the stick boundary into a domain,
//! which decides the side it exits to.
//!
//! This module needs no parser library: the runtime compiles it alone
//! (`stickslip-codegen` without its default `generator` feature).

use std::fmt;

/// Why a structure was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StructureError {
    /// No mapping named.
    Empty,
    /// `P_{` without its `}`, or a `}` without `P_{`.
    Unbalanced(String),
    /// A name that is not a mapping of the model.
    UnknownMapping {
        /// The name.
        name: String,
        /// The model.
        model: String,
        /// The model's mappings.
        known: String,
    },
    /// Consecutive mappings do not meet.
    Disconnected {
        /// The earlier mapping (in application order).
        first: String,
        /// Where it ends.
        ends_on: String,
        /// The mapping applied next.
        second: String,
        /// Where that one starts.
        starts_on: String,
    },
    /// Two stick mappings in a row, or a stick mapping with nowhere to go.
    StickExit(String),
    /// A period of zero forcing cycles.
    ZeroPeriod,
}

impl fmt::Display for StructureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => write!(f, "an empty mapping structure"),
            Self::Unbalanced(text) => write!(
                f,
                "`{text}` is not a structure: write `P_{{3_31 0_11 3_13 4_33}}` or the names alone"
            ),
            Self::UnknownMapping { name, model, known } => {
                write!(f, "`{name}` is not a mapping of model `{model}` (it has {known})")
            }
            Self::Disconnected {
                first,
                ends_on,
                second,
                starts_on,
            } => write!(
                f,
                "{first} ends on {ends_on}, but {second} starts on {starts_on}"
            ),
            Self::StickExit(name) => write!(
                f,
                "the stick mapping {name} must be followed by a mapping that leaves the stick boundary into a domain"
            ),
            Self::ZeroPeriod => write!(f, "the period N must be at least 1 forcing period"),
        }
    }
}

impl std::error::Error for StructureError {}

/// A mapping as the grammar sees it.
#[derive(Clone, Copy, Debug)]
pub struct MappingView<'a> {
    /// `j_βα`.
    pub name: &'a str,
    /// Boundary index it starts on.
    pub from: usize,
    /// Boundary index it ends on.
    pub to: usize,
    /// For a mapping through a domain: whether the domain lies above `from`.
    /// `None` for the stick mapping.
    pub domain_above_from: Option<bool>,
}

/// The side a stick mapping leaves to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// Towards higher velocities.
    Above,
    /// Towards lower velocities.
    Below,
}

/// The mapping names as written (right to left: the last is applied first).
pub fn written_names(text: &str) -> Result<Vec<&str>, StructureError> {
    let t = text.trim();
    let inner = match t.strip_prefix("P_{").or_else(|| t.strip_prefix("P{")) {
        Some(rest) => rest
            .strip_suffix('}')
            .ok_or_else(|| StructureError::Unbalanced(t.to_string()))?,
        None => t,
    };
    if inner.contains(['{', '}']) {
        return Err(StructureError::Unbalanced(t.to_string()));
    }
    let names: Vec<&str> = inner.split_whitespace().collect();
    if names.is_empty() {
        return Err(StructureError::Empty);
    }
    Ok(names)
}

/// Resolve mapping names given in application order against the model's
/// mappings (`labels`: boundary labels by index, for messages). Returns,
/// per step, the index of the first mapping of that name and, for the stick
/// mapping, the side the next mapping needs it to exit to.
pub fn resolve(
    model: &str,
    mappings: &[MappingView],
    labels: &[&str],
    applied: &[&str],
) -> Result<Vec<(usize, Option<Exit>)>, StructureError> {
    if applied.is_empty() {
        return Err(StructureError::Empty);
    }
    let unknown = |name: &str| {
        let mut known: Vec<&str> = Vec::new();
        for m in mappings {
            if !known.contains(&m.name) {
                known.push(m.name);
            }
        }
        StructureError::UnknownMapping {
            name: name.to_string(),
            model: model.to_string(),
            known: known.join(", "),
        }
    };
    let mut found = Vec::with_capacity(applied.len());
    for name in applied {
        found.push(
            mappings
                .iter()
                .position(|m| m.name == *name)
                .ok_or_else(|| unknown(name))?,
        );
    }
    let n = found.len();
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let m = &mappings[found[k]];
        let exit = match m.domain_above_from {
            Some(_) => None,
            None => {
                let next = &mappings[found[(k + 1) % n]];
                match next.domain_above_from {
                    Some(true) => Some(Exit::Above),
                    Some(false) => Some(Exit::Below),
                    None => return Err(StructureError::StickExit(m.name.to_string())),
                }
            }
        };
        out.push((found[k], exit));
    }
    for k in 0..n {
        let (a, b) = (&mappings[found[k]], &mappings[found[(k + 1) % n]]);
        if a.to != b.from {
            let label = |i: usize| labels.get(i).copied().unwrap_or("?").to_string();
            return Err(StructureError::Disconnected {
                first: a.name.to_string(),
                ends_on: label(a.to),
                second: b.name.to_string(),
                starts_on: label(b.from),
            });
        }
    }
    Ok(out)
}

/// [`written_names`] then [`resolve`], in application order.
pub fn parse(
    model: &str,
    mappings: &[MappingView],
    labels: &[&str],
    text: &str,
) -> Result<Vec<(usize, Option<Exit>)>, StructureError> {
    let mut names = written_names(text)?;
    names.reverse();
    resolve(model, mappings, labels, &names)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notations_and_their_errors() {
        assert_eq!(written_names("P_{a b}").unwrap(), ["a", "b"]);
        assert_eq!(written_names(" P{a  b} ").unwrap(), ["a", "b"]);
        assert_eq!(written_names("a b").unwrap(), ["a", "b"]);
        assert_eq!(written_names("P_{}"), Err(StructureError::Empty));
        assert_eq!(written_names("  "), Err(StructureError::Empty));
        assert!(matches!(
            written_names("P_{a b"),
            Err(StructureError::Unbalanced(_))
        ));
        assert!(matches!(
            written_names("a b}"),
            Err(StructureError::Unbalanced(_))
        ));
    }
}
