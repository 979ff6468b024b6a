//! One end of a step as a run sees it: the time and state, and the state rate and the
//! energy terms when the run needs them.

use nalgebra::SVector;

use crate::error::StepError;
use crate::stepper::Checked;
use crate::system::VariableMassSystem;

/// What a run computes at every point besides the time and state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Needs {
    /// The state rate, for Hermite interpolation (steppers without dense output).
    pub(crate) rate: bool,
    /// H and the power, for the energy budget.
    pub(crate) energy: bool,
}

/// One end of a step, with what the run knows there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Point<const S: usize> {
    /// The time.
    pub(crate) time: f64,
    /// The state `[q, p, m_s]`.
    pub(crate) state: SVector<f64, S>,
    /// The state rate, when Hermite interpolation needs it.
    pub(crate) rate: Option<SVector<f64, S>>,
    /// H and the power, when the energy budget needs them.
    pub(crate) energy: Option<(f64, f64)>,
}

impl<const S: usize> Point<S> {
    /// The point `(time, state)` of `system`, with the state rate and H and the power as
    /// `needs` says.
    pub(crate) fn at<Sys, const N: usize>(
        system: &Sys,
        time: f64,
        state: SVector<f64, S>,
        needs: Needs,
    ) -> Result<Self, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let to_step_error = |error| StepError::from_system(system, error, time, &state);
        system.check_flows(time, &state)?;
        let rate = if needs.rate {
            Some(system.state_rate(time, &state).map_err(to_step_error)?)
        } else {
            None
        };
        let energy = if needs.energy {
            let hamiltonian = system.hamiltonian(time, &state).map_err(to_step_error)?;
            let power = system.power(time, &state).map_err(to_step_error)?;
            Some((hamiltonian, power))
        } else {
            None
        };
        Ok(Self {
            time,
            state,
            rate,
            energy,
        })
    }
}
