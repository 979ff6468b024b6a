//! Where run-time sizes meet the const-generic core: `match` arms monomorphizing
//! [`integrate`] — and through it every stepper — for an `N` and a state length `S`. The
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
use super::plan::{Plan, Steps, MIN_TOLERANCE};
use crate::error::CliError;

/// The most coordinates a model run by the tool may have.
pub const MAX_COORDINATES: usize = 8;
/// The most state masses a model run by the tool may have.
pub const MAX_STATE_MASSES: usize = 3;

/// The exact arms `(N, S = 2N + K)`, then one padded arm per N with S = 2N + 3, spelled out
/// (const generic arithmetic is not stable).
macro_rules! sizes {
    ($program:ident, $plan:ident, $len:ident;
     exact $(($n:literal, $s:literal)),*;
     padded $(($pn:literal, $ps:literal)),* $(,)?) => {
        match ($program.coordinate_count(), $len) {
            $(($n, $s) => integrate::<$n, $s>($program, $plan),)*
            $(($pn, _) => padded::<$pn, $ps>($program, $plan, $len),)*
            _ => unreachable!("sizes are checked before"),
        }
    };
}

/// Integrates `program` with the monomorphized code for its size: its exact size when the
/// table has it, else its number of coordinates padded to `MAX_STATE_MASSES` state masses
/// (the points come back unpadded).
pub fn dispatch(program: Program, plan: &Plan) -> Result<Outcome, CliError> {
    let (n, k) = (program.coordinate_count(), program.state_mass_count());
    // The held values of sampled inputs take places of the padding too.
    let h = program.held_count();
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
    let len = program.state_len();
    sizes!(program, plan, len;
        exact (1, 2), (1, 3), (2, 4), (2, 5), (3, 6), (3, 7);
        padded (1, 5), (2, 7), (3, 9), (4, 11), (5, 13), (6, 15), (7, 17), (8, 19),
    )
}

/// [`integrate`] in the arm `(N, S)` of a model whose state is shorter (`len`): the plan
/// padded to `S`, the points given back unpadded.
fn padded<const N: usize, const S: usize>(
    program: Program,
    plan: &Plan,
    len: usize,
) -> Result<Outcome, CliError> {
    let mut outcome = integrate::<N, S>(program, &padded_plan(plan, len, S))?;
    outcome.points = std::mem::take(&mut outcome.points).narrowed(len);
    Ok(outcome)
}

/// `plan` for the padded state: the initial state with zeros after the model's own
/// entries, and an adaptive tolerance scaled by √(len / padded) so that the error norm,
/// a root mean square over every component, takes the same steps as without the padding
/// (the padding's errors are 0).
fn padded_plan(plan: &Plan, len: usize, padded: usize) -> Plan {
    let mut initial_state = plan.initial_state.clone();
    initial_state.resize(padded, 0.0);
    let scale = (len as f64 / padded as f64).sqrt();
    let steps = match plan.steps {
        // Never below the finest tolerance the core accepts: a --tol at that floor would
        // otherwise be refused for the padding, not for anything the user asked.
        Steps::Adaptive(tolerance) => Steps::Adaptive((tolerance * scale).max(MIN_TOLERANCE)),
        fixed => fixed,
    };
    Plan {
        from: plan.from,
        until: plan.until,
        initial_state,
        method: plan.method,
        steps,
        stop_when: plan.stop_when.clone(),
        every: plan.every,
        record: plan.record.clone(),
        max_steps: plan.max_steps,
        max_seconds: plan.max_seconds,
        progress: plan.progress,
        parameters: plan.parameters.clone(),
        flows: plan.flows.clone(),
        words: plan.words,
    }
}
