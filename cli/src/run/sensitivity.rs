//! `--sensitivity NAME`: forward sensitivities of a run (docs/sensitivities.md). The state
//! and its columns s = ∂[q, p, m_s]/∂w are integrated together by the core's
//! [`Sensitive`] over the run-time model (its symbolic Jacobians), and every recorded
//! quantity X gets a column `d(X)/d(w)`: at a point, the point moves with w along the
//! direction (dt, s_q, ∂q̇/∂w, s_m, dθ), and X by its gradient along it
//! ([`Program::derivative_along`]). Where a `--stop-when` condition X = c ends the run, its
//! time moves too: dτ/dw = −dX_w / Ẋ, and the last point's direction gains dτ/dw times the
//! motion (1, q̇, q̈, ṁ_s, 0), so that `d(y)/d(u_e)` there is the derivative of the height
//! at the event (an apogee's, a landing's), and `d(t)/d(w)` its time's.

use varmass::core::nalgebra::SVector;
use varmass::core::rail::Rail;
use varmass::core::sensitivity::{Column, Sensitive};
use varmass::core::{StepError, SystemError, VariableMassSystem};
use varmass::interpret::{Direction, Program, Quantity, TapeSystem};
use varmass::symbolic::expr::Id;

use super::dispatch::{check_sizes, padded_plan, padded_steps, Sizes};
use super::integrate::{describe, drive, Driven, Outcome};
use super::names::{shown, Observable};
use super::output::Table;
use super::plan::Plan;
use super::record::Recorded;
use crate::args::{Method, RunArgs};
use crate::error::CliError;

/// The most `--sensitivity` columns a run may have: each arm of the dispatch integrates
/// this many (the unused ones stay 0).
pub const MAX_SENSITIVITIES: usize = 6;

/// A column asked for: the name as given and what it differentiates by.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensitivity {
    /// `u_e`, `init:y'`.
    pub name: String,
    /// A parameter, or an entry of the initial velocity state `[q, q̇, m_s]`.
    pub column: Column,
}

/// The `--sensitivity` names of `args` resolved against `program`: a parameter, or
/// `init:x`, `init:x'`, `init:m` (a coordinate, its velocity, a state mass).
pub fn resolve(args: &RunArgs, program: &Program) -> Result<Vec<Sensitivity>, CliError> {
    resolve_names(&args.sensitivity, program)
}

/// The `--sensitivity` `names` resolved against `program` (as [`resolve`]).
pub fn resolve_names(names: &[String], program: &Program) -> Result<Vec<Sensitivity>, CliError> {
    if names.len() > MAX_SENSITIVITIES {
        return Err(CliError::Input(format!(
            "--sensitivity is given {} times; a run integrates at most {MAX_SENSITIVITIES} \
             columns (run again for the others)",
            names.len()
        )));
    }
    let mut resolved: Vec<Sensitivity> = Vec::new();
    for name in names {
        let column = column(name.trim(), program)?;
        if resolved.iter().any(|r| r.column == column) {
            return Err(CliError::Input(format!(
                "--sensitivity {name} is given twice; give each once"
            )));
        }
        resolved.push(Sensitivity {
            name: name.trim().to_string(),
            column,
        });
    }
    Ok(resolved)
}

