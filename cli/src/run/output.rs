//! What a run prints and writes: the summary, the recorded table and its CSV.

use std::fmt::{self, Write};
use std::path::Path;

use varmass::core::{Statistics, GIMBAL_WARNING};
use varmass::interpret::Program;

use super::names::shown;
use super::record::Recorded;
use crate::error::CliError;

/// The recorded quantities: names, and the value of each at every output time, stored by
/// column (the times, then one `Vec` per name): recording a point allocates nothing, and a
/// library caller hands each column on whole (the Python package's NumPy arrays).
#[derive(Clone, Debug)]
pub struct Table {
    /// The column names (without `t`).
    pub names: Vec<String>,
    /// The output times.
    times: Vec<f64>,
    /// One column per name, each as long as `times`.
    columns: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table of the columns `names`, with room for `capacity` rows.
    pub fn new(names: Vec<String>, capacity: usize) -> Self {
        let columns = names.iter().map(|_| Vec::with_capacity(capacity)).collect();
        Self {
            names,
            times: Vec::with_capacity(capacity),
            columns,
        }
    }

    /// The table of `rows`, `(t, values)` with one value per name.
    pub fn from_rows(names: Vec<String>, rows: impl IntoIterator<Item = (f64, Vec<f64>)>) -> Self {
        let mut table = Self::new(names, 0);
        for (t, values) in rows {
            table.push(t, &values);
        }
        table
    }

    /// Adds the row `values` (one per name) at the time `t`.
    pub fn push(&mut self, t: f64, values: &[f64]) {
        debug_assert_eq!(values.len(), self.columns.len(), "one value per column");
        self.times.push(t);
        for (column, value) in self.columns.iter_mut().zip(values) {
            column.push(*value);
        }
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether the table has no row.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// The output times.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The values of the `k`-th name at every output time.
    pub fn column(&self, k: usize) -> &[f64] {
        &self.columns[k]
    }

    /// The row `i`: its time and one value per name.
    pub fn row(&self, i: usize) -> (f64, Vec<f64>) {
        (self.times[i], self.columns.iter().map(|c| c[i]).collect())
    }

    /// Each row in turn, as [`Table::row`] gives it.
    pub fn rows(&self) -> impl Iterator<Item = (f64, Vec<f64>)> + '_ {
        (0..self.len()).map(|i| self.row(i))
    }

    /// The last row, if any.
    pub fn last(&self) -> Option<(f64, Vec<f64>)> {
        self.len().checked_sub(1).map(|i| self.row(i))
    }
}

/// A run's points: each output time and the state `[q, p, m_s]` there, the states one after
/// the other in one `Vec` (a point allocates nothing).
#[derive(Clone, Debug, Default)]
pub struct Points {
    /// The length of a state.
    width: usize,
    times: Vec<f64>,
    /// `width` values per point.
    states: Vec<f64>,
}

impl Points {
    /// No point yet, of states `width` long, with room for `capacity` points.
    pub fn new(width: usize, capacity: usize) -> Self {
        Self {
            width,
            times: Vec::with_capacity(capacity),
            states: Vec::with_capacity(capacity * width),
        }
    }

    /// Adds the point `state` (`width` long) at `t`.
    pub fn push(&mut self, t: f64, state: &[f64]) {
        debug_assert_eq!(state.len(), self.width, "a state of the points' width");
        self.times.push(t);
        self.states.extend_from_slice(state);
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether there is no point.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// The point `i`: its time and state.
    pub fn get(&self, i: usize) -> (f64, &[f64]) {
        (
            self.times[i],
            &self.states[i * self.width..(i + 1) * self.width],
        )
    }

    /// Each point in turn.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (f64, &[f64])> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The last point, if any.
    pub fn last(&self) -> Option<(f64, &[f64])> {
        self.len().checked_sub(1).map(|i| self.get(i))
    }

    /// The points with each state cut to its first `width` entries (a padded run's
    /// points, given back as the model's own).
    pub fn narrowed(self, width: usize) -> Self {
        if width >= self.width {
            return self;
        }
        let states = self
            .states
            .chunks_exact(self.width)
            .flat_map(|state| &state[..width])
            .copied()
            .collect();
        Self {
            width,
            times: self.times,
            states,
        }
    }
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
pub fn table<'a>(
    program: &Program,
    record: &[(String, Recorded)],
    points: impl ExactSizeIterator<Item = (f64, &'a [f64])>,
) -> Result<Table, Partial> {
    let names = record.iter().map(|(n, _)| n.clone()).collect();
    let mut table = Table::new(names, points.len());
    // One row's values, reused from point to point.
    let mut values = vec![0.0; record.len()];
    for (t, state) in points {
        for ((name, o), value) in record.iter().zip(&mut values) {
            // A value that is not a number is refused like one that cannot be evaluated:
            // a recorded √ of a negative, a division by zero or a ln of a non-positive
            // number is never written silently.
            let finite = match o.value(program, t, state) {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(v) => Err(format!("its value is {v}, not a finite number")),
                Err(e) => Err(e.to_string()),
            };
            match finite {
                Ok(v) => *value = v,
                Err(e) => {
                    let error = CliError::Run(format!(
                        "cannot record `{name}` at t = {t}: {e}; the points before this time \
                         are recorded; record other quantities, or stop the run before this \
                         time"
                    ));
                    return Err(Partial { table, error });
                }
            }
        }
        table.push(t, &values);
    }
    Ok(table)
}

/// Writes `table` as CSV: a header `t,<names>` and one row per output time, each number
/// in Rust's shortest round-trip form.
pub fn write_csv(table: &Table, path: &Path) -> Result<(), CliError> {
    let names: Vec<String> = table.names.iter().map(|n| csv_field(n)).collect();
    let mut text = format!("t,{}\n", names.join(","));
    for i in 0..table.len() {
        let _ = write!(text, "{}", table.times[i]);
        for column in &table.columns {
            let _ = write!(text, ",{}", column[i]);
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
/// The fields of a CSV line (RFC 4180 quotes, `""` inside for a quote; each field
/// trimmed): how the tool reads a flight log (`[flight] log`) and `varmass fit`'s data.
pub(crate) fn csv_fields(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let (mut field, mut quoted, mut chars) = (String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut field).trim().to_string()),
            _ => field.push(c),
        }
    }
    out.push(field.trim().to_string());
    out
}

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
    let mut out = String::new();
    let _ = EndState::new(program, time, state).write(&mut out);
    out
}

/// The state where a run ended, with what [`state_lines`] shows of it: the names, and the
/// velocities (`None` where they cannot be had).
#[derive(Clone, Debug)]
struct EndState {
    state: Vec<f64>,
    velocities: Option<Vec<f64>>,
    coordinates: Vec<String>,
    state_masses: Vec<String>,
}

impl EndState {
    fn new(program: &Program, time: f64, state: &[f64]) -> Self {
        let mut velocities = vec![f64::NAN; program.coordinate_count()];
        let have_velocities = program.velocities(time, state, &mut velocities).is_ok();
        Self {
            state: state.to_vec(),
            velocities: have_velocities.then_some(velocities),
            coordinates: program.coordinate_names().map(str::to_string).collect(),
            state_masses: program
                .mass_names()
                .take(program.state_mass_count())
                .map(str::to_string)
                .collect(),
        }
    }

