//! A scene file (`varmass run SCENE.toml`, docs/scenes.md) run from Python: the tool's own
//! reading, checks and phases (`varmass_cli::scene::run_file`), so its messages and
//! numbers are the tool's. The table comes back as a run's does ([`crate::run`]), with the
//! `phase` column first and the changes of phase beside it.

use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::{Mutex, MutexGuard};

use varmass_cli::scene::{run_file_sensitive, Models, SceneRun};

use crate::errors::to_py;
use crate::run::{columns, statistics};

/// The models a `varmass.Scene` derived, kept for its next run: a scene run again costs
/// its integration, not a derivation.
#[pyclass(module = "varmass._native", frozen)]
#[derive(Default)]
pub struct NativeScene {
    models: Mutex<Models>,
}

#[pymethods]
impl NativeScene {
    #[new]
    fn new() -> Self {
        Self::default()
    }

    /// How many derivations the scene's runs cost so far.
    fn derivations(&self) -> usize {
        self.lock().derivations()
    }
}

impl NativeScene {
    /// The models, for one run at a time (a poisoned lock is only a panic's leftover).
    fn lock(&self) -> MutexGuard<'_, Models> {
        self.models.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// A change of phase as Python's `PhaseChange` takes it: the phase, time, rule, kinetic
/// energy removed and the values set by expressions of the change's time.
type ChangeRow<'a> = (usize, f64, &'a str, f64, Vec<(String, f64)>);

/// Runs the scene file at `path` with the models `scene` derived before, and the
/// sensitivity columns `sensitivities` (docs/sensitivities.md#scenes): the recorded
/// columns (`phase` first), the changes of phase, the end, the statistics and the summary
/// the tool prints. A mistake in the file is the tool's `ValueError`/`ModelError`; a
/// failed run its `RunError`, with the points up to the failure as `_partial`.
#[pyfunction]
pub fn run_scene<'py>(
    py: Python<'py>,
    scene: &NativeScene,
    path: &str,
    sensitivities: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let path = std::path::PathBuf::from(path);
    let run = || run_file_sensitive(&path, &mut scene.lock(), &sensitivities);
    let mut done: SceneRun = py.detach(run).map_err(|e| to_py(py, e))?;
    if let Some(failure) = done.failure.take() {
        let error = to_py(py, failure);
        columns(py, &done.table).and_then(|d| error.value(py).setattr("_partial", d))?;
        return Err(error);
    }
    let out = columns(py, &done.table)?;
    let (time, state) = done.end.clone().unwrap_or((f64::NAN, Vec::new()));
    out.set_item(intern!(py, "end_time"), time)?;
    out.set_item(intern!(py, "end_state"), state)?;
    out.set_item(intern!(py, "stopped_by"), &done.stopped_by)?;
    let changes: Vec<ChangeRow<'_>> = done
        .changes
        .iter()
        .map(|c| {
            (
                c.phase,
                c.time,
                c.rule,
                c.kinetic_energy_removed,
                c.set.clone(),
            )
        })
        .collect();
    out.set_item(intern!(py, "changes"), changes)?;
    out.set_item(intern!(py, "statistics"), statistics(py, &done.statistics)?)?;
    out.set_item(intern!(py, "summary"), &done.summary)?;
    out.set_item(intern!(py, "lift_off"), done.lift_off)?;
    out.set_item(intern!(py, "rail_exit"), done.rail_exit)?;
    out.set_item(intern!(py, "flight"), flight(py, &done)?)?;
    Ok(out)
}

/// A scene's flight (`[flight]`, docs/scenes.md#flight) for `varmass._flight`: the summary
/// as the tool's JSON, the roles' columns as a table, the measured log's times and
/// altitudes; `None` without `[flight]`.
fn flight<'py>(py: Python<'py>, done: &SceneRun) -> PyResult<Option<Bound<'py, PyDict>>> {
    let Some(flight) = &done.flight else {
        return Ok(None);
    };
    let out = PyDict::new(py);
    out.set_item(intern!(py, "summary"), flight.json())?;
    out.set_item(intern!(py, "table"), columns(py, &flight.table)?)?;
    let log = flight
        .log
        .as_ref()
        .map(|l| (l.times.clone(), l.altitudes.clone()));
    out.set_item(intern!(py, "log"), log)?;
    Ok(Some(out))
}
