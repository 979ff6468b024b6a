//! `varmass run SCENE.toml`: a scene file (docs/scenes.md) runs a model through phases —
//! parameters, state masses and tags changed at events, the state carried by separation or
//! capture — into one table with the phase of every point.
//!
//! The file is read with serde (`file`), every name checked against the model before the
//! first step (`build`), and the phases run by the core's `run_phases_keeping` on the
//! interpreter's systems (`fly`). The recording, CSV, plot and error messages are
//! `varmass run`'s own.

mod build;
mod file;
pub mod flight;
mod fly;
mod models;
mod rerun;
mod sensitivities;
mod system;
mod timed;

use std::fmt::Write;
use std::path::Path;

use varmass::core::{Carry, Statistics};

use crate::args::RunArgs;
use crate::error::CliError;
use crate::run::names::shown;
use crate::run::output::{self, Table};
use crate::run::plot;
use crate::run::record::Recorded;

pub use build::ENERGY_RESIDUAL;
pub use models::Models;
pub use rerun::Rerun;

/// Whether `path` names a scene file (`.toml`) rather than a model.
pub fn is_scene(path: &Path) -> bool {
    path.extension().is_some_and(|e| e == "toml")
}

/// A scene's run, for the tool and for a library caller.
pub struct SceneRun {
    /// `phase`, the recorded quantities (and `energy_residual` if asked) at every point.
    pub table: Table,
    /// The summary the tool prints.
    pub summary: String,
    /// Where the scene asks the CSV to be written.
    pub csv: Option<std::path::PathBuf>,
    /// Why the run failed, if it did: the table then ends at the last accepted point.
    pub failure: Option<CliError>,
    /// The changes of phase, in time order.
    pub changes: Vec<Change>,
    /// The time and state `[q, p, m_s]` of the last point (`None` if there is none).
    pub end: Option<(f64, Vec<f64>)>,
    /// The `stop_when` condition that ended the last phase, if one did (else the scene
    /// reached `until`, or failed).
    pub stopped_by: Option<String>,
    /// The steppers' work over every phase.
    pub statistics: Statistics,
    /// When the body left its support (`support = "y"`, docs/scenes.md): the start if it
    /// lifted at once, `None` if it was still held at the end or the scene has no support.
    pub lift_off: Option<f64>,
    /// When the body left its rail (`[rail]`, docs/scenes.md#a-launch-rail) and its speed
    /// then (m/s), `None` if it was still on the rail at the end or the scene has no rail.
    pub rail_exit: Option<(f64, f64)>,
    /// The flight of a scene with `[flight]` (docs/scenes.md#flight), unless the run failed.
    pub flight: Option<flight::Flight>,
}

/// A change of phase, as the summary prints it.
#[derive(Clone, Debug, PartialEq)]
pub struct Change {
    /// The phase entered, counted from 1 as the table's `phase` column.
    pub phase: usize,
    /// The time of the change.
    pub time: f64,
    /// How the state was carried: `separation` or `capture`.
    pub rule: &'static str,
    /// The kinetic energy the change removed (docs/scenes.md).
    pub kinetic_energy_removed: f64,
    /// The values set here by expressions of the change's time (`drogue_t_open = "t +
    /// 1.5"`: docs/scenes.md#a-value-set-at-the-change), as evaluated.
    pub set: Vec<(String, f64)>,
}

/// Reads, checks and runs the scene file at `path`. A mistake in the file is an `Err`
/// before any step; a run that fails is an `Ok` whose `failure` is set, with the points so
/// far in the table.
pub fn run_file(path: &Path) -> Result<SceneRun, CliError> {
    run_file_with(path, &mut Models::default())
}

/// [`run_file`] with the models derived by the runs before (`models`, which keeps those
/// this run derives): a scene run again derives nothing again.
pub fn run_file_with(path: &Path, models: &mut Models) -> Result<SceneRun, CliError> {
    run_file_sensitive(path, models, &[])
}

