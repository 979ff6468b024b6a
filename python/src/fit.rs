//! `Model.fit` and `Scene.fit`: the tool's `varmass fit` (`varmass_cli::fit::fit`, and
//! `fit_scene_file` for a scene file) on data given as arrays.

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use varmass_cli::fit::{fit as fit_model, fit_scene_file, Fit, Series, Unknown};

use crate::errors::to_py;
use crate::model::NativeModel;
use crate::run::{table_block, RunFlags};

/// One measured quantity as Python gives it: the quantity, times, values and σ (or `None`).
type Measured = (String, Vec<f64>, Vec<f64>, Option<f64>);

/// What [`fit`] gives: the fitted values, their standard errors, the correlation matrix
/// (rows), the weighted residuals of each series, the runs made, whether it converged, and
/// the fitted run's recorded names and data (as `run` gives them).
type Fitted<'py> = (
    Vec<f64>,
    Vec<f64>,
    Vec<Vec<f64>>,
    Vec<Vec<f64>>,
    usize,
    bool,
    Vec<String>,
    Bound<'py, PyBytes>,
);

/// Fits `unknowns` ((name, lo, hi): a parameter or `init:x`) of `model` to `data`, from the
/// run `flags` with the parameter values `set` (the unknowns' start among them).
#[pyfunction]
pub fn fit<'py>(
    py: Python<'py>,
    model: &NativeModel,
    set: Vec<(String, f64)>,
    flags: &RunFlags,
    data: Vec<Measured>,
    unknowns: Vec<(String, f64, f64)>,
) -> PyResult<Fitted<'py>> {
    let (series, unknowns) = (series(data), unknowns_of(unknowns));
    let args = flags.args();
    let done = py
        .detach(|| fit_model(&mut model.lock(), args, set, &series, &unknowns))
        .map_err(|e| to_py(py, e))?;
    fitted(py, done)
}

/// Fits `unknowns` of the scene file at `path` to `data` (docs/sensitivities.md#fitting-a-scene):
/// [`fit`]'s result, and how many data lay outside the scene's span (left out).
#[pyfunction]
pub fn fit_scene<'py>(
    py: Python<'py>,
    path: &str,
    data: Vec<Measured>,
    unknowns: Vec<(String, f64, f64)>,
) -> PyResult<(Fitted<'py>, usize)> {
    let (series, unknowns) = (series(data), unknowns_of(unknowns));
    let path = std::path::PathBuf::from(path);
    let (done, left_out) = py
        .detach(|| fit_scene_file(&path, series, &unknowns))
        .map_err(|e| to_py(py, e))?;
    Ok((fitted(py, done)?, left_out))
}

/// The measured series as the tool takes them.
fn series(data: Vec<Measured>) -> Vec<Series> {
    (data.into_iter())
        .map(|(quantity, times, values, sigma)| Series {
            quantity,
            times,
            values,
            sigma,
        })
        .collect()
}

/// The unknowns (name, lo, hi) as the tool takes them.
fn unknowns_of(unknowns: Vec<(String, f64, f64)>) -> Vec<Unknown> {
    (unknowns.into_iter())
        .map(|(name, lo, hi)| Unknown {
            name,
            bounds: (lo, hi),
        })
        .collect()
}

/// The fit `done` as Python's `FitResult` takes it.
fn fitted(py: Python<'_>, done: Fit) -> PyResult<Fitted<'_>> {
    let correlation = (0..done.values.len())
        .map(|i| done.correlation.row(i).iter().copied().collect())
        .collect();
    let data = table_block(py, &done.table)?;
    Ok((
        done.values,
        done.errors,
        correlation,
        done.residuals,
        done.evaluations,
        done.converged,
        done.table.names.clone(),
        data,
    ))
}
