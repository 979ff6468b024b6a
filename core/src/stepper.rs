//! What every stepper shares: the [`Stepper`] trait a run drives, the [`Progress`] of a
//! stepper (time, state, last step, statistics) and the checks made after every step.

use nalgebra::SVector;

use crate::error::{is_finite, StepError, StepErrorKind};
use crate::system::VariableMassSystem;

/// What one call of [`Stepper::step`] achieved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepOutcome {
    /// An internal step was taken; the stop time is still ahead.
    Advanced,
    /// The step landed exactly on the stop time set by [`Stepper::set_stop_time`].
    ReachedStopTime,
}

/// Work counters of a stepper. They count the stepper's own work; the extras a run records
/// (H, power, event functions) are not included.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Steps accepted.
    pub accepted_steps: usize,
    /// Step attempts rejected by the error control (or because a trial state was unusable).
    pub rejected_steps: usize,
    /// Evaluations of the state rate (for the variational stepper: evaluations of the
    /// Lagrange-side functions at a midpoint).
    pub rate_evaluations: usize,
    /// Evaluations of the Jacobian ([`VariableMassSystem::jacobian`], or a finite-difference
    /// Jacobian of a discrete residual).
    pub jacobian_evaluations: usize,
    /// Newton iterations of implicit steppers.
    pub newton_iterations: usize,
    /// Whether Hairer's stiffness test of an explicit pair (Dormand–Prince, DOP853) found
    /// the step size limited by stability rather than accuracy: the scene is stiff, and an
    /// implicit stepper would take far fewer steps.
    pub stiffness_detected: bool,
}

impl Statistics {
    /// The work of two runs one after the other (the phases of a scene, the intervals of a
    /// recording): every count added, and the stiffness verdict kept if either found it —
    /// the one rule for adding up work, so no caller drops the flag.
    #[must_use]
    pub fn combine(self, later: Statistics) -> Statistics {
        Statistics {
            accepted_steps: self.accepted_steps + later.accepted_steps,
            rejected_steps: self.rejected_steps + later.rejected_steps,
            rate_evaluations: self.rate_evaluations + later.rate_evaluations,
            jacobian_evaluations: self.jacobian_evaluations + later.jacobian_evaluations,
            newton_iterations: self.newton_iterations + later.newton_iterations,
            stiffness_detected: self.stiffness_detected || later.stiffness_detected,
        }
    }
}

/// Where a stepper is: its time and state, the start of its last step, the stop time it
/// must not pass, and its statistics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress<const S: usize> {
    time: f64,
    state: SVector<f64, S>,
    previous_time: f64,
    previous_state: SVector<f64, S>,
    stop_time: Option<f64>,
    pub(crate) statistics: Statistics,
}

