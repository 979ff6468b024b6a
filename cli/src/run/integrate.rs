//! The one part of a run that knows the sizes at compile time: build the chosen core
//! stepper for a [`TapeSystem<N, S>`], watch the `--stop-when` events, and drive
//! [`varmass::core::run`] to the end (or to each output time in turn with `--every`).

use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{AdaptiveControl, FixedStep, StepControl};
use varmass::core::{
    run, Event, EventAction, RunConfig, Statistics, StepError, StepErrorKind, Stepper, StopReason,
    VariableMassSystem,
};
use varmass::interpret::{Program, TapeSystem};

use super::names::{evaluate, shown, Observable};
use super::output::Points;
use super::plan::{Plan, Steps};
use super::watch::Watched;
use crate::error::CliError;

/// What a run produced, sizes erased.
pub struct Outcome {
    /// The output times and states `[q, p, m_s]`.
    pub points: Points,
    /// The index of the `--stop-when` condition that ended the run, if one did.
    pub stopped_by: Option<usize>,
    /// The stepper's work.
    pub statistics: Statistics,
    /// The program, given back for recording.
    pub program: Program,
    /// Why the run failed, if it did: `points` then end at the last accepted point.
    pub failure: Option<CliError>,
}

/// Integrates `program` (with `N` coordinates and state length `S`) as `plan` says.
pub fn integrate<const N: usize, const S: usize>(
    program: Program,
    plan: &Plan,
) -> Result<Outcome, CliError> {
    let system = TapeSystem::<N, S>::padded(program).map_err(|e| CliError::Input(e.to_string()))?;
    let mut start = SVector::<f64, S>::from_column_slice(&plan.initial_state);
    let (t0, fail) = (plan.from, |e: StepError<S>| {
        describe(&system, plan, &plan.flows, e)
    });
    // The held inputs sampled at t0 before the first point is recorded (the run's own
    // sample there then changes nothing).
    let before = start;
    system
        .sample(t0, &mut start, varmass::core::input::Sampling::All)
        .map_err(|e| fail(StepError::from_system(&system, e, t0, &before)))?;
    // Every stepper is built as `Type::new(&system, t0, start, settings)` and driven alike;
    // only the type and its settings differ.
    macro_rules! drive_with {
        ($stepper:ident, $settings:expr) => {
            drive(
                &system,
                $stepper::new(&system, t0, start, $settings).map_err(fail)?,
                plan,
            )
        };
    }
    let driven = with_stepper!(plan.method, plan.steps, drive_with);
    let (points, stopped_by, statistics, failure) = match driven {
        Ok((points, stopped_by, statistics)) => (points, stopped_by, statistics, None),
        Err(failed) => {
            let (points, statistics, error) = *failed;
            (points, None, statistics, Some(fail(error)))
        }
    };
    Ok(Outcome {
        points,
        stopped_by,
        statistics,
        program: system.into_program(),
        failure,
    })
}

/// `$with!(Stepper, settings)` for the core stepper of `method` and its settings from
/// `steps`: the one table from `--method` to a stepper, read by `varmass run` and by the
/// scenes. A macro, as each stepper is its own type with its own type of settings.
macro_rules! with_stepper {
    ($method:expr, $steps:expr, $with:ident) => {{
        use varmass::core::steppers::{
            AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, Esdirk43, ExplicitEuler,
            FixedStep, ImplicitMidpoint, ImplicitMidpointConfig, Sdirk4, Taylor, TaylorControl,
            Variational, VariationalConfig,
        };
        use $crate::args::Method;
        use $crate::run::integrate::{control, step};
        use $crate::run::plan::Steps;
        match ($method, $steps) {
            (Method::DormandPrince, s) => {
                $with!(DormandPrince, control(s, AdaptiveControl::default()))
            }
            (Method::Dop853, s) => $with!(Dop853, control(s, AdaptiveControl::dop853())),
            (Method::Sdirk4, s) => $with!(Sdirk4, control(s, AdaptiveControl::sdirk4())),
            (Method::Esdirk43, s) => $with!(Esdirk43, control(s, AdaptiveControl::sdirk4())),
            (Method::Rk4, s) => $with!(ClassicalRk4, FixedStep { step: step(s) }),
            (Method::Euler, s) => $with!(ExplicitEuler, FixedStep { step: step(s) }),
            (Method::ImplicitMidpoint, s) => $with!(
                ImplicitMidpoint,
                ImplicitMidpointConfig {
                    step: step(s),
                    ..ImplicitMidpointConfig::default()
                }
            ),
            (Method::Taylor, Steps::Adaptive(tol)) => {
                $with!(Taylor, TaylorControl::adaptive(tol, tol))
            }
            (Method::Taylor, Steps::Fixed(h)) => {
                $with!(Taylor, TaylorControl::Fixed { order: 20, step: h })
            }
            (Method::Variational, s) => $with!(
                Variational,
                VariationalConfig {
                    step: step(s),
                    ..VariationalConfig::default()
                }
            ),
        }
    }};
}
pub(crate) use with_stepper;

