//! Where a scene meets the const-generic core: one arm per number of coordinates (the
//! sizes of `varmass run`, padded to the same state masses), each running the phases with
//! [`run_phases_keeping`] and the chosen stepper.

use varmass::core::nalgebra::SVector;
use varmass::core::phases::ALREADY_PAST;
use varmass::core::rail::{on_rail, pad_phase, slide_phase};
use varmass::core::sensitivity::{Column, Sensitive};
use varmass::core::support::{held_phase, starts_held};
use varmass::core::{
    continue_phases_keeping, run_phases_keeping, Phase, PhaseChange, PhasedSolution, Record,
    RunConfig, Statistics, StepError, StepErrorKind, StopReason, Supported, VariableMassSystem,
};
use varmass::interpret::{Program, TapeSystem};

use super::build::{End, RailSpec, Scene};
use super::system::SceneSystem;
use super::timed::{self, SetAt, Timed};
use crate::args::Method;
use crate::error::CliError;
use crate::run::dispatch::{on_sizes, padded_steps, SizedRun, Sizes};
use crate::run::integrate::{event, with_stepper, Watcher};
use crate::run::names::{evaluate, shown};
use crate::run::plan::Plan;
use crate::run::record::Recorded;
use crate::run::sensitivity::{on_sensitive_sizes, recorded_row, Constraint, SensitiveRun};
use crate::run::watch::Watched;

/// What a scene's run computed, sizes erased.
pub struct Flown {
    /// Every point of every phase, `[q, p, m_s]` (a change appears twice: before, after).
    pub points: Vec<(f64, Vec<f64>)>,
    /// The phase of each point.
    pub phase: Vec<usize>,
    /// The changes of phase.
    pub changes: Vec<PhaseChange>,
    /// The energy-budget residual at each point, when recorded.
    pub energy_residual: Vec<f64>,
    /// Whether the last phase ended on the scene's `stop_when`.
    pub stopped: bool,
    /// The work of every phase.
    pub statistics: Statistics,
    /// The phases' programs, given back for recording.
    pub programs: Vec<Program>,
    /// Why the run failed, if it did: the points end at the last accepted one.
    pub failure: Option<CliError>,
    /// When the body left its support (`support = "y"`): the start if it lifted at once,
    /// `None` if it was still held at the end (or the scene has no support).
    pub lift_off: Option<f64>,
    /// When the body left its rail (`[rail]`) and its speed then, `None` if it was still on
    /// the rail at the end (or the scene has no rail).
    pub rail_exit: Option<(f64, f64)>,
    /// The closest every accepted step of every phase came to a singular attitude, rad.
    pub closest_singular_attitude: Option<f64>,
    /// The values phases set at their changes by expressions of the change's time.
    pub sets: Vec<SetAt>,
    /// The derivative columns at each point (`--sensitivity`; each row empty without), as
    /// many rows as could be had.
    pub derivatives: Vec<Vec<f64>>,
}

/// Runs the scene's phases in turn, in the monomorphized code of the first phase's sizes
/// padded as `varmass run` pads ([`on_sizes`]; the phases share their coordinates and
/// state masses).
pub fn fly(mut scene: Scene) -> Result<Flown, CliError> {
    land_on_outputs(&mut scene);
    let sizes = Sizes::of(&scene.phases[0].program);
    if scene.plan.differentiated() {
        return on_sensitive_sizes(sizes, scene);
    }
    // Padded even where `varmass run` has an exact arm: a scene's numbers stay those of
    // the padded arms it has always run in.
    on_sizes(sizes, false, scene)
}

/// The plan's output times (a fit's data times) made stop times of every program that runs
/// a phase (the support's and the rail's too), so that each phase lands on them.
fn land_on_outputs(scene: &mut Scene) {
    let at = &scene.plan.at;
    let held = scene.support.iter_mut().map(|(_, program)| program);
    let railed = scene
        .rail
        .iter_mut()
        .flat_map(|rail| rail.programs.iter_mut());
    let phases = scene.phases.iter_mut().map(|phase| &mut phase.program);
    for program in phases.chain(held).chain(railed) {
        program.land_on(at);
    }
}

impl SizedRun for Scene {
    type Output = Flown;

