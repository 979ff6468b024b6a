//! `varmass._native`: the extension module under the `varmass` Python package.
//!
//! It is deliberately thin: a model is loaded and run by the command line tool's own code
//! (`varmass_cli`), so a run from Python has the tool's semantics and messages, and an
//! ensemble is the core's (`varmass::core::ensemble`). Argument checking that is about
//! Python types, and the user-facing classes (`Model`, `Solution`, `Ensemble`, …), live in
//! the pure-Python package beside it (`python/varmass/`).
//!
//! Every function that computes releases the GIL (`Python::detach`); every failure is a
//! Python exception (`errors.rs`), never a panic across the boundary.

mod ensemble;
mod errors;
mod fit;
mod model;
mod run;
mod sample;
mod scene;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The tool's list of methods, so that Python's checks cannot drift from it.
    m.add("METHODS", varmass_cli::args::Method::names())?;
    m.add_function(wrap_pyfunction!(model::load, m)?)?;
    m.add_function(wrap_pyfunction!(run::options, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::run_scene, m)?)?;
    m.add_class::<model::NativeModel>()?;
    m.add_class::<run::RunFlags>()?;
    m.add_class::<run::Details>()?;
    m.add_class::<scene::NativeScene>()?;
    m.add_class::<ensemble::NativeEnsemble>()?;
    m.add_class::<ensemble::NativePartial>()?;
    Ok(())
}