/// [`run_file_with`] with the sensitivity columns `sensitivities` (`--sensitivity`,
/// docs/sensitivities.md#scenes): each recorded quantity's `d(X)/d(w)` and `d(t)/d(w)`
/// after the scene's columns.
pub fn run_file_sensitive(
    path: &Path,
    models: &mut Models,
    sensitivities: &[String],
) -> Result<SceneRun, CliError> {
    let request = Request {
        sensitivities,
        at: &[],
        rates: false,
        quiet: false,
    };
    run_read(&file::read(path)?, path, models, &request)
}

/// What a run asks of a scene beside the file: sensitivity columns, and times to land on.
pub struct Request<'a> {
    /// The `--sensitivity` names (docs/sensitivities.md#scenes).
    pub sensitivities: &'a [String],
    /// Times each phase lands on and records a point at (a fit's data times), besides its
    /// steps; in the scene's span.
    pub at: &'a [f64],
    /// Whether each recorded quantity's rate `d(X)/d(t)` is recorded too (a fit of the
    /// data's time offset, docs/sensitivities.md#fitting-a-scene).
    pub rates: bool,
    /// Whether the model's warnings go unprinted (a fit's runs after its first).
    pub quiet: bool,
}

/// Runs the scene `read` from the file at `path`, as [`run_file_sensitive`] does, with
/// `request`.
fn run_read(
    read: &file::Read,
    path: &Path,
    models: &mut Models,
    request: &Request<'_>,
) -> Result<SceneRun, CliError> {
    let sensitivities = request.sensitivities;
    models.set_sensitivities(!sensitivities.is_empty() || request.rates);
    let mut scene = build::build(read, path, models, request)?;
    sensitivities::prepare(&mut scene, read, sensitivities)?;
    let derivative_names = derivative_names(&scene);
    let flight = flight::prepare(read, path, &scene, models)?;
    let csv = scene.csv.clone();
    let phases: Vec<(Carry, Vec<(String, Recorded)>)> = scene
        .phases
        .iter()
        .map(|p| (p.carry, p.record.clone()))
        .collect();
    let ends: Vec<Option<String>> = scene
        .phases
        .iter()
        .map(|p| p.end.as_ref().map(|e| e.text.clone()))
        .collect();
    let energy = scene.energy_residual;
    let support = read.scene.support.as_ref().map(|s| s.get_ref().clone());
    let held = scene.support.as_ref().map(|(k, _)| *k);
    let railed = scene.rail.is_some();
    let selected: Vec<_> = scene.phases.iter().map(|p| p.selected.clone()).collect();
    let entries = scene.record_entries.clone();
    let mut flown = fly::fly(scene)?;
    let phases = recorded_with_sets(phases, &flown, &selected, &entries)?;
    let mut names = vec!["phase".to_string()];
    names.extend(phases[0].1.iter().map(|(n, _)| n.clone()));
    if energy {
        names.push(ENERGY_RESIDUAL.to_string());
    }
    names.extend(derivative_names);
    let rows = rows(&mut flown, &phases, energy);
    let changes = changes_of(&flown, &phases);
    let stopped_by = match (flown.stopped, flown.phase.last()) {
        (true, Some(last)) => ends.get(*last).cloned().flatten(),
        _ => None,
    };
    let mut summary = summary(&flown, &changes, &ends, stopped_by.as_deref());
    if let (Some(support), Some(k)) = (&support, held) {
        let below = below_support(&flown, k);
        summary.insert_str(0, &lift_off_line(support, flown.lift_off, below));
    }
    if railed {
        summary.insert_str(0, &rail_lines(flown.lift_off, flown.rail_exit));
    }
    let ran = flight::Ran {
        changes: &changes,
        stopped_by: stopped_by.as_deref(),
        rail_exit: flown.rail_exit,
    };
    let flight = flight.and_then(|prepared| flown_flight(prepared, &mut flown, &ran));
    if let Some(done) = &flight {
        summary.push_str(&done.text());
    }
    Ok(SceneRun {
        table: Table::from_rows(names, rows),
        summary,
        csv,
        changes,
        end: flown.points.last().cloned(),
        stopped_by,
        statistics: flown.statistics,
        failure: flown.failure,
        lift_off: flown.lift_off,
        rail_exit: flown.rail_exit,
        flight,
    })
}

