//! The one part of a run that knows the sizes at compile time: build the chosen core
//! stepper for a [`TapeSystem<N, S>`], watch the `--stop-when` events, and drive
//! [`varmass::core::run`] to the end (or to each output time in turn with `--every`).

use varmass::core::nalgebra::SVector;
use varmass::core::phases::MASS_AGAINST_CARRY;
use varmass::core::steppers::{AdaptiveControl, FixedStep, StepControl, TaylorControl};
use varmass::core::tolerance::{Floor, Tolerance};
use varmass::core::{
    run, Direction, Event, EventAction, EventCondition, RunConfig, Statistics, StepError,
    StepErrorKind, Stepper, StopReason, SystemError, VariableMassSystem,
};
use varmass::interpret::{Program, TapeSystem};

use super::names::{evaluate, shown, Observable};
use super::output::Points;
use super::plan::{Plan, Steps};
use super::watch::Watched;
use crate::args::Words;
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
    /// The closest every accepted step (not only the kept points) came to a singular
    /// attitude of the model's Euler sequences, rad (`Solution::closest_singular_attitude`).
    pub closest_singular_attitude: Option<f64>,
    /// With `--sensitivity`, the derivative columns at each point
    /// (`sensitivity::column_names`); empty otherwise.
    pub derivatives: Vec<Vec<f64>>,
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
                system.program(),
                $stepper::new(&system, t0, start, $settings).map_err(fail)?,
                plan,
            )
        };
    }
    let Driven {
        points,
        stopped_by,
        statistics,
        closest_singular_attitude,
        error,
    } = with_stepper!(plan.method, plan.steps, drive_with);
    Ok(Outcome {
        points,
        stopped_by,
        statistics,
        failure: error.map(fail),
        program: system.into_program(),
        closest_singular_attitude,
        derivatives: Vec::new(),
    })
}