/// The step control of an adaptive method: `defaults` (the method's own safety and step
/// factors) at the tolerance asked for, or the fixed step.
pub(crate) fn control(steps: Steps, defaults: AdaptiveControl) -> StepControl {
    match steps {
        Steps::Adaptive(tol) => StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: tol,
            absolute_tolerance: tol,
            ..defaults
        }),
        Steps::Fixed(step) => StepControl::Fixed(FixedStep { step }),
    }
}

/// The step of a fixed-step method (the plan guarantees one; the adaptive tolerance never
/// reaches a fixed-step method).
pub(crate) fn step(steps: Steps) -> f64 {
    match steps {
        Steps::Fixed(step) | Steps::Adaptive(step) => step,
    }
}

/// A failed run: the points up to the failure, the work done and the error.
/// (Boxed: a failure is rare, and the success path should not carry its size.)
type Failed<const S: usize> = Box<(Points, Statistics, StepError<S>)>;

/// An event function g(t, state) borrowing the program.
type Watcher<'a, const S: usize> = Box<dyn Fn(f64, &SVector<f64, S>) -> f64 + 'a>;

/// Runs `stepper` to the end or a stopping event: one run over every accepted step, or
/// with `--every` one run to each output time in turn (the stepper lands on each). A
/// failed run gives back the points up to the failure with the error.
fn drive<St, const N: usize, const S: usize>(
    system: &TapeSystem<N, S>,
    stepper: St,
    plan: &Plan,
) -> Result<(Points, Option<usize>, Statistics), Failed<S>>
where
    St: Stepper<N, S, System = TapeSystem<N, S>>,
{
    let program = system.program();
    let watchers: Vec<Watcher<'_, S>> = plan
        .stop_when
        .iter()
        .map(|c| watcher(program, c.observable, c.value))
        .collect();
    let events: Vec<Event<'_, S>> = plan
        .stop_when
        .iter()
        .zip(&watchers)
        .map(|(c, w)| match c.observable {
            Observable::Coordinate(a) => Event::state_reaches(a, c.value, c.direction),
            // A state mass is a state entry, `[q, p, m_s]`: no program evaluation needed.
            Observable::Mass(i) if i < program.state_mass_count() => {
                Event::state_reaches(2 * N + i, c.value, c.direction)
            }
            _ => Event::function(w.as_ref(), c.direction, EventAction::Stop),
        })
        .collect();
    // The flows' rates are checked by the core's run at the start and after every step
    // (`TapeSystem::flow_rate`): a negative one fails it with the start point kept below.
    let start = *stepper.state();
    let watched = match plan.progress {
        true => Watched::new(stepper, plan.from, plan.until),
        false => Watched::quiet(stepper, plan.from, plan.until),
    };
    let mut stepper = watched.with_time_limit(plan.max_seconds);
    let mut points = Points::new(S, 64);
    points.push(plan.from, start.as_slice());
    let targets = output_times(plan);
    for (interval, target) in targets.into_iter().enumerate() {
        // --max-steps bounds the whole run, over every output interval.
        let taken = stepper.statistics().accepted_steps as u64;
        let max_steps = usize::try_from(plan.max_steps.saturating_sub(taken)).unwrap_or(usize::MAX);
        // Held inputs are sampled on their grid only, not at each output time.
        let config = RunConfig {
            max_steps,
            sample_at_start: interval == 0,
            ..RunConfig::until(target)
        };
        let (solution, failure) = match run(&mut stepper, &config, &events) {
            Ok(solution) => (solution, None),
            Err(failure) => (*failure.partial, Some(failure.error)),
        };
        let mut fresh = solution.times.iter().zip(&solution.states).skip(1);
        let kept: &mut dyn Iterator<Item = _> = match plan.every {
            None => &mut fresh,
            Some(_) => &mut fresh.last().into_iter(),
        };
        for (t, s) in kept {
            points.push(*t, s.as_slice());
        }
        if let Some(error) = failure {
            return Err(Box::new((points, *stepper.statistics(), error)));
        }
        if let StopReason::EventFound { index } = solution.stop {
            return Ok((points, Some(index), *stepper.statistics()));
        }
    }
    Ok((points, None, *stepper.statistics()))
}

