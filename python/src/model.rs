//! A model's facts for `varmass.Model`: derived by the tool's loader from its text, with the
//! names a run understands, its tags and its checks; and the derivation as text or LaTeX.

use std::path::Path;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use varmass::symbolic::expr::Identity;
use varmass::symbolic::mechanics::MassKind;
use varmass::symbolic::parse::{known_tags, parse_system};
use varmass_cli::error::CliError;
use varmass_cli::model::{load_source, LoadedModel};

use crate::errors::to_py;

/// Derives `source` (named `file` in diagnostics) with the tags `with`; `file` need not
/// exist.
pub fn derive(source: &str, file: &str, with: &[String]) -> Result<LoadedModel, CliError> {
    load_source(source, Path::new(file), with)
}

/// The model's facts: coordinates, parameters, masses (state masses first), tags, the
/// recordable quantities and each check with how it was decided.
#[pyfunction]
pub fn load<'py>(
    py: Python<'py>,
    source: &str,
    file: &str,
    with: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
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
    let checks: Vec<(String, String)> = d
        .checks
        .iter()
        .map(|c| (c.source.clone(), verdict(&c.verdict)))
        .collect();
    facts.set_item("checks", checks)?;
    Ok(facts)
}

/// How a check was decided, as `varmass check` prints it.
fn verdict(identity: &Identity) -> String {
    match identity {
        Identity::Proven => "proven".to_string(),
        Identity::Numerical { points } => format!("holds at {points} random points"),
        other => format!("{other:?}"),
    }
}

/// The whole derivation as text, or LaTeX (`align*` environments) with `latex`, exactly
/// as `varmass derive [--latex]` prints it.
#[pyfunction]
pub fn derivation(
    py: Python<'_>,
    source: &str,
    file: &str,
    with: Vec<String>,
    latex: bool,
) -> PyResult<String> {
    py.detach(|| {
        let mut loaded = derive(source, file, &with)?;
        Ok(match latex {
            true => loaded.derivation.to_latex(),
            false => loaded.derivation.to_text(),
        })
    })
    .map_err(|e| to_py(py, e))
}