/// The column `name` means.
fn column(name: &str, program: &Program) -> Result<Column, CliError> {
    if let Some(entry) = name.strip_prefix("init:") {
        return initial_entry(entry.trim(), program).map(Column::Initial);
    }
    let known: Vec<(String, &'static str)> = (program.parameter_names().iter())
        .map(|p| (p.to_string(), *p))
        .collect();
    super::names::resolve(name, &known, "a parameter")
        .map(Column::Parameter)
        .map_err(|e| CliError::Input(format!("--sensitivity: {e}; or init:x, init:x', init:m")))
}

/// The index in `[q, q̇, m_s]` of the initial value `entry` names.
fn initial_entry(entry: &str, program: &Program) -> Result<usize, CliError> {
    let n = program.coordinate_count();
    let mut known: Vec<(String, usize)> = Vec::new();
    for (a, x) in program.coordinate_names().enumerate() {
        known.push((x.to_string(), a));
        known.push((format!("{x}'"), n + a));
    }
    let state_masses = program.mass_names().take(program.state_mass_count());
    for (k, m) in state_masses.enumerate() {
        known.push((m.to_string(), 2 * n + k));
    }
    super::names::resolve(
        entry,
        &known,
        "an initial value (a coordinate, a velocity, a state mass)",
    )
    .map_err(|e| CliError::Input(format!("--sensitivity init:{entry}: {e}")))
}

/// Checks that the run can follow its sensitivities — an adaptive Runge–Kutta method or
/// Taylor's, no recorded expression (only the model's quantities have gradients), a model
/// the sensitivities follow — and compiles the gradients of what is recorded and watched.
pub fn prepare(program: &mut Program, plan: &Plan) -> Result<(), CliError> {
    check_method(plan.method, program)?;
    let watched = plan.stop_when.iter().map(|c| c.observable);
    prepare_observables(program, watched, &plan.record)
}

/// Whether `method` integrates the sensitivities of `program`: an adaptive Runge–Kutta
/// method or Taylor's (on a model whose q̇ has a closed form), a model they follow.
pub fn check_method(method: Method, program: &Program) -> Result<(), CliError> {
    if !matches!(
        method,
        Method::DormandPrince | Method::Dop853 | Method::Taylor
    ) {
        return Err(CliError::Input(format!(
            "--sensitivity runs with --method dormand-prince, dop853 or taylor (the \
             sensitivities of the other methods are not integrated yet), not {method:?}"
        )));
    }
    if method == Method::Taylor && !program.has_taylor_tangents() {
        return Err(CliError::Input(
            "--sensitivity with --method taylor: this model's q' is solved numerically (a \
             coupled mass matrix), whose Taylor series over tangents is not expanded; use \
             --method dop853"
                .to_string(),
        ));
    }
    if let Some(reason) = program.sensitivity_obstacle() {
        return Err(CliError::Input(format!(
            "--sensitivity: the sensitivities of this model cannot be integrated yet: it has \
             {reason} (docs/sensitivities.md)"
        )));
    }
    Ok(())
}

/// Compiles the gradients of the `watched` and `record`ed quantities of `program`; a
/// recorded expression, or a quantity without a gradient, is refused.
pub fn prepare_observables(
    program: &mut Program,
    watched: impl Iterator<Item = Observable>,
    record: &[(String, Recorded)],
) -> Result<(), CliError> {
    let watched = watched.map(Some);
    let recorded = record.iter().map(|(name, recorded)| match recorded {
        Recorded::Quantity(o) => Ok(Some(*o)),
        Recorded::Expression(_) => Err(CliError::Input(format!(
            "--sensitivity: `{name}` is an expression, whose derivative is not recorded yet; \
             record the model's quantities it reads"
        ))),
    });
    for observable in watched.map(Ok).chain(recorded) {
        let Some(observable) = observable? else {
            continue;
        };
        match root(program, observable) {
            Ok(Some(id)) => program.prepare_derivative(id),
            Ok(None) => {}
            Err(what) => {
                return Err(CliError::Input(format!(
                    "--sensitivity: {what} has no derivative here"
                )))
            }
        }
    }
    Ok(())
}

/// The expression of `observable` whose gradient its derivative reads: `None` for a state
/// entry or a velocity (read from the columns), an error for what has none.
fn root(program: &Program, observable: Observable) -> Result<Option<Id>, String> {
    let d = program.derivation();
    match observable {
        Observable::Coordinate(_) | Observable::Velocity(_) => Ok(None),
        Observable::Mass(i) if i < program.state_mass_count() => Ok(None),
        Observable::Mass(i) => d
            .closed_laws
            .get(i)
            .copied()
            .flatten()
            .map(Some)
            .ok_or(format!("mass {i}")),
        Observable::Held(_) => Err("a sampled input".to_string()),
        Observable::Quantity(q, index) => match d.quantity(q).get(index) {
            Some(id) => Ok(Some(*id)),
            None if q == Quantity::Accelerations => {
                Err("q'' (solved numerically for this model)".to_string())
            }
            None => Err(format!("{q:?}")),
        },
    }
}

/// dX of `observable` (t for `None`) at the velocity state `(t, velocity_state)` along
/// `direction`.
fn derivative(
    program: &Program,
    observable: Option<Observable>,
    t: f64,
    velocity_state: &[f64],
    direction: &Direction,
) -> Result<f64, SystemError> {
    let n = program.coordinate_count();
    let entry = |i: usize| direction.velocity_state.get(i).copied().unwrap_or(f64::NAN);
    match observable {
        None => Ok(direction.time),
        Some(Observable::Coordinate(a)) => Ok(entry(a)),
        Some(Observable::Velocity(a)) => Ok(entry(n + a)),
        Some(Observable::Mass(i)) if i < program.state_mass_count() => Ok(entry(2 * n + i)),
        Some(o) => {
            let id = root(program, o).ok().flatten();
            let along =
                id.and_then(|id| program.derivative_along(id, t, velocity_state, direction));
            along.unwrap_or(Ok(f64::NAN))
        }
    }
}

/// A job run with sensitivities in the monomorphized arm of its sizes ([`on_sensitive_sizes`]):
/// the model's `N`, its padded state `S` and the augmented state `SA = S (1 +
/// MAX_SENSITIVITIES)`.
pub trait SensitiveRun {
    /// What the job gives.
    type Output;
    /// The job in the arm `(N, S, SA)`.
    fn run<const N: usize, const S: usize, const SA: usize>(self)
        -> Result<Self::Output, CliError>;
}

/// The one dispatch with sensitivities, for `varmass run` and scenes: `job` in the arm of
/// its number of coordinates, every model padded to `MAX_STATE_MASSES` state masses and
/// `MAX_SENSITIVITIES` columns.
pub fn on_sensitive_sizes<J: SensitiveRun>(sizes: Sizes, job: J) -> Result<J::Output, CliError> {
    check_sizes(sizes)?;
    match sizes.coordinates {
        1 => job.run::<1, 5, 35>(),
        2 => job.run::<2, 7, 49>(),
        3 => job.run::<3, 9, 63>(),
        4 => job.run::<4, 11, 77>(),
        5 => job.run::<5, 13, 91>(),
        6 => job.run::<6, 15, 105>(),
        7 => job.run::<7, 17, 119>(),
        8 => job.run::<8, 19, 133>(),
        _ => unreachable!("sizes are checked before"),
    }
}

/// One run of a model with sensitivities.
struct Single<'a> {
    program: Program,
    plan: &'a Plan,
}

