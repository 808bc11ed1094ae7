//! `basins`: which attractor each start `(x, v)` at a phase reaches, over a
//! grid and random samples (`stickslip basins`), written to its file as the
//! CLI writes it, then read back for Python's arrays.

use std::path::PathBuf;
use std::sync::atomic::AtomicU64;

use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use stickslip::output::basins_summary;
use stickslip::study::basins::{run_basins_counting, BasinOptions, BasinSettings};
use stickslip::study::map::GridAxis;
use stickslip::Model;

use super::axis;
use crate::command::{params, with_model, Command, ModelSpec};
use crate::failure::{Failure, Kind};
use crate::progress::with_progress;

/// An axis of starts as Python gives it: `(from, to, count)`.
type Axis = (f64, f64, i64);

/// The JSON of `basins --json`, then every start in index order (the grid
/// row by row, then the samples): `x`, `v`, the attractor's position in the
/// JSON's list, and the largest exponent (NaN where none was computed).
type Answer = (String, Vec<f64>, Vec<f64>, Vec<i64>, Vec<f64>);

/// [`Answer`] with its columns as numpy arrays (moved, not copied).
type Arrays<'py> = (
    String,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<f64>>,
);

struct Basins<'a> {
    set: Vec<(String, f64)>,
    x: GridAxis,
    v: GridAxis,
    settings: BasinSettings,
    out: PathBuf,
    resume: bool,
    counter: &'a AtomicU64,
}

impl Command for Basins<'_> {
    type Output = Answer;
    fn run<M: Model>(self, base: M::Params) -> Result<Answer, Failure> {
        let p = params::<M>(base, &self.set)?;
        let opts = BasinOptions {
            resume: self.resume,
            ..BasinOptions::default()
        };
        let found = run_basins_counting::<M>(
            &p,
            &self.x,
            &self.v,
            &self.settings,
            Some(&self.out),
            &opts,
            Some(self.counter),
        )?;
        let json = basins_summary::json(&found)?;
        let starts = &found.starts;
        // Every start's attractor is in the summary, which is made of them.
        let id = |name: &str| {
            found
                .attractors
                .iter()
                .position(|a| a.name == name)
                .map(|k| k as i64)
                .ok_or_else(|| {
                    Failure::new(
                        Kind::Input,
                        format!("attractor `{name}` is not in the summary"),
                    )
                })
        };
        let mut a: Answer = (json, Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for s in starts {
            a.1.push(s.x);
            a.2.push(s.v);
            a.3.push(id(&s.attractor)?);
            a.4.push(s.exponent.unwrap_or(f64::NAN));
        }
        Ok(a)
    }
}

/// `stickslip basins --json`: the starts of the grid `x × v` (each `(from,
/// to, count)`) at the phase `W t = phase`, and `samples` random starts
/// (seeded by `seed`), each simulated at most `periods` forcing periods
/// (`lyapunov`: those of the exponent of a start that never settles), into
/// the file `out`, resumed from it with `resume`, with a progress bar
/// unless `progress` is false.
// One argument per Python keyword.
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (model, set, x, v, out, phase = 0.0, samples = 1000, seed = 1, periods = None, lyapunov = None, resume = false, progress = true))]
pub fn basins<'py>(
    py: Python<'py>,
    model: ModelSpec,
    set: Vec<(String, f64)>,
    x: Axis,
    v: Axis,
    out: PathBuf,
    phase: f64,
    samples: usize,
    seed: u64,
    periods: Option<u32>,
    lyapunov: Option<u32>,
    resume: bool,
    progress: bool,
) -> PyResult<Arrays<'py>> {
    let defaults = BasinSettings::default();
    let settings = BasinSettings {
        phase,
        samples,
        seed,
        periods: periods.unwrap_or(defaults.periods),
        lyapunov: lyapunov.unwrap_or(defaults.lyapunov),
    };
    let x = axis("x", x.0, x.1, x.2)?;
    let v = axis("v", v.0, v.1, v.2)?;
    let total = (x.count as u64)
        .saturating_mul(v.count as u64)
        .saturating_add(samples as u64);
    let done = with_progress(py, progress, total, "basins", |counter| {
        let cmd = Basins {
            set,
            x,
            v,
            settings,
            out,
            resume,
            counter,
        };
        with_model(&model, cmd)
    })?;
    let (json, xs, vs, ids, exponents) = done?;
    Ok((
        json,
        xs.into_pyarray(py),
        vs.into_pyarray(py),
        ids.into_pyarray(py),
        exponents.into_pyarray(py),
    ))
}