/// The end times of the runs: the end, or every `--every` step and the end.
fn output_times(plan: &Plan) -> Vec<f64> {
    let Some(every) = plan.every else {
        return vec![plan.until];
    };
    let mut times = Vec::new();
    let mut k = 1.0;
    loop {
        let t = plan.from + k * every;
        // A last interval shorter than a millionth of `every` is merged into the end.
        if t >= plan.until - 1e-6 * every {
            times.push(plan.until);
            return times;
        }
        times.push(t);
        k += 1.0;
    }
}

/// g(t, state) = observable − value; NaN where the observable cannot be had.
fn watcher<const S: usize>(
    program: &Program,
    observable: Observable,
    value: f64,
) -> Watcher<'_, S> {
    Box::new(move |t, state| {
        evaluate(program, observable, t, state.as_slice()).map_or(f64::NAN, |v| v - value)
    })
}

/// A failed run as a message with the error in the user's names, its time, the state by
/// name and what to do about it; `flows` names the flows of `system`'s model (a scene's
/// later phase may have other tags, so other flows, than the plan's first).
pub(crate) fn describe<const N: usize, const S: usize>(
    system: &TapeSystem<N, S>,
    plan: &Plan,
    flows: &[String],
    error: StepError<S>,
) -> CliError {
    let program = system.program();
    let (what, mut fix) = explain(program, plan, flows, error.kind);
    if let StepErrorKind::StepSizeUnderflow { step } = error.kind {
        // Far from t = 0 the rounding of t itself stops the steps, not the model.
        let ulp = error.time.abs().next_up() - error.time.abs();
        fix = format!(
            "{fix}; an ulp of t is {} here (the step {}): if the model needs finer steps than \
             that, t is too far from 0 — measure time from a nearer origin ({})",
            shown(ulp),
            shown(step),
            plan.words.setting("--from")
        );
    }
    let state = super::output::state_lines(program, error.time, error.state.as_slice());
    CliError::Run(format!(
        "the run failed at t = {}: {what}\nstate there:{state}\nhelp: {fix}",
        shown(error.time)
    ))
}

