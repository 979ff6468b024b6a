//! From a scene file to its phases, every name checked before the first step: each phase's
//! program (its tags and the parameter values in force), the state masses it sets, its
//! recorded columns, and the condition that ends it (the next phase's `when`, or the
//! scene's `stop_when` for the last). A mistake is a [`CliError::Input`] pointing at the
//! scene file's line.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use varmass::core::{Carry, Direction};
use varmass::interpret::Program;
use varmass::symbolic::parse::ast::SystemAst;

use super::file::{line_column, CarryRule, PhaseEntry, RailEntry, Read, SceneFile, SetValue};
use super::models::Models;
use super::timed::{SetExpression, Timed};
use crate::args::{ModelArgs, RunArgs, Words};
use crate::error::CliError;
use crate::model::LoadedModel;
use crate::run::input_tables::is_table_file;
use crate::run::names::{observables, resolve, Observable};
use crate::run::plan::{condition, not_yet_true, Plan};
use crate::run::record::{columns, Recorded, Scope};
use crate::run::Compiled;

/// The recorded column that holds the energy-budget residual.
pub const ENERGY_RESIDUAL: &str = "energy_residual";

/// A condition ending a phase: a quantity (or t) crossing a value.
pub struct End {
    /// What is watched; `None` for the time t.
    pub observable: Option<Observable>,
    /// The value crossed.
    pub value: f64,
    /// Which crossings count.
    pub direction: Direction,
    /// The condition as written.
    pub text: String,
    /// A program of the phase to evaluate the quantity with (the phase's own is moved into
    /// its system), when the quantity is not a state entry; in a cell, to take the values
    /// the phase sets at its change (`timed`).
    pub watch: Option<RefCell<Program>>,
}

/// One phase, ready to run.
pub struct ScenePhase {
    /// The model with this phase's tags and parameter values.
    pub program: Program,
    /// Its model's flows, named for messages (`outflow `nozzle``), in the derivation's order.
    pub flows: Vec<String>,
    /// How the state enters it.
    pub carry: Carry,
    /// The state masses it sets on entry.
    pub state_masses: Vec<(usize, f64)>,
    /// The recorded columns, resolved in this phase's model.
    pub record: Vec<(String, Recorded)>,
    /// What ends it before the end time.
    pub end: Option<End>,
    /// What it takes from the run at its change (values set by expressions, its own or
    /// carried over), if anything.
    pub timed: Option<Timed>,
    /// Its model's statements (for recorded expressions read again with the values set at
    /// the change), when it is `timed`.
    pub selected: Option<SystemAst>,
    /// Its tags and parameter values.
    in_force: InForce,
}

impl ScenePhase {
    /// Its tags (a `[flight]` role is resolved with them: scene/flight.rs).
    pub fn tags(&self) -> &[String] {
        &self.in_force.with
    }

    /// Its parameter values.
    pub fn parameters(&self) -> &[(String, f64)] {
        &self.in_force.parameters
    }
}

/// A scene, checked.
pub struct Scene {
    /// The phases in order.
    pub phases: Vec<ScenePhase>,
    /// The first phase's plan: start, end, initial state, stepper, step limit.
    pub plan: Plan,
    /// Whether the energy-budget residual is recorded.
    pub energy_residual: bool,
    /// Where to write the CSV (relative paths resolved against the scene file).
    pub csv: Option<PathBuf>,
    /// The coordinate that starts on its support (`support = "y"`) and a program of the
    /// first phase for the held phase's system.
    pub support: Option<(usize, Program)>,
    /// The launch rail the body starts on (`[rail]`).
    pub rail: Option<RailSpec>,
    /// The `record` entries each phase resolved (for a `timed` phase's, again at its change).
    pub record_entries: Vec<String>,
}

