//! Where a scene meets the const-generic core: one arm per number of coordinates (the
//! sizes of `varmass run`, padded to the same state masses), each running the phases with
//! [`run_phases_keeping`] and the chosen stepper.

use varmass::core::nalgebra::SVector;
use varmass::core::phases::ALREADY_PAST;
use varmass::core::{
    run_phases_keeping, Event, EventAction, Phase, PhaseChange, Record, RunConfig, Statistics,
    StepError, StepErrorKind, StopReason,
};
use varmass::interpret::{Program, TapeSystem};

use super::build::{End, Scene};
use crate::error::CliError;
use crate::run::dispatch::MAX_STATE_MASSES;
use crate::run::integrate::{describe, with_stepper};
use crate::run::names::{evaluate, shown, Observable};
use crate::run::plan::{Steps, MIN_TOLERANCE};
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
}

/// One arm per N with S = 2N + 3, as `varmass run` monomorphizes.
macro_rules! sizes {
    ($scene:ident; $(($n:literal, $s:literal)),* $(,)?) => {
        match $scene.phases[0].program.coordinate_count() {
            $($n => fly_sized::<$n, $s>($scene),)*
            n => Err(CliError::Input(format!(
                "the model has {n} coordinates; the tool runs models with 1 to 8 (use the \
                 #[variable_mass_system] macro for larger ones)"
            ))),
        }
    };
}

/// Runs the scene's phases in turn.
pub fn fly(scene: Scene) -> Result<Flown, CliError> {
    let k = scene.phases[0].program.state_mass_count();
    if k > MAX_STATE_MASSES {
        return Err(CliError::Input(format!(
            "the model has {k} state masses; the tool runs models with at most \
             {MAX_STATE_MASSES}"
        )));
    }
    sizes!(scene; (1, 5), (2, 7), (3, 9), (4, 11), (5, 13), (6, 15), (7, 17), (8, 19))
}

/// Whether `error` is the core's refusal of a phase whose end condition holds at its start.
fn never_triggers<const S: usize>(error: &StepError<S>) -> bool {
    matches!(error.kind, StepErrorKind::InvalidConfiguration { reason } if reason == ALREADY_PAST)
}

/// An event function g(t, state).
type EventFunction<'a, const S: usize> = dyn Fn(f64, &SVector<f64, S>) -> f64 + 'a;
/// One owned.
type Watcher<'a, const S: usize> = Box<EventFunction<'a, S>>;

