//! `curves`: the two-parameter transition curves of a box (`stickslip curves`).

use pyo3::prelude::*;
use stickslip::output::curves_table;
use stickslip::study::curves::{curves_with, CurvesOptions, CurvesSettings};
use stickslip::Model;

use crate::command::{params, with_model, Command, ModelSpec};
use crate::failure::Failure;

/// A side of the box as Python gives it: `(name, from, to)`.
type Side = (String, f64, f64);

struct Curves {
    set: Vec<(String, f64)>,
    x: Side,
    y: Side,
    seeds: Vec<(String, f64)>,
    at: Vec<(String, f64)>,
    settings: CurvesSettings,
}

impl Command for Curves {
    type Output = String;
    fn run<M: Model>(self, base: M::Params) -> Result<String, Failure> {
        let base = params::<M>(base, &self.set)?;
        let mut opts = CurvesOptions {
            x: (self.x.0, [self.x.1, self.x.2]),
            y: (self.y.0, [self.y.1, self.y.2]),
            seeds: Vec::new(),
            at: Vec::new(),
        };
        for (name, value) in &self.seeds {
            let line = opts.line("seed", name, *value)?;
            opts.seeds.push(line);
        }
        for (name, value) in &self.at {
            let line = opts.line("at", name, *value)?;
            opts.at.push(line);
        }
        let found = curves_with::<M>(&base, &opts, &self.settings)?;
        Ok(curves_table::json(&found)?)
    }
}

/// `stickslip curves --json`: the curves of the box `x × y` (each `(name,
/// from, to)`), from the seed lines `seeds` (`(name, value)`: the sweep
/// along the other parameter), with their crossings of the lines `at`;
/// `count` grid values per line's sweep, `spread` extra lines each way,
/// `max_mappings` the longest motion whose transitions are traced,
/// `probes` the short sweeps across each curve, `max_partners` the curves
/// traced by branch switching at codimension-two points, `edges` the box's
/// edges swept too (default true).
// One argument per Python keyword.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (model, set, x, y, seeds = Vec::new(), at = Vec::new(), count = None, spread = None, max_mappings = None, probes = None, max_partners = None, edges = true))]
pub fn curves(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    x: Side,
    y: Side,
    seeds: Vec<(String, f64)>,
    at: Vec<(String, f64)>,
    count: Option<usize>,
    spread: Option<usize>,
    max_mappings: Option<usize>,
    probes: Option<usize>,
    max_partners: Option<usize>,
    edges: bool,
) -> PyResult<String> {
    let defaults = CurvesSettings::default();
    let cmd = Curves {
        set,
        x,
        y,
        seeds,
        at,
        settings: CurvesSettings {
            count: count.unwrap_or(defaults.count),
            spread: spread.unwrap_or(defaults.spread),
            max_mappings: max_mappings.unwrap_or(defaults.max_mappings),
            probes: probes.unwrap_or(defaults.probes),
            max_partners: max_partners.unwrap_or(defaults.max_partners),
            edges,
            ..defaults
        },
    };
    Ok(py.detach(|| with_model(&model, cmd))?)
}