/// A scene's `[rail]`, checked: the position coordinates' indices, the rail's unit
/// direction in world axes (x east, y north, z up), the travel to the exit, and two
/// programs of the first phase for the systems on the pad and sliding up the rail.
pub struct RailSpec {
    /// The indices of the coordinates x, y, z of the body's reference point.
    pub position: [usize; 3],
    /// The unit vector up the rail.
    pub direction: [f64; 3],
    /// The travel of the reference point to the rail's exit, m.
    pub length: f64,
    /// Programs of the first phase, for the pad's system and the rail's.
    pub programs: [Program; 2],
}

/// What a phase needs from the one before: its tags and parameter values, and the
/// scene's input laws (`NAME=LAW`, as `--input` takes them).
#[derive(Clone)]
struct InForce {
    with: Vec<String>,
    parameters: Vec<(String, f64)>,
    input: Vec<String>,
    /// The parameters whose value is set by an expression at a change, this phase's or an
    /// earlier one's (`parameters` holds a stand-in for each until then).
    timed: Vec<String>,
    /// This phase's own sets by expression.
    expressions: Vec<(String, SetExpression)>,
}

/// Checks the scene read from `path` and builds its phases.
pub fn build(
    read: &Read,
    path: &Path,
    models: &mut Models,
    request: &super::Request<'_>,
) -> Result<Scene, CliError> {
    let scene = &read.scene;
    let at = |offset: usize| format!("{}:{}", path.display(), line_column(&read.source, offset));
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let model_file = base.join(scene.model.get_ref());
    let (entries_asked, energy_residual) = asked(scene);
    let in_force = first_in_force(scene, &base);
    let asked = (entries_asked.clone(), request.sensitivities.to_vec());
    let mut args = first_args(read, model_file.clone(), &in_force, asked);
    args.at = request.at.to_vec();
    args.rates = request.rates;
    let model_at = at(scene.model.span().start);
    let quiet = request.quiet;
    let (first, plan) = first_phase(&args, in_force, path, models, (&model_at, quiet))?;
    let record_entries = match entries_asked.is_empty() {
        true => plan.record.iter().map(|(n, _)| n.clone()).collect(),
        false => entries_asked,
    };
    let mut phases = ended_phases(scene, first, &model_file, &record_entries, &at, models)?;
    // With a support or a rail the first phase's conditions are watched from the lift-off
    // (the exit) on, where the core refuses one already past; during the hold, `fly` reads
    // them at every point. The free motion from the start is not the scene's.
    if scene.support.is_none() && scene.rail.is_none() {
        first_end_not_yet_true(scene, &phases[0], &plan, &at)?;
    }
    watch_programs(&mut phases, &model_file, models)?;
    let support = match &scene.support {
        Some(name) => {
            let k = supported(name.get_ref(), &phases[0].program)
                .map_err(|e| located(e, &at(name.span().start)))?;
            Some((k, program_of(&model_file, &phases[0].in_force, models)?))
        }
        None => None,
    };
    let rail = match &scene.rail {
        Some(entry) => {
            let at_rail = at(entry.span().start);
            if scene.support.is_some() {
                return Err(CliError::Input(format!(
                    "{at_rail}: `[rail]` with `support`: a rail holds the body on its bottom \
                     until lift-off by itself; remove `support`"
                )));
            }
            let (position, direction, length) = railed(entry.get_ref(), &phases[0].program, &at)?;
            let mut program = || program_of(&model_file, &phases[0].in_force, models);
            let programs = [program()?, program()?];
            Some(RailSpec {
                position,
                direction,
                length,
                programs,
            })
        }
        None => None,
    };
    Ok(Scene {
        phases,
        plan,
        energy_residual,
        csv: scene.csv.as_ref().map(|c| base.join(c)),
        support,
        rail,
        record_entries,
    })
}

