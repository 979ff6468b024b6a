//! From the command line to a run plan: parameter values, the initial state `[q, p, m_s]`,
//! the stop conditions, the stepper and the output times, all checked against the model.

use varmass::core::tolerance::Floor;
use varmass::core::Direction;
use varmass::interpret::{Program, Quantity};
use varmass::symbolic::mechanics::Derivation;
use varmass::symbolic::parse::ast::SystemAst;

use super::names::{
    assignment, evaluate, named, observables, resolve, shown, velocity_state, Observable,
};
use super::record::{columns, Recorded, Scope};
use crate::args::{Method, RunArgs, Words};
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
    /// What to record, with the names given (or the expressions' text).
    pub record: Vec<(String, Recorded)>,
    /// The most steps the run may take, accepted and rejected together.
    pub max_steps: u64,
    /// The wall-clock limit, if any.
    pub max_seconds: Option<f64>,
    /// Whether the run shows a progress bar (on a terminal, after a quiet second): the
    /// tool's runs do, a library caller's do not.
    pub progress: bool,
    /// The parameter values (`--set`).
    pub parameters: Vec<(String, f64)>,
    /// Each flow's name for messages (``outflow `rocket` ``), in the derivation's flow
    /// order: the derivation's own `flow_names`.
    pub flows: Vec<String>,
    /// How messages name the settings: flags, or a scene file's keys.
    pub words: Words,
    /// The `--sensitivity` columns (docs/sensitivities.md).
    pub sensitivities: Vec<super::sensitivity::Sensitivity>,
    /// Output times instead of every accepted step (a fit's data times, `RunArgs::at`):
    /// increasing, the run lands on each.
    pub at: Vec<f64>,
    /// Whether the rates `d(X)/d(t)` of the recorded quantities are recorded too
    /// (`RunArgs::rates`), beside the sensitivities' columns.
    pub rates: bool,
}

/// The default tolerance of the adaptive methods when `--tol` is not given.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// The finest `--tol` of `method`: its [`Floor`], where its error stops following the
/// tolerance (100 ε for the error-estimating steppers, 1e-15 for taylor: the run-time
/// models have no double-double head).
pub fn min_tolerance(method: Method) -> f64 {
    match method {
        Method::Taylor => Floor::Taylor,
        _ => Floor::ErrorEstimate,
    }
    .relative()
}

/// The loosest `--tol`. Above it the error control lets a step's error reach tens of per
/// cent (`--tol 10` gave an answer 17 % wrong): not an answer worth computing.
pub const MAX_TOLERANCE: f64 = 0.1;

/// Parses `--set` into (name, value) pairs; a name given twice is an error (the second
/// value would silently win).
pub fn parameters(args: &RunArgs) -> Result<Vec<(String, f64)>, CliError> {
    let mut values: Vec<(String, f64)> = Vec::new();
    for (index, text) in args.set.iter().enumerate() {
        let (name, value) = assignment(text, "--set")?;
        if values.iter().any(|(n, _)| *n == name) {
            let first = args.set[..index]
                .iter()
                .find(|t| t.split_once('=').is_some_and(|(n, _)| n.trim() == name))
                .map_or(String::new(), |t| format!(" (first as --set {t})"));
            return Err(CliError::Input(format!(
                "--set {text}: `{name}` is set twice{first}; give each parameter once"
            )));
        }
        values.push((name, value));
    }
    Ok(values)
}

/// A warning for each parameter given a value that enters none of the quantities the run
/// computes (declared or inferred, e.g. used only by a `check`, or multiplied by 0): its
/// value changes nothing, which the user should know. `used`: the parameters the equations
/// read, found once by `Derivation::used_parameters` (a walk of every expression).
pub fn unused_among(d: &Derivation, used: &[String], values: &[(String, f64)]) -> Vec<String> {
    values
        .iter()
        .filter(|(name, _)| d.parameters.iter().any(|(n, _)| n == name))
        .filter(|(name, _)| !used.contains(name))
        .map(|(name, value)| {
            format!(
                "--set {name}={value}: `{name}` enters none of the quantities this run computes, \
                 so its value changes nothing"
            )
        })
        .collect()
}

