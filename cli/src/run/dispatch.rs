//! Where run-time sizes meet the const-generic core: one `match` arm per supported
//! (coordinates, state masses) pair, each monomorphizing [`integrate`] — and through it
//! every stepper — for its `N` and `S = 2N + K`. A model outside the table is a clear error
//! naming the limits.
//!
//! The table is kept small because each arm compiles the eight steppers and the run loop
//! again; the build time this costs is noted in the crate's README section.

use varmass::interpret::Program;

use super::integrate::{integrate, Outcome};
use super::plan::Plan;
use crate::error::CliError;

/// The most coordinates a model run by the tool may have.
pub const MAX_COORDINATES: usize = 4;
/// The most state masses a model run by the tool may have.
pub const MAX_STATE_MASSES: usize = 2;

/// One arm per (N, K, S = 2N + K); `S` is spelled out because const generic arithmetic is
/// not stable.
macro_rules! sizes {
    ($program:ident, $plan:ident; $(($n:literal, $k:literal, $s:literal)),* $(,)?) => {
        match ($program.coordinate_count(), $program.state_mass_count()) {
            $(($n, $k) => integrate::<$n, $s>($program, $plan),)*
            (n, k) => Err(CliError::Input(format!(
                "the model has {n} coordinates and {k} state masses; the tool runs models with \
                 1 to {MAX_COORDINATES} coordinates and at most {MAX_STATE_MASSES} state masses \
                 (use the #[variable_mass_system] macro for larger ones)"
            ))),
        }
    };
}

/// Integrates `program` with the monomorphized code for its sizes.
pub fn dispatch(program: Program, plan: &Plan) -> Result<Outcome, CliError> {
    sizes!(program, plan;
        (1, 0, 2), (1, 1, 3), (1, 2, 4),
        (2, 0, 4), (2, 1, 5), (2, 2, 6),
        (3, 0, 6), (3, 1, 7), (3, 2, 8),
        (4, 0, 8), (4, 1, 9), (4, 2, 10),
    )
}