/// The scene's phases from the `first`: each later one begun by its entry (its tags and
/// values, checked against the first's coordinates), each ended by the next one's `when`,
/// the last by the scene's `stop_when` if it has one.
fn ended_phases(
    scene: &SceneFile,
    first: ScenePhase,
    model_file: &Path,
    record_entries: &[String],
    at: &dyn Fn(usize) -> String,
    models: &mut Models,
) -> Result<Vec<ScenePhase>, CliError> {
    let mut phases = vec![first];
    for (k, entry) in scene.phases.iter().enumerate() {
        let where_ = |offset| format!("{} (phase {})", at(offset), k + 2);
        let before = phases.len() - 1;
        let in_force = next_in_force(
            entry,
            phases[before].in_force.clone(),
            model_file,
            &where_,
            models,
        )?;
        let phase = phase(
            entry,
            in_force,
            model_file,
            record_entries,
            &phases[0],
            &where_,
            models,
        )?;
        let end = end(&entry.when, "`when`", &phases[before])
            .map_err(|e| located(e, &where_(entry.when.span().start)))?;
        phases[before].end = Some(end);
        phases.push(phase);
    }
    if let Some(stop) = &scene.stop_when {
        let last = phases.len() - 1;
        let end = end(stop, "`stop_when`", &phases[last])
            .map_err(|e| located(e, &at(stop.span().start)))?;
        phases[last].end = Some(end);
    }
    Ok(phases)
}

/// The scene's `record` entries other than `phase` (always recorded) and the energy
/// residual, and whether the residual is asked for.
fn asked(scene: &SceneFile) -> (Vec<String>, bool) {
    let mut entries = Vec::new();
    let mut energy_residual = false;
    for entry in &scene.record {
        match entry.get_ref().trim() {
            ENERGY_RESIDUAL => energy_residual = true,
            "phase" => {}
            _ => entries.push(entry.get_ref().clone()),
        }
    }
    (entries, energy_residual)
}

/// The first phase's tags, parameter values and input laws: the scene's own (input data
/// files relative to the scene file, at `base`).
fn first_in_force(scene: &SceneFile, base: &Path) -> InForce {
    InForce {
        with: scene.with.iter().map(|t| t.get_ref().clone()).collect(),
        parameters: scene
            .set
            .iter()
            .map(|(n, v)| (n.get_ref().clone(), *v))
            .collect(),
        input: scene
            .input
            .iter()
            .map(|(name, law)| format!("{}={}", name.get_ref(), law_at(law, base)))
            .collect(),
        timed: Vec::new(),
        expressions: Vec::new(),
    }
}

/// The first phase and the scene's plan, made as `varmass run` makes them from `args` (the
/// model's warnings printed unless `quiet`); a failure is located at the scene's `model`
/// line (`model_at`) or, for the plan, the scene file.
fn first_phase(
    args: &RunArgs,
    in_force: InForce,
    path: &Path,
    models: &mut Models,
    (model_at, quiet): (&str, bool),
) -> Result<(ScenePhase, Plan), CliError> {
    let model = models.load(&args.model).map_err(|e| located(e, model_at))?;
    let warn = |w: &str| {
        if !quiet {
            eprintln!("warning: {w}");
        }
    };
    model.warnings.iter().for_each(|w| warn(w));
    let (program, plan) = crate::run::plan::parameters(args)
        .and_then(|values| Compiled::new(model).prepared(args, values, warn))
        .map_err(|e| located(e, &format!("{} (the first phase)", path.display())))?;
    let first = ScenePhase {
        program,
        flows: plan.flows.clone(),
        carry: Carry::Separation,
        state_masses: Vec::new(),
        record: plan.record.clone(),
        end: None,
        timed: None,
        selected: None,
        in_force,
    };
    Ok((first, plan))
}

/// The condition ending the first phase (phase 2's `when`, or the scene's `stop_when` when
/// there is one phase) may not hold at the start, as `--stop-when` may not.
fn first_end_not_yet_true(
    scene: &SceneFile,
    first: &ScenePhase,
    plan: &Plan,
    at: &dyn Fn(usize) -> String,
) -> Result<(), CliError> {
    let Some(first_end) = &first.end else {
        return Ok(());
    };
    let Some(observable) = first_end.observable else {
        return Ok(());
    };
    let check = crate::run::plan::StopWhen {
        observable,
        value: first_end.value,
        direction: first_end.direction,
    };
    let (what, offset) = match (scene.phases.first(), &scene.stop_when) {
        (Some(next), _) => ("phase 2's `when", next.when.span().start),
        (None, Some(stop)) => ("`stop_when", stop.span().start),
        (None, None) => ("`stop_when", 0),
    };
    let what = format!("{what} = \"{}\"`", first_end.text);
    not_yet_true(
        &first.program,
        &check,
        &what,
        plan.from,
        &plan.initial_state,
    )
    .map_err(|e| located(e, &at(offset)))
}

