//! Why a step or a run failed: typed errors that carry the time and the state where it
//! happened, so a failure is never a silent NaN.

use nalgebra::SVector;

/// A failure of a stepper or of a run: what went wrong ([`StepErrorKind`]) and the time and
/// the state `[q, p, m_s]` where it was detected. `S` is the state dimension.
///
/// For [`StepErrorKind::InvalidConfiguration`], detected before any step is taken, `time` and
/// `state` are those of the stepper when the configuration was checked: the initial value a
/// constructor was given (even if that initial time is the unusable value), the stepper's
/// current time and state for [`Stepper::set_stop_time`](crate::Stepper::set_stop_time) and
/// for a run's configuration and events.
///
/// Displayed as `at t = <time>: <what happened>`.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("at t = {time}: {kind}")]
pub struct StepError<const S: usize> {
    /// Time of the failure (for a failed step: the start of the step, or the time of the
    /// offending state when it was produced).
    pub time: f64,
    /// The state at `time` (the offending state when it is the state itself that is wrong).
    pub state: SVector<f64, S>,
    /// What went wrong, with the data particular to that cause.
    pub kind: StepErrorKind,
}

/// What went wrong in a [`StepError`].
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StepErrorKind {
    /// A component of the state (or of a trial state) is NaN or infinite, typically because a
    /// fixed step is far past the stability limit.
    #[error("the state became non-finite")]
    NonFiniteState,
    /// The end of the next step, t + h, is not a finite time (it overflows f64). The error's
    /// time and state are those at the start of the step, which are finite.
    #[error("the time t + {step:e} is not finite")]
    NonFiniteTime {
        /// The step that would have been taken.
        step: f64,
    },
    /// An adaptive stepper had to shrink its step below what the time resolution allows.
    /// The error's time and state are those at the start of the failed step.
    #[error("the step size {step:e} underflowed")]
    StepSizeUnderflow {
        /// The step size that was too small.
        step: f64,
    },
    /// Newton's method of an implicit stepper did not converge (or its iteration matrix was
    /// singular). The error's time and state are those at the start of the failed step.
    #[error("Newton's method did not converge ({iterations} iterations)")]
    NewtonDivergence {
        /// Iterations done before giving up.
        iterations: usize,
    },
    /// A run needed more steps than its configuration allows. The error's time and state are
    /// those reached.
    #[error("more than {max_steps} steps were needed")]
    TooManySteps {
        /// The configured limit.
        max_steps: usize,
    },
    /// A run went round `steps` times in a row without moving t by more than a few
    /// roundings (a switch or an event it cannot get past, a stepper that cannot leave a
    /// point): it ends here instead of looping to [`TooManySteps`](Self::TooManySteps) or
    /// for ever. The error's time and state are those of the last point the run kept.
    #[error("the run stalled: {steps} passes without t moving more than a few roundings")]
    Stalled {
        /// The passes counted.
        steps: usize,
    },
    /// The energy budget stopped closing: |∫ power dt − (H − H₀)| exceeded the run's
    /// [`RunConfig::energy_tolerance`](crate::RunConfig) times the largest |H| or |p·q̇| so far. The
    /// typical cause is a fixed step past the stability limit, whose finite but meaningless
    /// states would otherwise go on until they overflow.
    #[error("the energy budget failed: residual {residual:e} against H scale {scale:e}")]
    EnergyBudgetExceeded {
        /// ∫ power dt − (H − H₀) there.
        residual: f64,
        /// The largest |H| or |p·q̇| seen so far.
        scale: f64,
    },
    /// A configuration value is unusable (non-positive step, non-finite time, an index out
    /// of range, …). Detected before any step is taken; see [`StepError`] for the time and
    /// state it carries.
    #[error("invalid configuration: {reason}")]
    InvalidConfiguration {
        /// What is wrong.
        reason: &'static str,
    },
    /// A flow's rate came out negative (Q1 of an outflow or Q2 of an inflow below 0): the
    /// statement declares mass leaving (or arriving) and the rate says the opposite, so the
    /// reactive forces (eqs. 15–16) would act with the wrong sign. A run checks
    /// [`VariableMassSystem::flow_rate`](crate::VariableMassSystem::flow_rate) at the start
    /// and after each step (through [`StepError::check_flow_rates`]), at the error's time
    /// and state; the flow's text is
    /// [`VariableMassSystem::flow_name`](crate::VariableMassSystem::flow_name).
    #[error("the rate of flow {index} is negative ({rate})")]
    NegativeFlowRate {
        /// The flow's index, in the order the model declares its flows.
        index: usize,
        /// Its rate there.
        rate: f64,
    },
    /// The run went on longer than the wall-clock limit its caller set. The error's time
    /// and state are those reached.
    #[error("the wall-clock limit of {seconds} s was reached")]
    WallClockExceeded {
        /// The limit, in seconds.
        seconds: f64,
    },
    /// A switching function
    /// ([`VariableMassSystem::switching_functions`](crate::VariableMassSystem::switching_functions))
    /// changed sign `crossings` times within a vanishing interval (Coulomb friction at rest,
    /// a Zeno bounce): the motion sticks or chatters on the switch, which the equations as
    /// written cannot continue. The error's time and state are those of the last crossing;
    /// the switch's text is
    /// [`VariableMassSystem::switch_name`](crate::VariableMassSystem::switch_name).
    #[error("switching function {switch} chatters: {crossings} sign changes within {within:e}")]
    Chattering {
        /// Index of the switching function.
        switch: usize,
        /// Sign changes counted.
        crossings: usize,
        /// The time they fell within.
        within: f64,
    },
    /// The system could not be evaluated at the state: a singular mass matrix, a mass ≤ 0,
    /// a table outside its data, a sampled input that is not finite
    /// ([`StepError::from_system`] attaches the time and state).
    #[error(transparent)]
    System(#[from] SystemError),
}

impl<const S: usize> StepError<S> {
    /// A failure of kind `kind` at `(time, state)`.
    pub const fn new(time: f64, state: SVector<f64, S>, kind: StepErrorKind) -> Self {
        Self { time, state, kind }
    }

    /// An [`StepErrorKind::InvalidConfiguration`] found while the stepper is at
    /// `(time, state)`.
    pub const fn invalid_configuration(
        time: f64,
        state: SVector<f64, S>,
        reason: &'static str,
    ) -> Self {
        Self::new(time, state, StepErrorKind::InvalidConfiguration { reason })
    }
}

impl<const S: usize> StepError<S> {
    /// Checks the flow rates `rates` (in the model's flow order) at `(time, state)`: the
    /// first negative one is a [`StepErrorKind::NegativeFlowRate`]. A rate of exactly 0 (a
    /// burnt-out motor) is fine; a NaN is left to the state checks, which see it too.
    pub fn check_flow_rates(
        time: f64,
        state: &SVector<f64, S>,
        rates: impl IntoIterator<Item = f64>,
    ) -> Result<(), Self> {
        match rates.into_iter().enumerate().find(|(_, rate)| *rate < 0.0) {
            Some((index, rate)) => Err(Self::new(
                time,
                *state,
                StepErrorKind::NegativeFlowRate { index, rate },
            )),
            None => Ok(()),
        }
    }
}

/// An unusable configuration value found before a stepper exists (a tolerance, a step size,
/// a Newton setting). It becomes a [`StepError`] with [`ConfigError::at`] once the time and
/// state it applies to are known.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("invalid configuration: {reason}")]
pub struct ConfigError {
    /// What is wrong.
    pub reason: &'static str,
}

impl ConfigError {
    /// The [`StepErrorKind::InvalidConfiguration`] of a stepper at `(time, state)`.
    pub fn at<const S: usize>(self, time: f64, state: &SVector<f64, S>) -> StepError<S> {
        StepError::invalid_configuration(time, *state, self.reason)
    }
}

/// Why a system could not be evaluated at a state: what the fallible methods of
/// [`VariableMassSystem`](crate::VariableMassSystem) return, and, with the time and state attached, [`StepErrorKind::System`].
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SystemError {
    /// The mass matrix ∂²L/∂q̇² is singular (or not positive definite) here, so q̇ cannot be
    /// recovered from p.
    #[error("the mass matrix is singular")]
    SingularMassMatrix,
    /// A mass (or inertia) is zero or negative, e.g. a rocket out of propellant; its index
    /// is into [`VariableMassSystem::MASSES`](crate::VariableMassSystem::MASSES).
    #[error("mass {index} is not positive")]
    NonPositiveMass {
        /// Index into [`VariableMassSystem::MASSES`](crate::VariableMassSystem::MASSES).
        index: usize,
    },
    /// A table (`outside error`, the default) was asked for a value outside its data, or
    /// at a NaN argument (docs/tables.md#outside-the-data): a thrust curve past burnout
    /// without `outside zero`, an atmosphere above its last altitude.
    #[error("table `{table}` has no value at {argument} (outside its data)")]
    TableOutside {
        /// The table's name (`F`, or `F'` for its derivative).
        table: &'static str,
        /// The argument asked for.
        argument: f64,
    },
    /// A coordinate held on its support (`crate::support`) couples here with another in
    /// the kinetic energy (M_kj ≠ 0, or p_k ≠ 0 at rest), which it did not where the hold
    /// began: holding it by clamping p_k would no longer be the constrained motion.
    #[error("the coordinate {index} held on its support couples with another here")]
    SupportCoupled {
        /// The held coordinate's index.
        index: usize,
    },
    /// A sampled input's value at a sample is not a finite number: its method (or its
    /// `--input` law) gave NaN or ±∞ there (docs/inputs.md#sampled-inputs). In a
    /// [`StepError`], its time is the sample's, its state the one sampled at.
    #[error("the sampled input `{input}` is not finite at its sample ({value})")]
    SampledInputNotFinite {
        /// The input's name.
        input: &'static str,
        /// The value it gave.
        value: f64,
    },
    /// Sensitivities to a parameter were asked of a system that names its parameters but
    /// gives no `parameter_jacobian` (generated code gives both with `emit = [...,
    /// "sensitivities"]`).
    #[error("the system gives no parameter Jacobian for its sensitivities")]
    NoParameterJacobian,
    /// Forward sensitivities crossed a switch whose gradient the system does not give
    /// ([`VariableMassSystem::switch_gradient`](crate::VariableMassSystem::switch_gradient)).
    #[error("the system gives no gradient of switch {switch} for its sensitivities")]
    NoSwitchGradient {
        /// The switch's index.
        switch: usize,
    },
    /// Forward sensitivities met a switch the run could not locate (a step was left standing
    /// across it, `run/switching.rs`): the columns' jump there is unknown.
    #[error("switch {switch} was crossed where the run could not locate it: the sensitivities' jump there is unknown")]
    UnlocatedSwitch {
        /// The switch's index.
        switch: usize,
    },
    /// Forward sensitivities met a switch crossed tangentially (dg/dt = 0 along the motion
    /// there): its time has no derivative with respect to the parameters.
    #[error("switch {switch} is crossed tangentially: its time has no derivative")]
    TangentSwitch {
        /// The switch's index.
        switch: usize,
    },
    /// Forward sensitivities met two switches crossed in one step over rounding whose times
    /// move differently with a column: which comes first depends on the column's sign, and
    /// the state has no derivative there.
    #[error("switches {first} and {second} cross together and move apart with a column")]
    SwitchesTogether {
        /// The first switch's index.
        first: usize,
        /// The second's.
        second: usize,
    },
    /// A body with sensitivities slides along a rail whose direction b couples with other
    /// coordinates in the kinetic energy (M b not along b): the rail's momentum rate is then
    /// not a fixed projection of the free one, and the columns, projected as the rates are
    /// (docs/sensitivities.md#on-a-pad-and-a-rail), would be wrong.
    #[error(
        "a rail guides a body with sensitivities whose direction couples with other coordinates"
    )]
    RailCoupled,
    /// A sensitivity column moves the body across the rail it slides on (its velocity
    /// ∂q̇/∂w leaves the rail's direction): a momentum at rest or a coupling that changes with
    /// the column (a turning launch frame, a coupling 0 at the nominal values only), which the
    /// columns, projected on the rail (docs/sensitivities.md#on-a-pad-and-a-rail), would miss.
    #[error("sensitivity column {column} moves the body across its rail")]
    RailColumnAcross {
        /// The column's index.
        column: usize,
    },
    /// A switch whose state rate jumps was crossed while held on a support or on a rail, with
    /// sensitivities: its time's derivative would need the constrained accelerations, which
    /// the columns' jump does not take.
    #[error("switch {switch} jumps the state rate while the body is held or on its rail, with sensitivities")]
    SupportedSwitch {
        /// The switch's index.
        switch: usize,
    },
    /// Forward sensitivities met a phase that ends where its end condition's state entry
    /// stands still (its rate 0 there): the change's time has no derivative.
    #[error(
        "a phase ends where state entry {entry} stands still: the change's time has no derivative"
    )]
    TangentPhaseEnd {
        /// The state entry of the end condition.
        entry: usize,
    },
    /// Forward sensitivities met a phase that ends where its end condition's velocity
    /// stands still (the coordinate's acceleration 0 there): the change's time has no
    /// derivative.
    #[error(
        "a phase ends where the velocity of coordinate {coordinate} stands still (its \
         acceleration 0): the change's time has no derivative"
    )]
    TangentVelocityEnd {
        /// The coordinate of the end condition.
        coordinate: usize,
    },
    /// Forward sensitivities carried into a phase whose system has other columns than the
    /// phase before (every phase needs the same list, a parameter another phase holds given
    /// as `Column::Elsewhere`).
    #[error("a phase with {after} sensitivity columns follows one with {before}")]
    PhaseColumns {
        /// The columns before the change.
        before: usize,
        /// The columns after it.
        after: usize,
    },
    /// Forward sensitivities carried into a phase whose column `column` is another initial
    /// entry's (or a parameter's where the phase before had an initial entry's): the
    /// derivative would change its meaning at the change.
    #[error("sensitivity column {column} is the derivative with respect to another initial entry (or a parameter) after the phase change than before it")]
    PhaseColumnDiffers {
        /// The column.
        column: usize,
    },
}

/// Whether every component of a vector is finite.
pub(crate) fn is_finite<const D: usize>(vector: &SVector<f64, D>) -> bool {
    vector.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first negative rate is named with its index, value, time and state; zero and
    /// positive rates pass.
    #[test]
    fn a_negative_flow_rate_is_a_typed_error() {
        let state = SVector::<f64, 2>::new(1.0, 2.0);
        assert_eq!(StepError::check_flow_rates(0.5, &state, [0.0, 3.0]), Ok(()));
        let error = StepError::check_flow_rates(0.5, &state, [1.0, -5.0, -7.0]).unwrap_err();
        assert_eq!(
            error,
            StepError::new(
                0.5,
                state,
                StepErrorKind::NegativeFlowRate {
                    index: 1,
                    rate: -5.0
                }
            )
        );
        assert_eq!(
            error.to_string(),
            "at t = 0.5: the rate of flow 1 is negative (-5)"
        );
    }
}
