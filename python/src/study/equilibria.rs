//! `equilibria`: steady sliding of an unforced model, its eigenvalues and
//! stability, at one parameter set or along a parameter with every change
//! of stability located (`stickslip equilibria`). A smooth-law model is
//! taken as the law itself.

use pyo3::prelude::*;
use stickslip::models::UnknownModel;
use stickslip::study::equilibria::{scan, scan_smooth, single, single_smooth, Scan};
use stickslip::{Model, ModelVisitor, ParamSet, SmoothModel};

use crate::command::{lookup, ModelSpec};
use crate::failure::{Failure, Kind};

struct Equilibria {
    set: Vec<(String, f64)>,
    range: Option<(String, f64, f64, usize)>,
}

impl Equilibria {
    fn pairs(&self) -> Vec<(&str, f64)> {
        self.set.iter().map(|(n, v)| (n.as_str(), *v)).collect()
    }
}

impl ModelVisitor for Equilibria {
    type Output = Result<Scan, Failure>;

    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        Some((|| {
            let p = base.with_pairs(M::identity(&base), &self.pairs())?;
            Ok(match &self.range {
                Some((name, from, to, count)) => scan::<M>(p, name, *from, *to, *count)?,
                None => single::<M>(p),
            })
        })())
    }

    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some((|| {
            let p = base.with_pairs(M::identity(&base), &self.pairs())?;
            Ok(match &self.range {
                Some((name, from, to, count)) => scan_smooth::<M>(p, name, *from, *to, *count)?,
                None => single_smooth::<M>(p),
            })
        })())
    }
}

/// `stickslip equilibria --json`: at the parameters `set`, or along
/// `range = (name, from, to, count)`.
#[pyfunction]
#[pyo3(signature = (model, set, range = None))]
pub fn equilibria(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    range: Option<(String, f64, f64, i64)>,
) -> PyResult<String> {
    let range = match range {
        Some((name, from, to, count)) => {
            let axis = super::axis(&name, from, to, count)?;
            Some((axis.name, axis.from, axis.to, axis.count))
        }
        None => None,
    };
    let model = lookup(&model)?;
    let cmd = Equilibria { set, range };
    let scan = py.detach(|| {
        model.visit(cmd)?.unwrap_or_else(|| {
            Err(match &model {
                stickslip::models::ModelRef::Name(name) => {
                    UnknownModel { name: name.clone() }.into()
                }
                other => Failure::new(Kind::Model, format!("`{other}`: no model to study")),
            })
        })
    })?;
    Ok(serde_json::to_string_pretty(&scan).map_err(Failure::from)?)
}
