//! Period-doubling cascades in a sweep: the chains of doublings (a branch
//! of period `N` doubling to one of `2N`, which doubles to `4N`, …), the
//! ratios of their spacings, and the cascade's accumulation point
//! extrapolated from them (Feigenbaum 1978: the spacings shrink
//! geometrically, by `δ = 4.669…` in the limit).
//!
//! With `n` located doublings at `p_1, p_2, …, p_n`, the ratios are
//! `δ_k = (p_k − p_{k−1}) / (p_{k+1} − p_k)`, and the accumulation point
//! is the geometric series' limit `p_∞ = p_n + (p_n − p_{n−1}) / (δ − 1)`,
//! once with the last measured ratio and once with Feigenbaum's constant.

use serde::Serialize;

use crate::bifurcation::TransitionKind;

/// Feigenbaum's constant `δ` (the limit of the spacing ratios of a
/// period-doubling cascade of a map with a quadratic maximum).
pub const FEIGENBAUM_DELTA: f64 = 4.669_201_609_102_99;

/// A chain of period doublings and where it accumulates.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cascade {
    /// The doublings in cascade order: the parameter value and the period
    /// `N` of the motion that doubles there.
    pub doublings: Vec<Doubling>,
    /// `δ_k = (p_k − p_{k−1}) / (p_{k+1} − p_k)`, one per three doublings.
    pub ratios: Vec<f64>,
    /// The accumulation point from the last measured ratio (three
    /// doublings or more).
    pub accumulation: Option<f64>,
    /// The accumulation point with `δ` = [`FEIGENBAUM_DELTA`] (two
    /// doublings or more).
    pub accumulation_feigenbaum: Option<f64>,
}

/// One located period doubling of a cascade.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Doubling {
    /// The parameter value.
    pub value: f64,
    /// Forcing periods of the motion that doubles there.
    #[serde(rename = "N")]
    pub n: u32,
}

/// A period doubling the sweep located: its value, the period and the
/// structure's notation of its branch.
#[derive(Clone, Copy)]
pub(super) struct Located<'a> {
    pub value: f64,
    pub kind: TransitionKind,
    pub n: u32,
    pub structure: &'a str,
}

/// The block a structure repeats: `P_{A}` of `(P_{A})^{×k}`, the structure
/// itself if it repeats none.
fn block(notation: &str) -> &str {
    match notation.strip_prefix('(').and_then(|r| r.rsplit_once(')')) {
        Some((inner, _)) => inner.trim(),
        None => notation,
    }
}

/// The cascades among the eigenvalue bifurcations `located`: every chain
/// of two or more period doublings of one repeated block, each of twice
/// the period of the one before, the nearest beyond it (in the direction
/// the chain's first two doublings set). Each doubling belongs to one
/// chain, the longest.
pub(super) fn cascades(located: &[Located]) -> Vec<Cascade> {
    let doublings: Vec<&Located> = located
        .iter()
        .filter(|l| l.kind == TransitionKind::PeriodDoubling)
        .collect();
    let next_of = |at: &Located, direction: f64| -> Option<&Located> {
        doublings
            .iter()
            .copied()
            .filter(|d| d.n == 2 * at.n && block(d.structure) == block(at.structure))
            .filter(|d| {
                let step = d.value - at.value;
                step.abs() > 1e-12 * at.value.abs().max(1.0)
                    && (direction == 0.0 || step.signum() == direction)
            })
            .min_by(|a, b| {
                (a.value - at.value)
                    .abs()
                    .total_cmp(&(b.value - at.value).abs())
            })
    };
    let mut chains: Vec<Vec<Located>> = Vec::new();
    for root in &doublings {
        // A root has no doubling of half its period in its chain's block.
        let has_parent = doublings
            .iter()
            .any(|d| 2 * d.n == root.n && block(d.structure) == block(root.structure));
        if has_parent {
            continue;
        }
        let mut chain = vec![**root];
        let mut direction = 0.0;
        while let Some(next) = next_of(&chain[chain.len() - 1], direction) {
            direction = (next.value - chain[chain.len() - 1].value).signum();
            chain.push(*next);
        }
        if chain.len() >= 2 {
            chains.push(chain);
        }
    }
    // Mirror-image motions give the same chain twice (same values and
    // periods, mirrored structures): report each once.
    chains.dedup_by(|a, b| {
        a.len() == b.len()
            && a.iter().zip(b.iter()).all(|(x, y)| {
                x.n == y.n && (x.value - y.value).abs() <= 1e-9 * x.value.abs().max(1.0)
            })
    });
    chains.iter().map(|c| cascade(c)).collect()
}

fn cascade(chain: &[Located]) -> Cascade {
    let p: Vec<f64> = chain.iter().map(|d| d.value).collect();
    let ratios: Vec<f64> = p
        .windows(3)
        .map(|w| (w[1] - w[0]) / (w[2] - w[1]))
        .collect();
    let n = p.len();
    let limit = |delta: f64| p[n - 1] + (p[n - 1] - p[n - 2]) / (delta - 1.0);
    Cascade {
        doublings: chain
            .iter()
            .map(|d| Doubling {
                value: d.value,
                n: d.n,
            })
            .collect(),
        accumulation: ratios
            .last()
            .filter(|r| r.is_finite() && **r > 1.0)
            .map(|&r| limit(r)),
        accumulation_feigenbaum: Some(limit(FEIGENBAUM_DELTA)),
        ratios,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Doublings spaced by an exact geometric ratio accumulate where the
    /// series sums to; a fold, and a doubling of another block, are not
    /// part of the chain.
    #[test]
    fn a_geometric_cascade_accumulates_at_its_limit() {
        let (p1, d, r): (f64, f64, f64) = (1.0, 0.5, 4.0);
        let values: Vec<f64> = (0..5)
            .map(|k| p1 + d * (1.0 - r.powi(-k)) / (1.0 - 1.0 / r))
            .collect();
        let names: Vec<String> = (0..5)
            .map(|k| match k {
                0 => "P_{a b}".to_string(),
                _ => format!("(P_{{a b}})^{{×{}}}", 1 << k),
            })
            .collect();
        let mut located: Vec<Located> = (0..5)
            .map(|k| Located {
                value: values[k],
                kind: TransitionKind::PeriodDoubling,
                n: 1 << k,
                structure: &names[k],
            })
            .collect();
        located.push(Located {
            value: 1.2,
            kind: TransitionKind::Fold,
            n: 4,
            structure: &names[2],
        });
        located.push(Located {
            value: 1.3,
            kind: TransitionKind::PeriodDoubling,
            n: 2,
            structure: "(P_{c d})^{×2}",
        });
        let found = cascades(&located);
        assert_eq!(found.len(), 1, "{found:?}");
        let c = &found[0];
        assert_eq!(c.doublings.len(), 5);
        assert_eq!(c.doublings[4].n, 16);
        for ratio in &c.ratios {
            assert!((ratio - r).abs() < 1e-12, "{ratio}");
        }
        let limit = p1 + d / (1.0 - 1.0 / r);
        assert!((c.accumulation.unwrap() - limit).abs() < 1e-12);
        let with_delta = values[4] + (values[4] - values[3]) / (FEIGENBAUM_DELTA - 1.0);
        assert_eq!(c.accumulation_feigenbaum, Some(with_delta));
    }
}
