//! The explicit Euler method, first order: the baseline every other stepper is measured
//! against.
//!
//! Butcher tableau (Euler 1768; Hairer–Nørsett–Wanner I, II.1):
//!
//! ```text
//!  0 |
//! ---+---
//!    | 1
//! ```

use nalgebra::SVector;

use super::FixedStep;
use crate::error::StepError;
use crate::stepper::{state_rate, Progress, ProgressMut, StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// Explicit Euler, y₁ = y₀ + h f(t₀, y₀), on the state `[q, p, m_s]`.
#[derive(Clone, Debug)]
pub struct ExplicitEuler<'a, Sys, const N: usize, const S: usize> {
    system: &'a Sys,
    progress: Progress<S>,
    step: f64,
}

impl<'a, Sys, const N: usize, const S: usize> ExplicitEuler<'a, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// Starts at `(time, state)`; the state is checked (finite, masses positive).
    pub fn new(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        config: FixedStep,
    ) -> Result<Self, StepError<S>> {
        Ok(Self {
            system,
            progress: Progress::new(system, time, state)?,
            step: FixedStep::validated(config.step).map_err(|e| e.at(time, &state))?,
        })
    }
}

impl<Sys, const N: usize, const S: usize> Stepper<N, S> for ExplicitEuler<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    type System = Sys;

    fn parts(&self) -> (&Sys, &Progress<S>) {
        (self.system, &self.progress)
    }

    fn parts_mut(&mut self) -> ProgressMut<'_, Sys, S> {
        ProgressMut::new(self.system, &mut self.progress)
    }

    fn step(&mut self) -> Result<StepOutcome, StepError<S>> {
        let (h, reaches_stop) = self.progress.next_step(self.step)?;
        let t0 = self.progress.time();
        let y0 = *self.progress.state();
        let rate = state_rate(self.system, &mut self.progress.statistics, t0, &y0)?;
        self.progress
            .accept(self.system, h, reaches_stop, y0 + rate * h)
    }
}