    fn run<const N: usize, const S: usize>(self, len: usize) -> Result<Flown, CliError> {
        fly_sized::<TapeSystem<N, S>, N, S>(self, len)
    }
}

/// With `--sensitivity`, each phase's system inside the core's `Sensitive`
/// (docs/sensitivities.md#scenes).
impl SensitiveRun for Scene {
    type Output = Flown;

    fn run<const N: usize, const S: usize, const SA: usize>(self) -> Result<Flown, CliError> {
        let len = self.phases[0].program.state_len();
        fly_sized::<Sensitive<TapeSystem<N, S>, S>, N, SA>(self, len)
    }
}

/// The scene's run settings: the plan's end and step limit (each phase's), and the
/// energy-budget residual if recorded.
fn config(plan: &Plan, energy_residual: bool) -> RunConfig {
    RunConfig {
        max_steps: usize::try_from(plan.max_steps).unwrap_or(usize::MAX),
        ..RunConfig::until(plan.until)
    }
    .recording(Record {
        energy_residual,
        ..Record::default()
    })
}

/// The scene's failure `e` in the tool's words, given the changes of phase so far and the
/// phase of the last point (`ended`): a phase whose end condition holds where it begins,
/// or the failure described in the model of the phase it happened in.
fn failure<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    e: StepError<S>,
    ended: (&[PhaseChange], usize),
    phases: &[Phase<'_, Supported<Sys>, S>],
    ends: &[Option<End>],
    plan: &Plan,
    flows: &[Vec<String>],
) -> CliError {
    let (changes, last) = ended;
    let entered = changes.last().map_or(0, |c| c.phase);
    if never_triggers(&e) {
        // The change into the phase is recorded; none of its points are.
        let when = ends
            .get(entered)
            .and_then(Option::as_ref)
            .map_or("?", |e| &e.text);
        return CliError::Run(format!(
            "phase {} ends when `{when}`, which already holds (or stands exactly on its \
             boundary) where the phase begins, at t = {}: it could never end the phase\n\
             help: give the phase a condition that its motion reaches later",
            entered + 1,
            shown(e.time)
        ));
    }
    // The phase the run failed in, with its own model's flows: the last one entered (a
    // failure at its first step leaves no point of it).
    let k = entered.max(last).min(phases.len() - 1);
    phases[k].system.system.describe(plan, &flows[k], e)
}

/// Whether `error` is the core's refusal of a phase whose end condition holds at its start.
fn never_triggers<const S: usize>(error: &StepError<S>) -> bool {
    matches!(error.kind, StepErrorKind::InvalidConfiguration { reason } if reason == ALREADY_PAST)
}

/// The scene's run in the arm `(N, S)` with the phases' systems `Sys` (plain, or with the
/// sensitivities' columns: then `S` is the augmented state's length).
fn fly_sized<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    scene: Scene,
    len: usize,
) -> Result<Flown, CliError> {
    let Scene {
        phases: built,
        plan,
        energy_residual,
        support,
        rail,
        ..
    } = scene;
    let columns: Vec<Column> = plan.sensitivities.iter().map(|s| s.column).collect();
    let k = built[0].program.state_mass_count();
    let Unpacked {
        systems,
        records,
        ends,
        masses,
        flows,
        timed,
    } = unpacked::<Sys, N, S>(built, &columns)?;
    let watchers = end_watchers::<S>(&ends);
    let mut phases = scene_phases::<Sys, N, S>(systems, &masses, (&ends, &watchers), k);
    let start = phases[0].system.system.start(&plan)?;
    let held = held_first(&mut phases, support, start, (&plan, &columns))?;
    let railed = rail_first(&mut phases, rail, start, (&plan, &columns))?;
    let inserted =
        usize::from(held == Some(true)) + railed.map_or(0, |on_pad| 1 + usize::from(on_pad));
    let timed::Ran {
        phased,
        error,
        refused,
        sets,
    } = fly_phases(
        &mut phases,
        aligned(timed, &ends, inserted),
        inserted,
        start,
        &plan,
        energy_residual,
        len,
    )?;
    let hold = Hold {
        inserted,
        held,
        railed,
    };
    let mut constraints = constraints(&phased, &phases);
    let (phased, lift_off, rail_exit) =
        after_hold((phased, &mut constraints), &phases, hold, start, &ends)?;
    let offset = inserted;
    let last = phased.phase.last().copied().unwrap_or(0);
    let failure = refused.or_else(|| {
        error.map(|e| {
            let ended = (&phased.changes[..], last);
            failure::<Sys, N, S>(e, ended, &phases[offset..], &ends, &plan, &flows)
        })
    });
    let stopped = phases.len() == last + 1 + offset
        && phases[last + offset].until.is_some()
        && phased.solution.stop == (StopReason::EventFound { index: 0 });
    let scene_phases = &phases[offset..];
    let (derivatives, unrecorded) = derivative_rows(
        (&phased, &constraints),
        scene_phases,
        (&plan, &records),
        (&ends, stopped),
    );
    let failure = failure.or(unrecorded);
    let mut flown = flown(phased, (phases, offset), len, stopped, failure);
    flown.lift_off = lift_off;
    flown.rail_exit = rail_exit;
    flown.sets = sets;
    flown.derivatives = derivatives;
    Ok(flown)
}

