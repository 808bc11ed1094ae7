//! The brute-force orbit diagram: at each value of one
//! parameter, after a transient, `K` stroboscopic samples `(x, v)` at
//! `W t ≡ 0 (mod 2π)` of the simulated motion; swept up and down, each
//! value starting from the previous value's final state, so that
//! hysteresis shows as a difference between the two directions. Beside it,
//! the largest Lyapunov exponent at each value ([`largest_exponent`]), and
//! the periodic branches `sweep` knows, at the same stroboscopic section
//! ([`branch_sections`]): the picture that connects the exact analysis
//! with what a simulation shows.
//!
//! Deterministic: each direction is one sequential simulation; the two
//! directions run in parallel.

mod section;

use serde::Serialize;

use crate::dynamics::simulate::{SimError, SimOptions, Simulator};
use crate::model::param::{ParamError, ParamSet};
use crate::model::Model;
use crate::orbit::lyapunov::{spectrum, LyapunovOptions};

pub use section::{branch_sections, overlay_branches, BranchSection, SectionPoint};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// How long to simulate at each value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiagramOptions {
    /// Forcing periods simulated and discarded at each value.
    pub transient: u32,
    /// Stroboscopic samples kept at each value (one per forcing period).
    pub periods: u32,
    /// Forcing periods of the largest Lyapunov exponent at each value (0: none).
    pub lyapunov: u32,
    /// The state `(x, v)` at `W t = 0` the first value of each direction starts from.
    pub start: (f64, f64),
}

impl Default for DiagramOptions {
    fn default() -> Self {
        Self {
            transient: 500,
            periods: 100,
            lyapunov: 500,
            start: (0.0, 0.0),
        }
    }
}

/// What the simulation shows at one parameter value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Column {
    /// The parameter value.
    pub value: f64,
    /// Displacements at the stroboscopic samples, in time order.
    pub x: Vec<f64>,
    /// Velocities there.
    pub v: Vec<f64>,
    /// The largest Lyapunov exponent per unit time (`None`: not computed or
    /// failed; `-inf`, shown as `null` in JSON, where a stick collapses the map).
    pub exponent: Option<f64>,
    /// Why the value has no samples (invalid parameters, a simulation error).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The orbit diagram over one parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrbitDiagram {
    /// The parameter.
    pub param: String,
    /// Increasing values, each starting from the previous one's final state.
    pub up: Vec<Column>,
    /// Decreasing values, likewise.
    pub down: Vec<Column>,
    /// The periodic branches at the section (empty without a sweep).
    pub branches: Vec<BranchSection>,
}

/// Why the diagram could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DiagramError {
    /// Not a parameter of the model.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// A bad range.
    #[error("bad orbit-diagram range: {0}")]
    Range(String),
    /// Zero samples asked for.
    #[error("--periods must be at least 1")]
    NoSamples,
}

/// The values of a range, ascending (the range may be given either way).
pub fn values(from: f64, to: f64, count: usize) -> Result<Vec<f64>, DiagramError> {
    if !(from.is_finite() && to.is_finite()) {
        return Err(DiagramError::Range(format!(
            "the bounds {from} and {to} must be finite"
        )));
    }
    if count == 0 {
        return Err(DiagramError::Range(
            "the point count must be at least 1".into(),
        ));
    }
    let (a, b) = (from.min(to), from.max(to));
    Ok((0..count)
        .map(|i| match (i, count) {
            (0, _) => a,
            (i, n) if i + 1 == n => b,
            (i, n) => a + (b - a) * i as f64 / (n - 1) as f64,
        })
        .collect())
}

/// The orbit diagram of `M` at `base` over parameter `name` (without branches:
/// add them with [`branch_sections`]).
pub fn orbit_diagram<M: Model>(
    base: M::Params,
    name: &str,
    from: f64,
    to: f64,
    count: usize,
    opts: DiagramOptions,
) -> Result<OrbitDiagram, DiagramError> {
    let index = base.index_of(name).ok_or_else(|| ParamError::Unknown {
        name: name.to_string(),
        model: M::info(&base).name.to_string(),
        known: base.names().join(", "),
    })?;
    if opts.periods == 0 {
        return Err(DiagramError::NoSamples);
    }
    let (sx, sv) = opts.start;
    if !(sx.is_finite() && sv.is_finite()) {
        return Err(DiagramError::Range(format!(
            "the start ({sx}, {sv}) must be finite"
        )));
    }
    let ascending = values(from, to, count)?;
    let descending: Vec<f64> = ascending.iter().rev().copied().collect();
    let (up, down) = rayon::join(
        || direction::<M>(base, index, &ascending, opts),
        || direction::<M>(base, index, &descending, opts),
    );
    Ok(OrbitDiagram {
        param: name.to_string(),
        up,
        down,
        branches: Vec::new(),
    })
}

/// One direction: the values in order, each from the previous final state.
fn direction<M: Model>(
    base: M::Params,
    index: usize,
    values: &[f64],
    opts: DiagramOptions,
) -> Vec<Column> {
    let mut state = opts.start;
    values
        .iter()
        .map(|&value| {
            let mut p = base;
            p.set(index, value);
            let column = Simulator::<M>::new(p, SimOptions::default())
                .and_then(|sim| column(&sim, value, state, opts));
            match column {
                Ok((c, end)) => {
                    state = end;
                    c
                }
                Err(e) => Column {
                    value,
                    x: Vec::new(),
                    v: Vec::new(),
                    exponent: None,
                    error: Some(e.to_string()),
                },
            }
        })
        .collect()
}

/// The samples at one value from `(x, v)` at `W t = 0`, and the final state.
fn column<M: Model>(
    sim: &Simulator<M>,
    value: f64,
    (x, v): (f64, f64),
    opts: DiagramOptions,
) -> Result<(Column, (f64, f64)), SimError> {
    let mut seg = sim.start(x, v, 0.0)?;
    let transient = TAU * f64::from(opts.transient);
    seg = sim.run(seg, transient, |_| {})?;
    let after = sim.state_at(&seg, transient);
    let k = opts.periods as usize;
    let (mut xs, mut vs) = (Vec::with_capacity(k), Vec::with_capacity(k));
    for i in 1..=opts.periods {
        let phase = transient + TAU * f64::from(i);
        seg = sim.run(seg, phase, |_| {})?;
        let (x, v) = sim.state_at(&seg, phase);
        xs.push(x);
        vs.push(v);
    }
    let end = (xs[k - 1], vs[k - 1]);
    let exponent = if opts.lyapunov == 0 {
        None
    } else {
        largest_exponent(sim, after, opts.lyapunov)
    };
    Ok((
        Column {
            value,
            x: xs,
            v: vs,
            exponent,
            error: None,
        },
        end,
    ))
}

/// The largest Lyapunov exponent (per unit time) of the stroboscopic map
/// from `(x, v)` at `W t = 0`, over `periods` forcing periods without a
/// further transient: the one call of the spectrum in the orbit diagram.
pub fn largest_exponent<M: Model>(
    sim: &Simulator<M>,
    (x, v): (f64, f64),
    periods: u32,
) -> Option<f64> {
    let opts = LyapunovOptions {
        transient: 0,
        periods,
    };
    spectrum(sim, (x, v, 0.0), opts)
        .ok()
        .map(|s| s.exponents[0])
}
