//! Runs: drive any [`Stepper`] to an end time, watching events and recording the extras
//! asked for, and return a [`Solution`].
//!
//! Between the ends of a step the run uses the stepper's dense output when it has one and
//! otherwise the cubic Hermite interpolant through the end states and end rates (third
//! order): it serves event location and the midpoint of the energy quadrature.
//!
//! The energy-budget residual integrates the power with Simpson's rule on every step, using
//! the interpolated midpoint, so the quadrature error (O(h⁵) per step with a fourth-order
//! interpolant) stays below the state's integration error and the residual measures the
//! latter.

use alloc::vec::Vec;

use nalgebra::SVector;

use crate::error::{StepError, StepErrorKind};
use crate::events::{locate_root, Event, EventAction, EventHit};
use crate::solution::{EnergyPoint, Record, Solution, StopReason};
use crate::stepper::{StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// How to run: the end time, the step limit, what to record and how finely to locate
/// events. Start from [`RunConfig::until`] and adjust the fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunConfig {
    /// The time to integrate to (not before the stepper's current time).
    pub end_time: f64,
    /// The most steps a run may take before [`StepErrorKind::TooManySteps`].
    pub max_steps: usize,
    /// The extras to record at every point.
    pub record: Record,
    /// How finely events are located in time (absolute, never below rounding of t).
    pub event_tolerance: f64,
    /// If set, the run fails with [`StepErrorKind::EnergyBudgetExceeded`] once the energy-budget
    /// residual exceeds this fraction of the largest |H| or |p·q̇| seen: a guard against the finite
    /// garbage of a fixed step past the stability limit. Costs H and the power at every
    /// point (and a midpoint), as recording the residual does.
    pub energy_tolerance: Option<f64>,
}