/// The scene's phases of `systems`, each with its state masses and its end (`ends`, with
/// their `watchers`) as an event; `k` state masses.
fn scene_phases<'a, Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    systems: Vec<(Supported<Sys>, varmass::core::Carry)>,
    masses: &'a [Vec<(usize, f64)>],
    (ends, watchers): (&[Option<End>], &'a [Option<Watcher<'a, S>>]),
    k: usize,
) -> Vec<Phase<'a, Supported<Sys>, S>> {
    let events = ends.iter().zip(watchers).map(|(end, w)| {
        end.as_ref()
            .map(|e| event::<N, S>(e.observable, e.value, e.direction, k, w.as_deref()))
    });
    systems
        .into_iter()
        .zip(masses)
        .zip(events)
        .map(|(((system, carry), state_masses), until)| Phase {
            system,
            carry,
            state_masses,
            until,
        })
        .collect()
}

/// What holds the body at each point of `phased` (before the support's and the rail's
/// phases are renumbered into the first scene phase): its phase's support or rail.
fn constraints<Sys, const N: usize, const S: usize>(
    phased: &PhasedSolution<N, S>,
    phases: &[Phase<'_, Supported<Sys>, S>],
) -> Vec<Constraint> {
    let constraint = |k: &usize| {
        phases
            .get(*k)
            .map_or(Constraint::default(), |p| Constraint {
                held: p.system.held,
                rail: p.system.rail,
            })
    };
    phased.phase.iter().map(constraint).collect()
}

/// The derivative columns of every point of `phased` (renumbered: phase k is `phases[k]`,
/// recording `records[k]`; the body held at each as `constraints` says), the last point's
/// moved with the time of the condition that ended the run there (`stopped`, the phase's
/// `ends`). Without sensitivities each row is empty. At the first point where they cannot
/// be had, the rows before it and the error.
fn derivative_rows<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    (phased, constraints): (&PhasedSolution<N, S>, &[Constraint]),
    phases: &[Phase<'_, Supported<Sys>, S>],
    (plan, records): (&Plan, &[Vec<(String, Recorded)>]),
    (ends, stopped): (&[Option<End>], bool),
) -> (Vec<Vec<f64>>, Option<CliError>) {
    let points = phased.solution.times.iter().zip(&phased.solution.states);
    let last = phased.phase.len().saturating_sub(1);
    let mut rows = Vec::with_capacity(phased.phase.len());
    for (i, ((t, state), &k)) in points.zip(&phased.phase).enumerate() {
        let event = match i == last && stopped {
            true => ends
                .get(k)
                .and_then(Option::as_ref)
                .and_then(|e| e.observable),
            false => None,
        };
        let system = &phases[k].system.system;
        let constraint = constraints.get(i).copied().unwrap_or_default();
        let row = system.derivatives((plan, &records[k]), (*t, state), event, constraint);
        match recorded_row(row, *t) {
            Ok(row) => rows.push(row),
            Err(error) => return (rows, Some(error)),
        }
    }
    (rows, None)
}

/// The scene's phases taken apart: each one's free system and carry rule, end, state
/// masses set, flows and values set at its change.
struct Unpacked<Sys> {
    systems: Vec<(Supported<Sys>, varmass::core::Carry)>,
    records: Vec<Vec<(String, Recorded)>>,
    ends: Vec<Option<End>>,
    masses: Vec<Vec<(usize, f64)>>,
    flows: Vec<Vec<String>>,
    timed: Vec<Option<Timed>>,
}

/// [`Unpacked`] of the built phases, each program sized to the arm's `N`, `S`.
fn unpacked<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    built: Vec<super::build::ScenePhase>,
    columns: &[Column],
) -> Result<Unpacked<Sys>, CliError> {
    let mut out = Unpacked {
        systems: Vec::new(),
        records: Vec::new(),
        ends: Vec::new(),
        masses: Vec::new(),
        flows: Vec::new(),
        timed: Vec::new(),
    };
    for phase in built {
        out.flows.push(phase.flows);
        out.timed.push(phase.timed);
        let system = Sys::build(phase.program, columns)?;
        out.systems.push((Supported::free(system), phase.carry));
        out.records.push(phase.record);
        out.ends.push(phase.end);
        out.masses.push(phase.state_masses);
    }
    Ok(out)
}

