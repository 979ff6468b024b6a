//! Recording only what a scene needs: chosen observables at chosen output times.
//!
//! [`observe`] drives a stepper to the last output time and, at each output time, evaluates
//! the observables on the state interpolated within the step that contains it (the
//! stepper's dense output, else the cubic Hermite interpolant through the step's ends), so
//! the output times are independent of the steps taken and nothing is kept per step. The
//! recording is allocated once, before the first step; the stepping loop allocates nothing.

use alloc::string::{String, ToString};
use alloc::vec::Vec;

use nalgebra::SVector;

use crate::error::{StepError, StepErrorKind};
use crate::input::Sampling;
use crate::run::interpolation::over_last_step;
use crate::run::next_target;
use crate::run::point::{Needs, Point};
use crate::stepper::{Statistics, StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// The most steps [`observe`] takes before [`StepErrorKind::TooManySteps`].
pub const MAX_OBSERVED_STEPS: usize = 10_000_000;

/// What an observable measures.
#[derive(Clone, Copy)]
pub enum Quantity<'a, const S: usize> {
    /// The Hamiltonian H(q, p, t) of the system.
    Hamiltonian,
    /// The energy-budget power dH/dt of the system.
    Power,
    /// Any function of the time and the state `[q, p, m_s]`.
    Function(&'a dyn Fn(f64, &SVector<f64, S>) -> f64),
}

/// A named quantity recorded at the output times.
#[derive(Clone, Copy)]
pub struct Observable<'a, const S: usize> {
    /// Its name (the column of the recording; the key of a fidelity comparison).
    pub name: &'a str,
    /// What it measures.
    pub quantity: Quantity<'a, S>,
}

impl<'a, const S: usize> Observable<'a, S> {
    /// A function of (t, state) named `name`.
    pub fn function(name: &'a str, function: &'a dyn Fn(f64, &SVector<f64, S>) -> f64) -> Self {
        Self {
            name,
            quantity: Quantity::Function(function),
        }
    }

    /// H, named `"H"`.
    pub fn hamiltonian() -> Self {
        Self {
            name: "H",
            quantity: Quantity::Hamiltonian,
        }
    }

    /// The power dH/dt, named `"power"`.
    pub fn power() -> Self {
        Self {
            name: "power",
            quantity: Quantity::Power,
        }
    }

    /// The value at (t, state) of `system`.
    fn evaluate<Sys, const N: usize>(
        &self,
        system: &Sys,
        time: f64,
        state: &SVector<f64, S>,
    ) -> Result<f64, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let value = match self.quantity {
            Quantity::Hamiltonian => system.hamiltonian(time, state),
            Quantity::Power => system.power(time, state),
            Quantity::Function(f) => Ok(f(time, state)),
        };
        let value = value.map_err(|error| StepError::from_system(system, error, time, state))?;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(StepError::new(time, *state, StepErrorKind::NonFiniteState))
        }
    }
}

/// Observables at output times, and what it cost to get them.
#[derive(Clone, Debug, PartialEq)]
pub struct Recording {
    /// The observables' names, in column order.
    pub names: Vec<String>,
    /// The output times.
    pub times: Vec<f64>,
    /// The values, one row per output time: `values[i * names.len() + j]` is observable `j`
    /// at `times[i]`.
    pub values: Vec<f64>,
    /// The stepper's work over the recording (summed over phases, see
    /// [`Recording::append`]).
    pub statistics: Statistics,
}

impl Recording {
    /// The value of observable `name` at output `index`, if both exist.
    pub fn value(&self, index: usize, name: &str) -> Option<f64> {
        let column = self.names.iter().position(|n| n == name)?;
        self.values.get(index * self.names.len() + column).copied()
    }

    /// The values of observable `name` at every output time (empty if it is not recorded).
    pub fn series(&self, name: &str) -> Vec<f64> {
        (0..self.times.len())
            .filter_map(|index| self.value(index, name))
            .collect()
    }

    /// Appends a later phase of the same scene (same observables, later times), adding its
    /// work. A phase whose first time repeats this one's last time drops that first row.
    pub fn append(&mut self, later: Recording) {
        let columns = self.names.len();
        let skip =
            usize::from(later.times.first() == self.times.last() && later.names == self.names);
        self.times.extend(later.times.iter().skip(skip));
        self.values.extend(later.values.iter().skip(skip * columns));
        self.statistics = self.statistics.combine(later.statistics);
    }
}

