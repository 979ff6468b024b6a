//! One stage of a diagonally implicit step: Z = G + hγ f(t₀ + ch, y₀ + Z) solved by
//! simplified Newton with the factorised I − hγJ (`sdirk4.f`'s loop 40), and the context
//! the stages of one step share.

use nalgebra::SVector;

use super::{DirkNewton, StageFailure};
use crate::math::powf;
use crate::stepper::{state_rate, Statistics};
use crate::steppers::newton::Lu;
use crate::system::VariableMassSystem;
use crate::tolerance::weighted_rms;

/// What the stages of one step share: the start, the step, the factorised I − hγJ, the
/// error weights and the Newton settings.
pub(super) struct StepContext<'c, Sys, const S: usize> {
    pub(super) system: &'c Sys,
    pub(super) t0: f64,
    pub(super) y0: SVector<f64, S>,
    pub(super) h: f64,
    pub(super) lu: &'c Lu<S>,
    /// Whether the Jacobian was evaluated at y₀ (rather than kept from an earlier step).
    pub(super) fresh_jacobian: bool,
    pub(super) weights: SVector<f64, S>,
    pub(super) newton: &'c DirkNewton,
    /// γ, the diagonal of the implicit stages.
    pub(super) gamma: f64,
}

/// The [`weighted_rms`] of v against the weights w.
pub(super) fn weighted_norm<const S: usize>(v: &SVector<f64, S>, weights: &SVector<f64, S>) -> f64 {
    weighted_rms(v, |i| weights[i])
}

/// A solved stage: its increment, its Newton iterations and slowest contraction rate.
pub(super) struct Stage<const S: usize> {
    pub(super) increment: SVector<f64, S>,
    pub(super) iterations: usize,
    pub(super) slowest_rate: f64,
}

impl<Sys, const S: usize> StepContext<'_, Sys, S> {
    /// Solves Z = G + hγ f(t₀ + ch, y₀ + Z) from `start` by simplified Newton (`sdirk4.f`'s
    /// loop 40), updating the stage's contraction factor.
    pub(super) fn solve_stage<const N: usize>(
        &self,
        statistics: &mut Statistics,
        c: f64,
        explicit: &SVector<f64, S>,
        start: SVector<f64, S>,
        contraction: &mut f64,
    ) -> Result<Stage<S>, StageFailure<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (h, newton) = (self.h, self.newton);
        let iterations = newton.max_iterations;
        let mut z = start;
        // `sdirk4.f` starts from the stage's last contraction factor, so that a fast
        // iteration may stop after one update. With a Jacobian kept from an earlier step
        // that factor is not known to hold: it is measured again (≥ 2 iterations unless
        // the first update is already within the tolerance). Without this the error of a
        // single update with a stale Jacobian set a floor (Kepler orbit: 1.2e-9 at a
        // tolerance of 1e-11, against 1.7e-10 with a fresh Jacobian).
        let mut factor = if self.fresh_jacobian {
            powf(contraction.max(f64::EPSILON), 0.8)
        } else {
            1.0
        };
        let (mut previous, mut slowest_rate) = (0.0, 0.0f64);
        let diverged = |iterations| StageFailure::Newton {
            iterations,
            shrink: 0.5,
        };
        for iteration in 1..=iterations {
            let time = self.t0 + c * h;
            let rate = state_rate(self.system, statistics, time, &(self.y0 + z))
                .map_err(StageFailure::Rate)?;
            let delta = self.lu.solve(explicit - z + rate * (h * self.gamma));
            statistics.newton_iterations += 1;
            let norm = weighted_norm(&delta, &self.weights);
            if !norm.is_finite() {
                return Err(diverged(iteration));
            }
            if iteration >= 2 {
                let theta = norm / previous;
                if theta >= 0.99 {
                    return Err(diverged(iteration));
                }
                slowest_rate = slowest_rate.max(theta);
                factor = theta / (1.0 - theta);
                if iteration < iterations {
                    // Will the remaining iterations reach the tolerance at this rate?
                    let exponent = (iterations - 1 - iteration) as i32;
                    let predicted = factor * norm * theta.powi(exponent);
                    let ratio = (predicted / newton.tolerance_fraction).clamp(1e-4, 16.0);
                    if ratio >= 1.0 {
                        let remaining = (iterations - iteration) as f64;
                        let shrink = 0.8 * powf(ratio, -1.0 / remaining);
                        return Err(StageFailure::Newton {
                            iterations: iteration,
                            shrink,
                        });
                    }
                }
            }
            previous = norm;
            z += delta;
            let rounding = self
                .y0
                .zip_map(&z, |y, z| 16.0 * f64::EPSILON * (y + z).abs());
            if factor * norm <= newton.tolerance_fraction || weighted_norm(&delta, &rounding) <= 1.0
            {
                *contraction = factor;
                return Ok(Stage {
                    increment: z,
                    iterations: iteration,
                    slowest_rate,
                });
            }
        }
        Err(diverged(iterations))
    }
}