/// `$with!(Stepper, settings)` for the core stepper of `method` and its settings from
/// `steps`: the one table from `--method` to a stepper, read by `varmass run` and by the
/// scenes. A macro, as each stepper is its own type with its own type of settings.
macro_rules! with_stepper {
    ($method:expr, $steps:expr, $with:ident) => {{
        use varmass::core::steppers::{
            AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, Esdirk43, ExplicitEuler,
            FixedStep, ImplicitMidpoint, ImplicitMidpointConfig, Sdirk4, Taylor, Variational,
            VariationalConfig,
        };
        use $crate::args::Method;
        use $crate::run::integrate::{control, step, taylor};
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
            (Method::Taylor, s) => $with!(Taylor, taylor(s)),
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

/// The Taylor stepper's control: adaptive at the tolerance asked for, or order 20 at the
/// fixed step.
pub(crate) fn taylor(steps: Steps) -> TaylorControl {
    match steps {
        Steps::Adaptive(tol) => TaylorControl::adaptive(
            // The plan admits only tolerances at or above the method's floor
            // (`plan::min_tolerance`), and padding leaves Taylor's unscaled
            // (`dispatch::padded_steps`), so this cannot fail.
            Tolerance::for_floor(tol, tol, Floor::Taylor).expect("checked by the plan"),
        ),
        Steps::Fixed(step) => TaylorControl::Fixed { order: 20, step },
    }
}

/// The step of a fixed-step method (the plan guarantees one; the adaptive tolerance never
/// reaches a fixed-step method).
pub(crate) fn step(steps: Steps) -> f64 {
    match steps {
        Steps::Fixed(step) | Steps::Adaptive(step) => step,
    }
}

/// What [`drive`] gives back: the points (up to the failure, if the run failed), the
/// `--stop-when` condition that ended it, the work, the closest approach to gimbal lock
/// over every accepted step of every output interval, and the error of a failed run.
pub(crate) struct Driven<const S: usize> {
    pub(crate) points: Points,
    pub(crate) stopped_by: Option<usize>,
    pub(crate) statistics: Statistics,
    pub(crate) closest_singular_attitude: Option<f64>,
    pub(crate) error: Option<StepError<S>>,
}

/// An event function g(t, state).
pub(crate) type EventFunction<'a, const S: usize> = dyn Fn(f64, &SVector<f64, S>) -> f64 + 'a;
/// One owned (borrowing the program it evaluates).
pub(crate) type Watcher<'a, const S: usize> = Box<EventFunction<'a, S>>;

/// Runs `stepper` to the end or a stopping event: one run over every accepted step, or
/// with `--every` one run to each output time in turn (the stepper lands on each). A
/// failed run gives back the points up to the failure with the error. `program` is the
/// model the stepper's system evaluates (the `--stop-when` conditions read it): a
/// [`TapeSystem`]'s, or, with sensitivities, the one under their columns (its state the
/// first entries of the stepper's).
pub(crate) fn drive<St, const N: usize, const S: usize>(
    program: &Program,
    stepper: St,
    plan: &Plan,
) -> Driven<S>
where
    St: Stepper<N, S>,
{
    let watchers: Vec<Option<Watcher<'_, S>>> = plan
        .stop_when
        .iter()
        .map(|c| watcher(Some(program), Some(c.observable), c.value))
        .collect();
    let k = program.state_mass_count();
    let events: Vec<Event<'_, S>> = plan
        .stop_when
        .iter()
        .zip(&watchers)
        .map(|(c, w)| event::<N, S>(Some(c.observable), c.value, c.direction, k, w.as_deref()))
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
    let mut closest: Option<f64> = None;
    let driven = |points, stopped_by, statistics: &Statistics, closest, error| Driven {
        points,
        stopped_by,
        statistics: *statistics,
        closest_singular_attitude: closest,
        error,
    };
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
        if let Some(distance) = solution.closest_singular_attitude {
            closest = Some(closest.map_or(distance, |c: f64| c.min(distance)));
        }
        let mut fresh = solution.times.iter().zip(&solution.states).skip(1);
        let kept: &mut dyn Iterator<Item = _> = match plan.every.is_some() || !plan.at.is_empty() {
            false => &mut fresh,
            true => &mut fresh.last().into_iter(),
        };
        for (t, s) in kept {
            points.push(*t, s.as_slice());
        }
        if failure.is_some() {
            return driven(points, None, stepper.statistics(), closest, failure);
        }
        if let StopReason::EventFound { index } = solution.stop {
            return driven(points, Some(index), stepper.statistics(), closest, None);
        }
    }
    driven(points, None, stepper.statistics(), closest, None)
}

/// The end times of the runs: the end, or every `--every` step and the end, or the given
/// output times after the start and the end (a fit's data times).
fn output_times(plan: &Plan) -> Vec<f64> {
    if !plan.at.is_empty() {
        let mut times: Vec<f64> = (plan.at.iter().copied())
            .filter(|t| *t > plan.from && *t < plan.until)
            .collect();
        times.push(plan.until);
        return times;
    }
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

/// g(t, state) = the observable minus `value`, evaluated with `program` (NaN where it
/// cannot be had), or t − `value` for the time (`observable` `None`); `None` for an
/// observable without a program (a state entry, which [`event`] reads from the state).
pub(crate) fn watcher<'a, const S: usize>(
    program: Option<&'a Program>,
    observable: Option<Observable>,
    value: f64,
) -> Option<Watcher<'a, S>> {
    let Some(observable) = observable else {
        return Some(Box::new(move |t, _: &SVector<f64, S>| t - value));
    };
    let program = program?;
    Some(Box::new(move |t, state: &SVector<f64, S>| {
        evaluate(program, observable, t, state.as_slice()).map_or(f64::NAN, |v| v - value)
    }))
}

/// The core event of "`observable` (t for `None`) crosses `value`", for `varmass run`'s
/// `--stop-when` and a scene's phase ends alike: a coordinate or one of the
/// `state_masses` state masses read from the state `[q, p, m_s]` (no program evaluation),
/// anything else through its `watcher`.
pub(crate) fn event<'a, const N: usize, const S: usize>(
    observable: Option<Observable>,
    value: f64,
    direction: Direction,
    state_masses: usize,
    watcher: Option<&'a EventFunction<'a, S>>,
) -> Event<'a, S> {
    match (observable, watcher) {
        (Some(Observable::Coordinate(a)), _) => Event::state_reaches(a, value, direction),
        (Some(Observable::Mass(i)), _) if i < state_masses => {
            Event::state_reaches(2 * N + i, value, direction)
        }
        // The core's own velocity and time events (the same g as the watcher's, evaluated
        // by the system): their gradients carry sensitivities across a change.
        (Some(Observable::Velocity(a)), _) => Event {
            condition: EventCondition::Velocity {
                coordinate: a,
                value,
            },
            direction,
            action: EventAction::Stop,
        },
        (None, _) => Event {
            condition: EventCondition::Time { value },
            direction,
            action: EventAction::Stop,
        },
        (_, Some(w)) => Event::function(w, direction, EventAction::Stop),
        // Every other condition has a watcher; were one missing, an index past the state is
        // the core's typed configuration error, not a silent non-event.
        (_, None) => Event::state_reaches(S, value, direction),
    }
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
    let advice = Advice::of(plan.words);
    match kind {
        StepErrorKind::System(error) => advice.in_the_model(program, error, what),
        StepErrorKind::NegativeFlowRate { index, rate } => {
            let flow = flows.get(index).map_or("a flow", String::as_str);
            let what = format!("the rate of the {flow} is negative ({rate})");
            (what, advice.negative_flow())
        }
        StepErrorKind::Chattering { switch, .. } => {
            let name = program.switch_name(switch).unwrap_or("?");
            let what = format!("{what}: the motion sticks on the switch `{name}`");
            (what, advice.chattering())
        }
        StepErrorKind::TooManySteps { .. } => {
            let max_steps = &advice.max_steps;
            let what = format!("more than {max_steps} {} steps were needed", plan.max_steps);
            (what, advice.too_many_steps())
        }
        StepErrorKind::Stalled { .. } => {
            let what = format!("{what}: it cannot get past this time");
            (what, advice.stalled())
        }
        StepErrorKind::WallClockExceeded { .. } => (what, advice.out_of_time()),
        // Only a fixed step can step past the stability limit: an adaptive run that meets a
        // non-finite state met it in the equations (a Taylor series of a table outside its
        // data is NaN, for one).
        StepErrorKind::NonFiniteState | StepErrorKind::EnergyBudgetExceeded { .. }
            if matches!(plan.steps, Steps::Fixed(_)) =>
        {
            (what, advice.past_the_stability_limit())
        }
        StepErrorKind::NonFiniteState => (what, advice.no_finite_value()),
        StepErrorKind::EnergyBudgetExceeded { .. } => (what, advice.energy_budget()),
        StepErrorKind::StepSizeUnderflow { .. } => (what, advice.singular_or_stiff()),
        StepErrorKind::NewtonDivergence { .. } => (what, advice.newton()),
        StepErrorKind::InvalidConfiguration { reason } if reason == MASS_AGAINST_CARRY => {
            (what, Advice::carry_rule())
        }
        StepErrorKind::NonFiniteTime { .. } | StepErrorKind::InvalidConfiguration { .. } => {
            (what, advice.settings())
        }
    }
}

