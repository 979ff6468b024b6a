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
//!
//! Written out, not through the explicit core (`explicit.rs`, whose stages give these same
//! bits): the costs bench's generated ÷ hand-written ratio, taken over RK4 steps, moved
//! from 0.996 to 1.046 on Kepler with the core's loop (both rates faster, the hand-written
//! more), and that ratio is a figure the project holds.

use super::fixed::{Explicit, Fixed, NewState, Step};
use crate::system::VariableMassSystem;

/// Classical RK4 on the state `[q, p, m_s]`, fixed step: [`Fixed`] with the step of
/// [`Rk4Method`].
pub type ClassicalRk4<'a, Sys, const N: usize, const S: usize> = Fixed<'a, Sys, Rk4Method, N, S>;

/// The step of [`ClassicalRk4`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Rk4Method;

impl<const N: usize, const S: usize> Explicit<N, S> for Rk4Method {
    fn formula<Sys: VariableMassSystem<N, S>>(mut step: Step<'_, Sys, S>) -> NewState<S> {
        let Step { t0, y0, h, .. } = step;
        let k1 = step.rate(t0, &y0)?;
        let k2 = step.rate(t0 + 0.5 * h, &(y0 + k1 * (0.5 * h)))?;
        let k3 = step.rate(t0 + 0.5 * h, &(y0 + k2 * (0.5 * h)))?;
        let k4 = step.rate(t0 + h, &(y0 + k3 * h))?;
        Ok(y0 + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0))
    }
}