/// Builds and checks the plan for `program`, whose model's statements (after tag
/// selection) are `ast` (for the `let` names `--record` may use), with the parameter values
/// given as numbers (`args.set` is read by [`parameters`] before).
pub fn plan_with(
    args: &RunArgs,
    parameters: Vec<(String, f64)>,
    program: &Program,
    ast: &SystemAst,
) -> Result<Plan, CliError> {
    let (from, until) = span(args)?;
    let known = observables(program);
    let initial_state = initial_state(args, program)?;
    let stop_when = stop_conditions(args, program, &known, &initial_state)?;
    let record = match args.record.is_empty() {
        true => default_record(&known, program)
            .into_iter()
            .map(|(n, o)| (n, Recorded::Quantity(o)))
            .collect(),
        false => {
            let scope = Scope::new(program, ast, &known, &parameters);
            columns(&args.record, &scope, args.words)?
        }
    };
    let every = args.every.map(|dt| every(dt, args, until)).transpose()?;
    let max_seconds = args
        .max_seconds
        .map(|s| positive(s, "--max-seconds", args.words))
        .transpose()?;
    if args.max_steps == 0 {
        return Err(CliError::Input(format!(
            "{}: a run needs at least one step",
            args.words.given("--max-steps", "0")
        )));
    }
    Ok(Plan {
        from,
        until,
        initial_state,
        method: args.method,
        steps: steps(args, until)?,
        stop_when,
        every,
        record,
        max_steps: args.max_steps,
        max_seconds,
        progress: true,
        parameters,
        flows: program.derivation().flow_names.clone(),
        words: args.words,
        sensitivities: super::sensitivity::resolve(args, program)?,
        at: output_at(args, from, until)?,
        rates: args.rates,
    })
}

/// The start and end times: both finite, the end given and not before the start, and the
/// span between them either none or wide enough to step (at least the smallest normal f64).
fn span(args: &RunArgs) -> Result<(f64, f64), CliError> {
    let from = args.from;
    let Some(until) = args.until else {
        return Err(CliError::Input(format!(
            "{} is required: the end time of the run (a scene file, SCENE.toml, gives its own)",
            args.words.given("--until", "T")
        )));
    };
    if !from.is_finite() {
        return Err(CliError::Input(format!(
            "{}: the start time must be finite",
            args.words.given("--from", &shown(from))
        )));
    }
    if !until.is_finite() || until < from {
        return Err(CliError::Input(format!(
            "{} must be finite and not before the start time {} ({}): a run goes forward in \
             time",
            args.words.given("--until", &shown(until)),
            shown(from),
            args.words.setting("--from")
        )));
    }
    let span = until - from;
    if span > 0.0 && span < f64::MIN_POSITIVE {
        return Err(CliError::Input(format!(
            "the run from t = {} to {} spans {}, below the smallest normal f64 ({:e}): steps \
             within it underflow (give a span of at least that, or none)",
            shown(from),
            args.words.given("--until", &shown(until)),
            shown(span),
            f64::MIN_POSITIVE
        )));
    }
    Ok((from, until))
}

/// The `--stop-when` conditions, each on a quantity of the model (`known`) and not yet
/// true at the start state `initial_state`.
fn stop_conditions(
    args: &RunArgs,
    program: &Program,
    known: &[(String, Observable)],
    initial_state: &[f64],
) -> Result<Vec<StopWhen>, CliError> {
    let flag = args.words.setting("--stop-when");
    let mut stop_when = Vec::new();
    for text in &args.stop_when {
        let what = format!("{flag} `{text}`");
        let (name, direction, value) = condition(text, &flag)?;
        let observable = resolve(&name, known, "a quantity")?;
        let condition = StopWhen {
            observable,
            value,
            direction,
        };
        not_yet_true(program, &condition, &what, args.from, initial_state)?;
        stop_when.push(condition);
    }
    Ok(stop_when)
}

