//! A model for `varmass.Model`: derived once by the tool's loader from its text and kept
//! compiled ([`NativeModel`], the tool's [`Compiled`]), with the names a run understands,
//! its tags and its checks, and the derivation as text or LaTeX.

use std::path::Path;
use std::sync::{Mutex, MutexGuard};

use pyo3::prelude::*;
use pyo3::types::PyDict;
use varmass::symbolic::expr::Identity;
use varmass::symbolic::mechanics::{Derivation, MassKind};
use varmass::symbolic::parse::{known_tags, parse_system};
use varmass_cli::error::CliError;
use varmass_cli::model::{load_source, LoadedModel};
use varmass_cli::run::Compiled;

use crate::errors::to_py;

/// Derives `source` (named `file` in diagnostics) with the tags `with`; `file` need not
/// exist.
pub fn derive(source: &str, file: &str, with: &[String]) -> Result<LoadedModel, CliError> {
    load_source(source, Path::new(file), with)
}

/// A derived model, compiled at its first run and reused by every later run (and by the
/// ensembles made from it): a run costs its integration, not a derivation.
#[pyclass(module = "varmass._native", frozen)]
pub struct NativeModel {
    compiled: Mutex<Compiled>,
}

impl NativeModel {
    /// The compiled model, for one run at a time (a poisoned lock is only a panic's
    /// leftover; the model itself is intact).
    pub fn lock(&self) -> MutexGuard<'_, Compiled> {
        self.compiled.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The derived model (to give an ensemble's threads their own compiled copies).
    pub fn loaded(&self) -> LoadedModel {
        self.lock().model().clone()
    }
}

#[pymethods]
impl NativeModel {
    /// The whole derivation as text, or LaTeX (`align*` environments) with `latex`, exactly
    /// as `varmass derive [--latex]` prints it.
    fn derivation(&self, py: Python<'_>, latex: bool) -> String {
        let mut derivation = Derivation::clone(&self.lock().model().derivation);
        py.detach(|| match latex {
            true => derivation.to_latex(),
            false => derivation.to_text(),
        })
    }
}

/// The model's facts: coordinates, parameters, masses (state masses first), tags, the
/// recordable quantities and each check with how it was decided; and the model itself.
#[pyfunction]
pub fn load<'py>(
    py: Python<'py>,
    source: &str,
    file: &str,
    with: Vec<String>,
) -> PyResult<(Bound<'py, PyDict>, NativeModel)> {
    let (loaded, tags) = py
        .detach(|| {
            let tags = parse_system(source).map(|ast| known_tags(&ast));
            derive(source, file, &with).map(|loaded| (loaded, tags.unwrap_or_default()))
        })
        .map_err(|e| to_py(py, e))?;
    let d = &loaded.derivation;
    let facts = PyDict::new(py);
    let coordinates: Vec<String> = d.coordinates.iter().map(|c| c.name.clone()).collect();
    facts.set_item("coordinates", &coordinates)?;
    facts.set_item("parameters", d.used_parameters())?;
    let masses = |state: bool| -> Vec<String> {
        d.masses
            .iter()
            .filter(|m| matches!(m.kind, MassKind::State { .. }) == state)
            .map(|m| m.name.clone())
            .collect()
    };
    facts.set_item("state_masses", masses(true))?;
    facts.set_item("mass_laws", masses(false))?;
    facts.set_item("tags", tags)?;
    // The tables declared from a RASP file: arrays given for one are read as such a file.
    let motors: Vec<&str> = d
        .tables
        .iter()
        .filter(|t| !t.runtime && t.path.extension().is_some_and(|e| e == "eng"))
        .map(|t| t.name.as_str())
        .collect();
    facts.set_item("motors", motors)?;
    let checks: Vec<(String, String)> = d
        .checks
        .iter()
        .map(|c| (c.source.clone(), verdict(&c.verdict)))
        .collect();
    facts.set_item("checks", checks)?;
    // What `varmass check` and `run` warn of (a parameter one edit from another name, most
    // likely a typo that became a parameter): `Model` warns of it when made.
    facts.set_item("warnings", &loaded.warnings)?;
    let model = NativeModel {
        compiled: Mutex::new(Compiled::new(loaded)),
    };
    Ok((facts, model))
}

/// How a check was decided, as `varmass check` prints it.
fn verdict(identity: &Identity) -> String {
    match identity {
        Identity::Proven => "proven".to_string(),
        Identity::Numerical { points } => format!("holds at {points} random points"),
        other => format!("{other:?}"),
    }
}
