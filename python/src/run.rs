//! One run with the command line tool's semantics: the options arrive typed (checked for
//! their Python types by `varmass/_checks.py`) and become the tool's [`RunArgs`] directly,
//! with messages in Python's words ([`Words::Python`]); the run is the tool's one path
//! ([`varmass_cli::run::Compiled::execute`]), so every default and check is the tool's.
//! The result comes back as raw little-endian `f64` bytes per column, which NumPy wraps
//! without a copy per value.

use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyFloat, PyString};
use varmass::core::Statistics;
use varmass_cli::args::{Method, ModelArgs, RunArgs, Words};
use varmass_cli::error::CliError;
use varmass_cli::run::{Failed, Summary, Table};

use crate::errors::{to_py, value_error};
use crate::model::NativeModel;

/// A run's options as `_checks.run_options` makes them: a dict of Python's keywords to
/// values of their types (the names and laws as text, as the tool reads them).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct Options {
    from_: f64,
    until: f64,
    init: Vec<(String, f64)>,
    stop_when: Vec<String>,
    method: String,
    tol: Option<f64>,
    step: Option<f64>,
    record: Vec<String>,
    every: Option<f64>,
    sensitivity: Vec<String>,
    inputs: Vec<(String, String)>,
    tables: Vec<(String, String)>,
}

/// The tool's arguments of a run of the model `file` with the tags `with` and `options`.
pub fn run_args(file: &str, with: &[String], options: Options) -> Result<RunArgs, CliError> {
    let method = <Method as clap::ValueEnum>::from_str(&options.method, false)
        .map_err(|_| CliError::Input(format!("method {:?} is unknown", options.method)))?;
    let pairs = |pairs: Vec<(String, String)>| -> Vec<String> {
        pairs.into_iter().map(|(n, v)| format!("{n}={v}")).collect()
    };
    Ok(RunArgs {
        model: ModelArgs {
            file: file.into(),
            with: with.to_vec(),
        },
        set: Vec::new(),
        input: pairs(options.inputs),
        table: pairs(options.tables),
        // `{:?}` writes the shortest text that reads back to the same bits.
        init: options
            .init
            .iter()
            .map(|(n, v)| format!("{n}={v:?}"))
            .collect(),
        from: options.from_,
        until: Some(options.until),
        stop_when: options.stop_when,
        method,
        tol: options.tol,
        step: options.step,
        max_steps: 10_000_000,
        max_seconds: None,
        record: options.record,
        sensitivity: options.sensitivity,
        at: Vec::new(),
        rates: false,
        every: options.every,
        csv: None,
        plot: None,
        summary_json: None,
        words: Words::Python,
    })
}

/// A run's options as the tool's arguments, made once (a `Model` keeps the last one, so a
/// sweep over parameter values with the same options makes them once).
#[pyclass(module = "varmass._native", frozen)]
pub struct RunFlags {
    args: RunArgs,
}

impl RunFlags {
    /// The tool's arguments.
    pub(crate) fn args(&self) -> &RunArgs {
        &self.args
    }
}

/// The arguments of a run of the model `file` with the tags `with` and `options`.
#[pyfunction]
pub fn options(
    py: Python<'_>,
    file: &str,
    with: Vec<String>,
    options: Options,
) -> PyResult<RunFlags> {
    let args = run_args(file, &with, options).map_err(|e| to_py(py, e))?;
    Ok(RunFlags { args })
}

/// What [`run`] gives: the recorded names, their data (as [`columns`] gives them), the
/// end time, the index of the `stop_when` condition that ended the run (or `None`) and the
/// rest of the run ([`Details`]), read when asked.
type Ran<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyBytes>,
    f64,
    Option<usize>,
    Details,
);

/// Runs `model` with the parameter values `set` and the parsed `flags` (the tool's `run`
/// without its files, on the model compiled once); returns what [`Ran`] lists. `set` is
/// the pairs `_checks.unique_values` gives, or the user's own `dict` when it is plain
/// (see [`plain`]); `None` when it is a `dict` that is not: `Model.run` then checks it
/// in Python, with its messages, and calls again with the pairs.
#[pyfunction]
pub fn run<'py>(
    py: Python<'py>,
    model: &NativeModel,
    set: &Bound<'py, PyAny>,
    flags: &RunFlags,
) -> PyResult<Option<Ran<'py>>> {
    let set = match set.cast_exact::<PyDict>() {
        Ok(dict) => match plain(dict) {
            Some(pairs) => pairs,
            None => return Ok(None),
        },
        Err(_) => set.extract::<Vec<(String, f64)>>()?,
    };
    run_checked(py, model, set, flags).map(Some)
}

