//! `map`: which motions exist at each point of a grid over two parameters
//! (`stickslip map`), written to its file as the CLI writes it, then read
//! back whole for Python.

use std::path::PathBuf;
use std::sync::atomic::AtomicU64;

use pyo3::prelude::*;
use serde_json::{json, Map, Value};
use stickslip::study::map::{run_map_counting, GridAxis, MapFile, MapMethod, MapOptions, Summary};
use stickslip::Model;

use super::axis;
use crate::command::{params, with_model, Command, ModelSpec};
use crate::failure::{Failure, Kind};
use crate::progress::with_progress;

/// An axis as Python gives it: `(name, from, to, count)`.
type Axis = (String, f64, f64, i64);

struct MapCmd<'a> {
    set: Vec<(String, f64)>,
    x: GridAxis,
    y: GridAxis,
    out: PathBuf,
    opts: MapOptions,
    counter: &'a AtomicU64,
}

/// The map as JSON (`Map.to_dict()`), and each point's label
/// (`PointResult::label`) in index order.
type Answer = (String, Vec<String>);

impl Command for MapCmd<'_> {
    type Output = Answer;
    fn run<M: Model>(self, base: M::Params) -> Result<Answer, Failure> {
        let base = params::<M>(base, &self.set)?;
        let summary = run_map_counting::<M>(
            &base,
            &self.x,
            &self.y,
            &self.out,
            &self.opts,
            Some(self.counter),
        )?;
        let file = MapFile::read(&self.out)?;
        let labels = file.points.iter().map(|p| p.label()).collect();
        Ok((
            serde_json::to_string(&document(&file, &summary, &self.opts))?,
            labels,
        ))
    }
}

fn axis_json(a: &GridAxis) -> Value {
    json!({"name": a.name, "from": a.from, "to": a.to, "count": a.count})
}

/// The map as `Map.to_dict()` gives it: the file's header (model, axes,
/// the other parameters), the run, the label counts, and its records, each
/// `{"index", <x name>, <y name>, "status", "motions"}` as in the CSV.
fn document(file: &MapFile, summary: &Summary, opts: &MapOptions) -> Value {
    let h = &file.header;
    let base: Map<String, Value> = h.base.iter().map(|(n, v)| (n.clone(), json!(v))).collect();
    let points: Vec<Value> = file
        .points
        .iter()
        .map(|p| {
            let mut o = Map::new();
            o.insert("index".into(), json!(p.index));
            o.insert(h.x.name.clone(), json!(p.x));
            o.insert(h.y.name.clone(), json!(p.y));
            o.insert("status".into(), json!(p.status));
            o.insert("motions".into(), json!(p.motions));
            Value::Object(o)
        })
        .collect();
    let labels: Vec<Value> = summary
        .labels
        .iter()
        .map(|(label, n)| json!({"label": label, "points": n}))
        .collect();
    let method = match opts.method {
        MapMethod::Continuation => "continuation",
        MapMethod::Simulation => "simulation",
    };
    json!({
        "model": h.model,
        "x": axis_json(&h.x),
        "y": axis_json(&h.y),
        "base": base,
        "method": method,
        "complete": summary.complete,
        "computed": summary.computed,
        "already_done": summary.already_done,
        "labels": labels,
        "points": points,
    })
}

/// `stickslip map`: the grid `x × y` (each `(name, from, to, count)`) into
/// the file `out`, resumed from it with `resume`, with a progress bar
/// unless `progress` is false: the map as JSON (`Map.to_dict()`), and
/// each point's label in index order.
// One argument per Python keyword.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (model, set, x, y, out, method = "continuation", resume = false, progress = true))]
pub fn map(
    py: Python<'_>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    x: Axis,
    y: Axis,
    out: PathBuf,
    method: &str,
    resume: bool,
    progress: bool,
) -> PyResult<Answer> {
    let method = MapMethod::parse(method).ok_or_else(|| {
        Failure::new(
            Kind::Input,
            format!("method `{method}`: expected `continuation` or `simulation`"),
        )
    })?;
    let x = axis(&x.0, x.1, x.2, x.3)?;
    let y = axis(&y.0, y.1, y.2, y.3)?;
    let total = (x.count as u64).saturating_mul(y.count as u64);
    let opts = MapOptions {
        resume,
        method,
        ..MapOptions::default()
    };
    let done = with_progress(py, progress, total, "map", |counter| {
        let cmd = MapCmd {
            set,
            x,
            y,
            out,
            opts,
            counter,
        };
        with_model(&model, cmd)
    })?;
    Ok(done?)
}