/// How to fix a failed run, naming each setting as the run's user wrote it (a flag, or a
/// scene file's key: [`Words::setting`]).
struct Advice {
    words: Words,
    until: String,
    stop_when: String,
    tol: String,
    step: String,
    method: String,
    max_steps: String,
}

impl Advice {
    fn of(words: Words) -> Advice {
        let w = |flag: &str| words.setting(flag);
        Advice {
            words,
            until: w("--until"),
            stop_when: w("--stop-when"),
            tol: w("--tol"),
            step: w("--step"),
            method: w("--method"),
            max_steps: w("--max-steps"),
        }
    }

    /// A failure of the model's equations at the state (the core's [`SystemError`]): what
    /// it is in the model's names, and the fix.
    fn in_the_model(
        &self,
        program: &Program,
        error: SystemError,
        what: String,
    ) -> (String, String) {
        let (until, stop_when) = (&self.until, &self.stop_when);
        match error {
            SystemError::NonPositiveMass { index } => {
                let name = program.mass_names().nth(index).unwrap_or("?");
                let stop = self.words.stop_when(&format!("{name} < VALUE"));
                let empty = self.words.stop_when(&format!("{name} = 0"));
                (
                    format!("the mass `{name}` is not positive"),
                    format!(
                        "end the run before `{name}` runs out, e.g. {stop} or an earlier \
                         {until}; a burn that empties `{name}` exactly ends on {empty}"
                    ),
                )
            }
            SystemError::SingularMassMatrix => (
                format!("{what} (the velocities cannot be recovered from the momenta)"),
                format!(
                    "the model's kinetic energy stops depending on a velocity here: stop before \
                     this state ({stop_when}), or check the masses and positions; a rigid body at \
                     the gimbal lock of its Euler sequence (middle angle ±90° for zyx-like, 0° or \
                     180° for zxz-like sequences) needs a sequence whose lock the motion avoids, \
                     or `orientation quaternion(e0, e1, e2, e3)`, singular nowhere \
                     (docs/mechanics.md#quaternions)"
                ),
            ),
            SystemError::SupportCoupled { index } => {
                let name = program.coordinate_names().nth(index).unwrap_or("?");
                (
                    format!(
                        "the coordinate `{name}` held on its support couples here with another \
                         in the kinetic energy (it did not where the hold began)"
                    ),
                    "holding it would no longer be the constrained motion: fly this model \
                     without `support`, or write the support's coordinate so that the others \
                     do not move it (docs/mechanics.md#a-support-that-holds-until-lifted)"
                        .to_string(),
                )
            }
            SystemError::SampledInputNotFinite { input, .. } => (
                what,
                format!(
                    "the {} law of `{input}` has no value at this sample (a square root of a \
                     negative number, a division by zero): correct the law or its parameters, or \
                     stop the run before ({until}, {stop_when})",
                    self.words.setting("--input")
                ),
            ),
            SystemError::TableOutside { .. } => (
                what,
                format!(
                    "the table has no data there: stop before it ({until}, {stop_when}), or give \
                     the table `outside zero` or `outside hold` in the model (a table given by {} \
                     NAME=FILE errs outside its data: extend the file)",
                    self.words.setting("--input")
                ),
            ),
            SystemError::TangentSwitch { .. }
            | SystemError::SwitchesTogether { .. }
            | SystemError::UnlocatedSwitch { .. }
            | SystemError::NoSwitchGradient { .. }
            | SystemError::NoParameterJacobian
            | SystemError::RailCoupled
            | SystemError::RailColumnAcross { .. }
            | SystemError::SupportedSwitch { .. }
            | SystemError::TangentPhaseEnd { .. }
            | SystemError::TangentVelocityEnd { .. }
            | SystemError::PhaseColumns { .. }
            | SystemError::PhaseColumnDiffers { .. } => (what, self.sensitivity_advice(error)),
        }
    }

