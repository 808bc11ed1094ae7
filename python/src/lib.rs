//! `stickslip._native`: the library's analyses for the Python package.
//!
//! Every function takes a model as a spec, `("name", NAME, None)`,
//! `("file", PATH, SCENE)` or `("source", TEXT, SCENE)` (as the CLI's
//! `--model` and `--model-file`, through the library's one lookup), the
//! parameters as `(name, value)` pairs (as `--set`), and returns what the
//! CLI prints with `--json` (the same serializers, so the numbers agree to
//! the last bit), which the pure-Python package (`python/stickslip/`)
//! wraps into result objects with numpy arrays; the large columns (a
//! history's samples, the basins' starts) come as numpy arrays already,
//! moved from their `Vec`s without a copy. Work runs with the GIL
//! released; a failure is raised as one of the exception types of
//! `stickslip.errors`, never a panic across the boundary.
#![forbid(unsafe_code)]

mod catalogue;
mod command;
mod diagram;
mod failure;
mod law;
mod motion;
mod progress;
mod study;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(catalogue::models, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::params, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::name, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::describe, m)?)?;
    m.add_function(wrap_pyfunction!(catalogue::check, m)?)?;
    m.add_function(wrap_pyfunction!(motion::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(law::simulate_law, m)?)?;
    m.add_function(wrap_pyfunction!(law::sweep_law, m)?)?;
    m.add_function(wrap_pyfunction!(motion::orbit, m)?)?;
    m.add_class::<motion::Trajectory>()?;
    m.add_function(wrap_pyfunction!(diagram::orbit_diagram, m)?)?;
    study::register(m)?;
    Ok(())
}