fn fly_sized<const N: usize, const S: usize>(scene: Scene) -> Result<Flown, CliError> {
    let Scene {
        phases: built,
        plan,
        energy_residual,
        ..
    } = scene;
    let len = built[0].program.state_len();
    let mut systems = Vec::new();
    let mut ends = Vec::new();
    let mut masses = Vec::new();
    let mut flows = Vec::new();
    for phase in built {
        flows.push(phase.flows);
        let system = TapeSystem::<N, S>::padded(phase.program)
            .map_err(|e| CliError::Input(e.to_string()))?;
        systems.push((system, phase.carry));
        ends.push(phase.end);
        masses.push(phase.state_masses);
    }
    let watchers: Vec<Option<Watcher<'_, S>>> =
        ends.iter().map(|e| e.as_ref().and_then(watcher)).collect();
    let events: Vec<Option<Event<'_, S>>> = ends
        .iter()
        .zip(&watchers)
        .map(|(end, w)| end.as_ref().map(|end| event::<N, S>(end, w.as_deref())))
        .collect();
    let phases: Vec<Phase<'_, TapeSystem<N, S>, S>> = systems
        .into_iter()
        .zip(&masses)
        .zip(events)
        .map(|(((system, carry), state_masses), until)| Phase {
            system,
            carry,
            state_masses,
            until,
        })
        .collect();
    let mut initial_state = plan.initial_state.clone();
    initial_state.resize(S, 0.0);
    let start = (
        plan.from,
        SVector::<f64, S>::from_column_slice(&initial_state),
    );
    let config = RunConfig {
        max_steps: usize::try_from(plan.max_steps).unwrap_or(usize::MAX),
        ..RunConfig::until(plan.until)
    }
    .recording(Record {
        energy_residual,
        ..Record::default()
    });
    let steps = match plan.steps {
        // The padding's errors are 0: scale as `varmass run` does (dispatch.rs).
        Steps::Adaptive(tol) => {
            Steps::Adaptive((tol * (len as f64 / S as f64).sqrt()).max(MIN_TOLERANCE))
        }
        fixed => fixed,
    };
    let (from, until) = (plan.from, plan.until);
    macro_rules! phased_with {
        ($stepper:ident, $settings:expr) => {
            run_phases_keeping(
                &phases,
                start,
                |system, t, state| {
                    $stepper::new(system, t, state, $settings).map(|s| Watched::new(s, from, until))
                },
                &config,
            )
        };
    }
    let (phased, error) = with_stepper!(plan.method, steps, phased_with);
    let last = phased.phase.last().copied().unwrap_or(0);
    let failure = error.map(|e| match never_triggers(&e) {
        // The change into the phase is recorded; none of its points are.
        true => {
            let k = phased.changes.last().map_or(0, |c| c.phase);
            let when = ends
                .get(k)
                .and_then(Option::as_ref)
                .map_or("?", |e| &e.text);
            CliError::Run(format!(
                "phase {} ends when `{when}`, which already holds (or stands exactly on its \
                 boundary) where the phase begins, at t = {}: it could never end the phase\n\
                 help: give the phase a condition that its motion reaches later",
                k + 1,
                shown(e.time)
            ))
        }
        false => {
            // The phase the run failed in, with its own model's flows: the last one
            // entered (a failure at its first step leaves no point of it).
            let entered = phased.changes.last().map_or(0, |c| c.phase).max(last);
            let k = entered.min(phases.len() - 1);
            describe(&phases[k].system, &plan, &flows[k], e)
        }
    });
    let stopped = phases.len() == last + 1
        && phases[last].until.is_some()
        && phased.solution.stop == (StopReason::EventFound { index: 0 });
    let points = phased
        .solution
        .times
        .iter()
        .zip(&phased.solution.states)
        .map(|(t, s)| (*t, s.as_slice()[..len].to_vec()))
        .collect();
    Ok(Flown {
        points,
        phase: phased.phase,
        changes: phased.changes,
        energy_residual: phased.solution.energy_residual,
        stopped,
        statistics: phased.solution.statistics,
        programs: phases
            .into_iter()
            .map(|p| p.system.into_program())
            .collect(),
        failure,
    })
}

/// g(t, state) of an end condition read from the model or the time: the time
/// minus the value for `t`, or the quantity minus the value (NaN where it cannot be had)
/// evaluated with the phase's own model; `None` for a state entry.
fn watcher<const S: usize>(end: &End) -> Option<Watcher<'_, S>> {
    let value = end.value;
    let Some(observable) = end.observable else {
        return Some(Box::new(move |t, _: &SVector<f64, S>| t - value));
    };
    let program = end.watch.as_ref()?;
    Some(Box::new(move |t, state: &SVector<f64, S>| {
        evaluate(program, observable, t, state.as_slice()).map_or(f64::NAN, |v| v - value)
    }))
}

/// The core event of an end condition: a state entry (a coordinate, a state mass) read
/// from the state, anything else through its `watcher`.
fn event<'a, const N: usize, const S: usize>(
    end: &'a End,
    watcher: Option<&'a EventFunction<'a, S>>,
) -> Event<'a, S> {
    match (end.observable, watcher) {
        (_, Some(w)) => Event::function(w, end.direction, EventAction::Stop),
        (Some(Observable::Coordinate(a)), None) => {
            Event::state_reaches(a, end.value, end.direction)
        }
        (Some(Observable::Mass(i)), None) => {
            Event::state_reaches(2 * N + i, end.value, end.direction)
        }
        // The build gives every other condition a watcher; were one missing, an index past
        // the state is the core's typed configuration error, not a silent non-event.
        (_, None) => Event::state_reaches(S, end.value, end.direction),
    }
}
