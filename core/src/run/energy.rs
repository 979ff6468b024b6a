//! The energy budget of a run: the residual ∫ power dt − (H − H₀), which is zero along the
//! exact motion and so measures the integration error without a reference solution; and the
//! guard that fails a run once that residual is out of proportion.
//!
//! The power is integrated with Simpson's rule on every step, using the interpolated
//! midpoint, so the quadrature error (O(h⁵) per step with a fourth-order interpolant) stays
//! below the state's integration error and the residual measures the latter.

use nalgebra::SVector;

use super::point::Point;
use crate::error::{StepError, StepErrorKind};
use crate::solution::EnergyPoint;
use crate::system::VariableMassSystem;

/// The running energy budget: ∫ power dt so far, H₀, the largest |H| or |p·q̇| seen and the
/// guard's tolerance. Its points must carry their energy terms ([`Point::energy`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EnergyBudget {
    integral: f64,
    initial_hamiltonian: f64,
    scale: f64,
    guard: Option<f64>,
}

impl EnergyBudget {
    /// A budget starting at `start`, failing once the residual exceeds `guard` times the
    /// scale, if a guard is given.
    pub(crate) fn start<const S: usize>(start: &Point<S>, guard: Option<f64>) -> Self {
        let initial_hamiltonian = start.energy.map_or(0.0, |(hamiltonian, _)| hamiltonian);
        Self {
            integral: 0.0,
            initial_hamiltonian,
            scale: initial_hamiltonian.abs(),
            guard,
        }
    }

    /// H, the power and the residual at `point`, given the integral up to it.
    pub(crate) fn at<const S: usize>(&self, point: &Point<S>) -> Option<EnergyPoint> {
        point.energy.map(|(hamiltonian, power)| EnergyPoint {
            hamiltonian,
            power,
            residual: self.integral - (hamiltonian - self.initial_hamiltonian),
        })
    }

    /// Adds ∫ power dt over the step from `start` to `end` by Simpson's rule, the midpoint
    /// state from `interpolate`.
    pub(crate) fn add_step<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        start: &Point<S>,
        end: &Point<S>,
        interpolate: &impl Fn(f64) -> SVector<f64, S>,
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let middle_time = 0.5 * (start.time + end.time);
        let middle_state = interpolate(middle_time);
        let middle_power = system
            .power(middle_time, &middle_state)
            .map_err(|error| StepError::from_system(system, error, middle_time, &middle_state))?;
        let width = end.time - start.time;
        self.integral += width / 6.0 * (start.power() + 4.0 * middle_power + end.power());
        Ok(())
    }

    /// With a guard: grows the scale by |H| and |p·q̇| at `point` and fails with
    /// [`StepErrorKind::EnergyBudgetExceeded`] if |residual| exceeds the guard times the
    /// scale. |H| alone can vanish while T and V are large (free fall from rest at y = 0),
    /// hence |p·q̇| too: twice the kinetic energy for a quadratic T.
    pub(crate) fn check<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        point: &Point<S>,
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (Some(tolerance), Some(energy)) = (self.guard, self.at(point)) else {
            return Ok(());
        };
        let (time, state) = (point.time, point.state);
        let velocities = system
            .velocities(time, &state)
            .map_err(|error| StepError::from_system(system, error, time, &state))?;
        let momentum_velocity = state.fixed_rows::<N>(N).dot(&velocities);
        self.scale = self
            .scale
            .max(energy.hamiltonian.abs())
            .max(momentum_velocity.abs());
        if energy.residual.abs() > tolerance * self.scale {
            let kind = StepErrorKind::EnergyBudgetExceeded {
                residual: energy.residual,
                scale: self.scale,
            };
            return Err(StepError::new(time, state, kind));
        }
        Ok(())
    }
}
