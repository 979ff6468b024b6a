//! Where run-time sizes meet the const-generic core, for `varmass run`, Python and scenes
//! alike ([`on_sizes`]): `match` arms monomorphizing a [`SizedRun`] — [`integrate`] for a
//! run, the phases for a scene, and through them every stepper — for an `N` and a state
//! length `S`. The
//! small models most runs and ensembles are made of (1 to 3 coordinates, 0 or 1 state mass)
//! have an arm of their exact size, `S = 2N + K`; every other model runs in the arm of its
//! `N` with `S = 2N + MAX_STATE_MASSES`, padded
//! ([`TapeSystem::padded`](varmass::interpret::TapeSystem::padded)): the extra state entries
//! are masses that never change and that the model never reads. A model outside the table
//! is a clear error naming the limits.
//!
//! Why not an exact arm for every (N, K): each arm compiles the eight steppers and the run
//! loop again (about 3 s of CPU each); eight padded arms reach 8 coordinates and 3 state
//! masses. Why exact arms for the small ones: there the padding is most of the state (the
//! sled's 2 entries ran as 5) and cost its run 18 % (52 µs instead of 44, DOP853 at 1e-12);
//! an exact arm runs the bare interpreter's steps bit for bit (`cli/tests/compiled.rs`).

use varmass::interpret::Program;

use super::integrate::{integrate, Outcome};
use super::plan::{min_tolerance, Plan, Steps};
use crate::args::Method;
use crate::error::CliError;

/// The most coordinates a model run by the tool may have.
pub const MAX_COORDINATES: usize = 8;
/// The most state masses a model run by the tool may have.
pub const MAX_STATE_MASSES: usize = 3;

/// The exact arms `(N, S = 2N + K)` (taken only when `$exact`), then one padded arm per N
/// with S = 2N + 3, spelled out (const generic arithmetic is not stable).
macro_rules! sizes {
    ($job:ident, $n:expr, $len:ident, $exact:ident;
     exact $(($en:literal, $es:literal)),*;
     padded $(($pn:literal, $ps:literal)),* $(,)?) => {
        match ($n, $len) {
            $(($en, $es) if $exact => $job.run::<$en, $es>($len),)*
            $(($pn, _) => $job.run::<$pn, $ps>($len),)*
            _ => unreachable!("sizes are checked before"),
        }
    };
}

/// What runs in the monomorphized code of one size: a run ([`dispatch`]) or a scene's
/// phases (`scene::fly`).
pub trait SizedRun {
    /// What it computes, sizes erased.
    type Output;
    /// Runs with `N` coordinates and the state length `S` (the model's own state is `len`
    /// long, `len <= S`: the rest is padding).
    fn run<const N: usize, const S: usize>(self, len: usize) -> Result<Self::Output, CliError>;
}

/// A program's sizes, as the dispatch reads them.
#[derive(Clone, Copy, Debug)]
pub struct Sizes {
    /// Its coordinates, N.
    pub coordinates: usize,
    /// Its state masses, K.
    pub state_masses: usize,
    /// The held values of its sampled inputs (each takes a state mass's place).
    pub held: usize,
    /// The length of its state, 2N + K + held.
    pub len: usize,
}

impl Sizes {
    /// The sizes of `program`.
    pub fn of(program: &Program) -> Self {
        Self {
            coordinates: program.coordinate_count(),
            state_masses: program.state_mass_count(),
            held: program.held_count(),
            len: program.state_len(),
        }
    }
}

/// The one dispatch on sizes, for `varmass run`, scenes and Python: checks that a program
/// of `sizes` fits the table (its held inputs count against the state masses' places),
/// then runs `job` in the arm of its exact size when `exact` and the table has it, else in
/// the arm of its number of coordinates padded to `MAX_STATE_MASSES` state masses.
pub fn on_sizes<J: SizedRun>(sizes: Sizes, exact: bool, job: J) -> Result<J::Output, CliError> {
    check_sizes(sizes)?;
    let (n, len) = (sizes.coordinates, sizes.len);
    sizes!(job, n, len, exact;
        exact (1, 2), (1, 3), (2, 4), (2, 5), (3, 6), (3, 7);
        padded (1, 5), (2, 7), (3, 9), (4, 11), (5, 13), (6, 15), (7, 17), (8, 19),
    )
}