/// A program of its own for each phase whose end condition evaluates the model (the
/// phase's program moves into its system).
fn watch_programs(
    phases: &mut [ScenePhase],
    model_file: &Path,
    models: &mut Models,
) -> Result<(), CliError> {
    for phase in phases {
        let needs_watch = phase
            .end
            .as_ref()
            .is_some_and(|e| needs_program(e, &phase.program));
        if needs_watch {
            let watch = program_of(model_file, &phase.in_force, models)?;
            if let Some(end) = &mut phase.end {
                end.watch = Some(RefCell::new(watch));
            }
        }
    }
    Ok(())
}

/// A `[rail]`'s position indices, unit direction (x east, y north, z up) and length,
/// checked: three distinct coordinates of the model, an inclination in (0°, 90°], a finite
/// heading, a positive length; each mistake at its line.
fn railed(
    entry: &RailEntry,
    program: &Program,
    at: &dyn Fn(usize) -> String,
) -> Result<([usize; 3], [f64; 3], f64), CliError> {
    let names = entry.position.get_ref();
    let mut position = [0; 3];
    if names.len() != 3 {
        return Err(CliError::Input(format!(
            "{}: `position` names {} coordinates; a rail needs the three of the body's \
             reference point, x (east), y (north), z (up)",
            at(entry.position.span().start),
            names.len()
        )));
    }
    for (slot, name) in position.iter_mut().zip(names) {
        let key = format!("the rail's position `{}`", name.get_ref());
        *slot = coordinate(name.get_ref(), program, &key)
            .map_err(|e| located(e, &at(name.span().start)))?;
    }
    if position[0] == position[1] || position[1] == position[2] || position[0] == position[2] {
        return Err(CliError::Input(format!(
            "{}: `position` names a coordinate twice",
            at(entry.position.span().start)
        )));
    }
    let inclination = *entry.inclination.get_ref();
    if !(inclination > 0.0 && inclination <= 90.0 && entry.heading.is_finite()) {
        return Err(CliError::Input(format!(
            "{}: a rail's `inclination` is in degrees above the horizontal, in (0, 90], and \
             its `heading` a finite number of degrees (got {inclination}, {})",
            at(entry.inclination.span().start),
            entry.heading
        )));
    }
    let length = *entry.exit_travel.get_ref();
    if !(length.is_finite() && length > 0.0) {
        return Err(CliError::Input(format!(
            "{}: a rail's `exit_travel` (the reference point's travel to the exit, m) must be \
             positive (got {length})",
            at(entry.exit_travel.span().start)
        )));
    }
    let (i, h) = (inclination.to_radians(), entry.heading.to_radians());
    let direction = [i.cos() * h.sin(), i.cos() * h.cos(), i.sin()];
    Ok((position, direction, length))
}

/// The index of the coordinate `name` that a scene's `support` names.
fn supported(name: &str, program: &Program) -> Result<usize, CliError> {
    coordinate(name, program, &format!("`support = \"{name}\"`"))
}

/// The index of the coordinate `name`, which the scene's `key` names.
fn coordinate(name: &str, program: &Program, key: &str) -> Result<usize, CliError> {
    let coordinates: Vec<&str> = program.coordinate_names().collect();
    coordinates.iter().position(|c| *c == name).ok_or_else(|| {
        CliError::Input(format!(
            "{key} names no coordinate of the model; its coordinates are {}",
            coordinates.join(", ")
        ))
    })
}

