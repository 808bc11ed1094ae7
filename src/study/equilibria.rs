//! Steady sliding along one parameter: the equilibrium at every grid value,
//! its eigenvalues and stability, and every change of stability located
//! between grid values (a Hopf point of a smooth law, the nonsmooth change
//! where a piecewise law's equilibrium leaves its band).
//!
//! ```
//! use stickslip::models::stribeck::{Params, Stribeck};
//! use stickslip::study::equilibria::scan_smooth;
//!
//! // The Stribeck law unforced: steady sliding is unstable at low belt
//! // speeds, where the law falls faster than the damping.
//! let base = Params { Q0: 0.0, ..Params::default() };
//! let s = scan_smooth::<Stribeck>(base, "V", 0.2, 3.0, 8)?;
//! let hopf = &s.changes[0];
//! // The textbook condition: 2 d = −f'(0) at the Hopf point.
//! let p = Params { V: hopf.change.at, ..base };
//! let slope = (0.6 - 0.3) * 9.8 / 0.4 * (-hopf.change.at / 0.4).exp() - 0.05;
//! assert!((2.0 * p.d - slope).abs() < 1e-12);
//! # Ok::<(), stickslip::ParamError>(())
//! ```

use serde::Serialize;

use crate::model::{FrictionOscillator, Model, ParamError, ParamSet, SmoothModel};
use crate::orbit::equilibrium::{
    locate, locate_in, steady_sliding, steady_sliding_smooth, Change, Equilibrium,
    EquilibriumError, Loss, Seat,
};

/// The equilibrium at one grid value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Point {
    /// The parameter value.
    pub value: f64,
    /// The equilibrium, if there is one.
    pub equilibrium: Option<Equilibrium>,
    /// Where it rests: `domain 15`, `Sigma5`, `law`.
    pub seat: Option<String>,
    /// Why there is none.
    pub none: Option<String>,
}

/// A located change of stability, with its names.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Located {
    /// The change.
    #[serde(flatten)]
    pub change: Change,
    /// What it is: `Hopf point`, `the equilibrium crosses Sigma5`.
    pub what: String,
}

/// Steady sliding along a parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Scan {
    /// The model's name.
    pub model: String,
    /// The parameter.
    pub param: String,
    /// Every grid value.
    pub points: Vec<Point>,
    /// Every change of stability between grid values, in order.
    pub changes: Vec<Located>,
}

/// `count` values from `from` to `to`, evenly spaced, the last exactly `to`.
pub fn grid(from: f64, to: f64, count: usize) -> Vec<f64> {
    match count {
        0 => Vec::new(),
        1 => vec![from],
        n => (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1) as f64;
                if i + 1 == n {
                    to
                } else {
                    from + t * (to - from)
                }
            })
            .collect(),
    }
}

#[allow(clippy::too_many_arguments)]
fn scan_with<P, E, S, L>(
    model: &str,
    param: &str,
    base: P,
    set: S,
    values: &[f64],
    at: E,
    name: L,
    locate_between: impl Fn(
        &dyn Fn(f64) -> Result<Equilibrium, EquilibriumError>,
        f64,
        f64,
    ) -> Option<Change>,
) -> Result<Scan, ParamError>
where
    P: Copy,
    S: Fn(P, f64) -> Result<P, ParamError>,
    E: Fn(&P) -> Result<Equilibrium, EquilibriumError>,
    L: Fn(&Seat) -> String,
{
    let mut points = Vec::with_capacity(values.len());
    for &value in values {
        let p = set(base, value)?;
        let e = at(&p);
        points.push(Point {
            value,
            seat: e.as_ref().ok().map(|e| name(&e.seat)),
            none: e.as_ref().err().map(ToString::to_string),
            equilibrium: e.ok(),
        });
    }
    let along = |v: f64| -> Result<Equilibrium, EquilibriumError> {
        match set(base, v) {
            Ok(p) => at(&p),
            Err(_) => Err(EquilibriumError::NoBand),
        }
    };
    let mut changes = Vec::new();
    for w in values.windows(2) {
        let (a, b) = if w[0] <= w[1] {
            (w[0], w[1])
        } else {
            (w[1], w[0])
        };
        if let Some(change) = locate_between(&along, a, b) {
            let what = match change.loss {
                Loss::Hopf => "Hopf point: the damping 2 d + f'(0) changes sign".to_string(),
                Loss::Band { boundary } => format!(
                    "the equilibrium crosses {} (the law's slope jumps)",
                    name(&Seat::Boundary {
                        boundary,
                        below: 0,
                        above: 0
                    })
                ),
                Loss::Domains { from, to } => format!(
                    "the equilibrium moves from {} to {}",
                    name(&Seat::Domain(from)),
                    name(&Seat::Domain(to))
                ),
                Loss::End => "steady sliding ends".to_string(),
            };
            changes.push(Located { change, what });
        }
    }
    Ok(Scan {
        model: model.to_string(),
        param: param.to_string(),
        points,
        changes,
    })
}

