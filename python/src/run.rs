//! One run with the command line tool's semantics: the options arrive as the tool's own
//! flags (`--until=…`, `--init=x=0`, …), parsed by its clap parser, so every default, check
//! and message is the tool's; the parameter values arrive as numbers. The result comes back
//! as raw little-endian `f64` bytes per column, which NumPy wraps without a copy per value.

use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use varmass::core::Statistics;
use varmass_cli::args::{Cli, Command, RunArgs};
use varmass_cli::error::CliError;
use varmass_cli::run::{Completed, Failed, Table};

use crate::errors::{to_py, value_error};
use crate::model::NativeModel;

/// `varmass run FILE <flags>` parsed by the tool's parser; a bad flag is the tool's message.
pub fn parse_args(file: &str, with: &[String], flags: &[String]) -> Result<RunArgs, CliError> {
    let mut argv = vec!["varmass".to_string(), "run".to_string(), file.to_string()];
    argv.extend(with.iter().map(|tag| format!("--with={tag}")));
    argv.extend(flags.iter().cloned());
    let cli = <Cli as clap::Parser>::try_parse_from(argv).map_err(|e| {
        // clap's own rendering, without its usage footer (the Python API has no usage).
        let text = e.to_string();
        let first = text
            .lines()
            .next()
            .unwrap_or("")
            .trim_start_matches("error: ");
        CliError::Input(first.to_string())
    })?;
    match cli.command {
        Command::Run(args) => Ok(*args),
        _ => Err(CliError::Input("not a run".to_string())),
    }
}

/// A run's flags, parsed once by the tool's parser (a `Model` keeps the last one, so a
/// sweep over parameter values with the same flags parses them once).
#[pyclass(module = "varmass._native", frozen)]
pub struct RunFlags {
    args: RunArgs,
}

/// Parses `flags` for a run of the model `file` with the tags `with`.
#[pyfunction]
pub fn parse(
    py: Python<'_>,
    file: &str,
    with: Vec<String>,
    flags: Vec<String>,
) -> PyResult<RunFlags> {
    let args = parse_args(file, &with, &flags).map_err(|e| to_py(py, e))?;
    Ok(RunFlags { args })
}

/// Runs `model` with the parameter values `set` and the parsed `flags` (the tool's `run`
/// without its files, on the model compiled once); returns the recorded columns, the end,
/// the statistics and the summary the tool prints.
#[pyfunction]
pub fn run<'py>(
    py: Python<'py>,
    model: &NativeModel,
    set: Vec<(String, f64)>,
    flags: &RunFlags,
) -> PyResult<Bound<'py, PyDict>> {
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
    result(py, &done)
}

/// The exception of a failed run; a `RunError` carries the points recorded up to the
/// failure as `_partial` (names, times and columns, as [`result`] gives them), which
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
    let rows = &table.rows;
    let mut data: Vec<u8> = Vec::with_capacity(8 * rows.len() * (table.names.len() + 1));
    data.extend(rows.iter().flat_map(|(t, _)| t.to_le_bytes()));
    for k in 0..table.names.len() {
        data.extend(rows.iter().flat_map(|(_, v)| v[k].to_le_bytes()));
    }
    out.set_item(intern!(py, "data"), PyBytes::new(py, &data))?;
    Ok(out)
}

/// The little-endian bytes of `values`.
pub fn bytes<'py>(py: Python<'py>, values: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let raw: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    PyBytes::new(py, &raw)
}

fn result<'py>(py: Python<'py>, done: &Completed) -> PyResult<Bound<'py, PyDict>> {
    let out = columns(py, &done.table)?;
    out.set_item(intern!(py, "end_time"), done.end.0)?;
    out.set_item(intern!(py, "end_state"), &done.end.1)?;
    out.set_item(intern!(py, "stopped_by"), done.stopped_by)?;
    out.set_item(intern!(py, "statistics"), statistics(py, &done.statistics)?)?;
    out.set_item(intern!(py, "summary"), &done.summary)?;
    Ok(out)
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