/// What goes before the scene's phases: how many phases were inserted (a support's held
/// phase, a rail's pad and slide), and the support's and the rail's "held at the start".
#[derive(Clone, Copy)]
struct Hold {
    inserted: usize,
    held: Option<bool>,
    railed: Option<bool>,
}

/// The run after a hold: the first phase's end condition checked over the hold
/// ([`met_while_held`]), the rail's exit (time, speed) read, the inserted phases numbered
/// as the scene's first ([`renumbered`]; `constraints`, one per point, lose the points it
/// drops), and the lift-off time.
#[allow(clippy::type_complexity)]
fn after_hold<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    (phased, constraints): (PhasedSolution<N, S>, &mut Vec<Constraint>),
    phases: &[Phase<'_, Supported<Sys>, S>],
    hold: Hold,
    start: (f64, SVector<f64, S>),
    ends: &[Option<End>],
) -> Result<(PhasedSolution<N, S>, Option<f64>, Option<(f64, f64)>), CliError> {
    let Hold {
        inserted,
        held,
        railed,
    } = hold;
    if inserted > 0 {
        let what = match railed {
            Some(_) => "on its `[rail]`",
            None => "on its `support`",
        };
        met_while_held(&phased, (phases, inserted), start, ends, what)?;
    }
    let exit = railed.and_then(|on_pad| phased.changes.get(usize::from(on_pad)));
    let rail_exit = exit.map(|change| (change.time, exit_speed(&phased, phases, change.time)));
    let (phased, removed) = renumbered(phased, inserted, constraints);
    let starts_held = held == Some(true) || railed == Some(true);
    let lift_off = match (held.or(railed), starts_held) {
        (None, _) => None,
        (Some(_), false) => Some(start.0),
        (Some(_), true) => removed.first().copied(),
    };
    Ok((phased, lift_off, rail_exit))
}

/// Runs the phases with the plan's stepper ([`timed::run`]: a phase that takes values at
/// its change is continued from the last point once its programs have them).
fn fly_phases<'a, Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phases: &mut [Phase<'a, Supported<Sys>, S>],
    (timed, watches): (
        Vec<Option<Timed>>,
        Vec<Option<&std::cell::RefCell<Program>>>,
    ),
    offset: usize,
    start: (f64, SVector<f64, S>),
    plan: &Plan,
    energy_residual: bool,
    len: usize,
) -> Result<timed::Ran<N, S>, CliError> {
    let config = config(plan, energy_residual);
    let (len, padded) = Sys::entries(len, plan.sensitivities.len());
    let steps = padded_steps(plan.steps, plan.method, len, padded)?;
    let (from, until) = (plan.from, plan.until);
    macro_rules! phased_with {
        ($stepper:ident, $settings:expr) => {
            timed::run(phases, &timed, &watches, offset, |phases, range, before| {
                let stepper_for = |system, t, state| {
                    $stepper::new(system, t, state, $settings).map(|s| Watched::new(s, from, until))
                };
                match before {
                    None => run_phases_keeping(&phases[range], start, stepper_for, &config),
                    Some(phased) => {
                        let system = &phases[range.start - 1].system;
                        continue_phases_keeping(
                            phased,
                            system,
                            &phases[range],
                            stepper_for,
                            &config,
                        )
                    }
                }
            })
        };
    }
    Ok(with_stepper!(plan.method, steps, phased_with))
}

