//! Run-time evaluation of a derivation: the alternative to generated code for models that
//! are only known when the program runs (a model file read by the `varmass` command line
//! tool, or the benches' comparison of evaluators).
//!
//! A [`Program`] holds a [`Derivation`](varmass_symbolic::mechanics::Derivation) with its
//! parameter values and compiles each group of quantities into one straight-line
//! [`Tape`](varmass_symbolic::expr::Tape): the mass laws, q̇ from p (closed form, or
//! M q̇ = p − b solved by a run-time Cholesky (`cholesky.rs`) beyond
//! [`SYMBOLIC_INVERSE_MAX_DOF`](varmass_symbolic::mechanics::SYMBOLIC_INVERSE_MAX_DOF)
//! coordinates), the state rate, and every velocity-form [`Quantity`] (forces, H, the
//! power, …). It works on slices, so its sizes are run-time values.
//!
//! [`TapeSystem<N, S>`] fixes the sizes and implements
//! [`VariableMassSystem`](varmass_core::VariableMassSystem), so the core's steppers and
//! [`run`](fn@varmass_core::run::run) integrate a run-time model exactly as they integrate
//! generated code: the same monomorphized stepper code, only the system differs.
//!
//! ```
//! use varmass::interpret::{Program, TapeSystem};
//! use varmass::prelude::*;
//! use varmass::symbolic::{derive_source, mechanics::Parameters};
//!
//! let source = "coordinates y
//!               mass m: state, rate -mu
//!               body rocket: mass m, position [y]
//!               potential m*g*y
//!               outflow rocket: rate mu, relative_velocity [-u_e]";
//! let derivation = derive_source(source, Parameters::Inferred).expect("derives");
//! let parameters = [("mu", 0.05), ("u_e", 300.0), ("g", 9.81)];
//! let program = Program::new(derivation, &parameters)?;
//! let rocket = TapeSystem::<1, 3>::new(program)?;
//! let start = SVector::<f64, 3>::new(0.0, 0.0, 1.0);
//! let mut stepper = DormandPrince::new(&rocket, 0.0, start, StepControl::default())?;
//! let burnout = Event::state_reaches(2, 0.1, Direction::Falling);
//! let solution = run(&mut stepper, &RunConfig::until(30.0), &[burnout])?;
//! let (time, state) = solution.last().unwrap();
//! // m = 1 − 0.05 t reaches 0.1 at t = 18; then v = u_e ln(m0/m) − g t (Tsiolkovsky).
//! assert!((time - 18.0).abs() < 1e-9);
//! assert!((state[1] / state[2] - (300.0 * 10f64.ln() - 9.81 * 18.0)).abs() < 1e-3);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod cholesky;
mod error;
mod names;
mod program;
mod system;
mod taylor;

pub use error::ProgramError;
pub use program::{Direction, Evaluation, Program, Quantity};
pub use system::TapeSystem;
