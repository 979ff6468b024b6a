//! From a scene file to its phases, every name checked before the first step: each phase's
//! program (its tags and the parameter values in force), the state masses it sets, its
//! recorded columns, and the condition that ends it (the next phase's `when`, or the
//! scene's `stop_when` for the last). A mistake is a [`CliError::Input`] pointing at the
//! scene file's line.

use std::path::{Path, PathBuf};

use varmass::core::{Carry, Direction};
use varmass::interpret::Program;
use varmass::symbolic::parse::ast::SystemAst;

use super::file::{line_column, CarryRule, PhaseEntry, Read};
use crate::args::{ModelArgs, RunArgs, Words};
use crate::error::CliError;
use crate::model::{load, LoadedModel};
use crate::run::names::{observables, resolve, Observable};
use crate::run::plan::{condition, not_yet_true, Plan};
use crate::run::record::{columns, Recorded, Scope};

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
    /// its system), when the quantity is not a state entry.
    pub watch: Option<Program>,
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
    /// Its tags and parameter values.
    in_force: InForce,
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
}

/// What a phase needs from the one before: its tags and parameter values.
#[derive(Clone)]
struct InForce {
    with: Vec<String>,
    parameters: Vec<(String, f64)>,
}

/// Checks the scene read from `path` and builds its phases.
pub fn build(read: &Read, path: &Path) -> Result<Scene, CliError> {
    let scene = &read.scene;
    let at = |offset: usize| format!("{}:{}", path.display(), line_column(&read.source, offset));
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let model_file = base.join(scene.model.get_ref());
    let mut entries_asked: Vec<String> = Vec::new();
    let mut energy_residual = false;
    for entry in &scene.record {
        match entry.get_ref().trim() {
            ENERGY_RESIDUAL => energy_residual = true,
            "phase" => {}
            _ => entries_asked.push(entry.get_ref().clone()),
        }
    }
    let in_force = InForce {
        with: scene.with.iter().map(|t| t.get_ref().clone()).collect(),
        parameters: scene
            .set
            .iter()
            .map(|(n, v)| (n.get_ref().clone(), *v))
            .collect(),
    };
    let args = first_args(read, model_file.clone(), &in_force, entries_asked.clone());
    let model = load(&args.model).map_err(|e| located(e, &at(scene.model.span().start)))?;
    for warning in &model.warnings {
        eprintln!("warning: {warning}");
    }
    let (program, plan) = crate::run::prepare(&args, model, |w| eprintln!("warning: {w}"))
        .map_err(|e| located(e, &format!("{} (the first phase)", path.display())))?;
    let record_entries = match entries_asked.is_empty() {
        true => plan.record.iter().map(|(n, _)| n.clone()).collect(),
        false => entries_asked,
    };
    let first = ScenePhase {
        program,
        flows: plan.flows.clone(),
        carry: Carry::Separation,
        state_masses: Vec::new(),
        record: plan.record.clone(),
        end: None,
        in_force,
    };
    let mut phases = vec![first];
    for (k, entry) in scene.phases.iter().enumerate() {
        let where_ = |offset| format!("{} (phase {})", at(offset), k + 2);
        let before = phases.len() - 1;
        let in_force = next_in_force(entry, phases[before].in_force.clone(), &model_file, &where_)?;
        let phase = phase(
            entry,
            in_force,
            &model_file,
            &record_entries,
            &phases[0],
            &where_,
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
    if let Some(first_end) = &phases[0].end {
        if let Some(observable) = first_end.observable {
            let check = crate::run::plan::StopWhen {
                observable,
                value: first_end.value,
                direction: first_end.direction,
            };
            // The condition ending the first phase: phase 2's `when`, or the scene's
            // `stop_when` when there is one phase.
            let (what, offset) = match (scene.phases.first(), &scene.stop_when) {
                (Some(next), _) => ("phase 2's `when", next.when.span().start),
                (None, Some(stop)) => ("`stop_when", stop.span().start),
                (None, None) => ("`stop_when", 0),
            };
            let what = format!("{what} = \"{}\"`", first_end.text);
            not_yet_true(
                &phases[0].program,
                &check,
                &what,
                plan.from,
                &plan.initial_state,
            )
            .map_err(|e| located(e, &at(offset)))?;
        }
    }
    for phase in &mut phases {
        let needs_watch = phase
            .end
            .as_ref()
            .is_some_and(|e| needs_program(e, &phase.program));
        if needs_watch {
            let watch = program_of(&model_file, &phase.in_force)?;
            if let Some(end) = &mut phase.end {
                end.watch = Some(watch);
            }
        }
    }
    Ok(Scene {
        phases,
        plan,
        energy_residual,
        csv: scene.csv.as_ref().map(|c| base.join(c)),
    })
}

/// The one-phase arguments of the scene's first phase, as `varmass run` would take them.
fn first_args(read: &Read, file: PathBuf, in_force: &InForce, record: Vec<String>) -> RunArgs {
    let scene = &read.scene;
    RunArgs {
        input: Vec::new(),
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
        every: None,
        csv: None,
        plot: None,
        words: Words::Scene,
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
) -> Result<InForce, CliError> {
    let with = match &entry.with {
        Some(tags) => tags.get_ref().iter().map(|t| t.get_ref().clone()).collect(),
        None => before.with,
    };
    let tag_span = entry
        .with
        .as_ref()
        .map_or(entry.when.span().start, |w| w.span().start);
    let model = load(&ModelArgs {
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
    let mut parameters: Vec<(String, f64)> = before
        .parameters
        .into_iter()
        .filter(|(n, _)| known.iter().any(|(k, _)| k == n))
        .collect();
    for (name, value) in &entry.set {
        resolve(name.get_ref(), &known, "a parameter")
            .map_err(|e| located(e, &where_(name.span().start)))?;
        parameters.retain(|(n, _)| n != name.get_ref());
        parameters.push((name.get_ref().clone(), *value));
    }
    Ok(InForce { with, parameters })
}

/// The phase `entry` begins, its coordinates and state masses checked against the first.
fn phase(
    entry: &PhaseEntry,
    in_force: InForce,
    file: &Path,
    record_entries: &[String],
    first: &ScenePhase,
    where_: &dyn Fn(usize) -> String,
) -> Result<ScenePhase, CliError> {
    let here = where_(entry.when.span().start);
    let model = load(&ModelArgs {
        file: file.to_path_buf(),
        with: in_force.with.clone(),
    })
    .map_err(|e| located(e, &here))?;
    let selected = model.selected.clone();
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
        in_force,
    })
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
fn program_of(file: &Path, in_force: &InForce) -> Result<Program, CliError> {
    let model = load(&ModelArgs {
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
        input: Vec::new(),
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
        every: None,
        csv: None,
        plot: None,
        words: Words::Scene,
    };
    let prepared = crate::run::program(&args, model, |_| {})?;
    Ok((prepared.program, prepared.flows))
}

/// `error` with the place in the scene file it comes from.
fn located(error: CliError, place: &str) -> CliError {
    match error {
        CliError::Input(message) => CliError::Input(format!("{place}: {message}")),
        read @ CliError::Read { .. } => CliError::Input(format!("{place}: {read}")),
        other => other,
    }
}