/// The one-phase arguments of the scene's first phase, as `varmass run` would take them.
/// `asked`: the entries recorded and the sensitivities' columns.
fn first_args(
    read: &Read,
    file: PathBuf,
    in_force: &InForce,
    (record, sensitivity): (Vec<String>, Vec<String>),
) -> RunArgs {
    let scene = &read.scene;
    RunArgs {
        input: in_force.input.clone(),
        table: Vec::new(),
        model: ModelArgs {
            file,
            with: in_force.with.clone(),
        },
        set: settings(&in_force.parameters),
        init: scene
            .init
            .iter()
            .map(|(n, v)| format!("{}={v:?}", n.get_ref()))
            .collect(),
        from: scene.from,
        until: Some(scene.until),
        stop_when: Vec::new(),
        method: scene.method.0,
        tol: scene.tol,
        step: scene.step,
        max_steps: scene.max_steps.unwrap_or(10_000_000),
        max_seconds: None,
        record,
        sensitivity,
        at: Vec::new(),
        rates: false,
        every: None,
        csv: None,
        plot: None,
        summary_json: None,
        words: Words::Scene,
    }
}

/// An input's law as `--input` reads it: a data file relative to the scene file (as the
/// model and the CSV are), an expression as written.
fn law_at(law: &str, base: &Path) -> String {
    match is_table_file(law) {
        true => base.join(law.trim()).display().to_string(),
        false => law.to_string(),
    }
}

/// `NAME=VALUE` with the value written back exactly.
fn settings(parameters: &[(String, f64)]) -> Vec<String> {
    parameters
        .iter()
        .map(|(n, v)| format!("{n}={v:?}"))
        .collect()
}

/// The tags and parameter values of the phase `entry` begins: its tags (or the ones before),
/// the values before that its model still has, and its own `set`, each a parameter of it.
fn next_in_force(
    entry: &PhaseEntry,
    before: InForce,
    file: &Path,
    where_: &dyn Fn(usize) -> String,
    models: &mut Models,
) -> Result<InForce, CliError> {
    let with = match &entry.with {
        Some(tags) => tags.get_ref().iter().map(|t| t.get_ref().clone()).collect(),
        None => before.with,
    };
    let tag_span = entry
        .with
        .as_ref()
        .map_or(entry.when.span().start, |w| w.span().start);
    let model = models
        .load(&ModelArgs {
            file: file.to_path_buf(),
            with: with.clone(),
        })
        .map_err(|e| located(e, &where_(tag_span)))?;
    let known: Vec<(String, ())> = model
        .derivation
        .parameters
        .iter()
        .map(|(n, _)| (n.clone(), ()))
        .collect();
    let has = |n: &String| known.iter().any(|(k, _)| k == n);
    let mut parameters: Vec<(String, f64)> = before
        .parameters
        .into_iter()
        .filter(|(n, _)| has(n))
        .collect();
    let mut timed: Vec<String> = before.timed.into_iter().filter(has).collect();
    for (name, value) in &entry.set {
        resolve(name.get_ref(), &known, "a parameter")
            .map_err(|e| located(e, &where_(name.span().start)))?;
        if let SetValue::Number(value) = value {
            parameters.retain(|(n, _)| n != name.get_ref());
            parameters.push((name.get_ref().clone(), *value));
            timed.retain(|n| n != name.get_ref());
        }
    }
    let in_force = model.with_defaults(&parameters);
    let expressions = set_expressions(entry, &in_force, &mut parameters, &mut timed, where_)?;
    Ok(InForce {
        with,
        parameters,
        input: before.input,
        timed,
        expressions,
    })
}

