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

use super::fixed::{step_only, Fixed, FixedMethod};
use super::FixedStep;
use crate::error::{ConfigError, StepError};
use crate::stepper::{state_rate, Statistics};
use crate::system::VariableMassSystem;

/// Classical RK4 on the state `[q, p, m_s]`, fixed step: [`Fixed`] with the step of
/// [`Rk4Method`].
pub type ClassicalRk4<'a, Sys, const N: usize, const S: usize> = Fixed<'a, Sys, Rk4Method, N, S>;

/// The step of [`ClassicalRk4`].
#[derive(Clone, Copy, Debug)]
pub struct Rk4Method;

impl<const N: usize, const S: usize> FixedMethod<N, S> for Rk4Method {
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
        let k1 = state_rate(system, statistics, t0, y0)?;
        let k2 = state_rate(system, statistics, t0 + 0.5 * h, &(y0 + k1 * (0.5 * h)))?;
        let k3 = state_rate(system, statistics, t0 + 0.5 * h, &(y0 + k2 * (0.5 * h)))?;
        let k4 = state_rate(system, statistics, t0 + h, &(y0 + k3 * h))?;
        Ok(y0 + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0))
    }
}