impl RunConfig {
    /// A run to `end_time` with at most 10⁷ steps, nothing extra recorded and events
    /// located to 1e-12 in t.
    pub fn until(end_time: f64) -> Self {
        Self {
            end_time,
            max_steps: 10_000_000,
            record: Record::default(),
            event_tolerance: 1e-12,
            energy_tolerance: None,
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
}

/// One end of a step, with what the run knows there.
#[derive(Clone, Copy)]
struct Point<const S: usize> {
    time: f64,
    state: SVector<f64, S>,
    /// The state rate, when Hermite interpolation needs it.
    rate: Option<SVector<f64, S>>,
    /// H and the power, when the energy budget needs them.
    energy: Option<(f64, f64)>,
}

/// Integrates with `stepper` to `config.end_time` or the first stopping event.
///
/// On a stopping event the solution ends at the located event time; the stepper itself is
/// left at the end of the step that contained it ([`Stepper::restart`] it at the event to
/// continue). On error, the error carries the time and state; the points so far are lost.
pub fn run<St, const N: usize, const S: usize>(
    stepper: &mut St,
    config: &RunConfig,
    events: &[Event<'_, S>],
) -> Result<Solution<N, S>, StepError<S>>
where
    St: Stepper<N, S>,
{
    let invalid =
        |reason| StepError::invalid_configuration(stepper.time(), *stepper.state(), reason);
    if config
        .energy_tolerance
        .is_some_and(|t| t.is_nan() || t <= 0.0)
    {
        return Err(invalid("the energy tolerance must be positive"));
    }
    if config.event_tolerance.is_nan() || config.event_tolerance < 0.0 {
        return Err(invalid("the event tolerance must be non-negative"));
    }
    for event in events {
        event
            .validate::<St::System, N>()
            .map_err(|e| invalid(e.reason))?;
    }
    stepper.set_stop_time(config.end_time)?;

    let record = config.record;
    let needs_energy = record.energy_residual || config.energy_tolerance.is_some();
    let start_time = stepper.time();
    let needs_rates =
        (needs_energy || !events.is_empty()) && stepper.dense_output(start_time).is_none();
    let mut solution = Solution::new();
    let mut previous = point(
        stepper.system(),
        start_time,
        *stepper.state(),
        needs_rates,
        needs_energy,
    )?;
    let initial_hamiltonian = previous.energy.map_or(0.0, |(hamiltonian, _)| hamiltonian);
    let mut energy_scale = initial_hamiltonian.abs();
    let mut integral = 0.0;
    solution.push(
        stepper.system(),
        &record,
        previous.time,
        previous.state,
        energy_point(&previous, integral, initial_hamiltonian),
    )?;
    // A run to where the stepper already is takes no step (a zero-length step would divide
    // by zero in some steppers and count work in others).
    if config.end_time == start_time {
        solution.stop = StopReason::ReachedEnd;
        solution.statistics = *stepper.statistics();
        return Ok(solution);
    }
    let mut event_values: Vec<f64> = events
        .iter()
        .map(|event| event.value(stepper.system(), previous.time, &previous.state))
        .collect();
    let mut pending: Vec<(f64, usize)> = Vec::with_capacity(events.len());

    for _ in 0..config.max_steps {
        let outcome = stepper.step()?;
        let system = stepper.system();
        let current = point(
            system,
            stepper.time(),
            *stepper.state(),
            needs_rates,
            needs_energy,
        )?;
        let interpolate = |time: f64| {
            stepper
                .dense_output(time)
                .unwrap_or_else(|| hermite(&previous, &current, time))
        };

        pending.clear();
        for (index, (event, before)) in events.iter().zip(event_values.iter_mut()).enumerate() {
            let after = event.value(system, current.time, &current.state);
            if event.triggered(*before, after) {
                let time = locate_root(
                    |time| event.value(system, time, &interpolate(time)),
                    (previous.time, *before),
                    (current.time, after),
                    config.event_tolerance,
                );
                pending.push((time, index));
            }
            *before = after;
        }
        pending.sort_by(|a, b| a.0.total_cmp(&b.0));

        for &(time, index) in &pending {
            let state = interpolate(time);
            solution.events.push(EventHit { index, time, state });
            if events.get(index).map(|event| event.action) == Some(EventAction::Stop) {
                let end = point(system, time, state, false, needs_energy)?;
                if needs_energy {
                    integral += simpson(system, &previous, &end, &interpolate)?;
                }
                let energy = energy_point(&end, integral, initial_hamiltonian);
                solution.push(system, &record, time, state, energy)?;
                solution.stop = StopReason::EventFound { index };
                solution.statistics = *stepper.statistics();
                return Ok(solution);
            }
        }

        if needs_energy {
            integral += simpson(system, &previous, &current, &interpolate)?;
        }
        let energy = energy_point(&current, integral, initial_hamiltonian);
        if let (Some(tolerance), Some(point)) = (config.energy_tolerance, energy) {
            // |H| alone can vanish while T and V are large (free fall from rest at y = 0):
            // measure against |p·q̇| too, twice the kinetic energy for a quadratic T.
            let velocities = system
                .velocities(current.time, &current.state)
                .map_err(|e| StepError::from_system(system, e, current.time, &current.state))?;
            let momentum_velocity = current.state.fixed_rows::<N>(N).dot(&velocities);
            energy_scale = energy_scale
                .max(point.hamiltonian.abs())
                .max(momentum_velocity.abs());
            if point.residual.abs() > tolerance * energy_scale {
                let kind = StepErrorKind::EnergyBudgetExceeded {
                    residual: point.residual,
                    scale: energy_scale,
                };
                return Err(StepError::new(current.time, current.state, kind));
            }
        }
        solution.push(system, &record, current.time, current.state, energy)?;
        previous = current;
        if outcome == StepOutcome::ReachedStopTime {
            solution.stop = StopReason::ReachedEnd;
            solution.statistics = *stepper.statistics();
            return Ok(solution);
        }
    }
    let kind = StepErrorKind::TooManySteps {
        max_steps: config.max_steps,
    };
    Err(StepError::new(stepper.time(), *stepper.state(), kind))
}

/// The run's view of one point: the state rate and the energy budget if needed.
fn point<Sys, const N: usize, const S: usize>(
    system: &Sys,
    time: f64,
    state: SVector<f64, S>,
    needs_rate: bool,
    needs_energy: bool,
) -> Result<Point<S>, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let to_step_error = |error| StepError::from_system(system, error, time, &state);
    let rate = if needs_rate {
        Some(system.state_rate(time, &state).map_err(to_step_error)?)
    } else {
        None
    };
    let energy = if needs_energy {
        let hamiltonian = system.hamiltonian(time, &state).map_err(to_step_error)?;
        let power = system.power(time, &state).map_err(to_step_error)?;
        Some((hamiltonian, power))
    } else {
        None
    };
    Ok(Point {
        time,
        state,
        rate,
        energy,
    })
}

/// The energy budget at a point, given ∫ power dt so far.
fn energy_point<const S: usize>(
    point: &Point<S>,
    integral: f64,
    initial_hamiltonian: f64,
) -> Option<EnergyPoint> {
    point.energy.map(|(hamiltonian, power)| EnergyPoint {
        hamiltonian,
        power,
        residual: integral - (hamiltonian - initial_hamiltonian),
    })
}

/// ∫ power dt over a step by Simpson's rule with the interpolated midpoint.
fn simpson<Sys, const N: usize, const S: usize>(
    system: &Sys,
    start: &Point<S>,
    end: &Point<S>,
    interpolate: &impl Fn(f64) -> SVector<f64, S>,
) -> Result<f64, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let middle_time = 0.5 * (start.time + end.time);
    let middle_state = interpolate(middle_time);
    let middle_power = system
        .power(middle_time, &middle_state)
        .map_err(|error| StepError::from_system(system, error, middle_time, &middle_state))?;
    let power = |point: &Point<S>| point.energy.map_or(0.0, |(_, power)| power);
    let width = end.time - start.time;
    Ok(width / 6.0 * (power(start) + 4.0 * middle_power + power(end)))
}

/// The cubic Hermite interpolant through the ends of a step and their rates. Without rates
/// (not needed by the caller) it falls back to linear interpolation.
fn hermite<const S: usize>(start: &Point<S>, end: &Point<S>, time: f64) -> SVector<f64, S> {
    let width = end.time - start.time;
    if width <= 0.0 {
        return end.state;
    }
    let s = (time - start.time) / width;
    let (Some(start_rate), Some(end_rate)) = (start.rate, end.rate) else {
        return start.state + (end.state - start.state) * s;
    };
    let s2 = s * s;
    let s3 = s2 * s;
    start.state * (2.0 * s3 - 3.0 * s2 + 1.0)
        + start_rate * (width * (s3 - 2.0 * s2 + s))
        + end.state * (3.0 * s2 - 2.0 * s3)
        + end_rate * (width * (s3 - s2))
}
