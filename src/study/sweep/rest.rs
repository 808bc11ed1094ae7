//! No motion (NM): the forced response of one domain that never reaches a
//! boundary. It is no branch of switching points; the sweep checks it at
//! every grid value from its closed form and locates where it starts to
//! graze a boundary by bisection.

use crate::dynamics::simulate::Simulator;
use crate::model::Model;
use crate::orbit::attractor::{self, NoMotion};

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
            let found = with(base, index, hi)
                .ok()
                .and_then(settle::simulator::<M>)
                .map(|s| settle::from_rest(&s, opts));
            let to = found
                .as_ref()
                .map_or("invalid".to_string(), |f| settle::name(info, f));
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