/// `plan`, made by [`plan_with`] for the same `args` and parameters of the same names, given
/// the values `parameters`: only what depends on the values is made and checked again (the
/// initial momenta and masses from `velocity_state`, [`initial_velocities`] of `args`, and
/// whether a `--stop-when` already holds at the start), in [`plan_with`]'s order, so a
/// refusal is the one [`plan_with`] would give (everything else it checks reads only
/// `args` and the model, and passed). A plan recording an expression is not refreshed
/// ([`Plan::refreshable`]): its parameters are constants in it.
pub fn refresh(
    plan: &mut Plan,
    args: &RunArgs,
    parameters: Vec<(String, f64)>,
    program: &Program,
    velocity_state: &[f64],
) -> Result<(), CliError> {
    let initial_state = momenta(program, args.from, velocity_state.to_vec())?;
    for (text, condition) in args.stop_when.iter().zip(&plan.stop_when) {
        let what = format!("{} `{text}`", args.words.setting("--stop-when"));
        not_yet_true(program, condition, &what, plan.from, &initial_state)?;
    }
    plan.initial_state = initial_state;
    plan.parameters = parameters;
    Ok(())
}

impl Plan {
    /// Whether the run records derivative columns (sensitivities or rates): it runs on the
    /// path of `run/sensitivity.rs`.
    pub fn differentiated(&self) -> bool {
        !self.sensitivities.is_empty() || self.rates
    }

    /// Whether [`refresh`] can give this plan other parameter values: it records no
    /// expression (an expression holds the values of the parameters it reads).
    pub fn refreshable(&self) -> bool {
        self.record
            .iter()
            .all(|(_, r)| matches!(r, Recorded::Quantity(_)))
    }
}

/// Splits a `--stop-when` condition `NAME = VALUE`, `NAME > VALUE` or `NAME < VALUE`
/// (`>=` and `<=` read as `>` and `<`: a crossing has no width); `flag` is the setting
/// as its user wrote it (`--stop-when`, a scene's `when`).
pub(crate) fn condition(text: &str, flag: &str) -> Result<(String, Direction, f64), CliError> {
    let Some(at) = text.find(['=', '<', '>']) else {
        return Err(CliError::Input(format!(
            "{flag} `{text}`: expected NAME = VALUE, NAME > VALUE or NAME < VALUE"
        )));
    };
    let (name, rest) = text.split_at(at);
    let (direction, value) = match rest.split_at(1) {
        (">", value) => (Direction::Rising, value.strip_prefix('=').unwrap_or(value)),
        ("<", value) => (Direction::Falling, value.strip_prefix('=').unwrap_or(value)),
        (_, value) => (Direction::Either, value),
    };
    let (name, value) = named(text, flag, name, value)?;
    Ok((name, direction, value))
}

/// A `>` or `<` condition that already holds at the start would wait for a crossing the
/// user did not mean: refused, with the value there; `what` names the condition as its
/// user wrote it.
pub(crate) fn not_yet_true(
    program: &Program,
    condition: &StopWhen,
    what: &str,
    from: f64,
    state: &[f64],
) -> Result<(), CliError> {
    let start = evaluate(program, condition.observable, from, state)
        .map_err(|e| CliError::Input(format!("{what}: {e} at the start")))?;
    let holds = match condition.direction {
        Direction::Rising => start > condition.value,
        Direction::Falling => start < condition.value,
        Direction::Either => false,
    };
    if holds {
        return Err(CliError::Input(format!(
            "{what} already holds at the start (the value there is {start}): a run stops \
             when the quantity crosses the value"
        )));
    }
    if start != condition.value || condition.direction == Direction::Either {
        return Ok(());
    }
    // Exactly on its value: the run's events watch for a crossing from the other side, so
    // a motion that enters the condition's side at once (a rocket sinking from y = 0 under
    // `y < 0`) would never be stopped. The side it enters is refused as holding.
    match entered(program, condition, from, state)? {
        Some((time, value))
            if (value > condition.value) == (condition.direction == Direction::Rising) =>
        {
            Err(CliError::Input(format!(
                "{what} stands exactly on its value at the start and the motion enters it at \
                 once (at t = {} the value is {}): a run stops when the quantity crosses the \
                 value; start a hair away from it, or hold the body on a `support` in a scene",
                shown(time),
                shown(value)
            )))
        }
        _ => Ok(()),
    }
}

