//! `Model.fit` and `Scene.fit`: the tool's `varmass fit` (`varmass_cli::fit::fit`, and
//! `fit_scene_file` for a scene file) on data given as arrays, and its `--predict`.

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use varmass_cli::fit::{fit as fit_model, fit_scene_file, Fit, Predict, Series, Unknown};

use crate::errors::to_py;
use crate::model::NativeModel;
use crate::run::{table_block, RunFlags};

/// One measured quantity as Python gives it: the quantity, times, values and σ (or `None`).
type Measured = (String, Vec<f64>, Vec<f64>, Option<f64>);

/// A prediction as Python takes it: the condition, the event's time and its error, its
/// time on the data's clock and its error (with the data's offset fitted), and each data
/// quantity's (name, value, error) there.
type Predicted = (
    String,
    (f64, f64),
    Option<(f64, f64)>,
    Vec<(String, f64, f64)>,
);

/// What [`fit`] gives: the fitted values, their standard errors, the correlation matrix
/// (rows), the weighted residuals of each series, the runs made, whether it converged, the
/// fitted run's recorded names and data (as `run` gives them), and the prediction asked
/// (`None` without one) or why it failed.
type Fitted<'py> = (
    Vec<f64>,
    Vec<f64>,
    Vec<Vec<f64>>,
    Vec<Vec<f64>>,
    usize,
    bool,
    Vec<String>,
    Bound<'py, PyBytes>,
    (Option<Predicted>, Option<String>),
);

/// A prediction asked from Python: the condition and the time its run may reach.
type Asked = Option<(String, Option<f64>)>;

/// Fits `unknowns` ((name, lo, hi): a parameter or `init:x`) of `model` to `data`, from the
/// run `flags` with the parameter values `set` (the unknowns' start among them); then
/// predicts what `predict` asks ((condition, until), `varmass fit --predict`), if given.
#[pyfunction]
#[pyo3(signature = (model, set, flags, data, unknowns, predict=None))]
pub fn fit<'py>(
    py: Python<'py>,
    model: &NativeModel,
    set: Vec<(String, f64)>,
    flags: &RunFlags,
    data: Vec<Measured>,
    unknowns: Vec<(String, f64, f64)>,
    predict: Asked,
) -> PyResult<Fitted<'py>> {
    let (series, unknowns) = (series(data), unknowns_of(unknowns));
    let (args, predict) = (flags.args(), request(predict));
    let done = py
        .detach(|| {
            let mut compiled = model.lock();
            fit_model(
                &mut compiled,
                args,
                set,
                &series,
                &unknowns,
                predict.as_ref(),
            )
        })
        .map_err(|e| to_py(py, e))?;
    fitted(py, done)
}

/// Fits `unknowns` of the scene file at `path` to `data` (docs/sensitivities.md#fitting-a-scene)
/// and predicts what `predict` asks, if given: [`fit`]'s result, and how many data lay
/// outside the scene's span (left out).
#[pyfunction]
#[pyo3(signature = (path, data, unknowns, predict=None))]
pub fn fit_scene<'py>(
    py: Python<'py>,
    path: &str,
    data: Vec<Measured>,
    unknowns: Vec<(String, f64, f64)>,
    predict: Asked,
) -> PyResult<(Fitted<'py>, usize)> {
    let (series, unknowns) = (series(data), unknowns_of(unknowns));
    let (path, predict) = (std::path::PathBuf::from(path), request(predict));
    let (done, left_out) = py
        .detach(|| fit_scene_file(&path, series, &unknowns, predict.as_ref()))
        .map_err(|e| to_py(py, e))?;
    Ok((fitted(py, done)?, left_out))
}

/// The prediction asked from Python as the tool takes it.
fn request(predict: Asked) -> Option<Predict> {
    predict.map(|(condition, until)| Predict { condition, until })
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
    let prediction = match done.prediction {
        Some(Ok(p)) => (Some((p.condition, p.time, p.clock, p.quantities)), None),
        Some(Err(e)) => (None, Some(e)),
        None => (None, None),
    };
    Ok((
        done.values,
        done.errors,
        correlation,
        done.residuals,
        done.evaluations,
        done.converged,
        done.table.names.clone(),
        data,
        prediction,
    ))
}