impl SensitiveRun for Single<'_> {
    type Output = Outcome;

    fn run<const N: usize, const S: usize, const SA: usize>(self) -> Result<Outcome, CliError> {
        integrate::<N, S, SA>(self.program, self.plan)
    }
}

/// Integrates `program` with the sensitivities of `plan` ([`on_sensitive_sizes`]).
pub fn dispatch(program: Program, plan: &Plan) -> Result<Outcome, CliError> {
    on_sensitive_sizes(Sizes::of(&program), Single { program, plan })
}

/// The run with sensitivities in the arm `(N, S, SA)`.
fn integrate<const N: usize, const S: usize, const SA: usize>(
    program: Program,
    plan: &Plan,
) -> Result<Outcome, CliError> {
    let len = program.state_len();
    let system = TapeSystem::<N, S>::padded(program).map_err(|e| CliError::Input(e.to_string()))?;
    let mut columns: Vec<Column> = plan.sensitivities.iter().map(|s| s.column).collect();
    let asked = columns.len();
    columns.resize(MAX_SENSITIVITIES, Column::Elsewhere);
    let sensitive = Sensitive::<_, S>::new::<N, SA>(system, &columns)
        .map_err(|e| CliError::Input(format!("--sensitivity: {e}")))?;
    let mut padded = padded_plan(plan, len, S)?;
    let entries = (len * (1 + asked), S * (1 + MAX_SENSITIVITIES));
    padded.steps = padded_steps(plan.steps, plan.method, entries.0, entries.1)?;
    let fail = |e: StepError<S>| describe(sensitive.system(), &padded, &padded.flows, e);
    let head = |e: StepError<SA>| StepError {
        time: e.time,
        state: e.state.fixed_rows::<S>(0).into_owned(),
        kind: e.kind,
    };
    let t0 = plan.from;
    let initial = SVector::<f64, S>::from_column_slice(&padded.initial_state);
    let system = sensitive.system();
    let at_start = |e| fail(StepError::from_system(system, e, t0, &initial));
    let velocity_state = system.velocity_state(t0, &initial).map_err(at_start)?;
    let start: SVector<f64, SA> =
        (sensitive.start_at_velocities(t0, &velocity_state)).map_err(at_start)?;
    macro_rules! drive_with {
        ($stepper:ident, $settings:expr) => {{
            let stepper =
                $stepper::new(&sensitive, t0, start, $settings).map_err(|e| fail(head(e)))?;
            drive(sensitive.system().program(), stepper, &padded)
        }};
    }
    let driven: Driven<SA> =
        super::integrate::with_stepper!(padded.method, padded.steps, drive_with);
    let (derivatives, unrecorded) = derivatives::<N, S, SA>(&sensitive, plan, &driven);
    let Driven {
        points,
        stopped_by,
        statistics,
        closest_singular_attitude,
        error,
    } = driven;
    // The rows up to the first point without its derivatives are kept (the table is cut
    // there); the run's own failure comes first.
    let failure = error.map(|e| fail(head(e))).or(unrecorded);
    Ok(Outcome {
        points: points.narrowed(len),
        stopped_by,
        statistics,
        failure,
        program: sensitive.into_system().into_program(),
        closest_singular_attitude,
        derivatives,
    })
}