/// The time and value of `condition`'s quantity where the motion first leaves its value,
/// from `state` at `from`: two-stage Euler probes y + s·f(t + s, y + s·f(t, y)) of
/// s = 4ε·max(|t|, 1)·2ᵏ up to 10⁶ of those (as a run leaves a switch standing on zero,
/// `core::run::switching`); the second stage sees a quantity whose rate is zero at the
/// start (a body at rest under a force). `None` if none leaves it within reach.
fn entered(
    program: &Program,
    condition: &StopWhen,
    from: f64,
    state: &[f64],
) -> Result<Option<(f64, f64)>, CliError> {
    let failed = |e: varmass::core::SystemError| CliError::Input(format!("{e} at the start"));
    let mut rate = vec![0.0; state.len()];
    program.state_rate(from, state, &mut rate).map_err(failed)?;
    let rounding = 4.0 * f64::EPSILON * from.abs().max(1.0);
    let (mut step, mut later) = (rounding, vec![0.0; state.len()]);
    while step <= 1e6 * rounding {
        let time = from + step;
        let predicted: Vec<f64> = state.iter().zip(&rate).map(|(y, f)| y + step * f).collect();
        program
            .state_rate(time, &predicted, &mut later)
            .map_err(failed)?;
        let probe: Vec<f64> = state
            .iter()
            .zip(&later)
            .map(|(y, f)| y + step * f)
            .collect();
        let value = evaluate(program, condition.observable, time, &probe).map_err(failed)?;
        if value != condition.value {
            return Ok(Some((time, value)));
        }
        step *= 2.0;
    }
    Ok(None)
}

fn positive(value: f64, flag: &str, words: Words) -> Result<f64, CliError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CliError::Input(format!(
            "{}: must be positive and finite",
            words.given(flag, &shown(value))
        )))
    }
}

fn steps(args: &RunArgs, until: f64) -> Result<Steps, CliError> {
    match (args.method, args.step, args.tol) {
        // clap refuses the pair on the command line; a scene file reaches here with both.
        (_, Some(_), Some(_)) => Err(CliError::Input(
            "a tolerance and a fixed step do not go together: a fixed step has no error \
             control (give `tol` or `step`, not both)"
                .into(),
        )),
        (_, Some(h), _) => fixed_step(h, args, until).map(Steps::Fixed),
        (
            Method::DormandPrince
            | Method::Dop853
            | Method::Sdirk4
            | Method::Esdirk43
            | Method::Taylor,
            None,
            tol,
        ) => tolerance(tol.unwrap_or(DEFAULT_TOLERANCE), args).map(Steps::Adaptive),
        (method, None, _) => {
            let method = method_name(method, args.words);
            Err(CliError::Input(format!(
                "{} takes a fixed step: give {}",
                args.words.given("--method", &method),
                args.words.given("--step", "H")
            )))
        }
    }
}

/// An `--every` that is positive and asks for no more output times than `--max-steps`
/// allows steps (each output time ends a step): `--every 1e-12 --until 1` is refused here,
/// not after building 10¹² output times.
fn every(dt: f64, args: &RunArgs, until: f64) -> Result<f64, CliError> {
    let dt = positive(dt, "--every", args.words)?;
    let span = until - args.from;
    let times = (span / dt).ceil();
    if times > args.max_steps as f64 {
        let words = args.words;
        return Err(CliError::Input(format!(
            "{} asks for {} output times from t = {} to {}, more than {}; the usable \
             spacings are {:.3e} to {} (or raise {})",
            words.given("--every", &shown(dt)),
            count(times),
            shown(args.from),
            words.given("--until", &shown(until)),
            words.given("--max-steps", &args.max_steps.to_string()),
            span / args.max_steps as f64,
            shown(span),
            words.setting("--max-steps")
        )));
    }
    Ok(dt)
}

