//! The state rate of a derivation evaluated at run time, the alternative to generated code:
//! a thin adapter over [`varmass::interpret::Program`] (mass laws, q̇ from p in closed form
//! or by Cholesky, then ṗ and ṁ_s), each stage either a compiled tape or a walk of the
//! expression DAG.

use varmass::interpret::{Evaluation, Program};
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// How each stage is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// A straight-line tape per stage (`ExprPool::compile`).
    Tape,
    /// `ExprPool::eval` on each root: a recursive walk, no compilation.
    Tree,
}

/// A derivation ready to evaluate its state rate at run time.
pub struct Interpreted {
    program: Program,
}

impl Interpreted {
    /// Derives `source` with the given parameter values.
    pub fn new(source: &str, parameters: &[(&str, f64)], mode: Mode) -> Result<Self, String> {
        let names = parameters.iter().map(|(n, _)| n.to_string()).collect();
        let d = derive_source(source, Parameters::Declared(names)).map_err(|e| format!("{e:?}"))?;
        let evaluation = match mode {
            Mode::Tape => Evaluation::Tape,
            Mode::Tree => Evaluation::Tree,
        };
        let program =
            Program::with_evaluation(d, parameters, evaluation).map_err(|e| e.to_string())?;
        Ok(Self { program })
    }

    /// Instructions in the three tapes together: the interpreter's work per evaluation.
    pub fn tape_length(&self) -> usize {
        self.program.tape_length()
    }

    /// Instructions of the q̇ stage alone.
    pub fn velocity_tape_length(&self) -> usize {
        self.program.velocity_tape_length()
    }

    /// The state rate [q̇, ṗ, ṁ_s] at `(t, state)` into `out` (NaN where it cannot be had).
    pub fn state_rate(&self, t: f64, state: &[f64], out: &mut [f64]) {
        if self.program.state_rate(t, state, out).is_err() {
            out.fill(f64::NAN);
        }
    }
}
