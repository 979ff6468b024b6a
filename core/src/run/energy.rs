//! The energy budget of a run: the residual ∫ power dt − (H − H₀), which is zero along the
//! exact motion and so measures the integration error without a reference solution; and the
//! guard that fails a run once that residual is out of proportion.
//!
//! The power is integrated over every step along the stepper's own interpolant (its dense
//! output, or the cubic Hermite for steppers without one: the state the run reports between
//! its points) by adaptive Gauss–Kronrod quadrature ([`quadrature`]). Within a step P is
//! smooth (a run stops at every switch, knot and event), so the 15-point rule is near exact
//! on a step and the bisections an error estimate asks for stay few; the quadrature error
//! then lies below the state's own, and the residual measures the integration error, even
//! over the long steps of DOP853 and Taylor, where Simpson's rule (the former quadrature,
//! O(h⁵) per step) was off by 1e-7..1e-5 of H on a state right to 1e-14.

use nalgebra::SVector;

use super::point::Point;

mod quadrature;
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

    /// Adds ∫ power dt over the step from `start` to `end`, the states within it from
    /// `interpolate` ([`quadrature::integral`]).
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
        let mut failure = None;
        let power = |time: f64| {
            let state = interpolate(time);
            system.power(time, &state).unwrap_or_else(|error| {
                failure.get_or_insert_with(|| StepError::from_system(system, error, time, &state));
                f64::NAN
            })
        };
        let step = quadrature::integral(power, start.time, end.time);
        if let Some(error) = failure {
            return Err(error);
        }
        self.integral += step;
        Ok(())
    }

    /// With a guard: grows the scale by |H| and |p·q̇| at `point` and fails with
    /// [`StepErrorKind::EnergyBudgetExceeded`] if |residual| exceeds the guard times the
    /// scale, or is NaN (the budget is lost, not kept). |H| alone can vanish while T and V are large (free fall from rest at y = 0),
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
        // A NaN residual (a NaN power or H) fails too: `>` is false for it.
        if energy.residual.is_nan() || energy.residual.abs() > tolerance * self.scale {
            let kind = StepErrorKind::EnergyBudgetExceeded {
                residual: energy.residual,
                scale: self.scale,
            };
            return Err(StepError::new(time, state, kind));
        }
        Ok(())
    }
}
