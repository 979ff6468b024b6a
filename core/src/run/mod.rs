//! Runs: drive any [`Stepper`] to an end time, watching events and recording the extras
//! asked for, and return a [`Solution`].
//!
//! The parts of a run, one file each in `run/`: `point.rs` (what the run computes at the end
//! of a step), `interpolation.rs` (states within the last step: the stepper's dense output or
//! a cubic Hermite interpolant), `watch.rs` (events), `switching.rs` (switches), `energy.rs`
//! (the energy budget and its guard), `record.rs` (the solution being filled), `drive.rs`
//! (the loop: one pass a step) and `stall.rs` (the progress guard). [`run`] only sequences
//! them.

mod drive;
mod energy;
mod failure;
pub(crate) mod interpolation;
pub(crate) mod point;
mod record;
mod stall;
mod switching;
pub(crate) mod watch;

pub use failure::RunError;
pub use switching::Switching;
pub use watch::EVENT_NOT_A_NUMBER;

use crate::error::StepError;
use crate::events::Event;
use crate::input::Sampling;
use crate::solution::{Record, Solution, StopReason};
use crate::stepper::Stepper;
use crate::system::VariableMassSystem;

use alloc::boxed::Box;

use nalgebra::SVector;

use drive::Running;
use point::{Needs, Point};
use record::Recorder;
use switching::SwitchWatch;
use watch::EventWatch;

/// How to run: the end time, the step limit, what to record and how finely to locate
/// events. Start from [`RunConfig::until`] and adjust the fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunConfig {
    /// The time to integrate to (not before the stepper's current time).
    pub end_time: f64,
    /// The most steps a run may take before [`StepErrorKind::TooManySteps`](crate::StepErrorKind::TooManySteps).
    pub max_steps: usize,
    /// The extras to record at every point.
    pub record: Record,
    /// How finely events are located in time (absolute, never below rounding of t).
    pub event_tolerance: f64,
    /// If set, the run fails with [`StepErrorKind::EnergyBudgetExceeded`](crate::StepErrorKind::EnergyBudgetExceeded) once the energy-budget
    /// residual exceeds this fraction of the largest |H| or |p·q̇| seen: a guard against the finite
    /// garbage of a fixed step past the stability limit. Costs H and the power at every
    /// point (and a midpoint), as recording the residual does.
    pub energy_tolerance: Option<f64>,
    /// How the system's switching functions are treated: located and restarted at, with a
    /// chattering guard, by default (docs/mechanics.md#switches).
    pub switching: Switching,
    /// Whether the run samples every held input at its start ([`VariableMassSystem::sample`],
    /// docs/inputs.md#sampled-inputs): yes by default, so a flight's first held value is
    /// u(t₀, …); a run that continues an earlier one (the next phase, the next output
    /// interval) sets it off with [`RunConfig::continuing`], so the held values keep their
    /// grid k·T instead of being sampled again where the earlier run stopped: it samples at
    /// its start only the inputs whose grid holds t₀.
    pub sample_at_start: bool,
    /// How many passes in a row (steps, redos before a switch, crossings, retries of a step
    /// refused for a mass) the run may take without moving t by more than a few roundings
    /// before it ends with [`StepErrorKind::Stalled`](crate::StepErrorKind::Stalled) (1 000 by default).
    pub stall_passes: usize,
}

impl RunConfig {
    /// A run to `end_time` with at most 10⁷ steps, nothing extra recorded, events
    /// located to 1e-12 in t, and 1 000 passes without progress before it stalls.
    pub fn until(end_time: f64) -> Self {
        Self {
            end_time,
            max_steps: 10_000_000,
            record: Record::default(),
            event_tolerance: 1e-12,
            energy_tolerance: None,
            switching: Switching::default(),
            sample_at_start: true,
            stall_passes: 1_000,
        }
    }

    /// The same run, continuing an earlier one: at the start only the held inputs whose
    /// grid holds it are sampled (see [`RunConfig::sample_at_start`]).
    pub fn continuing(self) -> Self {
        Self {
            sample_at_start: false,
            ..self
        }
    }

    /// The same run, stepping across the system's switches instead of landing on them (the
    /// steppers then lose their order at every jump or kink).
    pub fn without_switching(self) -> Self {
        Self {
            switching: Switching {
                locate: false,
                ..self.switching
            },
            ..self
        }
    }

