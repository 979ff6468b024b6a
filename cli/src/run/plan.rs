//! From the command line to a run plan: parameter values, the initial state `[q, p, m_s]`,
//! the stop conditions, the stepper and the output times, all checked against the model.

use varmass::core::Direction;
use varmass::interpret::{Program, Quantity};

use super::names::{assignment, evaluate, named, observables, resolve, velocity_state, Observable};
use crate::args::{Method, RunArgs};
use crate::error::CliError;

/// A `--stop-when` condition: an observable crossing a value.
#[derive(Clone, Copy, Debug)]
pub struct StopWhen {
    /// What is watched.
    pub observable: Observable,
    /// The value whose crossing stops the run.
    pub value: f64,
    /// Which crossings count: `=` either, `>` rising through the value, `<` falling.
    pub direction: Direction,
}

/// How the stepper takes its steps.
#[derive(Clone, Copy, Debug)]
pub enum Steps {
    /// An adaptive method with error control at this tolerance (relative and absolute).
    Adaptive(f64),
    /// A fixed step.
    Fixed(f64),
}

/// Everything a run needs, checked.
#[derive(Debug)]
pub struct Plan {
    /// The start time.
    pub from: f64,
    /// The end time.
    pub until: f64,
    /// The initial state `[q, p, m_s]`.
    pub initial_state: Vec<f64>,
    /// The stepper.
    pub method: Method,
    /// Its steps.
    pub steps: Steps,
    /// The stop conditions.
    pub stop_when: Vec<StopWhen>,
    /// Output spacing, if not every accepted step.
    pub every: Option<f64>,
    /// What to record, with the names given.
    pub record: Vec<(String, Observable)>,
}

/// The default tolerance of the adaptive methods when `--tol` is not given.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// Parses `--set` into (name, value) pairs.
pub fn parameters(args: &RunArgs) -> Result<Vec<(String, f64)>, CliError> {
    args.set.iter().map(|s| assignment(s, "--set")).collect()
}

/// Builds and checks the plan for `program`.
pub fn plan(args: &RunArgs, program: &Program) -> Result<Plan, CliError> {
    let from = args.from;
    let until = args.until;
    if !from.is_finite() || !until.is_finite() || until < from {
        return Err(CliError::Input(format!(
            "--until {until} must be finite and not before the start time {from}"
        )));
    }
    let known = observables(program);
    let initial_state = initial_state(args, program)?;
    let mut stop_when = Vec::new();
    for text in &args.stop_when {
        let (name, direction, value) = condition(text)?;
        let observable = resolve(&name, &known, "a quantity")?;
        let condition = StopWhen {
            observable,
            value,
            direction,
        };
        not_yet_true(program, &condition, text, from, &initial_state)?;
        stop_when.push(condition);
    }
    let record = match args.record.is_empty() {
        true => default_record(&known, program),
        false => args
            .record
            .iter()
            .map(|name| {
                let name = name.trim();
                resolve(name, &known, "a quantity").map(|o| (name.to_string(), o))
            })
            .collect::<Result<_, _>>()?,
    };
    let every = args.every.map(|dt| positive(dt, "--every")).transpose()?;
    Ok(Plan {
        from,
        until,
        initial_state,
        method: args.method,
        steps: steps(args)?,
        stop_when,
        every,
        record,
    })
}

/// Splits a `--stop-when` condition `NAME = VALUE`, `NAME > VALUE` or `NAME < VALUE`
/// (`>=` and `<=` read as `>` and `<`: a crossing has no width).
fn condition(text: &str) -> Result<(String, Direction, f64), CliError> {
    let Some(at) = text.find(['=', '<', '>']) else {
        return Err(CliError::Input(format!(
            "--stop-when `{text}`: expected NAME = VALUE, NAME > VALUE or NAME < VALUE"
        )));
    };
    let (name, rest) = text.split_at(at);
    let (direction, value) = match rest.split_at(1) {
        (">", value) => (Direction::Rising, value.strip_prefix('=').unwrap_or(value)),
        ("<", value) => (Direction::Falling, value.strip_prefix('=').unwrap_or(value)),
        (_, value) => (Direction::Either, value),
    };
    let (name, value) = named(text, "--stop-when", name, value)?;
    Ok((name, direction, value))
}