/// The output times of `args.at` (a fit's data times), checked: increasing, finite, in
/// [`from`, `until`], and not with --every.
fn output_at(args: &RunArgs, from: f64, until: f64) -> Result<Vec<f64>, CliError> {
    if args.at.is_empty() {
        return Ok(Vec::new());
    }
    if args.every.is_some() {
        return Err(CliError::Input(
            "--every and the data's times both set the output times: give one".to_string(),
        ));
    }
    if let Some(t) = (args.at.iter()).find(|t| !(t.is_finite() && (from..=until).contains(*t))) {
        return Err(CliError::Input(format!(
            "the datum at t = {} is outside the run, from {} to {}: set {} and {} around \
             the data",
            shown(*t),
            shown(from),
            shown(until),
            args.words.setting("--from"),
            args.words.setting("--until")
        )));
    }
    match args.at.windows(2).all(|w| w[0] < w[1]) {
        true => Ok(args.at.clone()),
        false => Err(CliError::Input(
            "the data's times must increase".to_string(),
        )),
    }
}

/// A count of steps or output times as a message gives it: past f64's range (a subnormal
/// step) it is "over 1.8e308", not "inf".
fn count(n: f64) -> String {
    match n.is_finite() {
        true => format!("{n:.3e}"),
        false => format!("over {:.1e}", f64::MAX),
    }
}

/// `method` as the caller names it (`--method`'s value, or a scene's or Python's).
fn method_name(method: Method, words: Words) -> String {
    let name = clap::ValueEnum::to_possible_value(&method)
        .map(|v| v.get_name().to_string())
        .unwrap_or_default();
    words.name(&name)
}

/// A `--tol` within [`min_tolerance`] of the method and [`MAX_TOLERANCE`].
fn tolerance(tol: f64, args: &RunArgs) -> Result<f64, CliError> {
    let floor = min_tolerance(args.method);
    let method = method_name(args.method, args.words);
    // Every digit of the floor: a rounded one (2.2e-14 of 2.220446e-14) would be refused.
    let floor_text = shown(floor);
    let range = format!("the usable range of {method} is {floor_text} to {MAX_TOLERANCE}");
    let why = if !(tol.is_finite() && tol > 0.0) {
        "must be positive and finite".to_string()
    } else if tol < floor {
        format!(
            "is finer than {method} can honour (its floor is {floor_text}, below which its \
             error stops following the tolerance)"
        )
    } else if tol > MAX_TOLERANCE {
        "is too loose: each step's error could reach tens of per cent of the state".to_string()
    } else {
        return Ok(tol);
    };
    Err(CliError::Input(format!(
        "{} {why}; {range}",
        args.words.given("--tol", &shown(tol))
    )))
}

/// A `--step` that is positive and reaches `--until` within `--max-steps` steps: checked
/// here, before the first step, instead of found out at the step limit.
fn fixed_step(h: f64, args: &RunArgs, until: f64) -> Result<f64, CliError> {
    let h = positive(h, "--step", args.words)?;
    let span = until - args.from;
    let needed = (span / h).ceil();
    // u64 → f64 is exact to 2⁵³, far above any step budget that finishes.
    let limit = args.max_steps as f64;
    if needed > limit {
        let words = args.words;
        return Err(CliError::Input(format!(
            "{} needs {} steps from t = {} to {}, more than {}; the usable steps are {:.3e} \
             to {} (or raise {})",
            words.given("--step", &shown(h)),
            count(needed),
            shown(args.from),
            words.given("--until", &shown(until)),
            words.given("--max-steps", &args.max_steps.to_string()),
            span / limit,
            shown(span),
            words.setting("--max-steps")
        )));
    }
    Ok(h)
}

