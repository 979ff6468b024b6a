//! `varmass run SCENE.toml --sensitivity NAME` (docs/sensitivities.md#scenes): the scene's
//! columns resolved against its first phase's model and checked against every phase before
//! the first step — the changes the core carries the columns across, no value set at a
//! change, no parameter of a column set by a later phase — and the gradients of what each
//! phase records and watches compiled.

use varmass::core::sensitivity::Column;

use crate::error::CliError;
use crate::run::names::Observable;
use crate::run::sensitivity::{check_method, prepare_observables, resolve_names};

use super::build::{End, Scene};
use super::file::Read;

/// Resolves `names` into the scene's plan and prepares its phases' programs; nothing to do
/// without `names` or the quantities' rates.
pub fn prepare(scene: &mut Scene, read: &Read, names: &[String]) -> Result<(), CliError> {
    if names.is_empty() && !scene.plan.rates {
        return Ok(());
    }
    let first = &scene.phases[0];
    scene.plan.sensitivities = resolve_names(names, &first.program)?;
    check_method(scene.plan.method, &first.program)?;
    let columns: Vec<&str> = (scene.plan.sensitivities.iter())
        .filter_map(|s| match s.column {
            Column::Parameter(name) => Some(name),
            _ => None,
        })
        .collect();
    held_starts(scene)?;
    let first = &scene.phases[0];
    let first_values = first.parameters().to_vec();
    let last = scene.phases.len() - 1;
    for (i, phase) in scene.phases.iter_mut().enumerate() {
        if phase.timed.is_some() {
            return Err(refused(i, "sets a value at its change"));
        }
        if i < last {
            carried(i, phase.end.as_ref(), phase.program.state_mass_count())?;
        }
        // Set by the phase itself, to any value (the same number too: the scene fixes it
        // there, and the column's parameter is the first phase's), or in force with
        // another value (a model without it).
        let sets = |name: &&&str| {
            i > 0 && (read.scene.phases[i - 1].set.keys()).any(|k| k.get_ref() == **name)
        };
        let value = |values: &[(String, f64)], name: &str| {
            values.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
        };
        let differs = |name: &&&str| value(phase.parameters(), name) != value(&first_values, name);
        if let Some(name) = columns.iter().find(sets) {
            return Err(refused(
                i,
                &format!("sets `{name}`, a parameter of a column"),
            ));
        }
        if let Some(name) = columns.iter().find(differs) {
            let does = format!("has another `{name}` (a parameter of a column) than phase 1");
            return Err(refused(i, &does));
        }
        let watched = phase.end.iter().filter_map(|e| e.observable);
        prepare_observables(&mut phase.program, watched, &phase.record)?;
    }
    Ok(())
}

/// Refuses a column of an initial value the support or the rail fixes: the body starts at
/// rest there (a velocity's column would start it moving), and the rail is laid from the
/// start (its origin does not move with the initial position, where a run from a moved
/// start lays it there: the review of this change measured ∂(x, z)/∂x₀ = (1.36, −0.06)
/// against (1, 0)).
fn held_starts(scene: &Scene) -> Result<(), CliError> {
    let n = scene.phases[0].program.coordinate_count();
    let rail = scene.rail.as_ref().map(|r| r.position);
    let support = scene.support.as_ref().map(|(k, _)| *k);
    for s in &scene.plan.sensitivities {
        let Column::Initial(i) = s.column else {
            continue;
        };
        let velocity = (n..2 * n).contains(&i);
        let fixed = match (rail, support) {
            (Some(position), _) => velocity || position.contains(&i),
            (None, Some(k)) => i == n + k,
            (None, None) => false,
        };
        if fixed {
            return Err(CliError::Input(format!(
                "--sensitivity {}: the scene's {} fixes this initial value (the body starts \
                 at rest on it, and a rail is laid from the start); its derivative is not \
                 followed (docs/sensitivities.md#scenes)",
                s.name,
                if rail.is_some() {
                    "`[rail]`"
                } else {
                    "`support`"
                }
            )));
        }
    }
    Ok(())
}

/// Whether the change at the end of phase `i` carries the columns: an end on a
/// coordinate, a velocity or a state mass reaching a value, or at a time (the core's
/// `Event::state_reaches`, `velocity_reaches`, `time_reaches`; a support's lift-off and a
/// rail's exit are carried too, before the scene's phases).
fn carried(i: usize, end: Option<&End>, state_masses: usize) -> Result<(), CliError> {
    match end.map(|e| e.observable) {
        Some(None | Some(Observable::Coordinate(_) | Observable::Velocity(_))) => Ok(()),
        Some(Some(Observable::Mass(k))) if k < state_masses => Ok(()),
        _ => {
            let text = end.map_or("", |e| e.text.as_str());
            Err(refused(
                i,
                &format!(
                    "ends on `{text}`, whose time's derivative is not carried yet (only a \
                     change on a coordinate, a velocity or a state mass reaching a value, or \
                     at a time, is)"
                ),
            ))
        }
    }
}

/// The refusal of a scene whose phase `i` (from 0) `does` what the columns cannot follow.
fn refused(i: usize, does: &str) -> CliError {
    CliError::Input(format!(
        "--sensitivity: phase {} {does}; a scene's sensitivities follow a support, a rail \
         and changes on a coordinate, a velocity or a state mass reaching a value, or at a \
         time (docs/sensitivities.md#scenes)",
        i + 1
    ))
}