/// Whether a program of `sizes` fits the table of the monomorphized sizes (its held inputs
/// count against the state masses' places); else the error naming the limits.
pub fn check_sizes(sizes: Sizes) -> Result<(), CliError> {
    let Sizes {
        coordinates: n,
        state_masses: k,
        held: h,
        ..
    } = sizes;
    if !(1..=MAX_COORDINATES).contains(&n) || k + h > MAX_STATE_MASSES {
        let held = match h {
            0 => String::new(),
            h => format!(" and {h} sampled inputs (each held value takes a state mass's place)"),
        };
        return Err(CliError::Input(format!(
            "the model has {n} coordinates and {k} state masses{held}; the tool runs models with \
             1 to {MAX_COORDINATES} coordinates and at most {MAX_STATE_MASSES} state masses \
             (use the #[variable_mass_system] macro for larger ones)"
        )));
    }
    Ok(())
}

/// One run of `program` as `plan` says.
struct Single<'a> {
    program: Program,
    plan: &'a Plan,
}

impl SizedRun for Single<'_> {
    type Output = Outcome;

    fn run<const N: usize, const S: usize>(self, len: usize) -> Result<Outcome, CliError> {
        if len == S {
            return integrate::<N, S>(self.program, self.plan);
        }
        // The plan padded to `S`, the points given back unpadded.
        let mut outcome = integrate::<N, S>(self.program, &padded_plan(self.plan, len, S)?)?;
        outcome.points = std::mem::take(&mut outcome.points).narrowed(len);
        Ok(outcome)
    }
}

/// Integrates `program` with the monomorphized code for its size: its exact size when the
/// table has it, else its number of coordinates padded to `MAX_STATE_MASSES` state masses
/// (the points come back unpadded).
pub fn dispatch(program: Program, plan: &Plan) -> Result<Outcome, CliError> {
    if plan.differentiated() {
        return super::sensitivity::dispatch(program, plan);
    }
    on_sizes(Sizes::of(&program), true, Single { program, plan })
}

/// The adaptive tolerance for a state padded from `len` to `padded` entries: scaled by
/// √(len / padded) so that the error norm, a root mean square over every component, takes
/// the same steps as without the padding (the padding's errors are 0). Taylor's control
/// reads max norms (`core::steppers::taylor`), which the padding's zeros do not change: its
/// tolerance is kept. A tolerance that the scaling would take below the finest `method`
/// accepts is refused, with the finest this padding can honour: clamping it instead would
/// run every such tolerance at one looser tolerance than asked, silently.
pub fn padded_steps(
    steps: Steps,
    method: Method,
    len: usize,
    padded: usize,
) -> Result<Steps, CliError> {
    let scale = match method {
        Method::Taylor => 1.0,
        _ => (len as f64 / padded as f64).sqrt(),
    };
    let finest = min_tolerance(method) / scale;
    match steps {
        Steps::Adaptive(tolerance) if tolerance < finest => Err(CliError::Input(format!(
            "the tolerance {tolerance:e} is below the finest this model's run can honour, \
             {finest:.3e}: its state of {len} entries runs in the compiled code for {padded} \
             (one size serves every model of its shape), whose error norm scales the \
             tolerance by √({len}/{padded}); ask for {finest:.3e} or more"
        ))),
        Steps::Adaptive(tolerance) => Ok(Steps::Adaptive(tolerance * scale)),
        fixed => Ok(fixed),
    }
}

/// `plan` for the padded state: the initial state with zeros after the model's own
/// entries, and the tolerance of [`padded_steps`].
pub(crate) fn padded_plan(plan: &Plan, len: usize, padded: usize) -> Result<Plan, CliError> {
    let mut initial_state = plan.initial_state.clone();
    initial_state.resize(padded, 0.0);
    Ok(Plan {
        from: plan.from,
        until: plan.until,
        initial_state,
        method: plan.method,
        steps: padded_steps(plan.steps, plan.method, len, padded)?,
        stop_when: plan.stop_when.clone(),
        every: plan.every,
        record: plan.record.clone(),
        max_steps: plan.max_steps,
        max_seconds: plan.max_seconds,
        progress: plan.progress,
        parameters: plan.parameters.clone(),
        flows: plan.flows.clone(),
        words: plan.words,
        sensitivities: plan.sensitivities.clone(),
        at: plan.at.clone(),
        rates: plan.rates,
    })
}