/// The values `entry` sets by an expression of the change's time, each resolved against
/// the parameters with a value in force (`in_force`, defaults included); each gets a
/// stand-in value in `parameters` until the change (its value before, else 0) and is marked
/// `timed` (docs/scenes.md#a-value-set-at-the-change).
fn set_expressions(
    entry: &PhaseEntry,
    in_force: &[(String, f64)],
    parameters: &mut Vec<(String, f64)>,
    timed: &mut Vec<String>,
    where_: &dyn Fn(usize) -> String,
) -> Result<Vec<(String, SetExpression)>, CliError> {
    let mut expressions = Vec::new();
    for (name, value) in &entry.set {
        let SetValue::Expression(text) = value else {
            continue;
        };
        let name = name.get_ref();
        let expression = SetExpression::new(text, in_force).map_err(|e| {
            let here = where_(
                entry
                    .set
                    .keys()
                    .find(|k| k.get_ref() == name)
                    .map_or(0, |k| k.span().start),
            );
            located(e, &format!("{here}: `{name}`"))
        })?;
        let stand_in = in_force
            .iter()
            .find(|(n, _)| n == name)
            .map_or(0.0, |(_, v)| *v);
        parameters.retain(|(n, _)| n != name);
        parameters.push((name.clone(), stand_in));
        timed.retain(|n| n != name);
        timed.push(name.clone());
        expressions.push((name.clone(), expression));
    }
    Ok(expressions)
}

/// The phase `entry` begins, its coordinates and state masses checked against the first.
fn phase(
    entry: &PhaseEntry,
    in_force: InForce,
    file: &Path,
    record_entries: &[String],
    first: &ScenePhase,
    where_: &dyn Fn(usize) -> String,
    models: &mut Models,
) -> Result<ScenePhase, CliError> {
    let here = where_(entry.when.span().start);
    let model = models
        .load(&ModelArgs {
            file: file.to_path_buf(),
            with: in_force.with.clone(),
        })
        .map_err(|e| located(e, &here))?;
    let selected = model.selected.clone();
    let timed = timed_of(&in_force, &model.with_defaults(&in_force.parameters));
    let (program, flows) = program_from(model, &in_force).map_err(|e| located(e, &here))?;
    let same = |p: &Program| {
        let k = p.state_mass_count();
        let coordinates: Vec<&str> = p.coordinate_names().collect();
        let masses: Vec<&str> = p.mass_names().take(k).collect();
        (coordinates.join(", "), masses.join(", "))
    };
    if same(&program) != same(&first.program) {
        let (now, then) = (same(&program), same(&first.program));
        let tag_span = entry
            .with
            .as_ref()
            .map_or(entry.when.span().start, |w| w.span().start);
        return Err(CliError::Input(format!(
            "{}: this phase's model has the coordinates [{}] and state masses [{}], the first \
             phase's [{}] and [{}]: phases switch parameters and tags of one scene, never its \
             coordinates",
            where_(tag_span),
            now.0,
            now.1,
            then.0,
            then.1
        )));
    }
    let state_masses = state_masses(entry, &program, where_)?;
    let record = record(&program, &selected, &in_force.parameters, record_entries)
        .map_err(|e| located(e, &here))?;
    let carry = match entry.carry {
        CarryRule::Separation => Carry::Separation,
        CarryRule::Capture => Carry::Capture,
    };
    Ok(ScenePhase {
        program,
        flows,
        carry,
        state_masses,
        record,
        end: None,
        selected: timed.is_some().then(|| selected.clone()),
        timed,
        in_force,
    })
}

/// What the phase with `in_force` (its values `values`, defaults included) takes from the
/// run at its change: `None` if it sets nothing by an expression and carries no such value.
fn timed_of(in_force: &InForce, values: &[(String, f64)]) -> Option<Timed> {
    if in_force.timed.is_empty() {
        return None;
    }
    let own: Vec<&String> = in_force.expressions.iter().map(|(n, _)| n).collect();
    Some(Timed {
        values: values.to_vec(),
        sets: in_force.expressions.clone(),
        carried: (in_force.timed.iter())
            .filter(|n| !own.contains(n))
            .cloned()
            .collect(),
    })
}

/// The recorded columns of phase `phase` again, with the values its change set: a recorded
/// expression reads a parameter's value when it is resolved.
pub fn record_again(
    program: &Program,
    selected: &SystemAst,
    values: &[(String, f64)],
    record_entries: &[String],
) -> Result<Vec<(String, Recorded)>, CliError> {
    record(program, selected, values, record_entries)
}

