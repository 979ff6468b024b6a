//! What a run returns: the accepted points, the extras the caller asked to record, the
//! events found, why it stopped and what it cost.

use alloc::vec::Vec;

use nalgebra::SVector;

use crate::error::StepError;
use crate::events::EventHit;
use crate::stepper::Statistics;
use crate::system::VariableMassSystem;

/// Which extras a run records at every point (all off by default: a run then stores only
/// times and states).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Record {
    /// The Hamiltonian H(q, p, t) (eqs. 9–10).
    pub hamiltonian: bool,
    /// The generalized forces Q*, R1, R2 and the mass-flux term.
    pub forces: bool,
    /// The energy-budget power dH/dt (docs/mechanics.md#energy-budget).
    pub power: bool,
    /// The energy-budget residual ∫ power dt − (H − H₀), an error estimate needing no
    /// reference solution.
    pub energy_residual: bool,
}

/// The generalized forces at one point, in the paper's names.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralizedForces<const N: usize> {
    /// Q*, the active non-potential force.
    pub active: SVector<f64, N>,
    /// R1, the reactive thrust.
    pub reactive_thrust: SVector<f64, N>,
    /// R2, the impact force.
    pub impact: SVector<f64, N>,
    /// Σᵢ ṁᵢ ∂*p/∂mᵢ, the term that turns d*p/dt into the true ṗ.
    pub mass_flux: SVector<f64, N>,
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The end time was reached.
    ReachedEnd,
    /// A stopping event was found; `index` is its position in the run's event list.
    EventFound {
        /// Index of the event in the run's list.
        index: usize,
    },
    /// The run failed (the solution is the part of a [`RunError`](crate::RunError)).
    Failed,
}

/// The result of a run. `times` and `states` hold every accepted step (and the event point
/// a run stopped at); each recorded extra has one entry per point, and is empty when not
/// asked for.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution<const N: usize, const S: usize> {
    /// Times of the points.
    pub times: Vec<f64>,
    /// States `[q, p, m_s]` at the points.
    pub states: Vec<SVector<f64, S>>,
    /// H at the points, if recorded.
    pub hamiltonian: Vec<f64>,
    /// Q*, R1, R2 and the mass-flux term at the points, if recorded.
    pub forces: Vec<GeneralizedForces<N>>,
    /// The power dH/dt at the points, if recorded.
    pub power: Vec<f64>,
    /// ∫ power dt − (H − H₀) at the points, if recorded.
    pub energy_residual: Vec<f64>,
    /// The events found, in time order.
    pub events: Vec<EventHit<S>>,
    /// Why the run ended.
    pub stop: StopReason,
    /// The stepper's work counters at the end of the run.
    pub statistics: Statistics,
    /// The closest the run's points came to a singular attitude of the system's Euler
    /// sequences (gimbal lock), rad ([`VariableMassSystem::singular_attitude_distance`]);
    /// `None` without spatial rigid bodies. Within [`GIMBAL_WARNING`] of it the angles'
    /// rates, and the integration error with them, grow as 1/distance: the command line
    /// tool's summary warns.
    pub closest_singular_attitude: Option<f64>,
}

/// How close to gimbal lock (rad) a run comes before the command line tool's summary warns
/// ([`Solution::closest_singular_attitude`]): at 1e-2 rad the error of a run through it
/// measured 70 times that of the same motion far from it (issue 34).
pub const GIMBAL_WARNING: f64 = 1e-2;

impl<const N: usize, const S: usize> Solution<N, S> {
    pub(crate) fn new() -> Self {
        Self {
            times: Vec::new(),
            states: Vec::new(),
            hamiltonian: Vec::new(),
            forces: Vec::new(),
            power: Vec::new(),
            energy_residual: Vec::new(),
            events: Vec::new(),
            stop: StopReason::ReachedEnd,
            statistics: Statistics::default(),
            closest_singular_attitude: None,
        }
    }

    /// Takes `distance` from a singular attitude into the closest approach.
    pub(crate) fn note_attitude(&mut self, distance: f64) {
        let closest = self
            .closest_singular_attitude
            .map_or(distance, |c| c.min(distance));
        self.closest_singular_attitude = Some(closest);
    }

    /// The last time and state.
    pub fn last(&self) -> Option<(f64, &SVector<f64, S>)> {
        Some((*self.times.last()?, self.states.last()?))
    }

    /// Appends a point with the requested extras. `hamiltonian`, `power` and
    /// `energy_residual` are passed in when the energy budget already computed them.
    pub(crate) fn push<Sys>(
        &mut self,
        system: &Sys,
        record: &Record,
        time: f64,
        state: SVector<f64, S>,
        energy: Option<EnergyPoint>,
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let to_step_error = |error| StepError::from_system(system, error, time, &state);
        if let Some(distance) = system.singular_attitude_distance(time, &state) {
            self.note_attitude(distance);
        }
        if record.hamiltonian {
            let hamiltonian = match energy {
                Some(point) => point.hamiltonian,
                None => system.hamiltonian(time, &state).map_err(to_step_error)?,
            };
            self.hamiltonian.push(hamiltonian);
        }
        if record.power {
            let power = match energy {
                Some(point) => point.power,
                None => system.power(time, &state).map_err(to_step_error)?,
            };
            self.power.push(power);
        }
        if record.energy_residual {
            self.energy_residual
                .push(energy.map_or(f64::NAN, |point| point.residual));
        }
        if record.forces {
            let velocity_state = system.velocity_state(time, &state).map_err(to_step_error)?;
            self.forces.push(GeneralizedForces {
                active: system.active_force(time, &velocity_state),
                reactive_thrust: system.reactive_thrust(time, &velocity_state),
                impact: system.impact_force(time, &velocity_state),
                mass_flux: system.mass_flux_force(time, &velocity_state),
            });
        }
        self.times.push(time);
        self.states.push(state);
        Ok(())
    }
}

/// The energy budget at one point: H, the power and the residual ∫ power dt − (H − H₀).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EnergyPoint {
    pub(crate) hamiltonian: f64,
    pub(crate) power: f64,
    pub(crate) residual: f64,
}
