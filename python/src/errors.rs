//! The tool's errors as Python exceptions. `ModelError` and `RunError` are Python classes
//! (`varmass/_errors.py`) built here from the tool's message; they parse what they carry
//! (file, line and column; time and state) from it, so their text is exactly the tool's.
//! Bad input is a `ValueError` with the tool's message, which names the argument.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use varmass_cli::error::CliError;

/// The Python exception for `error`.
pub fn to_py(py: Python<'_>, error: CliError) -> PyErr {
    match &error {
        CliError::Model { rendered, .. } => build(py, "ModelError", rendered),
        CliError::Run(message) => build(py, "RunError", message),
        CliError::Read { .. } | CliError::Write { .. } | CliError::Input(_) => {
            PyValueError::new_err(error.to_string())
        }
    }
}

/// `varmass._errors.<class>(message)`.
fn build(py: Python<'_>, class: &str, message: &str) -> PyErr {
    let made = py
        .import("varmass._errors")
        .and_then(|module| module.getattr(class))
        .and_then(|class| class.call1((message,)));
    match made {
        Ok(instance) => PyErr::from_value(instance),
        Err(error) => error,
    }
}

/// A `ValueError` with `message`.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}