/// What went wrong, in the model's names, and how to fix it, naming the settings as the
/// run's user wrote them (flags, or a scene file's keys: `plan.words`).
fn explain(
    program: &Program,
    plan: &Plan,
    flows: &[String],
    kind: StepErrorKind,
) -> (String, String) {
    let what = kind.to_string();
    let w = |flag: &str| plan.words.setting(flag);
    let (stop_when, until, tol, step) = (w("--stop-when"), w("--until"), w("--tol"), w("--step"));
    match kind {
        StepErrorKind::NonPositiveMass { index } => {
            let name = program.mass_names().nth(index).unwrap_or("?");
            (
                format!("the mass `{name}` is not positive"),
                format!(
                    "end the run before `{name}` runs out, e.g. {} or an earlier {until}",
                    plan.words.stop_when(&format!("{name} < VALUE"))
                ),
            )
        }
        StepErrorKind::NegativeFlowRate { index, rate } => {
            let flow = flows.get(index).map_or("a flow", String::as_str);
            (
                format!("the rate of the {flow} is negative ({rate})"),
                format!(
                    "a flow's rate is the mass it moves per second, ≥ 0 by definition; correct \
                     the parameters it reads ({}), or write the flow the other way round \
                     (outflow ↔ inflow)",
                    w("--set")
                ),
            )
        }
        StepErrorKind::TooManySteps { .. } => (
            format!(
                "more than {} {} steps were needed",
                w("--max-steps"),
                plan.max_steps
            ),
            format!(
                "raise {}, loosen {tol}, or use {} sdirk4 if the model is stiff",
                w("--max-steps"),
                w("--method")
            ),
        ),
        StepErrorKind::WallClockExceeded { .. } => (
            what,
            format!(
                "raise {}, loosen {tol}, or shorten {until}",
                w("--max-seconds")
            ),
        ),
        // Only a fixed step can step past the stability limit: an adaptive run that meets a
        // non-finite state met it in the equations (a Taylor series of a table outside its
        // data is NaN, for one).
        StepErrorKind::NonFiniteState | StepErrorKind::EnergyBudgetExceeded { .. }
            if matches!(plan.steps, Steps::Fixed(_)) =>
        {
            (
                what,
                format!(
                    "a fixed step past the stability limit does this: use a smaller {step} or \
                     an adaptive method ({tol})"
                ),
            )
        }
        StepErrorKind::NonFiniteState => (
            what,
            format!(
                "the equations have no finite value here (a division by zero, a root of a \
                 negative number, a table read outside its data): stop before this time \
                 ({stop_when}, {until}), or correct the parameters ({})",
                w("--set")
            ),
        ),
        StepErrorKind::EnergyBudgetExceeded { .. } => (
            what,
            format!("tighten {tol}, or stop before this time ({stop_when}, {until})"),
        ),
        StepErrorKind::StepSizeUnderflow { .. } => (
            what,
            format!(
                "the solution is singular here, or the model stiff: stop before this time \
                 ({stop_when}, {until}), or use {} sdirk4",
                w("--method")
            ),
        ),
        StepErrorKind::NewtonDivergence { .. } => (
            what,
            format!("use a smaller {step}, or an adaptive method ({tol})"),
        ),
        StepErrorKind::SingularMassMatrix => (
            format!("{what} (the velocities cannot be recovered from the momenta)"),
            format!(
                "the model's kinetic energy stops depending on a velocity here: stop before \
                 this state ({stop_when}), or check the masses and positions; a rigid body at \
                 the gimbal lock of its Euler sequence (middle angle ±90° for zyx-like, 0° or \
                 180° for zxz-like sequences) needs a sequence whose lock the motion avoids \
                 (docs/mechanics.md#rigid-bodies)"
            ),
        ),
        StepErrorKind::Chattering { switch, .. } => {
            let name = program.switch_name(switch).unwrap_or("?");
            (
                format!("{what}: the motion sticks on the switch `{name}`"),
                format!(
                    "the equations as written cannot continue on the switch: model the stuck \
                     motion as its own phase (a scene file), or stop before it ({stop_when})"
                ),
            )
        }
        StepErrorKind::NonFiniteTime { .. } | StepErrorKind::InvalidConfiguration { .. } => (
            what,
            format!("check {}, {until}, {step} and {tol}", w("--from")),
        ),
        StepErrorKind::SampledInputNotFinite { input, .. } => (
            what,
            format!(
                "the {} law of `{input}` has no value at this sample (a square root of a \
                 negative number, a division by zero): correct the law or its parameters, or \
                 stop the run before ({until}, {stop_when})",
                w("--input")
            ),
        ),
        StepErrorKind::TableOutside { .. } => (
            what,
            format!(
                "the table has no data there: stop before it ({until}, {stop_when}), or give \
                 the table `outside zero` or `outside hold` in the model (a table given by {} \
                 NAME=FILE errs outside its data: extend the file)",
                w("--input")
            ),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::args::Method;

    fn plan(from: f64, until: f64, every: Option<f64>) -> Plan {
        Plan {
            from,
            until,
            initial_state: Vec::new(),
            method: Method::Rk4,
            steps: Steps::Fixed(0.1),
            stop_when: Vec::new(),
            every,
            record: Vec::new(),
            max_steps: 10,
            max_seconds: None,
            progress: false,
            parameters: Vec::new(),
            flows: Vec::new(),
            words: Default::default(),
        }
    }

    #[test]
    fn output_times_end_exactly_at_the_end() {
        assert_eq!(output_times(&plan(0.0, 1.0, None)), [1.0]);
        assert_eq!(
            output_times(&plan(1.0, 2.0, Some(0.25))),
            [1.25, 1.5, 1.75, 2.0]
        );
        // A remainder shorter than the spacing is a last, shorter interval.
        assert_eq!(output_times(&plan(0.0, 1.0, Some(0.4))), [0.4, 0.8, 1.0]);
        // Rounding of k·dt just below the end does not add a sliver interval.
        let times = output_times(&plan(0.0, 0.3, Some(0.1)));
        assert_eq!(times.len(), 3);
        assert_eq!(times.last(), Some(&0.3));
    }
}
