//! A scene's flight (`[flight]`, docs/scenes.md#flight): the roles of the model's
//! quantities (`roles`), evaluated at every recorded row into the flight table, the summary
//! computed from it (`summary`, the apogee located by `apogee`), a measured log read
//! (`log`) and the panels drawn (`plot`).

mod apogee;
mod log;
mod plot;
mod roles;
mod summary;

use std::path::Path;

pub use apogee::{locate_apogee, Apogee};
pub use log::Log;
pub use plot::LOG_SERIES;
pub use roles::{FlightTable, LogEntry, Role, Roles, ROLES};
pub use summary::{
    End, Extreme, FlightSummary, Landing, LogComparison, PhaseEvent, RailExit, StaticMargin,
};

use super::build::Scene;
use super::file::{line_column, Read};
use super::fly::Flown;
use super::models::Models;
use super::Change;
use crate::error::CliError;
use crate::run::output::{self, Table};

/// A scene's flight: the roles' values at every row, the summary, the log.
pub struct Flight {
    /// The roles present and their expressions.
    pub roles: Roles,
    /// Each role's value (a column named by its key) at every row of the scene's table.
    pub table: Table,
    /// The summary.
    pub summary: FlightSummary,
    /// The measured log, if `[flight]` names one.
    pub log: Option<Log>,
}

impl Flight {
    /// The block the tool prints.
    pub fn text(&self) -> String {
        summary::text(&self.summary)
    }

    /// The summary as JSON (numbers in their shortest round-trip form).
    pub fn json(&self) -> String {
        serde_json::to_string_pretty(&self.summary).unwrap_or_else(|e| format!("\"{e}\""))
    }

    /// Writes [`Flight::json`] to `path`.
    pub fn write_json(&self, path: &Path) -> Result<(), CliError> {
        std::fs::write(path, self.json() + "\n").map_err(|e| CliError::Write {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })
    }

    /// Draws the flight's panels into `path`.
    pub fn plot(&self, title: &str, path: &Path) -> Result<(), CliError> {
        plot::plot(&self.table, &self.roles, self.log.as_ref(), title, path)
    }
}

/// A flight checked before the first step: its roles in every phase, its log, its burnout.
pub(crate) struct Prepared {
    roles: Roles,
    log: Option<Log>,
    burnout: Option<f64>,
}

/// The scene's `[flight]`, checked against each phase of `scene` (`None` without one).
pub(crate) fn prepare(
    read: &Read,
    path: &Path,
    scene: &Scene,
    models: &mut Models,
) -> Result<Option<Prepared>, CliError> {
    let Some(table) = &read.scene.flight else {
        return Ok(None);
    };
    let at = |offset: usize| format!("{}:{}", path.display(), line_column(&read.source, offset));
    let model_file = roles::model_file(path, read.scene.model.get_ref());
    let phases: Vec<roles::PhaseScope<'_>> = scene
        .phases
        .iter()
        .map(|p| roles::PhaseScope {
            program: &p.program,
            tags: p.tags(),
            parameters: p.parameters(),
        })
        .collect();
    let roles = roles::resolve(table, &phases, &model_file, models, &at)?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let log = match &table.get_ref().log {
        Some(entry) => Some(log::read(entry, &base, &at)?),
        None => None,
    };
    Ok(Some(Prepared {
        roles,
        log,
        burnout: table.get_ref().burnout,
    }))
}

/// What the scene's run gives the flight besides its points.
pub(crate) struct Ran<'a> {
    /// The changes of phase.
    pub changes: &'a [Change],
    /// The `stop_when` that ended the run.
    pub stopped_by: Option<&'a str>,
    /// The rail exit (time, speed), when the run has one.
    pub rail_exit: Option<(f64, f64)>,
}

/// The flight of the run `flown`: the roles evaluated at each point (in its phase's
/// model), then summarized. A role that cannot be evaluated at a point is the run's
/// failure there, as a recorded column's is.
pub(crate) fn finish(prepared: Prepared, flown: &Flown, ran: &Ran<'_>) -> Result<Flight, CliError> {
    let Prepared {
        roles,
        log,
        burnout,
    } = prepared;
    let names: Vec<String> = roles
        .present
        .iter()
        .map(|(r, _)| r.key().to_string())
        .collect();
    let mut table = Table::new(names, flown.points.len());
    let mut start = 0;
    while start < flown.points.len() {
        let k = flown.phase[start];
        let end = start + flown.phase[start..].iter().take_while(|p| **p == k).count();
        let points = flown.points[start..end]
            .iter()
            .map(|(t, s)| (*t, s.as_slice()));
        let part = output::table(&flown.programs[k], &roles.columns[k], points)
            .map_err(|partial| partial.error)?;
        for (t, values) in part.rows() {
            table.push(t, &values);
        }
        start = end;
    }
    let events = summary::Events {
        changes: ran.changes,
        lift_off: flown.lift_off,
        rail_exit: ran.rail_exit,
        stopped_by: ran.stopped_by,
        burnout,
        log: log.as_ref(),
    };
    let summary = summary::summarize(&table, &roles, &events);
    Ok(Flight {
        roles,
        table,
        summary,
        log,
    })
}