/// The derivative columns at every point of `driven`: for each column in turn, each
/// recorded quantity's (`d(X)/d(w)` in the plan's record order) then `d(t)/d(w)`
/// ([`column_names`]). At the first point where they cannot be had (a tangential event, a
/// value that is not finite), the rows before it and the error.
fn derivatives<const N: usize, const S: usize, const SA: usize>(
    sensitive: &Sensitive<TapeSystem<N, S>, S>,
    plan: &Plan,
    driven: &Driven<SA>,
) -> (Vec<Vec<f64>>, Option<CliError>) {
    let last = driven.points.len().saturating_sub(1);
    let mut rows = Vec::with_capacity(driven.points.len());
    for (i, (t, state)) in driven.points.iter().enumerate() {
        let state = SVector::<f64, SA>::from_column_slice(state);
        let event = match (i == last, driven.stopped_by) {
            (true, Some(index)) => plan.stop_when.get(index).map(|c| c.observable),
            _ => None,
        };
        let row = point_derivatives(
            sensitive,
            (plan, &plan.record),
            (t, &state),
            event,
            Constraint::default(),
        );
        match recorded_row(row, t) {
            Ok(row) => rows.push(row),
            Err(error) => return (rows, Some(error)),
        }
    }
    (rows, None)
}

/// The derivative columns `row` at time `t` as recorded: every one a finite number, or the
/// run's failure there (the points before it are recorded).
pub(crate) fn recorded_row(row: Result<Vec<f64>, String>, t: f64) -> Result<Vec<f64>, CliError> {
    let row = row.and_then(|row| match row.iter().all(|x| x.is_finite()) {
        true => Ok(row),
        false => Err("a derivative is not a finite number".to_string()),
    });
    row.map_err(|e| {
        CliError::Run(format!(
            "cannot record the sensitivities at t = {}: {e}; the points before this time are \
             recorded",
            shown(t)
        ))
    })
}

/// What holds a point's body (a scene's support or rail; nothing elsewhere): the rates
/// `d(X)/d(t)` and an event's moving time there follow the constrained motion, as the run
/// integrates it (`Supported`'s), not the free one.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Constraint {
    /// The coordinate a support holds.
    pub held: Option<usize>,
    /// The rail the body is on (or rests on the bottom of).
    pub rail: Option<Rail>,
}

/// The derivative columns at one point `(t, state)` of `plan`'s run recording `record` (a
/// scene's phase records its own); `event` is the observable of the condition that ended
/// the run there, if one did; `constraint` what holds the body there.
pub(crate) fn point_derivatives<const N: usize, const S: usize, const SA: usize>(
    sensitive: &Sensitive<TapeSystem<N, S>, S>,
    (plan, record): (&Plan, &[(String, Recorded)]),
    (t, state): (f64, &SVector<f64, SA>),
    event: Option<Observable>,
    constraint: Constraint,
) -> Result<Vec<f64>, String> {
    let system = sensitive.system();
    let program = system.program();
    let parameters = program.parameter_names().len();
    let head: SVector<f64, S> = state.fixed_rows::<S>(0).into_owned();
    let velocity_state = system.velocity_state(t, &head).map_err(|e| e.to_string())?;
    let dv = sensitive
        .velocity_sensitivities::<N, SA>(t, state)
        .map_err(|e| e.to_string())?;
    let motion = match event.is_some() || plan.rates {
        true => Some(motion(
            system,
            (t, &head, &velocity_state),
            parameters,
            constraint,
        )?),
        false => None,
    };
    let vs = velocity_state.as_slice();
    // Column by column: each recorded quantity's derivative, then t's (`column_names`).
    let mut row = Vec::with_capacity(plan.sensitivities.len() * (record.len() + 1));
    for (c, sensitivity) in plan.sensitivities.iter().enumerate() {
        let mut direction = Direction {
            time: 0.0,
            velocity_state: (0..S)
                .map(|i| match (N..2 * N).contains(&i) {
                    true => dv[c][i - N],
                    false => state[S * (1 + c) + i],
                })
                .collect(),
            parameters: (program.parameter_names().iter())
                .map(|name| f64::from(sensitivity.column == Column::Parameter(name)))
                .collect(),
        };
        if let (Some(observable), Some(motion)) = (event, &motion) {
            moved(program, observable, t, vs, &mut direction, motion)?;
        }
        for (_, recorded) in record {
            let Recorded::Quantity(o) = recorded else {
                return Err("an expression has no derivative".to_string());
            };
            let value =
                derivative(program, Some(*o), t, vs, &direction).map_err(|e| e.to_string())?;
            row.push(value);
        }
        row.push(direction.time);
    }
    if let (true, Some(motion)) = (plan.rates, &motion) {
        for (_, recorded) in record {
            let Recorded::Quantity(o) = recorded else {
                return Err("an expression has no rate".to_string());
            };
            let rate = derivative(program, Some(*o), t, vs, motion).map_err(|e| e.to_string())?;
            row.push(rate);
        }
    }
    Ok(row)
}