/// Integrates with `stepper` to the last of `output_times` and records `observables` at
/// every output time. The times must be finite, ascending and not before the stepper's
/// time; a time equal to it is recorded from the current state.
///
/// The held values of sampled inputs (docs/inputs.md#sampled-inputs) are the stepper's: a
/// held input is sampled at the start only when its grid holds the start time (so a later
/// phase's recording keeps the value held where the earlier one stopped), then at each of
/// its sample times. To start a flight between samples with u(t₀, …), sample the initial
/// state first with [`VariableMassSystem::sample`] and
/// [`Sampling::All`].
pub fn observe<St, const N: usize, const S: usize>(
    stepper: &mut St,
    output_times: &[f64],
    observables: &[Observable<'_, S>],
) -> Result<Recording, StepError<S>>
where
    St: Stepper<N, S>,
{
    check_times(stepper, output_times)?;
    let before = *stepper.statistics();
    let mut recording = Recording {
        names: observables.iter().map(|o| o.name.to_string()).collect(),
        times: Vec::with_capacity(output_times.len()),
        values: Vec::with_capacity(output_times.len() * observables.len()),
        statistics: Statistics::default(),
    };
    let Some(&end) = output_times.last() else {
        return Ok(recording);
    };
    let mut pending = output_times;
    let start_time = stepper.time();
    // The recording continues the stepper's state as it is: only the held inputs whose
    // grid holds the start are sampled there (as a continuing run does).
    let state = *stepper.state();
    crate::run::sample(stepper, start_time, state, Sampling::Due)?;
    while let Some((&time, rest)) = pending.split_first().filter(|(t, _)| **t <= start_time) {
        record(
            stepper.system(),
            &mut recording,
            observables,
            time,
            stepper.state(),
        )?;
        pending = rest;
    }
    if !pending.is_empty() {
        stepper.set_stop_time(next_target(stepper.system(), start_time, end))?;
        step_through(stepper, &mut recording, observables, (pending, end))?;
    }
    recording.statistics = work_since(&before, stepper.statistics());
    Ok(recording)
}

/// Steps until every time of `pending` (all after the stepper's time) is recorded, landing
/// on the system's stop times before `end` and restarting there as a run does (sampling
/// the held inputs: an output time on a sample shows the value sampled there).
fn step_through<St, const N: usize, const S: usize>(
    stepper: &mut St,
    recording: &mut Recording,
    observables: &[Observable<'_, S>],
    (mut pending, end): (&[f64], f64),
) -> Result<(), StepError<S>>
where
    St: Stepper<N, S>,
{
    let needs = Needs {
        rate: stepper.dense_output(stepper.time()).is_none(),
        energy: false,
    };
    let mut previous = Point::at(stepper.system(), stepper.time(), *stepper.state(), needs)?;
    for _ in 0..MAX_OBSERVED_STEPS {
        let outcome = stepper.step()?;
        let current = Point::at(stepper.system(), stepper.time(), *stepper.state(), needs)?;
        let landed = outcome == StepOutcome::ReachedStopTime;
        let reached_end = landed && current.time >= end;
        // An end on a sample time shows the value after it, as every output time on a
        // sample does (the run's end samples too).
        let mut at_end = None;
        while let Some((&time, rest)) = pending.split_first() {
            if (time > current.time || (landed && time == current.time)) && !reached_end {
                break;
            }
            if reached_end && time >= current.time && at_end.is_none() {
                let state = current.state;
                at_end = Some(crate::run::sample(
                    stepper,
                    current.time,
                    state,
                    Sampling::Due,
                )?);
            }
            let state = match at_end {
                Some(Some(sampled)) => sampled,
                _ => over_last_step(&*stepper, &previous, &current, time.min(current.time)),
            };
            record(stepper.system(), recording, observables, time, &state)?;
            pending = rest;
        }
        if pending.is_empty() {
            return Ok(());
        }
        previous = current;
        if landed {
            // A stop time of the system: restart there (the inputs whose grid holds it
            // sampled).
            let (time, state) = (previous.time, previous.state);
            match crate::run::sample(stepper, time, state, Sampling::Due)? {
                Some(sampled) => previous = Point::at(stepper.system(), time, sampled, needs)?,
                None => stepper.restart(time, state)?,
            }
            stepper.set_stop_time(next_target(stepper.system(), time, end))?;
        }
    }
    let kind = StepErrorKind::TooManySteps {
        max_steps: MAX_OBSERVED_STEPS,
    };
    Err(StepError::new(stepper.time(), *stepper.state(), kind))
}

/// One row: every observable at (time, state).
fn record<Sys, const N: usize, const S: usize>(
    system: &Sys,
    recording: &mut Recording,
    observables: &[Observable<'_, S>],
    time: f64,
    state: &SVector<f64, S>,
) -> Result<(), StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    recording.times.push(time);
    for observable in observables {
        let value = observable.evaluate(system, time, state)?;
        recording.values.push(value);
    }
    Ok(())
}

/// Refuses output times that are not finite, not ascending, or before the stepper's time.
fn check_times<St, const N: usize, const S: usize>(
    stepper: &St,
    output_times: &[f64],
) -> Result<(), StepError<S>>
where
    St: Stepper<N, S>,
{
    let invalid = |reason| {
        Err(StepError::invalid_configuration(
            stepper.time(),
            *stepper.state(),
            reason,
        ))
    };
    if output_times.iter().any(|t| !t.is_finite()) {
        return invalid("an output time is not finite");
    }
    if output_times.windows(2).any(|w| w[1] < w[0]) {
        return invalid("the output times are not ascending");
    }
    if output_times.first().is_some_and(|&t| t < stepper.time()) {
        return invalid("an output time is before the stepper's time");
    }
    Ok(())
}

/// The work done between two readings of a stepper's statistics.
fn work_since(before: &Statistics, after: &Statistics) -> Statistics {
    Statistics {
        accepted_steps: after.accepted_steps - before.accepted_steps,
        rejected_steps: after.rejected_steps - before.rejected_steps,
        rate_evaluations: after.rate_evaluations - before.rate_evaluations,
        jacobian_evaluations: after.jacobian_evaluations - before.jacobian_evaluations,
        newton_iterations: after.newton_iterations - before.newton_iterations,
        // A verdict, not a count: whether the scene has been found stiff by now.
        stiffness_detected: after.stiffness_detected,
    }
}
