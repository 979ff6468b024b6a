//! What a run prints and writes: the summary, the recorded table and its CSV.

use std::fmt::Write;
use std::path::Path;

use varmass::core::Statistics;
use varmass::interpret::Program;

use super::record::Recorded;
use crate::error::CliError;

/// The recorded quantities: names, and one row of values per output time.
pub struct Table {
    /// The column names (without `t`).
    pub names: Vec<String>,
    /// (t, values) per output time.
    pub rows: Vec<(f64, Vec<f64>)>,
}

/// A recording that stopped at a point whose quantity cannot be had: the rows before that
/// point, and the error naming the quantity and the time. Nothing already recorded is lost:
/// the callers write these rows (the CSV up to the failing point) or hand them to the
/// library caller with the error.
pub struct Partial {
    /// The rows before the failing point.
    pub table: Table,
    /// Which quantity could not be recorded, and at what time.
    pub error: CliError,
}

impl Partial {
    /// The rows and the error to report for a run whose own outcome was `failure`: the
    /// recording's error, which ends the table, followed by the run's if it failed later.
    pub fn with_run_failure(self, failure: Option<CliError>) -> (Table, CliError) {
        let error = match failure {
            None => self.error,
            Some(run) => CliError::Run(format!(
                "{}
(then: {run})",
                self.error
            )),
        };
        (self.table, error)
    }
}

/// Evaluates `record` at every point; a quantity that cannot be had ends the recording with
/// its time, the rows before it kept in the [`Partial`].
pub fn table(
    program: &Program,
    record: &[(String, Recorded)],
    points: &[(f64, Vec<f64>)],
) -> Result<Table, Partial> {
    let names = record.iter().map(|(n, _)| n.clone()).collect();
    let mut table = Table {
        names,
        rows: Vec::with_capacity(points.len()),
    };
    for (t, state) in points {
        let values = record
            .iter()
            .map(|(name, o)| {
                o.value(program, *t, state).map_err(|e| {
                    CliError::Run(format!(
                        "cannot record `{name}` at t = {t}: {e}; the points before this time \
                         are recorded; record other quantities, or stop the run before this \
                         time"
                    ))
                })
            })
            .collect::<Result<Vec<f64>, CliError>>();
        match values {
            Ok(values) => table.rows.push((*t, values)),
            Err(error) => return Err(Partial { table, error }),
        }
    }
    Ok(table)
}

/// Writes `table` as CSV: a header `t,<names>` and one row per output time, each number
/// in Rust's shortest round-trip form.
pub fn write_csv(table: &Table, path: &Path) -> Result<(), CliError> {
    let names: Vec<String> = table.names.iter().map(|n| csv_field(n)).collect();
    let mut text = format!("t,{}\n", names.join(","));
    for (t, values) in &table.rows {
        let _ = write!(text, "{t}");
        for v in values {
            let _ = write!(text, ",{v}");
        }
        text.push('\n');
    }
    std::fs::write(path, text).map_err(|e| CliError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

/// A header field as CSV (RFC 4180): quoted, its quotes doubled, when it holds a comma or a
/// quote (a recorded expression such as `atan2(y, x)`).
fn csv_field(name: &str) -> String {
    if name.contains([',', '"', '\n']) {
        format!("\"{}\"", name.replace('"', "\"\""))
    } else {
        name.to_string()
    }
}

/// The state by name: coordinates, velocities (when they can be had), momenta and state
/// masses, one per line.
pub fn state_lines(program: &Program, time: f64, state: &[f64]) -> String {
    let n = program.coordinate_count();
    let mut velocities = vec![f64::NAN; n];
    let have_velocities = program.velocities(time, state, &mut velocities).is_ok();
    let mut out = String::new();
    for (a, x) in program.coordinate_names().enumerate() {
        let _ = write!(out, "\n  {x} = {}", state[a]);
        if have_velocities {
            let _ = write!(out, "\n  {x}' = {}", velocities[a]);
        }
        let _ = write!(out, "\n  p_{x} = {}", state[n + a]);
    }
    for (k, m) in program
        .mass_names()
        .take(program.state_mass_count())
        .enumerate()
    {
        let _ = write!(out, "\n  {m} = {}", state[2 * n + k]);
    }
    out
}

/// The summary printed after a run.
pub fn summary(
    program: &Program,
    time: f64,
    state: &[f64],
    stopped_by: Option<&str>,
    statistics: &Statistics,
) -> String {
    let why = match stopped_by {
        Some(condition) => format!("--stop-when {condition}"),
        None => "reached --until".to_string(),
    };
    let mut out = format!("stopped at t = {time} ({why})\nstate:");
    out.push_str(&state_lines(program, time, state));
    let _ = write!(
        out,
        "\nsteps: {} accepted, {} rejected; {} rate evaluations, {} Jacobians, {} Newton iterations\n",
        statistics.accepted_steps,
        statistics.rejected_steps,
        statistics.rate_evaluations,
        statistics.jacobian_evaluations,
        statistics.newton_iterations
    );
    out
}