/// The changes of phase of `flown`, as the summary prints them (`phases`: each phase's
/// carry rule).
fn changes_of(flown: &fly::Flown, phases: &PhaseColumns) -> Vec<Change> {
    let change = |change: &varmass::core::PhaseChange| Change {
        phase: change.phase + 1,
        time: change.time,
        rule: match phases.get(change.phase).map(|p| p.0) {
            Some(Carry::Capture) => "capture",
            _ => "separation",
        },
        kinetic_energy_removed: change.kinetic_energy_removed,
        set: set_at(&flown.sets, change.phase),
    };
    flown.changes.iter().map(change).collect()
}

/// The names of the derivative columns: for each column w, each recorded quantity's
/// `d(X)/d(w)` (the first phase's names, every phase's) and `d(t)/d(w)`; then, with rates,
/// each quantity's `d(X)/d(t)` (`point_derivatives`' order).
fn derivative_names(scene: &build::Scene) -> Vec<String> {
    let record = &scene.phases[0].record;
    let mut names = Vec::new();
    for s in &scene.plan.sensitivities {
        names.extend(record.iter().map(|(x, _)| format!("d({x})/d({})", s.name)));
        names.push(format!("d(t)/d({})", s.name));
    }
    if scene.plan.rates {
        names.extend(record.iter().map(|(x, _)| format!("d({x})/d(t)")));
    }
    names
}

/// The flight of a run that did not fail; a role that cannot be evaluated at a point
/// becomes the run's failure (`flown.failure`).
fn flown_flight(
    prepared: flight::Prepared,
    flown: &mut fly::Flown,
    ran: &flight::Ran<'_>,
) -> Option<flight::Flight> {
    if flown.failure.is_some() {
        return None;
    }
    match flight::finish(prepared, flown, ran) {
        Ok(done) => Some(done),
        Err(error) => {
            flown.failure = Some(error);
            None
        }
    }
}

/// Each phase's carry rule and recorded columns.
type PhaseColumns = Vec<(Carry, Vec<(String, Recorded)>)>;

/// The recorded columns of each phase that took values at its change, resolved again with
/// them (a recorded expression reads a parameter's value when it is resolved).
fn recorded_with_sets(
    mut phases: PhaseColumns,
    flown: &fly::Flown,
    selected: &[Option<varmass::symbolic::parse::ast::SystemAst>],
    entries: &[String],
) -> Result<PhaseColumns, CliError> {
    for set in &flown.sets {
        let k = set.phase;
        if let (Some(Some(ast)), Some(program)) = (selected.get(k), flown.programs.get(k)) {
            phases[k].1 = build::record_again(program, ast, &set.values, entries)?;
        }
    }
    Ok(phases)
}

/// The values set by expressions at the change into `phase` (counted from 0).
fn set_at(sets: &[timed::SetAt], phase: usize) -> Vec<(String, f64)> {
    sets.iter()
        .find(|s| s.phase == phase)
        .map(|s| s.set.clone())
        .unwrap_or_default()
}

/// The summary's line on the support: when the body lifted off it, or that it did not;
/// and a warning if it went below the support's height after lifting (`below`: when, and
/// how far below at the lowest point).
fn lift_off_line(coordinate: &str, lift_off: Option<f64>, below: Option<(f64, f64)>) -> String {
    let mut line = match lift_off {
        Some(time) => format!(
            "lifted off its support ({coordinate}) at t = {}\n",
            shown(time)
        ),
        None => format!("never lifted off its support ({coordinate}): held to the end\n"),
    };
    if let Some((time, depth)) = below {
        line.push_str(&format!(
            "warning: after the lift-off {coordinate} went below its support, {} under it at \
             t = {}: the support does not catch the body again (a landing is another model; \
             docs/scenes.md), so the motion below it passes through the pad\n",
            shown(depth),
            shown(time)
        ));
    }
    line
}

