//! Why a step or a run failed: typed errors that carry the time and the state where it
//! happened, so a failure is never a silent NaN.

use nalgebra::SVector;

use crate::system::{SystemError, VariableMassSystem};

/// A failure of a stepper or of a run, with the time and the state `[q, p, m_s]` where it was
/// detected. `S` is the state dimension.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StepError<const S: usize> {
    /// A component of the state (or of a trial state) is NaN or infinite, typically because a
    /// fixed step is far past the stability limit.
    #[error("the state became non-finite at t = {time}")]
    NonFiniteState {
        /// Time of the non-finite state.
        time: f64,
        /// The offending state.
        state: SVector<f64, S>,
    },
    /// A mass or inertia reached zero or became negative, e.g. a rocket out of propellant.
    #[error("mass {index} is not positive at t = {time}")]
    NonPositiveMass {
        /// Time of the state.
        time: f64,
        /// The state whose mass is not positive.
        state: SVector<f64, S>,
        /// Index into [`VariableMassSystem::MASSES`].
        index: usize,
    },
    /// The mass matrix ∂²L/∂q̇² is singular here, so q̇ cannot be recovered from p.
    #[error("the mass matrix is singular at t = {time}")]
    SingularMassMatrix {
        /// Time of the state.
        time: f64,
        /// The state.
        state: SVector<f64, S>,
    },
    /// An adaptive stepper had to shrink its step below what the time resolution allows.
    #[error("the step size {step:e} underflowed at t = {time}")]
    StepSizeUnderflow {
        /// Time at the start of the failed step.
        time: f64,
        /// State at the start of the failed step.
        state: SVector<f64, S>,
        /// The step size that was too small.
        step: f64,
    },
    /// Newton's method of an implicit stepper did not converge (or its iteration matrix was
    /// singular).
    #[error("Newton's method did not converge at t = {time} ({iterations} iterations)")]
    NewtonDivergence {
        /// Time at the start of the failed step.
        time: f64,
        /// State at the start of the failed step.
        state: SVector<f64, S>,
        /// Iterations done before giving up.
        iterations: usize,
    },
    /// A run needed more steps than its configuration allows.
    #[error("more than {max_steps} steps were needed; stopped at t = {time}")]
    TooManySteps {
        /// Time reached.
        time: f64,
        /// State reached.
        state: SVector<f64, S>,
        /// The configured limit.
        max_steps: usize,
    },
    /// The energy budget stopped closing: |∫ power dt − (H − H₀)| exceeded the run's
    /// [`RunConfig::energy_tolerance`](crate::RunConfig) times the largest |H| or |p·q̇| so far. The
    /// typical cause is a fixed step past the stability limit, whose finite but meaningless
    /// states would otherwise go on until they overflow.
    #[error(
        "the energy budget failed at t = {time}: residual {residual:e} against H scale {scale:e}"
    )]
    EnergyBudgetExceeded {
        /// Time of the state.
        time: f64,
        /// The state.
        state: SVector<f64, S>,
        /// ∫ power dt − (H − H₀) there.
        residual: f64,
        /// The largest |H| or |p·q̇| seen so far.
        scale: f64,
    },
    /// A configuration value is unusable (non-positive step, non-finite time, an index out
    /// of range, …). Detected before any step is taken.
    #[error("invalid configuration: {reason}")]
    InvalidConfiguration {
        /// What is wrong.
        reason: &'static str,
    },
}

impl<const S: usize> StepError<S> {
    /// The time at which the failure was detected, if it happened during stepping.
    pub fn time(&self) -> Option<f64> {
        match self {
            Self::NonFiniteState { time, .. }
            | Self::NonPositiveMass { time, .. }
            | Self::SingularMassMatrix { time, .. }
            | Self::StepSizeUnderflow { time, .. }
            | Self::NewtonDivergence { time, .. }
            | Self::TooManySteps { time, .. }
            | Self::EnergyBudgetExceeded { time, .. } => Some(*time),
            Self::InvalidConfiguration { .. } => None,
        }
    }

    /// The state at which the failure was detected, if it happened during stepping.
    pub fn state(&self) -> Option<&SVector<f64, S>> {
        match self {
            Self::NonFiniteState { state, .. }
            | Self::NonPositiveMass { state, .. }
            | Self::SingularMassMatrix { state, .. }
            | Self::StepSizeUnderflow { state, .. }
            | Self::NewtonDivergence { state, .. }
            | Self::TooManySteps { state, .. }
            | Self::EnergyBudgetExceeded { state, .. } => Some(state),
            Self::InvalidConfiguration { .. } => None,
        }
    }

    /// Attaches the time and state to a [`SystemError`]. A singular mass matrix is reported
    /// as the non-positive mass that caused it when there is one, and a non-finite state as
    /// such, because those are the causes a user can act on.
    pub fn from_system<Sys, const N: usize>(
        system: &Sys,
        error: SystemError,
        time: f64,
        state: &SVector<f64, S>,
    ) -> Self
    where
        Sys: VariableMassSystem<N, S> + ?Sized,
    {
        let state = *state;
        if !is_finite(&state) {
            return Self::NonFiniteState { time, state };
        }
        let error = match error {
            SystemError::SingularMassMatrix => match system.check_masses(time, &state) {
                Err(mass_error) => mass_error,
                Ok(()) => error,
            },
            SystemError::NonPositiveMass { .. } => error,
        };
        match error {
            SystemError::SingularMassMatrix => Self::SingularMassMatrix { time, state },
            SystemError::NonPositiveMass { index } => Self::NonPositiveMass { time, state, index },
        }
    }
}

/// Whether every component of a vector is finite.
pub(crate) fn is_finite<const D: usize>(vector: &SVector<f64, D>) -> bool {
    vector.iter().all(|x| x.is_finite())
}