fn setter<M: FrictionOscillator>(
    param: &str,
) -> impl Fn(M::Params, f64) -> Result<M::Params, ParamError> + '_ {
    move |base: M::Params, v: f64| base.with_pairs(M::identity(&base), &[(param, v)])
}

/// Steady sliding of the piecewise-linear model `M` along `param` from
/// `from` to `to` in `count` values (the other parameters from `base`).
pub fn scan<M: Model>(
    base: M::Params,
    param: &str,
    from: f64,
    to: f64,
    count: usize,
) -> Result<Scan, ParamError> {
    let info = M::info(&base);
    let name = |seat: &Seat| seat.label(info);
    let values = grid(from, to, count);
    scan_with(
        info.name,
        param,
        base,
        setter::<M>(param),
        &values,
        steady_sliding::<M>,
        name,
        |at, a, b| locate_in::<M, _>(&base, at, a, b, 0.0),
    )
}

/// Steady sliding of the smooth-law model `M` along `param`, on the law
/// itself (its exact slope).
pub fn scan_smooth<M: SmoothModel>(
    base: M::Params,
    param: &str,
    from: f64,
    to: f64,
    count: usize,
) -> Result<Scan, ParamError> {
    scan_smooth_at::<M>(base, param, &grid(from, to, count))
}

/// Steady sliding of the smooth-law model `M` at the values `values` of
/// `param` (in order; each change located between neighbours).
pub fn scan_smooth_at<M: SmoothModel>(
    base: M::Params,
    param: &str,
    values: &[f64],
) -> Result<Scan, ParamError> {
    scan_with(
        M::identity(&base).name,
        param,
        base,
        setter::<M>(param),
        values,
        steady_sliding_smooth::<M>,
        |_| "law".to_string(),
        |at, a, b| locate(at, a, b, 0.0),
    )
}

/// Steady sliding of the piecewise-linear model `M` at the one parameter
/// set `p` (a scan of one point, with no parameter).
pub fn single<M: Model>(p: M::Params) -> Scan {
    let info = M::info(&p);
    let name = |seat: &Seat| seat.label(info);
    scan_with(
        info.name,
        "",
        p,
        |p, _| Ok(p),
        &[0.0],
        steady_sliding::<M>,
        name,
        |_, _, _| None,
    )
    .expect("a fixed parameter set")
}

/// Steady sliding of the smooth-law model `M` at the one parameter set `p`.
pub fn single_smooth<M: SmoothModel>(p: M::Params) -> Scan {
    scan_with(
        M::identity(&p).name,
        "",
        p,
        |p, _| Ok(p),
        &[0.0],
        steady_sliding_smooth::<M>,
        |_| "law".to_string(),
        |_, _, _| None,
    )
    .expect("a fixed parameter set")
}

/// What the `equilibria` command and Python's `Model.equilibria` ask of any
/// model, piecewise or a smooth law itself: its defaults with `set`
/// applied, then the one parameter set, or the scan along `range =
/// (name, from, to, count)`. Visited through [`crate::models::ModelRef`].
pub struct Request {
    /// Parameters set, `(name, value)`.
    pub set: Vec<(String, f64)>,
    /// The parameter and its grid, if any.
    pub range: Option<(String, f64, f64, usize)>,
}

impl Request {
    fn params<M: FrictionOscillator>(&self, base: M::Params) -> Result<M::Params, ParamError> {
        let pairs: Vec<(&str, f64)> = self.set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        base.with_pairs(M::identity(&base), &pairs)
    }
}

impl crate::model::ModelVisitor for Request {
    type Output = Result<Scan, ParamError>;

    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        Some(self.params::<M>(base).and_then(|p| match &self.range {
            Some((name, from, to, count)) => scan::<M>(p, name, *from, *to, *count),
            None => Ok(single::<M>(p)),
        }))
    }

    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some(self.params::<M>(base).and_then(|p| match &self.range {
            Some((name, from, to, count)) => scan_smooth::<M>(p, name, *from, *to, *count),
            None => Ok(single_smooth::<M>(p)),
        }))
    }
}
