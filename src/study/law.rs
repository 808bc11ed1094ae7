//! A smooth law itself along a parameter (`stickslip sweep` of a model with
//! a smooth law and no scene): at every grid value, steady sliding with its
//! stability and every self-excited cycle on the section `v = 0`, stable
//! and unstable ([`crate::orbit::smooth::ReturnMap::cycles`]); between grid
//! values, the located changes: the equilibrium's change of stability (the
//! Hopf point, from [`crate::study::equilibria`]) and where the stick-slip
//! cycle appears or vanishes (its stick shrinks to nothing where it meets
//! the slip cycle: a non-smooth fold of cycles), by bisection on the
//! existence of a stick-slip cycle through the stick's end.

use serde::Serialize;

use crate::model::oscillator::FrictionOscillator;
use crate::model::param::{ParamError, ParamSet};
use crate::model::smooth::SmoothModel;
use crate::orbit::smooth::{ReturnMap, SmoothCycle, SmoothError};
use crate::study::equilibria::{grid, scan_smooth_at, Located, Point as Rest};

/// Relative tolerance of the integrator.
const RTOL: f64 = 1e-12;

/// One grid value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LawPoint {
    /// Steady sliding there (or why there is none).
    #[serde(flatten)]
    pub rest: Rest,
    /// Every cycle through the section, by its section point `x`.
    pub cycles: Vec<SmoothCycle>,
}

/// Where the stick-slip cycle appears or vanishes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StickSlipEdge {
    /// The parameter value (the bracket's end where the cycle exists).
    pub at: f64,
    /// Whether the cycle exists below `at` (else above).
    pub below: bool,
    /// What it is.
    pub what: String,
}

/// The law along a parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LawSweep {
    /// The model's name.
    pub model: String,
    /// The parameter.
    pub param: String,
    /// Every grid value.
    pub points: Vec<LawPoint>,
    /// The equilibrium's changes of stability, located.
    pub changes: Vec<Located>,
    /// Where the stick-slip cycle appears or vanishes, located.
    pub stick_slip: Vec<StickSlipEdge>,
}

/// Why the sweep failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LawError {
    /// A parameter the model rejects.
    #[error(transparent)]
    Params(#[from] ParamError),
    /// The forcing is on.
    #[error("the forcing is on (A0 = {0}): a sweep of the smooth law itself follows the unforced oscillator's steady sliding and cycles; set the forcing amplitude to 0 (e.g. --set Q0=0), or sweep one of its `pieces` scenes (--scene)")]
    Forced(f64),
    /// No values to sweep.
    #[error("no values to sweep: give at least one")]
    Empty,
    /// The integration failed at a grid value.
    #[error("at {param} = {value}: {source}")]
    At {
        /// The parameter.
        param: String,
        /// Its value.
        value: f64,
        /// What failed.
        source: SmoothError,
    },
}

/// The smooth law `M` along `param` from `from` to `to` in `count` values
/// (the others from `base`; the forcing must be off).
pub fn sweep_law<M: SmoothModel>(
    base: M::Params,
    param: &str,
    from: f64,
    to: f64,
    count: usize,
) -> Result<LawSweep, LawError> {
    sweep_law_at::<M>(base, param, &grid(from, to, count))
}

/// The smooth law `M` at the values `values` of `param`, in order (the
/// others from `base`; the forcing must be off).
pub fn sweep_law_at<M: SmoothModel>(
    base: M::Params,
    param: &str,
    values: &[f64],
) -> Result<LawSweep, LawError> {
    let set = |v: f64| base.with_pairs(M::identity(&base), &[(param, v)]);
    let Some(&first) = values.first() else {
        return Err(LawError::Empty);
    };
    let amplitude = <M as FrictionOscillator>::oscillator(&set(first)?).amplitude;
    if amplitude != 0.0 {
        return Err(LawError::Forced(amplitude));
    }
    let scan = scan_smooth_at::<M>(base, param, values)?;
    let at = |value: f64, source: SmoothError| LawError::At {
        param: param.to_string(),
        value,
        source,
    };
    let mut points = Vec::with_capacity(scan.points.len());
    let mut has_stick_slip = Vec::with_capacity(scan.points.len());
    for rest in scan.points {
        let value = rest.value;
        let cycles = if rest.equilibrium.is_some() {
            let map = ReturnMap::<M>::new(set(value)?, RTOL).map_err(|e| at(value, e))?;
            map.cycles().map_err(|e| at(value, e))?
        } else {
            Vec::new()
        };
        has_stick_slip.push(cycles.iter().any(|c| c.stick > 0.0));
        points.push(LawPoint { rest, cycles });
    }
    let exists = |v: f64| -> Result<bool, LawError> {
        let map = ReturnMap::<M>::new(set(v)?, RTOL).map_err(|e| at(v, e))?;
        Ok(map.stick_slip().map_err(|e| at(v, e))?.is_some())
    };
    let mut stick_slip = Vec::new();
    for (i, w) in has_stick_slip.windows(2).enumerate() {
        if w[0] == w[1] {
            continue;
        }
        let (mut a, mut b) = (points[i].rest.value, points[i + 1].rest.value);
        let below = w[0];
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if m <= a.min(b) || m >= a.max(b) || (b - a).abs() <= 1e-13 * m.abs().max(1e-300) {
                break;
            }
            if exists(m)? == below {
                a = m;
            } else {
                b = m;
            }
        }
        let edge = if below { a } else { b };
        stick_slip.push(StickSlipEdge {
            at: edge,
            below,
            what: format!(
                "the stick-slip cycle {} {} here: its stick shrinks to nothing where it meets the slip cycle (a non-smooth fold of cycles)",
                if below { "exists below" } else { "exists above" },
                if below { "and vanishes" } else { "and is born" },
            ),
        });
    }
    Ok(LawSweep {
        model: scan.model,
        param: scan.param,
        points,
        changes: scan.changes,
        stick_slip,
    })
}