impl<const S: usize> Progress<S> {
    /// Checks the initial value and starts at it.
    pub(crate) fn new<Sys, const N: usize>(
        system: &Sys,
        time: f64,
        state: SVector<f64, S>,
    ) -> Result<Self, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if !time.is_finite() {
            return Err(StepError::invalid_configuration(
                time,
                state,
                "the initial time is not finite",
            ));
        }
        system.check_state(time, &state)?;
        Ok(Self {
            time,
            state,
            previous_time: time,
            previous_state: state,
            stop_time: None,
            statistics: Statistics::default(),
        })
    }

    /// Restarts at a new initial value, keeping the statistics and the stop time.
    pub(crate) fn restart<Sys, const N: usize>(
        &mut self,
        system: &Sys,
        time: f64,
        state: SVector<f64, S>,
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let statistics = self.statistics;
        let stop_time = self.stop_time;
        *self = Self::new(system, time, state)?;
        self.statistics = statistics;
        self.stop_time = stop_time.filter(|&stop| stop >= time);
        Ok(())
    }

    /// The current time.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The current state `[q, p, m_s]`.
    pub fn state(&self) -> &SVector<f64, S> {
        &self.state
    }

    /// The time at the start of the last accepted step (the initial time before any step).
    pub fn previous_time(&self) -> f64 {
        self.previous_time
    }

    /// The state at the start of the last accepted step.
    pub fn previous_state(&self) -> &SVector<f64, S> {
        &self.previous_state
    }

    /// The time the stepper will land on exactly and not pass, if one is set.
    pub fn stop_time(&self) -> Option<f64> {
        self.stop_time
    }

    /// The work counters.
    pub fn statistics(&self) -> &Statistics {
        &self.statistics
    }

    /// Sets the stop time; it must be finite and not before the current time.
    pub(crate) fn set_stop_time(&mut self, stop_time: f64) -> Result<(), StepError<S>> {
        if !stop_time.is_finite() || stop_time < self.time {
            return Err(StepError::invalid_configuration(
                self.time,
                self.state,
                "the stop time must be finite and not before the current time",
            ));
        }
        self.stop_time = Some(stop_time);
        Ok(())
    }

    /// The step to take given a nominal one: the nominal step, or what remains to the stop
    /// time when that is (nearly) less. The `bool` says whether the step reaches it. A
    /// remainder within a millionth of a step of the stop time is absorbed into this step
    /// rather than left as a sliver step that only rounding would create.
    ///
    /// The nominal step is compared with the remainder, not t + h with the stop time: within
    /// an ulp or two of the stop, t + h rounds onto it for any h the controller shrinks to,
    /// so a rejected attempt was tried again with the same remainder for ever (review of
    /// session 33: DOP853 at t = 1 − 2⁻⁵², h = 2⁻⁵²). Now a rejection shrinks the step below
    /// the remainder, down to the step-size underflow, a typed error.
    ///
    /// Fails with [`StepErrorKind::NonFiniteTime`] at the current time and state when the end
    /// of the step would not be a finite time (t + h overflows f64).
    pub(crate) fn next_step(&self, nominal: f64) -> Result<(f64, bool), StepError<S>> {
        let (step, reaches) = match self.stop_time {
            Some(stop) if nominal * (1.0 + 1e-6) >= stop - self.time => (stop - self.time, true),
            _ => (nominal, false),
        };
        if (self.time + step).is_finite() {
            Ok((step, reaches))
        } else {
            Err(StepError::new(
                self.time,
                self.state,
                StepErrorKind::NonFiniteTime { step },
            ))
        }
    }

    /// Accepts a new state after checking it. With `reaches_stop` the time is set to the
    /// stop time exactly, so rounding in `time + h` cannot leave a sliver.
    pub(crate) fn accept<Sys, const N: usize>(
        &mut self,
        system: &Sys,
        step: f64,
        reaches_stop: bool,
        state: SVector<f64, S>,
    ) -> Result<StepOutcome, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let time = match (reaches_stop, self.stop_time) {
            (true, Some(stop)) => stop,
            _ => self.time + step,
        };
        system.check_state(time, &state)?;
        self.previous_time = self.time;
        self.previous_state = self.state;
        self.time = time;
        self.state = state;
        self.statistics.accepted_steps += 1;
        Ok(if reaches_stop {
            StepOutcome::ReachedStopTime
        } else {
            StepOutcome::Advanced
        })
    }
}

/// The checks made on the states a stepper produces and a run records, and q̇ with a failure
/// typed: methods of every system (a blanket impl), so that a step writes
/// `system.check_state(t, &y)?`.
pub(crate) trait Checked<const N: usize, const S: usize>: VariableMassSystem<N, S> {
    /// The checks made on every state a stepper produces: finite, every mass positive.
    fn check_state(&self, time: f64, state: &SVector<f64, S>) -> Result<(), StepError<S>> {
        if !is_finite(state) {
            return Err(StepError::new(time, *state, StepErrorKind::NonFiniteState));
        }
        self.check_masses(time, state)
            .map_err(|error| StepError::from_system(self, error, time, state))
    }

    /// The velocity state at `(time, state)`, a failure turned into a typed error.
    fn velocity_state_at(&self, time: f64, state: &SVector<f64, S>) -> StateResult<S> {
        self.velocity_state(time, state)
            .map_err(|error| StepError::from_system(self, error, time, state))
    }

    /// Checks the system's flow rates at `(time, state)` (nothing to do without flows): the
    /// first negative one ends the run as [`StepErrorKind::NegativeFlowRate`] there. A rate
    /// is ≥ 0 by definition; a negative one (`mu = -5` on an inflow, or a rate `mu - k*t`
    /// past `mu/k`) would reverse the reactive forces (eqs. 15–16) without a word. Every
    /// point a run or an observation computes passes here: the start, the end of every
    /// step, an event's and a switch's point.
    fn check_flows(&self, time: f64, state: &SVector<f64, S>) -> Result<(), StepError<S>> {
        let count = self.flow_count();
        if count == 0 {
            return Ok(());
        }
        // Where q̇ cannot be had (a mass run out past a switch the run is about to land on),
        // there is no rate to check: the stepper or the point's own needs report the cause,
        // and a switch's redo must not be preempted by it.
        let Ok(velocity_state) = self.velocity_state(time, state) else {
            return Ok(());
        };
        let rates = (0..count).map(|index| self.flow_rate(index, time, &velocity_state));
        StepError::check_flow_rates(time, state, rates)
    }
}

