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

use nalgebra::SMatrix;

use super::fixed::{Fixed, FixedMethod, NewState, Step};
use super::newton::{self, Newton, NewtonConfig};
use super::FixedStep;
use crate::error::{ConfigError, StepError};
use crate::stepper::state_rate;
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

/// The implicit midpoint rule on the state `[q, p, m_s]`, fixed step: [`Fixed`] with the
/// step of [`ImplicitMidpointMethod`].
pub type ImplicitMidpoint<'a, Sys, const N: usize, const S: usize> =
    Fixed<'a, Sys, ImplicitMidpointMethod, N, S>;

/// The step of [`ImplicitMidpoint`]: its Newton iteration.
#[derive(Clone, Debug)]
pub struct ImplicitMidpointMethod {
    newton: Newton,
}

impl<const N: usize, const S: usize> FixedMethod<N, S> for ImplicitMidpointMethod {
    type Config = ImplicitMidpointConfig;

    fn configure(config: ImplicitMidpointConfig) -> Result<(f64, Self), ConfigError> {
        let step = FixedStep::validated(config.step)?;
        let newton = config.newton.validated()?;
        Ok((step, Self { newton }))
    }

    fn advance<Sys: VariableMassSystem<N, S>>(&self, mut step: Step<'_, Sys, S>) -> NewState<S> {
        let Step { t0, y0, h, .. } = step;
        let t_mid = t0 + 0.5 * h;

        // Explicit Euler half step as the predictor of the stage.
        let predictor = y0 + step.rate(t0, &y0)? * (0.5 * h);
        let Step {
            system, statistics, ..
        } = step;
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
            (t0, &y0),
        )?;
        Ok(stage * 2.0 - y0)
    }
}
