//! The classical fourth-order Runge–Kutta method.
//!
//! Butcher tableau (Kutta 1901; Hairer–Nørsett–Wanner I, II.1, Table 1.2):
//!
//! ```text
//!  0   |
//!  1/2 | 1/2
//!  1/2 | 0    1/2
//!  1   | 0    0    1
//! -----+--------------------
//!      | 1/6  1/3  1/3  1/6
//! ```

use nalgebra::SVector;

use super::FixedStep;
use crate::error::StepError;
use crate::stepper::{state_rate, Progress, ProgressMut, StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// Classical RK4 on the state `[q, p, m_s]`, fixed step.
#[derive(Clone, Debug)]
pub struct ClassicalRk4<'a, Sys, const N: usize, const S: usize> {
    system: &'a Sys,
    progress: Progress<S>,
    step: f64,
}

impl<'a, Sys, const N: usize, const S: usize> ClassicalRk4<'a, Sys, N, S>
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

impl<Sys, const N: usize, const S: usize> Stepper<N, S> for ClassicalRk4<'_, Sys, N, S>
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
        let statistics = &mut self.progress.statistics;
        let k1 = state_rate(self.system, statistics, t0, &y0)?;
        let k2 = state_rate(
            self.system,
            statistics,
            t0 + 0.5 * h,
            &(y0 + k1 * (0.5 * h)),
        )?;
        let k3 = state_rate(
            self.system,
            statistics,
            t0 + 0.5 * h,
            &(y0 + k2 * (0.5 * h)),
        )?;
        let k4 = state_rate(self.system, statistics, t0 + h, &(y0 + k3 * h))?;
        let y1 = y0 + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
        self.progress.accept(self.system, h, reaches_stop, y1)
    }
}
