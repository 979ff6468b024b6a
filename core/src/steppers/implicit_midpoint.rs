//! The implicit midpoint rule, the one-stage Gauss–Legendre method: second order,
//! symplectic on (q, p) for constant masses, and conserving every quadratic invariant.
//!
//! Butcher tableau (HNW I, II.7; Hairer–Lubich–Wanner, *Geometric Numerical Integration*,
//! VI.3):
//!
//! ```text
//!  1/2 | 1/2
//! -----+-----
//!      | 1
//! ```
//!
//! The stage Y = y₀ + (h/2) f(t₀ + h/2, Y) is solved by simplified Newton with the iteration
//! matrix I − (h/2) J, J = [`VariableMassSystem::jacobian`] at the predictor; then
//! y₁ = 2Y − y₀. With mass change the flow is not symplectic, and the method simply
//! integrates the true state rate to second order.

use nalgebra::{SMatrix, SVector};

use super::newton::{self, Newton, NewtonConfig};
use super::FixedStep;
use crate::error::StepError;
use crate::stepper::{state_rate, Progress, ProgressMut, StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// Settings of the implicit midpoint stepper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImplicitMidpointConfig {
    /// The fixed step size h > 0.
    pub step: f64,
    /// The Newton iteration.
    pub newton: NewtonConfig,
}

impl Default for ImplicitMidpointConfig {
    fn default() -> Self {
        Self {
            step: 1e-3,
            newton: NewtonConfig::default(),
        }
    }
}

/// The implicit midpoint rule on the state `[q, p, m_s]`, fixed step.
#[derive(Clone, Debug)]
pub struct ImplicitMidpoint<'a, Sys, const N: usize, const S: usize> {
    system: &'a Sys,
    progress: Progress<S>,
    step: f64,
    newton: Newton,
}

impl<'a, Sys, const N: usize, const S: usize> ImplicitMidpoint<'a, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// Starts at `(time, state)`; the state and the configuration are checked.
    pub fn new(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        config: ImplicitMidpointConfig,
    ) -> Result<Self, StepError<S>> {
        Ok(Self {
            system,
            progress: Progress::new(system, time, state)?,
            step: FixedStep::validated(config.step).map_err(|e| e.at(time, &state))?,
            newton: config.newton.validated().map_err(|e| e.at(time, &state))?,
        })
    }
}

impl<Sys, const N: usize, const S: usize> Stepper<N, S> for ImplicitMidpoint<'_, Sys, N, S>
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
        let t_mid = t0 + 0.5 * h;
        let system = self.system;
        let statistics = &mut self.progress.statistics;

        // Explicit Euler half step as the predictor of the stage.
        let predictor = y0 + state_rate(system, statistics, t0, &y0)? * (0.5 * h);
        statistics.jacobian_evaluations += 1;
        let jacobian = system
            .jacobian(t_mid, &predictor)
            .map_err(|error| StepError::from_system(system, error, t_mid, &predictor))?;
        let iteration_matrix = SMatrix::<f64, S, S>::identity() - jacobian * (0.5 * h);
        let stage = newton::solve(
            |stage, statistics| {
                let rate = state_rate(system, statistics, t_mid, stage)?;
                Ok(stage - y0 - rate * (0.5 * h))
            },
            iteration_matrix,
            predictor,
            &self.newton,
            statistics,
            t0,
            &y0,
        )?;
        let y1 = stage * 2.0 - y0;
        self.progress.accept(system, h, reaches_stop, y1)
    }
}