    /// The same run, failing once the energy budget misses by more than `tolerance` of the
    /// largest |H| or |p·q̇| (see [`RunConfig::energy_tolerance`]).
    pub fn guarding_energy(self, tolerance: f64) -> Self {
        Self {
            energy_tolerance: Some(tolerance),
            ..self
        }
    }

    /// The same run, recording `record`.
    pub fn recording(self, record: Record) -> Self {
        Self { record, ..self }
    }

    /// Whether H and the power are needed at every point (to record the residual or to
    /// guard it).
    fn needs_energy(&self) -> bool {
        self.record.energy_residual || self.energy_tolerance.is_some()
    }

    /// Checks the energy and event tolerances.
    fn check(&self) -> Result<(), &'static str> {
        if self
            .energy_tolerance
            .is_some_and(|t| t.is_nan() || t <= 0.0)
        {
            return Err("the energy tolerance must be positive");
        }
        if self.event_tolerance.is_nan() || self.event_tolerance < 0.0 {
            return Err("the event tolerance must be non-negative");
        }
        let chatter = self.switching.chatter_window;
        if self.switching.chatter_crossings < 2 || chatter.is_nan() || chatter < 0.0 {
            return Err("chattering needs at least 2 crossings in a non-negative window");
        }
        Ok(())
    }
}