/// The summary's lines on the rail: the lift-off from its bottom, and the exit with its speed
/// (or that the body never got there).
fn rail_lines(lift_off: Option<f64>, exit: Option<(f64, f64)>) -> String {
    let lift = match lift_off {
        Some(time) => format!("lifted off its rail's bottom at t = {}\n", shown(time)),
        None => "never lifted off its rail's bottom: held to the end\n".to_string(),
    };
    let exit = match (lift_off, exit) {
        (_, Some((time, speed))) => {
            format!(
                "left its rail at t = {}, at {} m/s\n",
                shown(time),
                shown(speed)
            )
        }
        (Some(_), None) => "still on its rail at the end\n".to_string(),
        (None, None) => String::new(),
    };
    lift + &exit
}

/// The lowest point of the held coordinate `k` after the lift-off, if it is below the
/// support's height (its value at the start): its time and the depth under the support.
fn below_support(flown: &fly::Flown, k: usize) -> Option<(f64, f64)> {
    let lift_off = flown.lift_off?;
    let pad = flown.points.first()?.1.get(k).copied()?;
    // A run stopped by its condition ends on the located crossing, which stands within the
    // location's tolerance on either side of its value: a landing at `y < 0` is not a fall
    // through the pad.
    let kept = flown.points.len() - usize::from(flown.stopped);
    let after = flown.points[..kept].iter().filter(|(t, _)| *t > lift_off);
    let (time, lowest) = after
        .filter_map(|(t, state)| Some((*t, *state.get(k)?)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    (lowest < pad).then_some((time, pad - lowest))
}

/// The table's rows: each point's phase (counted from 1), its phase's recorded quantities
/// and, if asked, the energy residual. A point that cannot be recorded ends the rows there,
/// the rows before it kept, and becomes `flown`'s failure (the run's own, if it failed
/// later, follows in the message).
fn rows(
    flown: &mut fly::Flown,
    phases: &[(Carry, Vec<(String, Recorded)>)],
    energy: bool,
) -> Vec<(f64, Vec<f64>)> {
    let mut rows = Vec::with_capacity(flown.points.len());
    let mut start = 0;
    while start < flown.points.len() {
        let k = flown.phase[start];
        let end = start + flown.phase[start..].iter().take_while(|p| **p == k).count();
        let recorded = output::table(
            &flown.programs[k],
            &phases[k].1,
            flown.points[start..end]
                .iter()
                .map(|(t, s)| (*t, s.as_slice())),
        );
        let (part, complete) = match recorded {
            Ok(part) => (part, true),
            Err(partial) => {
                let (part, error) = partial.with_run_failure(flown.failure.take());
                flown.failure = Some(error);
                (part, false)
            }
        };
        for (i, (t, values)) in part.rows().enumerate() {
            // The derivatives end where they could not be had (`flown.failure` says why).
            let Some(derivatives) = flown.derivatives.get(start + i) else {
                return rows;
            };
            let mut row = vec![(k + 1) as f64];
            row.extend(values);
            if energy {
                row.extend(flown.energy_residual.get(start + i));
            }
            row.extend(derivatives);
            rows.push((t, row));
        }
        if !complete {
            break;
        }
        start = end;
    }
    rows
}

/// `varmass run SCENE.toml`: runs the scene, writes its CSV (`--csv` overrides the file's
/// `csv`) and plot, and returns the summary; a failed run writes the points so far and
/// returns its error.
pub fn run(args: &RunArgs, given: &[String]) -> Result<String, CliError> {
    refuse_one_phase_flags(args, given)?;
    let path = &args.model.file;
    let done = run_file_sensitive(path, &mut Models::default(), &args.sensitivity)?;
    if let Some(csv) = args.csv.as_ref().or(done.csv.as_ref()) {
        output::write_csv(&done.table, csv)?;
    }
    if let Some(failure) = done.failure {
        return Err(failure);
    }
    let title = path.display().to_string();
    match (&args.plot, &done.flight) {
        (Some(plot_path), Some(flight)) => flight.plot(&title, plot_path)?,
        (Some(plot_path), None) => plot::plot(&done.table, &title, plot_path)?,
        (None, _) => {}
    }
    match (&args.summary_json, &done.flight) {
        (Some(json), Some(flight)) => flight.write_json(json)?,
        (Some(_), None) => {
            return Err(CliError::Input(format!(
                "--summary-json: `{title}` has no `[flight]` table, so no flight summary \
                 (docs/scenes.md#flight)"
            )))
        }
        (None, _) => {}
    }
    Ok(done.summary)
}

/// The flags that go with a scene file: the file itself, and where its output goes.
const SCENE_FLAGS: [&str; 5] = ["file", "csv", "plot", "summary_json", "sensitivity"];

/// The flags of a one-phase run have no meaning beside a scene, which gives them itself:
/// `given` holds the ids of the flags on the command line (a flag given at its default
/// value is refused too, so that `--method rk4` is never silently ignored).
fn refuse_one_phase_flags(args: &RunArgs, given: &[String]) -> Result<(), CliError> {
    match given.iter().find(|id| !SCENE_FLAGS.contains(&id.as_str())) {
        Some(id) => Err(CliError::Input(format!(
            "--{}: `{}` is a scene file, which gives its own settings (docs/scenes.md); \
             write it there (only --csv, --plot, --summary-json and --sensitivity go with a \
             scene file)",
            id.replace('_', "-"),
            args.model.file.display()
        ))),
        None => Ok(()),
    }
}

/// Where a scene stopped by its `stop_when` stopped (a landing: `stop_when = "z < 0"`): its
/// coordinates, ` at z = -1.2e-14`; nothing for another end.
fn stopped_at(
    program: &varmass::interpret::Program,
    state: &[f64],
    stopped_by: Option<&str>,
) -> String {
    if stopped_by.is_none() {
        return String::new();
    }
    let at: Vec<String> = (program.coordinate_names().zip(state))
        .map(|(name, value)| format!("{name} = {}", shown(*value)))
        .collect();
    format!(" at {}", at.join(", "))
}

/// The values a change set by expressions, for its summary line: `; set drogue_t_open = 4.56`.
fn set_here(set: &[(String, f64)]) -> String {
    if set.is_empty() {
        return String::new();
    }
    let values: Vec<String> = set
        .iter()
        .map(|(name, value)| format!("{name} = {}", shown(*value)))
        .collect();
    format!("; set {}", values.join(", "))
}

/// The summary: how the scene ended, each change with the kinetic energy it removed, the
/// final state and the work.
fn summary(
    flown: &fly::Flown,
    changes: &[Change],
    ends: &[Option<String>],
    stopped_by: Option<&str>,
) -> String {
    let phases = ends.len();
    let Some(((time, state), last)) = flown.points.last().zip(flown.phase.last()) else {
        return "the scene computed no point\n".to_string();
    };
    let why = match stopped_by {
        Some(condition) => format!("stop_when '{condition}'"),
        None => "reached until".to_string(),
    };
    let mut out = format!(
        "stopped at t = {} in phase {} of {phases} ({why}){}\n",
        shown(*time),
        last + 1,
        stopped_at(&flown.programs[*last], state, stopped_by),
    );
    if *last + 1 < phases && flown.failure.is_none() {
        let _ = writeln!(
            out,
            "note: phase {} was never entered: its condition `{}` did not occur before the end",
            last + 2,
            ends.get(*last).and_then(Option::as_deref).unwrap_or("?")
        );
    }
    for change in changes {
        let _ = writeln!(
            out,
            "phase {} began at t = {} ({}); kinetic energy removed: {}{}",
            change.phase,
            shown(change.time),
            change.rule,
            shown(change.kinetic_energy_removed),
            set_here(&change.set)
        );
    }
    out.push_str("state:");
    out.push_str(&output::state_lines(&flown.programs[*last], *time, state));
    out.push('\n');
    out.push_str(&output::work(&flown.statistics));
    out.push_str(&output::gimbal_warning(flown.closest_singular_attitude));
    out
}