    /// The help of the errors only a run with sensitivities meets.
    fn sensitivity_advice(&self, error: SystemError) -> String {
        let (until, stop_when) = (&self.until, &self.stop_when);
        match error {
            SystemError::TangentPhaseEnd { .. } | SystemError::TangentVelocityEnd { .. } => {
                format!(
                    "the derivatives do not exist where a phase's end condition is only touched: \
                 end that phase on another condition, or drop the sensitivity that moves it \
                 ({until}, {stop_when})"
                )
            }
            SystemError::PhaseColumns { .. } | SystemError::PhaseColumnDiffers { .. } => {
                "every phase carries the same sensitivities: \
                 this is a bug of the scene's set-up, please report it"
                    .to_string()
            }
            SystemError::TangentSwitch { .. } | SystemError::SwitchesTogether { .. } => format!(
                "the derivatives do not exist where a switch is grazed or two cross at once: \
                 end the run before it ({until}, {stop_when}), or drop the sensitivity that \
                 moves it"
            ),
            SystemError::UnlocatedSwitch { .. } => {
                "a tighter --tol lets the run locate the switch, where the sensitivities jump"
                    .to_string()
            }
            SystemError::NoSwitchGradient { .. } => "the model gives no gradients of its \
                 switches: derive it with its sensitivities (the tool's runs do)"
                .to_string(),
            SystemError::RailCoupled => "the rail's direction couples with the body's \
                 other coordinates (its reference point is not its centre of mass): put the \
                 rail on centre-of-mass coordinates, or fly without --sensitivity"
                .to_string(),
            SystemError::RailColumnAcross { .. } => "this sensitivity moves the body across \
                 its rail (a coupling or a turning frame that changes with it), which the \
                 columns on the rail do not follow: fly without it"
                .to_string(),
            SystemError::SupportedSwitch { .. } => "a switch that jumps the rate while the \
                 body rests or slides on its support: start the run after it, or drop the \
                 sensitivity"
                .to_string(),
            _ => "the model gives no parameter Jacobian: derive it with its sensitivities"
                .to_string(),
        }
    }