/// A `>` or `<` condition that already holds at the start would wait for a crossing the
/// user did not mean: refused, with the value there.
fn not_yet_true(
    program: &Program,
    condition: &StopWhen,
    text: &str,
    from: f64,
    state: &[f64],
) -> Result<(), CliError> {
    let start = evaluate(program, condition.observable, from, state)
        .map_err(|e| CliError::Input(format!("--stop-when `{text}`: {e} at the start")))?;
    let holds = match condition.direction {
        Direction::Rising => start > condition.value,
        Direction::Falling => start < condition.value,
        Direction::Either => false,
    };
    if holds {
        return Err(CliError::Input(format!(
            "--stop-when `{text}` already holds at the start (the value there is {start}): \
             a run stops when the quantity crosses the value"
        )));
    }
    Ok(())
}

fn positive(value: f64, flag: &str) -> Result<f64, CliError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CliError::Input(format!(
            "{flag} {value}: must be positive and finite"
        )))
    }
}

fn steps(args: &RunArgs) -> Result<Steps, CliError> {
    match (args.method, args.step, args.tol) {
        (_, Some(h), _) => Ok(Steps::Fixed(positive(h, "--step")?)),
        (
            Method::DormandPrince
            | Method::Dop853
            | Method::Sdirk4
            | Method::Esdirk43
            | Method::Taylor,
            None,
            tol,
        ) => Ok(Steps::Adaptive(positive(
            tol.unwrap_or(DEFAULT_TOLERANCE),
            "--tol",
        )?)),
        (method, None, _) => Err(CliError::Input(format!(
            "--method {} takes a fixed step: give --step H",
            clap::ValueEnum::to_possible_value(&method)
                .map(|v| v.get_name().to_string())
                .unwrap_or_default()
        ))),
    }
}

/// Coordinates, velocities and state masses.
fn default_record(known: &[(String, Observable)], program: &Program) -> Vec<(String, Observable)> {
    let state_masses = program.state_mass_count();
    known
        .iter()
        .filter(|(_, o)| match o {
            Observable::Coordinate(_) | Observable::Velocity(_) => true,
            Observable::Mass(i) => *i < state_masses,
            _ => false,
        })
        .cloned()
        .collect()
}

/// What `--init` may set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Initial {
    Coordinate(usize),
    Velocity(usize),
    StateMass(usize),
}

/// `[q, p, m_s]` from `--init` (coordinates and state masses required, velocities 0 by
/// default), with p = ∂*L/∂q̇ at the start.
fn initial_state(args: &RunArgs, program: &Program) -> Result<Vec<f64>, CliError> {
    let n = program.coordinate_count();
    let k = program.state_mass_count();
    let mut settable = Vec::new();
    for (a, x) in program.coordinate_names().enumerate() {
        settable.push((x.to_string(), Initial::Coordinate(a)));
        settable.push((format!("{x}'"), Initial::Velocity(a)));
    }
    for (i, m) in program.mass_names().take(k).enumerate() {
        settable.push((m.to_string(), Initial::StateMass(i)));
    }
    let mut values: Vec<Option<f64>> = vec![None; 2 * n + k];
    for text in &args.init {
        let (name, value) = assignment(text, "--init")?;
        let slot = match resolve(&name, &settable, "a coordinate, velocity or state mass")? {
            Initial::Coordinate(a) => a,
            Initial::Velocity(a) => n + a,
            Initial::StateMass(i) => 2 * n + i,
        };
        values[slot] = Some(value);
    }
    let missing: Vec<&str> = settable
        .iter()
        .filter(|(_, s)| !matches!(s, Initial::Velocity(_)))
        .filter(|(_, s)| match s {
            Initial::Coordinate(a) => values[*a].is_none(),
            Initial::StateMass(i) => values[2 * n + i].is_none(),
            Initial::Velocity(_) => false,
        })
        .map(|(name, _)| name.as_str())
        .collect();
    if !missing.is_empty() {
        return Err(CliError::Input(format!(
            "no initial value for {}: give --init NAME=VALUE",
            missing.join(", ")
        )));
    }
    let velocity_state: Vec<f64> = values.iter().map(|v| v.unwrap_or(0.0)).collect();
    let mut state = velocity_state.clone();
    program.evaluate(
        Quantity::Momenta,
        args.from,
        &velocity_state,
        &mut state[n..2 * n],
    );
    // Round trip: the momenta must give back the velocities (M positive definite).
    velocity_state_check(program, args.from, &state)?;
    Ok(state)
}

fn velocity_state_check(program: &Program, t: f64, state: &[f64]) -> Result<(), CliError> {
    velocity_state(program, t, state)
        .map(|_| ())
        .map_err(|e| CliError::Input(format!("the initial state is unusable: {e}")))
}
