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
    /// A repeated block whose power is not `^{×k}` with a whole `k ≥ 1`.
    Repeat(String),
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
            Self::Repeat(text) => write!(
                f,
                "`{text}` is not a repeated structure: write `(P_{{1_11 0_11 2_11}})^{{×4}}` (a block and how many times it repeats, at least 1)"
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
/// A block repeated `k` times may be written `(P_{…})^{×k}` (also `^×k`,
/// `^{xk}`, `^{*k}`): a period-doubling cascade's motions are one block of
/// mappings repeated, with other switching points in each repetition.
pub fn written_names(text: &str) -> Result<Vec<&str>, StructureError> {
    let t = text.trim();
    if let Some(rest) = t.strip_prefix('(') {
        let (inner, power) = rest
            .rsplit_once(')')
            .ok_or_else(|| StructureError::Unbalanced(t.to_string()))?;
        let k = repetitions(power).ok_or_else(|| StructureError::Repeat(t.to_string()))?;
        let block = written_names(inner)?;
        return Ok(block
            .iter()
            .copied()
            .cycle()
            .take(block.len() * k)
            .collect());
    }
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

/// `k` of a power `^{×k}` (or `^×k`, `^{xk}`, `^{*k}`, `^k`), at least 1.
fn repetitions(power: &str) -> Option<usize> {
    let p = power.trim().strip_prefix('^')?.trim();
    let p = match p.strip_prefix('{') {
        Some(inner) => inner.strip_suffix('}')?.trim(),
        None => p,
    };
    let p = p
        .strip_prefix('×')
        .or_else(|| p.strip_prefix('x'))
        .or_else(|| p.strip_prefix('*'))
        .unwrap_or(p)
        .trim();
    p.parse::<usize>().ok().filter(|&k| k >= 1)
}

/// The mapping names written right to left (`names`, in written order),
/// compactly: a sequence that is one block repeated `k ≥ 2` times is
/// written `(P_{block})^{×k}` with the shortest such block, any other as
/// `P_{…}`. [`written_names`] reads both back.
pub fn notation(names: &[&str]) -> String {
    let m = names.len();
    let block = (1..m)
        .filter(|b| m % b == 0)
        .find(|&b| names.chunks(b).all(|c| c == &names[..b]));
    match block {
        Some(b) => format!("(P_{{{}}})^{{×{}}}", names[..b].join(" "), m / b),
        None => format!("P_{{{}}}", names.join(" ")),
    }
}

/// How many times the block of a compact notation `(P_{…})^{×k}` repeats
/// (`k`), or 1 for a structure written out.
pub fn repeats(notation: &str) -> usize {
    let t = notation.trim();
    if !t.starts_with('(') {
        return 1;
    }
    t.rsplit_once(')')
        .and_then(|(_, power)| repetitions(power))
        .unwrap_or(1)
}

/// The forcing periods a structure's notation implies when none is given:
/// one per repetition of a compact block (a period-doubling cascade's
/// motion of `N` periods is its period-one block repeated `N` times),
/// else 1.
pub fn implied_periods(notation: &str) -> u32 {
    u32::try_from(repeats(notation)).unwrap_or(u32::MAX)
}

/// A structure's name with its period `N`: `P_{…}^N`, the `^N` left out
/// where the notation implies it ([`implied_periods`]: `P_{…}` of one
/// forcing period, `(P_{…})^{×k}` of `k`) and for an autonomous cycle
/// (`N = 0`: its period is a time, not a number of forcing periods).
pub fn with_periods(notation: &str, n: u32) -> String {
    // n = 0: an autonomous cycle, whose period is a time, not a number of
    // forcing periods.
    if n == 0 || n == implied_periods(notation) {
        notation.to_string()
    } else {
        format!("{notation}^{n}")
    }
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

    #[test]
    fn a_repeated_block_is_written_compactly_and_read_back() {
        let names = ["a", "b", "a", "b", "a", "b"];
        assert_eq!(notation(&names), "(P_{a b})^{×3}");
        assert_eq!(written_names("(P_{a b})^{×3}").unwrap(), names);
        for same in [
            "(P_{a b})^×3",
            "( P{a b} )^{x3}",
            "(a b)^{*3}",
            "(P_{a b})^3",
        ] {
            assert_eq!(written_names(same).unwrap(), names, "{same}");
        }
        // No repetition, or a block only in part: written out in full.
        assert_eq!(notation(&["a", "b", "c"]), "P_{a b c}");
        assert_eq!(notation(&["a", "b", "a"]), "P_{a b a}");
        assert_eq!(notation(&["a"]), "P_{a}");
        // The shortest block: four times `a b`, not twice `a b a b`.
        assert_eq!(
            notation(&["a", "b", "a", "b", "a", "b", "a", "b"]),
            "(P_{a b})^{×4}"
        );
        for bad in [
            "(P_{a b})^{×0}",
            "(P_{a b})^{×}",
            "(P_{a b})",
            "(P_{a b})^{×2.5}",
        ] {
            assert!(
                matches!(written_names(bad), Err(StructureError::Repeat(_))),
                "{bad}"
            );
        }
        assert!(matches!(
            written_names("(P_{a b}^{×2}"),
            Err(StructureError::Unbalanced(_))
        ));
        // The period: implied by the repetitions, written where it is not.
        assert_eq!(implied_periods("(P_{a b})^{×4}"), 4);
        assert_eq!(implied_periods("P_{a b}"), 1);
        assert_eq!(with_periods("(P_{a b})^{×4}", 4), "(P_{a b})^{×4}");
        assert_eq!(with_periods("(P_{a b})^{×4}", 8), "(P_{a b})^{×4}^8");
        assert_eq!(with_periods("P_{a b}", 1), "P_{a b}");
        assert_eq!(with_periods("P_{a b}", 2), "P_{a b}^2");
    }
}
