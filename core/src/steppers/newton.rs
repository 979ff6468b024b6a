//! Simplified Newton iteration for the implicit steppers: one LU factorisation of the
//! iteration matrix per step (an `SMatrix` on the stack), then z ← z − A⁻¹ r(z) until the
//! increments are below tolerance.
//!
//! The factorisation is a small partial-pivoting LU written here rather than nalgebra's
//! `lu()`, because the latter needs `Const<S>: DimMin<Const<S>>`, a typenum bound that
//! would leak into every implicit stepper's public signature for a generic `S`.
//!
//! Convergence test (HNW II, IV.8): with the contraction rate θₖ = ‖Δₖ‖/‖Δₖ₋₁‖
//! the remaining error is about θₖ/(1 − θₖ)·‖Δₖ‖, and the iteration stops when that is below
//! tolerance. An increment already at the rounding level of z also stops it, since no
//! further iteration can improve on rounding.

use nalgebra::{SMatrix, SVector};

use crate::error::{ConfigError, StepError, StepErrorKind};
use crate::stepper::Statistics;
use crate::tolerance::{weighted_rms, Tolerance};

/// Settings of the Newton iteration of the implicit steppers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonConfig {
    /// Relative tolerance on the solution. The default 1e-12 is near rounding so that a
    /// symplectic method stays symplectic to that level over long runs.
    pub relative_tolerance: f64,
    /// Absolute tolerance on the solution (for components near zero).
    pub absolute_tolerance: f64,
    /// Iterations allowed per step before [`StepErrorKind::NewtonDivergence`].
    pub max_iterations: usize,
}

impl Default for NewtonConfig {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-12,
            absolute_tolerance: 1e-14,
            max_iterations: 25,
        }
    }
}

impl NewtonConfig {
    /// The checked settings: a usable [`Tolerance`] and at least one iteration.
    pub(crate) fn validated(self) -> Result<Newton, ConfigError> {
        let tolerance =
            Tolerance::new(self.relative_tolerance, self.absolute_tolerance).map_err(|_| {
                ConfigError {
                    reason: "Newton: tolerances must be finite, non-negative and not both zero",
                }
            })?;
        if self.max_iterations == 0 {
            return Err(ConfigError {
                reason: "Newton: at least one iteration must be allowed",
            });
        }
        Ok(Newton {
            tolerance,
            max_iterations: self.max_iterations,
        })
    }
}

/// [`NewtonConfig`] after its check: what [`solve`] runs with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Newton {
    /// The tolerance on the solution z, weighing component i by atol + rtol·|zᵢ|.
    pub(crate) tolerance: Tolerance,
    /// Iterations allowed per step, at least 1.
    pub(crate) max_iterations: usize,
}

/// Solves r(z) = 0 from `initial` with the fixed iteration matrix ≈ ∂r/∂z. `time` and
/// `state` (the start of the step) go into a divergence error.
pub(crate) fn solve<const S: usize, R>(
    mut residual: R,
    iteration_matrix: SMatrix<f64, S, S>,
    initial: SVector<f64, S>,
    config: &Newton,
    statistics: &mut Statistics,
    (time, state): (f64, &SVector<f64, S>),
) -> Result<SVector<f64, S>, StepError<S>>
where
    R: FnMut(&SVector<f64, S>, &mut Statistics) -> Result<SVector<f64, S>, StepError<S>>,
{
    let diverged =
        |iterations| StepError::new(time, *state, StepErrorKind::NewtonDivergence { iterations });
    let Some(lu) = Lu::factor(iteration_matrix) else {
        return Err(diverged(0));
    };
    let mut z = initial;
    let mut previous_norm = f64::INFINITY;
    for iteration in 1..=config.max_iterations {
        let r = residual(&z, statistics)?;
        let increment = lu.solve(-r);
        z += increment;
        statistics.newton_iterations += 1;
        let norm = config.tolerance.norm(&increment, |i| z[i].abs());
        if !norm.is_finite() {
            return Err(diverged(iteration));
        }
        if norm <= 1.0 {
            return Ok(z);
        }
        let rounding = weighted_rms(&increment, |i| 16.0 * f64::EPSILON * z[i].abs());
        if rounding <= 1.0 {
            return Ok(z);
        }
        let rate = norm / previous_norm;
        if iteration > 1 {
            if rate >= 1.0 {
                return Err(diverged(iteration));
            }
            if rate / (1.0 - rate) * norm <= 1.0 {
                return Ok(z);
            }
        }
        previous_norm = norm;
    }
    Err(diverged(config.max_iterations))
}

/// An LU factorisation P A = L U with partial pivoting; L (unit diagonal) and U share one
/// matrix.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lu<const S: usize> {
    factors: SMatrix<f64, S, S>,
    /// Row `k` of the factorised matrix is row `pivots[k]` of A.
    pivots: [usize; S],
}

impl<const S: usize> Lu<S> {
    /// Factors `a`; `None` if a pivot is zero or not finite (A singular to working
    /// precision, or not finite).
    pub(crate) fn factor(mut a: SMatrix<f64, S, S>) -> Option<Self> {
        let mut pivots = [0; S];
        for (k, pivot) in pivots.iter_mut().enumerate() {
            *pivot = k;
        }
        for k in 0..S {
            let mut best = k;
            for row in k + 1..S {
                if a[(row, k)].abs() > a[(best, k)].abs() {
                    best = row;
                }
            }
            let pivot = a[(best, k)];
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            if best != k {
                a.swap_rows(best, k);
                pivots.swap(best, k);
            }
            for row in k + 1..S {
                let factor = a[(row, k)] / pivot;
                a[(row, k)] = factor;
                for column in k + 1..S {
                    let update = factor * a[(k, column)];
                    a[(row, column)] -= update;
                }
            }
        }
        Some(Self { factors: a, pivots })
    }

    /// Solves A x = b.
    pub(crate) fn solve(&self, b: SVector<f64, S>) -> SVector<f64, S> {
        let a = &self.factors;
        let mut x = SVector::<f64, S>::from_fn(|row, _| b[self.pivots[row]]);
        for row in 0..S {
            for column in 0..row {
                let update = a[(row, column)] * x[column];
                x[row] -= update;
            }
        }
        for row in (0..S).rev() {
            for column in row + 1..S {
                let update = a[(row, column)] * x[column];
                x[row] -= update;
            }
            x[row] /= a[(row, row)];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The LU solve against a hand-checked 3×3 system that needs pivoting (zero in the
    /// top-left corner).
    #[test]
    fn lu_solves_a_system_that_needs_pivoting() {
        let a = SMatrix::<f64, 3, 3>::new(0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0);
        let x = SVector::<f64, 3>::new(1.0, -2.0, 3.0);
        let b = a * x;
        let lu = Lu::factor(a).expect("the matrix is regular");
        let solved = lu.solve(b);
        // Exact small integers: only rounding in a few operations.
        assert!((solved - x).norm() < 1e-14, "{solved}");
        assert!(Lu::factor(SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0)).is_none());
    }
}