/// Each phase's values set at its change and the program watching its end condition,
/// aligned with the phases run (`offset` 1 behind a held phase, which sets nothing).
fn aligned(
    timed: Vec<Option<Timed>>,
    ends: &[Option<End>],
    offset: usize,
) -> (
    Vec<Option<Timed>>,
    Vec<Option<&std::cell::RefCell<Program>>>,
) {
    let mut watches: Vec<_> = ends
        .iter()
        .map(|e| e.as_ref().and_then(|e| e.watch.as_ref()))
        .collect();
    let mut timed = timed;
    for _ in 0..offset {
        timed.insert(0, None);
        watches.insert(0, None);
    }
    (timed, watches)
}

/// The watcher of each phase's end condition (none for a phase without one).
fn end_watchers<const S: usize>(ends: &[Option<End>]) -> Vec<Option<Watcher<'_, S>>> {
    ends.iter()
        .map(|e| {
            e.as_ref()
                .and_then(|e| watcher(e.watch.as_ref(), e.observable, e.value))
        })
        .collect()
}

/// g(t, state) = the observable minus `value` (t − `value` for the time), as
/// `run::integrate::watcher`, its program in a cell that takes the values set at a change.
fn watcher<'a, const S: usize>(
    program: Option<&'a std::cell::RefCell<Program>>,
    observable: Option<crate::run::names::Observable>,
    value: f64,
) -> Option<Watcher<'a, S>> {
    let Some(observable) = observable else {
        return Some(Box::new(move |t, _: &SVector<f64, S>| t - value));
    };
    let program = program?;
    Some(Box::new(move |t, state: &SVector<f64, S>| {
        let program = program.borrow();
        evaluate(&program, observable, t, state.as_slice()).map_or(f64::NAN, |v| v - value)
    }))
}