/// The motion's direction at the point `(t, head)` (the state, and its velocity state):
/// (1, q̇, q̈, ṁ_s, 0), under `constraint` as `Supported` integrates it (on a rail q̈ = b s̈
/// and q̇ projected on b, both 0 on its pad; a held coordinate's rows 0).
fn motion<const N: usize, const S: usize>(
    system: &TapeSystem<N, S>,
    (t, head, velocity_state): (f64, &SVector<f64, S>, &SVector<f64, S>),
    parameters: usize,
    constraint: Constraint,
) -> Result<Direction, String> {
    let (mut rate, mut accelerations) = match constraint.rail {
        Some(rail) => (
            rail.state_rate(system, t, head),
            rail.accelerations(system, t, velocity_state),
        ),
        None => (
            system.state_rate(t, head),
            system.accelerations(t, velocity_state),
        ),
    };
    let (rate, accelerations) = (
        rate.as_mut().map_err(|e| e.to_string())?,
        accelerations.as_mut().map_err(|e| e.to_string())?,
    );
    if let Some(k) = constraint.held.filter(|&k| k < N) {
        (rate[k], rate[N + k], accelerations[k]) = (0.0, 0.0, 0.0);
    }
    Ok(Direction {
        time: 1.0,
        velocity_state: (0..S)
            .map(|i| match (N..2 * N).contains(&i) {
                true => accelerations[i - N],
                false => rate[i],
            })
            .collect(),
        parameters: vec![0.0; parameters],
    })
}

/// Moves `direction` with the time of the event on `observable`: dτ = −dX/Ẋ, then
/// direction += dτ · motion.
fn moved(
    program: &Program,
    observable: Observable,
    t: f64,
    velocity_state: &[f64],
    direction: &mut Direction,
    motion: &Direction,
) -> Result<(), String> {
    let along = derivative(program, Some(observable), t, velocity_state, direction);
    let rate = derivative(program, Some(observable), t, velocity_state, motion);
    let (along, rate) = (
        along.map_err(|e| e.to_string())?,
        rate.map_err(|e| e.to_string())?,
    );
    if rate == 0.0 || !rate.is_finite() {
        return Err(format!(
            "the stop condition is met tangentially (its rate is {rate}): the event's time has \
             no derivative"
        ));
    }
    let dt = -along / rate;
    direction.time += dt;
    for (d, m) in direction
        .velocity_state
        .iter_mut()
        .zip(&motion.velocity_state)
    {
        *d += dt * m;
    }
    Ok(())
}

/// The names of the derivative columns of `plan`, in [`derivatives`]' order.
pub fn column_names(plan: &Plan) -> Vec<String> {
    let mut names = Vec::new();
    for s in &plan.sensitivities {
        for (name, _) in &plan.record {
            names.push(format!("d({name})/d({})", s.name));
        }
        names.push(format!("d(t)/d({})", s.name));
    }
    if plan.rates {
        names.extend(
            plan.record
                .iter()
                .map(|(name, _)| format!("d({name})/d(t)")),
        );
    }
    names
}

/// `table` with the derivative columns of `plan` after its own, row by row (`rows` one per
/// point, as many as the table's or fewer after a failure).
pub fn with_derivatives(table: Table, plan: &Plan, rows: &[Vec<f64>]) -> Table {
    let mut names = table.names.clone();
    names.extend(column_names(plan));
    let joined = table.rows().zip(rows).map(|((t, mut values), extra)| {
        values.extend_from_slice(extra);
        (t, values)
    });
    Table::from_rows(names, joined.collect::<Vec<_>>())
}
