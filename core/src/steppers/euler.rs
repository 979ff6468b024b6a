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

use super::fixed::{step_only, Fixed, FixedMethod};
use super::FixedStep;
use crate::error::{ConfigError, StepError};
use crate::stepper::{state_rate, Statistics};
use crate::system::VariableMassSystem;

/// Explicit Euler, y₁ = y₀ + h f(t₀, y₀), on the state `[q, p, m_s]`: [`Fixed`] with the
/// step of [`EulerMethod`].
pub type ExplicitEuler<'a, Sys, const N: usize, const S: usize> = Fixed<'a, Sys, EulerMethod, N, S>;

/// The step of [`ExplicitEuler`].
#[derive(Clone, Copy, Debug)]
pub struct EulerMethod;

impl<const N: usize, const S: usize> FixedMethod<N, S> for EulerMethod {
    type Config = FixedStep;

    fn configure(config: FixedStep) -> Result<(f64, Self), ConfigError> {
        Ok((step_only(config)?, Self))
    }

    fn advance<Sys>(
        &self,
        system: &Sys,
        statistics: &mut Statistics,
        (t0, y0): (f64, &SVector<f64, S>),
        h: f64,
    ) -> Result<SVector<f64, S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let rate = state_rate(system, statistics, t0, y0)?;
        Ok(y0 + rate * h)
    }
}