    fn negative_flow(&self) -> String {
        format!(
            "a flow's rate is the mass it moves per second, ≥ 0 by definition; correct \
             the parameters it reads ({}), or write the flow the other way round \
             (outflow ↔ inflow)",
            self.words.setting("--set")
        )
    }

    fn chattering(&self) -> String {
        format!(
            "the equations as written cannot continue on the switch: model the stuck \
             motion as its own phase (a scene file), or stop before it ({})",
            self.stop_when
        )
    }

    fn too_many_steps(&self) -> String {
        let (max_steps, tol, method) = (&self.max_steps, &self.tol, &self.method);
        format!("raise {max_steps}, loosen {tol}, or use {method} sdirk4 if the model is stiff")
    }

    fn stalled(&self) -> String {
        let (until, stop_when, tol, method) =
            (&self.until, &self.stop_when, &self.tol, &self.method);
        format!(
            "a switch or an event the run cannot cross here (a discontinuity it keeps \
             finding at the same time): try another {method} or {tol}, or stop before it \
             ({stop_when}, {until}); please report the model"
        )
    }

    fn out_of_time(&self) -> String {
        let (until, tol) = (&self.until, &self.tol);
        let max_seconds = self.words.setting("--max-seconds");
        format!("raise {max_seconds}, loosen {tol}, or shorten {until}")
    }

    fn past_the_stability_limit(&self) -> String {
        let (tol, step) = (&self.tol, &self.step);
        format!(
            "a fixed step past the stability limit does this: use a smaller {step} or \
             an adaptive method ({tol})"
        )
    }

    fn no_finite_value(&self) -> String {
        let (until, stop_when) = (&self.until, &self.stop_when);
        format!(
            "the equations have no finite value here (a division by zero, a root of a \
             negative number, a table read outside its data): stop before this time \
             ({stop_when}, {until}), or correct the parameters ({})",
            self.words.setting("--set")
        )
    }

    fn energy_budget(&self) -> String {
        let (until, stop_when, tol) = (&self.until, &self.stop_when, &self.tol);
        format!("tighten {tol}, or stop before this time ({stop_when}, {until})")
    }

    fn singular_or_stiff(&self) -> String {
        let (until, stop_when, method) = (&self.until, &self.stop_when, &self.method);
        format!(
            "the solution is singular here, or the model stiff: stop before this time \
             ({stop_when}, {until}), or use {method} sdirk4"
        )
    }

    fn newton(&self) -> String {
        let (tol, step) = (&self.tol, &self.step);
        format!("use a smaller {step}, or an adaptive method ({tol})")
    }

    /// A phase whose masses change against its carry rule (the core's
    /// [`MASS_AGAINST_CARRY`]).
    fn carry_rule() -> String {
        "give the phase `carry = \"capture\"` if it gains mass, `\"separation\"` if it \
         loses it"
            .to_string()
    }

    /// A time, step or tolerance the core refuses.
    fn settings(&self) -> String {
        let (until, tol, step) = (&self.until, &self.tol, &self.step);
        format!(
            "check {}, {until}, {step} and {tol}",
            self.words.setting("--from")
        )
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
            sensitivities: Vec::new(),
            at: Vec::new(),
            rates: false,
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