/// The state masses `entry` sets, by index, each positive.
fn state_masses(
    entry: &PhaseEntry,
    program: &Program,
    where_: &dyn Fn(usize) -> String,
) -> Result<Vec<(usize, f64)>, CliError> {
    let k = program.state_mass_count();
    let known: Vec<(String, usize)> = program
        .mass_names()
        .take(k)
        .enumerate()
        .map(|(i, m)| (m.to_string(), i))
        .collect();
    let mut set = Vec::new();
    for (name, value) in &entry.masses {
        let here = where_(name.span().start);
        let index =
            resolve(name.get_ref(), &known, "a state mass").map_err(|e| located(e, &here))?;
        if !(value.is_finite() && *value > 0.0) {
            return Err(CliError::Input(format!(
                "{here}: the state mass `{}` is set to {value}: a mass must be positive",
                name.get_ref()
            )));
        }
        set.push((index, *value));
    }
    Ok(set)
}

/// The recorded columns in the phase's model (the same names as the first phase's).
fn record(
    program: &Program,
    selected: &SystemAst,
    parameters: &[(String, f64)],
    record_entries: &[String],
) -> Result<Vec<(String, Recorded)>, CliError> {
    let known = observables(program);
    let scope = Scope::new(program, selected, &known, parameters);
    columns(record_entries, &scope, Words::Scene)
}

/// The condition `text` (the scene's `key`) ending `phase`: `t` or one of its quantities
/// crossing a value.
fn end(text: &toml::Spanned<String>, key: &str, phase: &ScenePhase) -> Result<End, CliError> {
    let text = text.get_ref();
    let (name, direction, value) = condition(text, key)?;
    let observable = match name.as_str() {
        "t" => None,
        _ => Some(resolve(&name, &observables(&phase.program), "a quantity")?),
    };
    Ok(End {
        observable,
        value,
        direction,
        text: text.clone(),
        watch: None,
    })
}

/// Whether `end` needs the model to be evaluated (it is not t, a coordinate or a state
/// mass, which the core reads from the state).
fn needs_program(end: &End, program: &Program) -> bool {
    match end.observable {
        None | Some(Observable::Coordinate(_)) => false,
        Some(Observable::Mass(i)) => i >= program.state_mass_count(),
        Some(_) => true,
    }
}

/// The program of `file` with `in_force`'s tags and values.
fn program_of(file: &Path, in_force: &InForce, models: &mut Models) -> Result<Program, CliError> {
    let model = models.load(&ModelArgs {
        file: file.to_path_buf(),
        with: in_force.with.clone(),
    })?;
    Ok(program_from(model, in_force)?.0)
}

/// The program of a loaded model with `in_force`'s values, as `varmass run` builds it, and
/// its flows' names.
fn program_from(
    model: LoadedModel,
    in_force: &InForce,
) -> Result<(Program, Vec<String>), CliError> {
    let args = RunArgs {
        input: in_force.input.clone(),
        table: Vec::new(),
        model: ModelArgs {
            file: PathBuf::new(),
            with: in_force.with.clone(),
        },
        set: settings(&in_force.parameters),
        init: Vec::new(),
        from: 0.0,
        until: Some(0.0),
        stop_when: Vec::new(),
        method: crate::args::Method::DormandPrince,
        tol: None,
        step: None,
        max_steps: 1,
        max_seconds: None,
        record: Vec::new(),
        sensitivity: Vec::new(),
        at: Vec::new(),
        rates: false,
        every: None,
        csv: None,
        plot: None,
        summary_json: None,
        words: Words::Scene,
    };
    let values = crate::run::plan::parameters(&args)?;
    Compiled::new(model).program_only(&args, &values)
}

/// `error` with the place in the scene file it comes from.
fn located(error: CliError, place: &str) -> CliError {
    match error {
        CliError::Input(message) => CliError::Input(format!("{place}: {message}")),
        read @ CliError::Read { .. } => CliError::Input(format!("{place}: {read}")),
        other => other,
    }
}