impl<Sys: VariableMassSystem<N, S>, const N: usize, const S: usize> Checked<N, S> for Sys {}

/// A state (or a rate, or a velocity state) of a system, or why it could not be had.
pub(crate) type StateResult<const S: usize> = Result<SVector<f64, S>, StepError<S>>;

/// The state rate at `(time, state)`, counted, with a failure turned into a typed error.
pub(crate) fn state_rate<Sys, const N: usize, const S: usize>(
    system: &Sys,
    statistics: &mut Statistics,
    time: f64,
    state: &SVector<f64, S>,
) -> Result<SVector<f64, S>, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    statistics.rate_evaluations += 1;
    if !is_finite(state) {
        return Err(StepError::new(time, *state, StepErrorKind::NonFiniteState));
    }
    system
        .state_rate(time, state)
        .map_err(|error| StepError::from_system(system, error, time, state))
}

/// Mutable access to where a stepper is, for the methods [`Stepper`] provides
/// ([`Stepper::set_stop_time`], [`Stepper::restart`]). Opaque outside this crate: only a
/// step or a checked restart moves a stepper.
pub struct ProgressMut<'s, Sys, const S: usize> {
    pub(crate) system: &'s Sys,
    pub(crate) progress: &'s mut Progress<S>,
}

impl<'s, Sys, const S: usize> ProgressMut<'s, Sys, S> {
    /// The system and the progress of a stepper.
    pub(crate) fn new(system: &'s Sys, progress: &'s mut Progress<S>) -> Self {
        Self { system, progress }
    }
}

/// The proof that [`Stepper::forget_history`] is called by [`Stepper::restart`]; only this
/// crate makes one, so a stepper forgets its history only when its progress restarted.
pub struct Restarting(());

/// A monomorphized one-step method for a [`VariableMassSystem`]. Runs
/// ([`crate::run::run`]) drive any stepper through this trait.
///
/// A stepper provides one accessor, [`parts`](Stepper::parts) (with its mutable form
/// [`parts_mut`](Stepper::parts_mut)): the system and its [`Progress`]; the system, the
/// progress, the stop time and the restart are read through it. A stepper that carries
/// something from one step to the next (an FSAL rate, a controller's memory, a Jacobian)
/// drops it in [`forget_history`](Stepper::forget_history).
pub trait Stepper<const N: usize, const S: usize> {
    /// The system being integrated.
    type System: VariableMassSystem<N, S>;

    /// The system being integrated and where the stepper is.
    fn parts(&self) -> (&Self::System, &Progress<S>);

    /// The same, for the provided methods that move the stepper.
    fn parts_mut(&mut self) -> ProgressMut<'_, Self::System, S>;

    /// Drops what the stepper carries from one step to the next, which belongs to the old
    /// initial value; [`restart`](Stepper::restart) calls it after the progress restarted.
    /// Nothing for a stepper that carries nothing.
    fn forget_history(&mut self, _restarting: Restarting) {}

    /// The system being integrated.
    fn system(&self) -> &Self::System {
        self.parts().0
    }

    /// Time, state, last step and statistics.
    fn progress(&self) -> &Progress<S> {
        self.parts().1
    }

    /// Sets a time the stepper will land on exactly and not pass. It must be finite and not
    /// before the current time.
    fn set_stop_time(&mut self, stop_time: f64) -> Result<(), StepError<S>> {
        self.parts_mut().progress.set_stop_time(stop_time)
    }

    /// Restarts from a new initial value (e.g. after an event changed the state), keeping
    /// the statistics and, if still ahead, the stop time.
    fn restart(&mut self, time: f64, state: SVector<f64, S>) -> Result<(), StepError<S>> {
        let ProgressMut { system, progress } = self.parts_mut();
        progress.restart(system, time, state)?;
        self.forget_history(Restarting(()));
        Ok(())
    }

    /// Takes one accepted step. The new state is checked (finite, masses positive) before it
    /// is accepted; on error the stepper stays at its last accepted state.
    fn step(&mut self) -> Result<StepOutcome, StepError<S>>;

    /// The stepper's own continuous extension over the last step, if it has one; `None`
    /// otherwise, and runs then interpolate by cubic Hermite with the state rates at the
    /// ends of the step.
    fn dense_output(&self, _time: f64) -> Option<SVector<f64, S>> {
        None
    }

    /// The current time.
    fn time(&self) -> f64 {
        self.progress().time()
    }

    /// The current state `[q, p, m_s]`.
    fn state(&self) -> &SVector<f64, S> {
        self.progress().state()
    }

    /// The work counters.
    fn statistics(&self) -> &Statistics {
        self.progress().statistics()
    }
}