/// The pairs of `set` when each key is a `str` as written (beginning and ending with an
/// ASCII letter, digit or `_`: nothing Python's `strip` would take off) and each value a
/// finite `float`, exactly the pairs `_checks.unique_values` gives such a
/// dict (a sweep's `set`): checked here at a fraction of the Python loop's cost. `None`
/// for anything else.
fn plain(set: &Bound<'_, PyDict>) -> Option<Vec<(String, f64)>> {
    let mut pairs = Vec::with_capacity(set.len());
    for (key, value) in set.iter() {
        let name = key.cast_exact::<PyString>().ok()?.to_cow().ok()?;
        let value = value.cast_exact::<PyFloat>().ok()?.value();
        let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
        if !name.starts_with(word) || !name.ends_with(word) || !value.is_finite() {
            return None;
        }
        pairs.push((name.into_owned(), value));
    }
    Some(pairs)
}

fn run_checked<'py>(
    py: Python<'py>,
    model: &NativeModel,
    set: Vec<(String, f64)>,
    flags: &RunFlags,
) -> PyResult<Ran<'py>> {
    let args = &flags.args;
    if let Some((name, value)) = set.iter().find(|(_, v)| !v.is_finite()) {
        return Err(value_error(format!(
            "set: `{name}` = {value} is not finite"
        )));
    }
    let done = py
        .detach(|| {
            let values: Vec<(&str, f64)> = set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
            model.lock().run(&values, args)
        })
        .map_err(|failed| failure(py, failed))?;
    let table = &done.table;
    let names = table.names.as_slice().into_pyobject(py)?.into_any();
    let data = table_block(py, table)?;
    let details = Details {
        end_state: done.end.1,
        statistics: done.statistics,
        summary: done.summary,
    };
    Ok((names, data, done.end.0, done.stopped_by, details))
}

/// The end state, the statistics and the summary of a run, made into Python objects (the
/// summary into text) only when `Solution` is asked for them: most runs of a sweep never
/// are.
#[pyclass(module = "varmass._native", frozen)]
pub struct Details {
    end_state: Vec<f64>,
    statistics: Statistics,
    summary: Summary,
}

#[pymethods]
impl Details {
    /// The state `[q, p, m_s]` where the run ended.
    fn end_state(&self) -> Vec<f64> {
        self.end_state.clone()
    }

    /// The stepper's work by name.
    fn statistics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        statistics(py, &self.statistics)
    }

    /// The summary the tool prints.
    fn summary(&self) -> String {
        self.summary.to_string()
    }
}

/// The exception of a failed run; a `RunError` carries the points recorded up to the
/// failure as `_partial` (names, times and columns, as [`columns`] gives them), which
/// `Model.run` turns into `RunError.points`.
fn failure(py: Python<'_>, failed: Failed) -> PyErr {
    let error = to_py(py, failed.error);
    if let Some(table) = &failed.table {
        let partial = columns(py, table).and_then(|d| error.value(py).setattr("_partial", d));
        if let Err(e) = partial {
            return e;
        }
    }
    error
}

/// The names of `table` and its data: the times, then each column in turn, as one block
/// of little-endian bytes (NumPy wraps it once and gives each column as a view).
pub fn columns<'py>(py: Python<'py>, table: &Table) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item(intern!(py, "names"), &table.names)?;
    out.set_item(intern!(py, "data"), table_block(py, table)?)?;
    Ok(out)
}

/// The times of `table`, then each column in turn, as one block of little-endian bytes.
pub(crate) fn table_block<'py>(py: Python<'py>, table: &Table) -> PyResult<Bound<'py, PyBytes>> {
    let columns = (0..table.names.len()).map(|k| table.column(k));
    block(
        py,
        table.len(),
        std::iter::once(table.times()).chain(columns),
    )
}

/// The columns `columns`, each `len` long, one after the other as one block of little-endian
/// bytes, written straight into the Python object (one copy of each column).
fn block<'a, 'py>(
    py: Python<'py>,
    len: usize,
    columns: impl Iterator<Item = &'a [f64]> + Clone,
) -> PyResult<Bound<'py, PyBytes>> {
    let size = 8 * len * columns.clone().count();
    PyBytes::new_with(py, size, |out| {
        let values = columns.flat_map(|c| c.iter());
        for (chunk, v) in out.chunks_exact_mut(8).zip(values) {
            chunk.copy_from_slice(&v.to_le_bytes());
        }
        Ok(())
    })
}

/// The little-endian bytes of `values`.
pub fn bytes<'py>(py: Python<'py>, values: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let raw: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    PyBytes::new(py, &raw)
}

/// The stepper's work by name.
pub fn statistics<'py>(py: Python<'py>, s: &Statistics) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item(intern!(py, "accepted_steps"), s.accepted_steps)?;
    out.set_item(intern!(py, "rejected_steps"), s.rejected_steps)?;
    out.set_item(intern!(py, "rate_evaluations"), s.rate_evaluations)?;
    out.set_item(intern!(py, "jacobian_evaluations"), s.jacobian_evaluations)?;
    out.set_item(intern!(py, "newton_iterations"), s.newton_iterations)?;
    out.set_item(intern!(py, "stiffness_detected"), s.stiffness_detected)?;
    Ok(out)
}