/// Integrates with `stepper` to `config.end_time` or the first stopping event.
///
/// On a stopping event the solution ends at the located event time; the stepper itself is
/// left at the end of the step that contained it ([`Stepper::restart`] it at the event to
/// continue). The system's switches are located and the stepper restarted at each
/// ([`RunConfig::switching`]), and it lands on and restarts at each of the system's stop
/// times ([`VariableMassSystem::next_stop_time`]).
/// On error, the [`RunError`] carries the time, the state and the kind, and the solution up
/// to the last accepted point.
pub fn run<St, const N: usize, const S: usize>(
    stepper: &mut St,
    config: &RunConfig,
    events: &[Event<'_, S>],
) -> Result<Solution<N, S>, RunError<N, S>>
where
    St: Stepper<N, S>,
{
    let mut recorder = None;
    match drive(stepper, config, events, &mut recorder) {
        Ok(stop) => match recorder {
            Some(recorder) => Ok(recorder.finish(stepper, stop)),
            None => Ok(Solution::new()),
        },
        Err(error) => {
            let partial = match recorder {
                Some(recorder) => recorder.finish(stepper, StopReason::Failed),
                None => Solution {
                    stop: StopReason::Failed,
                    ..Solution::new()
                },
            };
            Err(RunError {
                error,
                partial: Box::new(partial),
            })
        }
    }
}

/// [`run`], filling `recorder` (created at the first point) and returning why it stopped.
fn drive<St, const N: usize, const S: usize>(
    stepper: &mut St,
    config: &RunConfig,
    events: &[Event<'_, S>],
    recorder: &mut Option<Recorder<N, S>>,
) -> Result<StopReason, StepError<S>>
where
    St: Stepper<N, S>,
{
    check(stepper, config, events)?;
    let start_time = stepper.time();
    // The held inputs are sampled at the start, so the first held value is u(t₀, …); a run
    // continuing another samples those whose grid holds t₀ (a phase entered on a sample
    // time, where the run before stopped on an event before sampling).
    let which = match config.sample_at_start {
        true => Sampling::All,
        false => Sampling::Due,
    };
    let state = *stepper.state();
    sample(stepper, start_time, state, which)?;
    stepper.set_stop_time(next_target(stepper.system(), start_time, config.end_time))?;
    let switches = stepper.system().switch_count() > 0 && config.switching.locate;
    let needs = Needs {
        rate: (config.needs_energy() || !events.is_empty() || switches)
            && stepper.dense_output(start_time).is_none(),
        energy: config.needs_energy(),
    };
    let start = Point::at(stepper.system(), start_time, *stepper.state(), needs)?;
    let recorder = recorder.insert(Recorder::start(stepper.system(), config, &start)?);
    // A run to where the stepper already is takes no step (a zero-length step would divide
    // by zero in some steppers and count work in others).
    if config.end_time == start_time {
        return Ok(StopReason::ReachedEnd);
    }
    let system = stepper.system();
    Running {
        watch: EventWatch::start(events, system, &start)?,
        switches: SwitchWatch::start(system, config.switching, &start, config.end_time)?,
        stepper,
        config,
        needs,
        recorder,
        previous: start,
        refused: None,
    }
    .go()
}

/// Samples the held inputs `which` takes at `(time, state)` ([`VariableMassSystem::sample`],
/// docs/inputs.md#sampled-inputs) and, if a held value changed, restarts the stepper there
/// with the sampled state and returns it (nothing is done when none changed: a system
/// without sampled inputs, or a time off every grid, steps on as before).
pub(crate) fn sample<St, const N: usize, const S: usize>(
    stepper: &mut St,
    time: f64,
    state: SVector<f64, S>,
    which: Sampling,
) -> Result<Option<SVector<f64, S>>, StepError<S>>
where
    St: Stepper<N, S>,
{
    let mut sampled = state;
    let system = stepper.system();
    system
        .sample(time, &mut sampled, which)
        .map_err(|error| StepError::from_system(system, error, time, &state))?;
    // Compared bit for bit, so that a NaN sampled is a change (the restart refuses it).
    let same = (sampled.iter().zip(&state)).all(|(a, b)| a.to_bits() == b.to_bits());
    if same {
        return Ok(None);
    }
    stepper.restart(time, sampled)?;
    Ok(Some(sampled))
}

/// What [`sample_point`] did.
enum Sampled {
    /// No held value changed (nothing was due, or the values came out the same): the
    /// stepper was left as it was.
    Unchanged,
    /// The stepper was restarted with the values sampled.
    Changed,
    /// The jump of a held value met a stopping event.
    Stopped(StopReason),
}

/// Samples the held inputs `which` takes at `previous`, the point the run stands at. When
/// a value changed, the stepper is restarted with it, the point after the sample replaces
/// `previous` and is recorded (the solution holds both), the events are checked across the
/// jump (a condition on u hits at the sample time) and the switches are taken afresh (a
/// switch on a held value changes there without the state crossing it).
fn sample_point<St, const N: usize, const S: usize>(
    stepper: &mut St,
    (recorder, watch, switch_watch): Watches<'_, '_, '_, '_, N, S>,
    previous: &mut Point<S>,
    which: Sampling,
    needs: Needs,
) -> Result<Sampled, StepError<S>>
where
    St: Stepper<N, S>,
{
    let time = previous.time;
    let Some(sampled) = sample(stepper, time, previous.state, which)? else {
        return Ok(Sampled::Unchanged);
    };
    let after = Point::at(stepper.system(), time, sampled, needs)?;
    let before = core::mem::replace(previous, after);
    let hits = recorder.hits();
    let hold = |_| sampled;
    let hit = watch.check_step(stepper.system(), (&before, previous), &hold, 0.0, hits)?;
    recorder.push(stepper.system(), previous)?;
    if let Some(hit) = hit {
        return Ok(Sampled::Stopped(StopReason::EventFound {
            index: hit.index,
        }));
    }
    if let Some(switch_watch) = switch_watch {
        switch_watch.resume(stepper.system(), previous)?;
    }
    Ok(Sampled::Changed)
}

/// What a sample updates besides the stepper: the solution, the events and the switches.
type Watches<'r, 'w, 'e, 'a, const N: usize, const S: usize> = (
    &'r mut Recorder<N, S>,
    &'w mut EventWatch<'e, 'a, S>,
    Option<&'w mut SwitchWatch>,
);

/// Ends a run at `end`, a point on the run's end time: an end on a sample time samples the
/// inputs due there too, so that a run continuing this one starts from the value held there.
fn reach_end<St, const N: usize, const S: usize>(
    stepper: &mut St,
    recorder: &mut Recorder<N, S>,
    end: &Point<S>,
    needs: Needs,
) -> Result<StopReason, StepError<S>>
where
    St: Stepper<N, S>,
{
    if let Some(sampled) = sample(stepper, end.time, end.state, Sampling::Due)? {
        let point = Point::at(stepper.system(), end.time, sampled, needs)?;
        recorder.push(stepper.system(), &point)?;
    }
    Ok(StopReason::ReachedEnd)
}

/// How [`cross_past`] ended.
enum Crossed<const S: usize> {
    /// The stepper restarted at this point past the switch.
    Past(Point<S>),
    /// A stopping event in the sliver before the switch, or the run's end within it.
    Stopped(StopReason),
}

/// Crosses a switch from `previous` to `(time, state)`, the far end of the crossing's
/// bracket reached by one Euler step ([`SwitchWatch::cross_from`]): that sliver is recorded
/// as any step is — its events located on the Euler line, its energy added, the point past
/// the switch appended — and the stepper restarts there. A stopping event in the sliver
/// ends the run at its hit (docs/mechanics.md#switches). A sliver that reaches the run's end
/// time (a switch within a few roundings of `--until`) ends the run there, on the sliver's
/// line: it is not crossed past the end.
fn cross_past<St, const N: usize, const S: usize>(
    stepper: &mut St,
    sliver: (&mut Recorder<N, S>, &mut EventWatch<'_, '_, S>, &RunConfig),
    previous: &Point<S>,
    (time, state): (f64, SVector<f64, S>),
    needs: Needs,
) -> Result<Crossed<S>, StepError<S>>
where
    St: Stepper<N, S>,
{
    let system = stepper.system();
    let width = time - previous.time;
    let line = |at: f64| match width > 0.0 {
        true => previous.state + (state - previous.state) * ((at - previous.time) / width),
        false => state,
    };
    let end_time = sliver.2.end_time;
    let ends = time >= end_time;
    let past = match ends {
        true => Point::at(system, end_time, line(end_time), needs)?,
        false => Point::at(system, time, state, needs)?,
    };
    let recorder = &mut *sliver.0;
    if let Some(stop) = record_step(
        system,
        (recorder, sliver.1, sliver.2),
        (previous, &past),
        &line,
    )? {
        return Ok(Crossed::Stopped(stop));
    }
    if ends {
        return Ok(Crossed::Stopped(reach_end(
            stepper, sliver.0, &past, needs,
        )?));
    }
    stepper.restart(time, state)?;
    Ok(Crossed::Past(past))
}

/// The next time the stepper must land on: the system's next stop time after `time` if it
/// comes before `end_time`, else `end_time`.
pub(crate) fn next_target<Sys, const N: usize, const S: usize>(
    system: &Sys,
    time: f64,
    end_time: f64,
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    system
        .next_stop_time(time)
        .filter(|&stop| stop > time && stop < end_time)
        .unwrap_or(end_time)
}

/// Records a step from `previous` to `current` (the stepper's last, or the Euler sliver
/// across a switch), the states within it from `interpolate`: the events in it first, and
/// if one of them stops the run, the point and the energy budget up to that event and the
/// reason to stop; otherwise the energy budget, its guard and `current`.
fn record_step<Sys, const N: usize, const S: usize>(
    system: &Sys,
    (recorder, watch, config): (&mut Recorder<N, S>, &mut EventWatch<'_, '_, S>, &RunConfig),
    (previous, current): (&Point<S>, &Point<S>),
    interpolate: &impl Fn(f64) -> SVector<f64, S>,
) -> Result<Option<StopReason>, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let step = (previous, current);
    let hits = recorder.hits();
    if let Some(hit) = watch.check_step(system, step, interpolate, config.event_tolerance, hits)? {
        let needs = Needs {
            rate: false,
            energy: config.needs_energy(),
        };
        let end = Point::at(system, hit.time, hit.state, needs)?;
        recorder.step_to(system, (previous, &end), interpolate, false)?;
        return Ok(Some(StopReason::EventFound { index: hit.index }));
    }
    recorder.step_to(system, step, interpolate, true)?;
    Ok(None)
}

/// Checks the run's configuration and events before any step, reporting a problem at the
/// stepper's time and state.
fn check<St, const N: usize, const S: usize>(
    stepper: &St,
    config: &RunConfig,
    events: &[Event<'_, S>],
) -> Result<(), StepError<S>>
where
    St: Stepper<N, S>,
{
    let invalid =
        |reason| StepError::invalid_configuration(stepper.time(), *stepper.state(), reason);
    config.check().map_err(invalid)?;
    for event in events {
        event
            .validate::<St::System, N>()
            .map_err(|error| invalid(error.reason))?;
    }
    Ok(())
}