/// Refuses a scene whose first phase's end condition was met while the body was held on its
/// support or rail (`what`): conditions are watched from the lift-off (the rail's exit) on
/// (docs/scenes.md), so a phase change or a stop due during the hold would be skipped without
/// a word. `phased` is the run before renumbering (the `inserted` phases of the hold come
/// first, the scene's first phase begins at the first point of phase `inserted`; a body held
/// to the end is checked to its last point). The condition is read at every point of the
/// hold, not only at its ends: one met and unmet again while held (an oscillator that passes
/// its value and comes back) was skipped before (review of session 33).
fn met_while_held<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phased: &PhasedSolution<N, S>,
    (phases, inserted): (&[Phase<'_, Supported<Sys>, S>], usize),
    (t0, y0): (f64, SVector<f64, S>),
    ends: &[Option<End>],
    what: &str,
) -> Result<(), CliError> {
    let lift_off = phased.phase.iter().position(|&p| p == inserted);
    let Some(last) = lift_off.or(phased.phase.len().checked_sub(1)) else {
        return Ok(());
    };
    let (Some(first), Some(Some(end))) = (phases.get(inserted), ends.first()) else {
        return Ok(());
    };
    let Some(until) = &first.until else {
        return Ok(());
    };
    let g0 = until.value(&first.system, t0, &y0);
    // From the first point after the start (the start's own sign is g0's).
    let held = (phased.solution.times[..=last].iter())
        .zip(&phased.solution.states)
        .skip(1);
    let met = held
        .map(|(&t, y)| (t, until.value(&first.system, t, y)))
        .find(|&(_, g)| crossed(until.direction, g0, g));
    let Some((t1, _)) = met else {
        return Ok(());
    };
    Err(CliError::Input(format!(
        "`{}` (the end of phase 1) was met while the body was held {what}, between t = {} and \
         t = {}, before the end of the hold: a scene's conditions are watched from the lift-off \
         on (docs/scenes.md), so it would be skipped; write a condition met after the \
         lift-off, or fly the scene without the hold",
        end.text,
        shown(t0),
        shown(t1)
    )))
}

/// Whether g, from `g0` at the start of a hold, has crossed its boundary in `direction`:
/// strictly past it (a body resting at the boundary itself, z = 0 or z' = 0 on its pad,
/// has not met `z < 0` or `z' < 0`), or, either way, to the other side of it.
fn crossed(direction: varmass::core::Direction, g0: f64, g: f64) -> bool {
    use varmass::core::Direction::{Either, Falling, Rising};
    match direction {
        Rising => g > 0.0 && g0 <= 0.0,
        Falling => g < 0.0 && g0 >= 0.0,
        Either => g != 0.0 && (g0 == 0.0 || g.signum() != g0.signum()),
    }
}

/// The speed of the body's reference point along the rail's position coordinates at the
/// rail's exit `t` (the point of the run at that time, before renumbering): |q̇| over the
/// rail's three coordinates, the body's velocity being along the rail there.
fn exit_speed<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phased: &PhasedSolution<N, S>,
    phases: &[Phase<'_, Supported<Sys>, S>],
    t: f64,
) -> f64 {
    let i = phased.solution.times.iter().position(|&time| time == t);
    let rail = phases.iter().find_map(|p| p.system.rail);
    let (Some(i), Some(rail)) = (i, rail) else {
        return f64::NAN;
    };
    let state = &phased.solution.states[i];
    let v = phases[0].system.velocities(t, state);
    v.map_or(f64::NAN, |v| {
        rail.position
            .iter()
            .map(|&k| v[k] * v[k])
            .sum::<f64>()
            .sqrt()
    })
}

/// [`hold`], and the refusal of a held phase under Taylor (the held phase has no Taylor
/// coefficients of its own).
fn held_first<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phases: &mut Vec<Phase<'_, Supported<Sys>, S>>,
    support: Option<(usize, Program)>,
    start: (f64, SVector<f64, S>),
    (plan, columns): (&Plan, &[Column]),
) -> Result<Option<bool>, CliError> {
    let held = hold(phases, support, start, columns)?;
    if held == Some(true) && matches!(plan.method, Method::Taylor) {
        return Err(CliError::Input(
            "`support` with `method = \"taylor\"`: the held phase has no Taylor coefficients \
             of its own (docs/scenes.md); fly it with another method, e.g. \"dop853\""
                .to_string(),
        ));
    }
    Ok(held)
}

/// Puts the rail's phases before `phases` when the scene has a `[rail]`: the slide up the
/// rail, and before it the pad when the body rests on the rail's bottom at the start.
/// `Some(on_pad)` with a rail, `None` without. A body not at rest, and `method = "taylor"`
/// (the rail's motion has no Taylor coefficients of its own), are refused.
fn rail_first<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phases: &mut Vec<Phase<'_, Supported<Sys>, S>>,
    rail: Option<RailSpec>,
    (time, state): (f64, SVector<f64, S>),
    (plan, columns): (&Plan, &[Column]),
) -> Result<Option<bool>, CliError> {
    let Some(spec) = rail else {
        return Ok(None);
    };
    if matches!(plan.method, Method::Taylor | Method::Variational) {
        return Err(CliError::Input(format!(
            "`[rail]` with `method = \"{}\"`: the motion on the rail has no Taylor \
             coefficients of its own, and the variational stepper reads the Lagrange side, \
             where the rail's projection onto its line does not act (docs/scenes.md); fly it \
             with another method, e.g. \"dop853\"",
            clap::ValueEnum::to_possible_value(&plan.method)
                .map_or_else(String::new, |v| v.get_name().to_string())
        )));
    }
    let refused = |e: StepError<S>| match e.kind {
        StepErrorKind::InvalidConfiguration { reason } => {
            CliError::Input(format!("`[rail]`: {reason}"))
        }
        kind => CliError::Run(format!("`[rail]`: at t = {}: {kind}", shown(e.time))),
    };
    let geometry = (spec.position, spec.direction);
    let free = &phases[0].system.system;
    let (rail, on_pad) = on_rail(free, geometry, spec.length, (time, &state)).map_err(refused)?;
    let [pad, slide] = spec.programs;
    let system = |p| Sys::build(p, columns);
    phases.insert(0, slide_phase(system(slide)?, rail, spec.length));
    if on_pad {
        phases.insert(0, pad_phase(system(pad)?, rail));
    }
    Ok(Some(on_pad))
}