    fn write(&self, out: &mut impl Write) -> fmt::Result {
        let (n, state) = (self.coordinates.len(), &self.state);
        for (a, x) in self.coordinates.iter().enumerate() {
            write!(out, "\n  {x} = {}", shown(state[a]))?;
            if let Some(velocities) = &self.velocities {
                write!(out, "\n  {x}' = {}", shown(velocities[a]))?;
            }
            write!(out, "\n  p_{x} = {}", shown(state[n + a]))?;
        }
        for (k, m) in self.state_masses.iter().enumerate() {
            write!(out, "\n  {m} = {}", shown(state[2 * n + k]))?;
        }
        Ok(())
    }
}

/// The summary printed after a run: what it is made of, its text written only when shown
/// (`to_string()`, `{}`) — a library caller that runs many times and reads the summary
/// rarely (the Python package's `Solution.summary`) does not pay for the text of each run.
#[derive(Clone, Debug)]
pub struct Summary {
    time: f64,
    end: EndState,
    /// The condition that stopped the run, as written (quoted in the text).
    stopped_by: Option<String>,
    statistics: Statistics,
    /// The closest the run's points came to gimbal lock, rad ([`Summary::near_gimbal_lock`]).
    closest_singular_attitude: Option<f64>,
}

impl Summary {
    /// The summary of a run that ended at `time` in `state`, stopped by the `--stop-when`
    /// condition `stopped_by` (or at `--until`), having done the work `statistics`.
    pub fn new(
        program: &Program,
        time: f64,
        state: &[f64],
        stopped_by: Option<&str>,
        statistics: &Statistics,
    ) -> Self {
        Self {
            time,
            end: EndState::new(program, time, state),
            stopped_by: stopped_by.map(str::to_string),
            statistics: *statistics,
            closest_singular_attitude: None,
        }
    }

    /// With the run's closest approach (over every accepted step, whatever `--every` kept)
    /// to a singular attitude of the model's Euler sequences, warned of within
    /// `GIMBAL_WARNING` (`Program::singular_attitude_distance`).
    pub fn near_gimbal_lock(mut self, closest: Option<f64>) -> Self {
        self.closest_singular_attitude = closest;
        self
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let time = shown(self.time);
        match &self.stopped_by {
            Some(condition) => write!(out, "stopped at t = {time} (--stop-when '{condition}')")?,
            None => write!(out, "stopped at t = {time} (reached --until)")?,
        }
        out.write_str("\nstate:")?;
        self.end.write(out)?;
        write!(out, "\n{}", work(&self.statistics))?;
        out.write_str(&gimbal_warning(self.closest_singular_attitude))
    }
}

/// The summary's warning line when a run came within `GIMBAL_WARNING` of a singular attitude
/// of its Euler sequences (`closest`, rad, over every accepted step); empty otherwise. The
/// summaries of `varmass run` and of a scene end with it.
pub fn gimbal_warning(closest: Option<f64>) -> String {
    match closest {
        Some(closest) if closest < GIMBAL_WARNING => format!(
            "warning: the attitude came within {} rad of gimbal lock (the Euler sequence's \
             singular attitude), where the angles' rates and the error grow as 1/distance; \
             `orientation quaternion(e0, e1, e2, e3)` has none\n",
            shown(closest)
        ),
        _ => String::new(),
    }
}

/// The line of a run's work, as the summaries of `varmass run` and of a scene end.
pub fn work(s: &Statistics) -> String {
    format!(
        "steps: {} accepted, {} rejected; {} rate evaluations, {} Jacobians, {} Newton \
         iterations\n",
        s.accepted_steps,
        s.rejected_steps,
        s.rate_evaluations,
        s.jacobian_evaluations,
        s.newton_iterations
    )
}