/// Coordinates, velocities, state masses and held inputs.
fn default_record(known: &[(String, Observable)], program: &Program) -> Vec<(String, Observable)> {
    let state_masses = program.state_mass_count();
    known
        .iter()
        .filter(|(_, o)| match o {
            Observable::Coordinate(_) | Observable::Velocity(_) | Observable::Held(_) => true,
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
    let velocity_state = initial_velocities(args, program)?;
    momenta(program, args.from, velocity_state)
}

/// `[q, q̇, m_s]` from `--init` (coordinates and state masses required, velocities 0 by
/// default): what of the initial state reads only the arguments, not the values.
pub fn initial_velocities(args: &RunArgs, program: &Program) -> Result<Vec<f64>, CliError> {
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
        let (name, value) = assignment(text, &args.words.setting("--init"))?;
        let slot = match resolve(&name, &settable, "a coordinate, velocity or state mass")? {
            Initial::Coordinate(a) => a,
            Initial::Velocity(a) => n + a,
            Initial::StateMass(i) => 2 * n + i,
        };
        if values[slot].is_some() {
            return Err(CliError::Input(format!(
                "{} {text}: `{name}` is given twice; give each initial value once",
                args.words.setting("--init")
            )));
        }
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
    Ok(values.iter().map(|v| v.unwrap_or(0.0)).collect())
}

/// `[q, p, m_s, u_held]` from `[q, q̇, m_s]` at `from`, with the program's values: every
/// mass positive there, p = ∂*L/∂q̇ giving the velocities back, and the held values of the
/// sampled inputs sampled at the start.
fn momenta(program: &Program, from: f64, velocity_state: Vec<f64>) -> Result<Vec<f64>, CliError> {
    let n = program.coordinate_count();
    let mut velocity_state = velocity_state;
    // The held values of sampled inputs: replaced by the first sample below.
    velocity_state.resize(program.state_len(), 0.0);
    masses_positive(program, from, &velocity_state)?;
    let mut state = velocity_state.clone();
    program.evaluate(
        Quantity::Momenta,
        from,
        &velocity_state,
        &mut state[n..2 * n],
    );
    // Round trip: the momenta must give back the velocities (M positive definite).
    velocity_state_check(program, from, &state)?;
    // The held inputs sampled at the start (the run's own sample there changes nothing),
    // so the first row and `--stop-when` see u(t₀, …).
    program
        .sample(from, &mut state, varmass::core::input::Sampling::All)
        .map_err(|e| CliError::Input(format!("the sampled inputs at the start: {e}")))?;
    Ok(state)
}

/// Every mass positive at the start: a zero or negative mass is named, with its law and
/// value, before the mass matrix it makes singular is tried.
fn masses_positive(program: &Program, t: f64, velocity_state: &[f64]) -> Result<(), CliError> {
    let d = program.derivation();
    let mut masses = vec![f64::NAN; d.masses.len()];
    program.masses(t, velocity_state, &mut masses);
    let names = program.mass_names();
    for ((name, value), law) in names.zip(&masses).zip(&d.closed_laws) {
        if *value > 0.0 {
            continue;
        }
        let law = law.map_or(String::new(), |l| {
            format!(" ({name} = {})", d.pool.display(l))
        });
        let value = match value.is_nan() {
            true => "undefined".to_string(),
            false => value.to_string(),
        };
        return Err(CliError::Input(format!(
            "the mass `{name}` is {value} at the start t = {t}{law}: a mass must be positive; \
             start from a state where it is (--init, --set)"
        )));
    }
    Ok(())
}

fn velocity_state_check(program: &Program, t: f64, state: &[f64]) -> Result<(), CliError> {
    velocity_state(program, t, state).map(|_| ()).map_err(|e| {
        CliError::Input(format!(
            "the initial state is unusable: {e}; the kinetic energy must depend on every \
                 velocity at the start (check --init and the masses)"
        ))
    })
}
