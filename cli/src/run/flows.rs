//! The flows' rates during a run, for the guard that refuses a negative one.
//!
//! A flow's rate (Q1 of an outflow, Q2 of an inflow, eqs. 15–16) is ≥ 0 by definition: the
//! statement says which way the mass goes. A rate that comes out negative (`--set mu=-5` on
//! an inflow) would turn the reactive forces round without a word, so the run checks every
//! rate at the start and after each step and stops with
//! [`StepErrorKind::NegativeFlowRate`], the core's typed error, naming the flow.
//!
//! The rates are evaluated from the derivation's `flow_rates` on one tape, in an environment
//! filled as [`Program`] fills its own: parameters once, then t, q, q̇, p and every mass
//! at each state.

use std::cell::RefCell;

use varmass::core::nalgebra::SVector;
use varmass::core::{StepError, StepErrorKind};
use varmass::interpret::Program;
use varmass::symbolic::expr::Tape;

/// The flow rates of a program, ready to evaluate.
pub struct FlowRates<'a> {
    program: &'a Program,
    tape: Tape,
    env: RefCell<Vec<f64>>,
}

impl<'a> FlowRates<'a> {
    /// The rates of `program`'s flows with the parameter values `parameters`.
    pub fn new(program: &'a Program, parameters: &[(String, f64)]) -> Self {
        let d = program.derivation();
        let mut env = vec![f64::NAN; d.pool.symbols().len()];
        for (name, symbol) in &d.parameters {
            if let Some((_, value)) = parameters.iter().find(|(n, _)| n == name) {
                set(&mut env, symbol.index(), *value);
            }
        }
        Self {
            program,
            tape: d.pool.compile(&d.flow_rates),
            env: RefCell::new(env),
        }
    }

    /// Whether the model has flows at all (without, there is nothing to guard).
    pub fn is_empty(&self) -> bool {
        self.program.derivation().flow_rates.is_empty()
    }

    /// Every flow's rate at `(t, state)`, `state` = `[q, p, m_s]`; `None` where q̇ cannot be
    /// had (a singular mass matrix, which the stepper reports itself).
    pub fn at(&self, t: f64, state: &[f64]) -> Option<Vec<f64>> {
        let d = self.program.derivation();
        let n = self.program.coordinate_count();
        let mut velocities = vec![f64::NAN; n];
        self.program.velocities(t, state, &mut velocities).ok()?;
        let mut masses = vec![f64::NAN; d.masses.len()];
        self.program.masses(t, state, &mut masses);
        let env = &mut *self.env.borrow_mut();
        set(env, d.time.index(), t);
        for (a, c) in d.coordinates.iter().enumerate() {
            set(env, c.q.index(), state.get(a).copied().unwrap_or(f64::NAN));
            set(env, c.velocity.index(), velocities[a]);
            set(
                env,
                c.momentum.index(),
                state.get(n + a).copied().unwrap_or(f64::NAN),
            );
        }
        for (m, value) in d.masses.iter().zip(&masses) {
            set(env, m.symbol.index(), *value);
        }
        let mut rates = vec![f64::NAN; d.flow_rates.len()];
        self.tape.eval(env, &mut rates);
        Some(rates)
    }

    /// The check of every rate at `(t, state)`: a negative one is
    /// [`StepErrorKind::NegativeFlowRate`] (through [`StepError::check_flow_rates`]).
    pub fn check(&self, t: f64, state: &[f64]) -> Result<(), StepErrorKind> {
        let Some(rates) = self.at(t, state) else {
            return Ok(());
        };
        // The core's check is on a fixed-size state; the kind alone is what is wanted here.
        StepError::<0>::check_flow_rates(t, &SVector::<f64, 0>::zeros(), rates).map_err(|e| e.kind)
    }
}

fn set(env: &mut [f64], slot: usize, value: f64) {
    if let Some(s) = env.get_mut(slot) {
        *s = value;
    }
}
