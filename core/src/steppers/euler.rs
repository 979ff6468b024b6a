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

use super::explicit::{self, Row};
use super::fixed::{Explicit, Fixed, NewState, Step};
use crate::system::VariableMassSystem;

/// Explicit Euler, y₁ = y₀ + h f(t₀, y₀), on the state `[q, p, m_s]`: [`Fixed`] with the
/// step of [`EulerMethod`].
pub type ExplicitEuler<'a, Sys, const N: usize, const S: usize> = Fixed<'a, Sys, EulerMethod, N, S>;

/// The step of [`ExplicitEuler`].
#[derive(Clone, Copy, Debug, Default)]
pub struct EulerMethod;

impl<const N: usize, const S: usize> Explicit<N, S> for EulerMethod {
    /// The explicit core's new state with b = (1): y₀ + (k₁·1)·h, the bits of y₀ + k₁ h.
    fn formula<Sys: VariableMassSystem<N, S>>(mut step: Step<'_, Sys, S>) -> NewState<S> {
        const WEIGHTS: Row = &[(1, 1.0)];
        let y0 = step.y0;
        let rate = step.rate(step.t0, &y0)?;
        Ok(explicit::solution(WEIGHTS, &y0, &[rate], step.h))
    }
}