/// What the scene computed, sizes erased: the points cut to the model's own state `len`,
/// the programs given back for recording.
fn flown<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phased: PhasedSolution<N, S>,
    (phases, offset): (Vec<Phase<'_, Supported<Sys>, S>>, usize),
    len: usize,
    stopped: bool,
    failure: Option<CliError>,
) -> Flown {
    let solution = phased.solution;
    let points = solution
        .times
        .iter()
        .zip(&solution.states)
        .map(|(t, s)| (*t, s.as_slice()[..len].to_vec()))
        .collect();
    Flown {
        points,
        phase: phased.phase,
        changes: phased.changes,
        energy_residual: solution.energy_residual,
        stopped,
        statistics: solution.statistics,
        // The held phase (if any) comes first: its program is the first phase's again.
        programs: phases
            .into_iter()
            .skip(offset)
            .map(|p| p.system.system.into_program())
            .collect(),
        failure,
        lift_off: None,
        rail_exit: None,
        closest_singular_attitude: solution.closest_singular_attitude,
        sets: Vec::new(),
        derivatives: Vec::new(),
    }
}

/// Puts the held phase before `phases` when the scene's `support` (its coordinate and a
/// program of the first phase) holds the body at the start: `Some(true)` if it does,
/// `Some(false)` if the body lifts at once, `None` without a support. A body not at rest
/// along its support, or a coordinate that couples with another, is refused.
fn hold<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phases: &mut Vec<Phase<'_, Supported<Sys>, S>>,
    support: Option<(usize, Program)>,
    (time, state): (f64, SVector<f64, S>),
    columns: &[Column],
) -> Result<Option<bool>, CliError> {
    let Some((k, program)) = support else {
        return Ok(None);
    };
    let refused = |e: StepError<S>| match e.kind {
        StepErrorKind::InvalidConfiguration { reason } => {
            CliError::Input(format!("`support`: {reason}"))
        }
        kind => CliError::Run(format!("`support`: at t = {}: {kind}", shown(e.time))),
    };
    if !starts_held(&phases[0].system.system, k, (time, &state)).map_err(refused)? {
        return Ok(Some(false));
    }
    let system = Sys::build(program, columns)?;
    phases.insert(0, held_phase(system, k));
    Ok(Some(true))
}

/// The run with the `inserted` phases of a hold (a support's held phase, a rail's pad and
/// slide) numbered as part of the scene's first (their points are phase 1, the changes
/// between them no changes of phase), and the times of the changes removed (the lift-off,
/// the rail's exit), as many as the run reached.
fn renumbered<const N: usize, const S: usize>(
    mut phased: PhasedSolution<N, S>,
    inserted: usize,
    constraints: &mut Vec<Constraint>,
) -> (PhasedSolution<N, S>, Vec<f64>) {
    let mut removed = Vec::new();
    for _ in 0..inserted {
        // A change's two points (before and after) are one state: keep the first (and
        // what held the body there: the phase before's).
        if let Some(i) = phased.phase.iter().position(|&p| p == 1) {
            drop_point(&mut phased, i);
            if i < constraints.len() {
                constraints.remove(i);
            }
        }
        for phase in &mut phased.phase {
            *phase = phase.saturating_sub(1);
        }
        if phased.changes.is_empty() {
            break;
        }
        removed.push(phased.changes.remove(0).time);
        for change in &mut phased.changes {
            change.phase -= 1;
        }
    }
    (phased, removed)
}

/// Removes point `i` from `phased` and from every extra recorded at it.
fn drop_point<const N: usize, const S: usize>(phased: &mut PhasedSolution<N, S>, i: usize) {
    let solution = &mut phased.solution;
    phased.phase.remove(i);
    solution.times.remove(i);
    solution.states.remove(i);
    for extra in [
        &mut solution.hamiltonian,
        &mut solution.power,
        &mut solution.energy_residual,
    ] {
        if i < extra.len() {
            extra.remove(i);
        }
    }
    if i < solution.forces.len() {
        solution.forces.remove(i);
    }
}
