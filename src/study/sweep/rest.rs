//! No motion (NM): the forced response of one domain that never reaches a
//! boundary. It is no branch of switching points; the sweep checks it at
//! every grid value from its closed form and locates where it starts to
//! graze a boundary by bisection.

use crate::dynamics::simulate::Simulator;
use crate::model::Model;
use crate::orbit::attractor::{self, Attractor, NoMotion};
use crate::orbit::equilibrium::{locate_in, steady_sliding, Loss, Verdict};
use crate::orbit::motion::OrbitError;

use super::explore::Explorer;
use super::settle;
use super::{with, SweepOptions, Transition, TransitionKind};

/// The steady forced response in `domain`, if it is an attractor (damped)
/// that stays inside the band.
pub(super) fn steady_nm<M: Model>(sim: &Simulator<M>, domain: usize) -> Option<NoMotion> {
    // On the forced response itself the homogeneous part is zero.
    let r = crate::orbit::steady::steady_response::<M>(sim.params(), domain)?;
    let x = r.a + r.offset;
    let v = sim.oscillator().frequency * r.b;
    attractor::no_motion_certificate(sim, domain, x, v, 0.0)
}

/// The NM of every domain at every grid value (`None` where there is none),
/// and the transitions where one starts to graze, between grid values where
/// it exists and where it does not, located to the sweep's tolerance; past
/// each edge a simulation from rest says what lives there.
pub(super) fn regimes<M: Model>(
    base: &M::Params,
    index: usize,
    values: &[f64],
    opts: &SweepOptions,
    explorer: &mut Explorer<'_, M>,
) -> Vec<Vec<NoMotion>> {
    let info = M::info(base);
    let domains = info.domains.len();
    let at = |value: f64, j: usize| {
        with(base, index, value)
            .ok()
            .and_then(settle::simulator::<M>)
            .and_then(|s| steady_nm(&s, j))
    };
    let grid: Vec<Vec<Option<NoMotion>>> = values
        .iter()
        .map(|&v| (0..domains).map(|j| at(v, j)).collect())
        .collect();
    // `j` is the domain: it indexes the grid's rows and names the domain.
    #[allow(clippy::needless_range_loop)]
    for j in 0..domains {
        for i in 1..values.len() {
            let (a, b) = (grid[i - 1][j].is_some(), grid[i][j].is_some());
            if a == b {
                continue;
            }
            // NM at `lo`, none at `hi`.
            let (mut lo, mut hi) = if a {
                (values[i - 1], values[i])
            } else {
                (values[i], values[i - 1])
            };
            if let Some(edge) = steady_sliding_edge::<M>(base, index, lo, hi, explorer, opts) {
                if let Some(t) = edge {
                    explorer.transition(t);
                }
                continue;
            }
            for _ in 0..200 {
                if (hi - lo).abs() <= opts.tolerance {
                    break;
                }
                let mid = 0.5 * (lo + hi);
                if at(mid, j).is_some() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let (to, found) = past::<M>(base, index, hi, opts);
            let dom = info.domains[j];
            let boundary = [dom.upper, dom.lower]
                .into_iter()
                .flatten()
                .next()
                .map(|k| info.boundaries[k].label.to_string());
            explorer.transition(Transition {
                value: lo,
                from: "NM".into(),
                to,
                kind: TransitionKind::Grazing,
                boundary,
            });
            if let Some(found) = found {
                explorer.take(hi, &found);
            }
        }
    }
    grid.into_iter()
        .map(|row| row.into_iter().flatten().collect())
        .collect()
}

/// An NM edge of an unforced model, where the NM is steady sliding: the
/// equilibrium leaving one domain's band is no grazing. Where it goes on,
/// stable, in the next band, nothing happens (`Some(None)`); where it
/// loses stability, the change is located exactly ([`locate_in`]) and is a
/// [`TransitionKind::SteadySliding`], with what a simulation from rest
/// finds past it. `None` for a forced model (the edge is a grazing).
fn steady_sliding_edge<M: Model>(
    base: &M::Params,
    index: usize,
    lo: f64,
    hi: f64,
    explorer: &mut Explorer<'_, M>,
    opts: &SweepOptions,
) -> Option<Option<Transition>> {
    let at = |v: f64| {
        with(base, index, v)
            .map_err(|_| crate::orbit::equilibrium::EquilibriumError::NoBand)
            .and_then(|p| steady_sliding::<M>(&p))
    };
    let e_lo = at(lo).ok()?;
    if e_lo.verdict != Verdict::Stable {
        return None;
    }
    if matches!(at(hi), Ok(e) if e.verdict == Verdict::Stable) {
        return Some(None);
    }
    let (a, b) = if lo < hi { (lo, hi) } else { (hi, lo) };
    let p = with(base, index, lo).ok()?;
    let change = locate_in::<M, _>(&p, at, a, b, 0.0)?;
    let info = M::info(base);
    let boundary = match change.loss {
        Loss::Band { boundary } => Some(info.boundaries[boundary].label.to_string()),
        _ => None,
    };
    let (to, found) = past::<M>(base, index, hi, opts);
    if let Some(found) = found {
        explorer.take(hi, &found);
    }
    Some(Some(Transition {
        value: change.at,
        from: "steady sliding".into(),
        to,
        kind: TransitionKind::SteadySliding,
        boundary,
    }))
}

/// What a simulation from rest finds at `value` past an edge, and its name
/// (`invalid` where the parameters are).
fn past<M: Model>(
    base: &M::Params,
    index: usize,
    value: f64,
    opts: &SweepOptions,
) -> (String, Option<Result<Attractor, OrbitError>>) {
    let found = with(base, index, value)
        .ok()
        .and_then(settle::simulator::<M>)
        .map(|s| settle::from_rest(&s, opts));
    let to = found
        .as_ref()
        .map_or("invalid".to_string(), |f| settle::name(M::info(base), f));
    (to, found)
}
