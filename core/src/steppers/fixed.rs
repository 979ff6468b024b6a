//! The fixed-step steppers — explicit Euler, classical RK4, implicit midpoint and the
//! variational integrator — as one stepper, [`Fixed`], over the method that takes a step
//! ([`FixedMethod`]). They hold the same things (the system, where they are, the step) and
//! step the same way (the step, cut to land on the stop time, from (t₀, y₀) to a new state
//! checked before it is accepted); only the formula for the new state differs, and it is
//! all each method's file writes. Nothing is carried from one step to the next.

use nalgebra::SVector;

use super::FixedStep;
use crate::error::{ConfigError, StepError};
use crate::stepper::{state_rate, Progress, ProgressMut, Statistics, StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// A fixed-step method: its settings and the formula of one step.
pub trait FixedMethod<const N: usize, const S: usize>: Sized {
    /// Its settings: the step size and whatever else the method takes.
    type Config;

    /// Checks the settings and returns the step size and the method.
    fn configure(config: Self::Config) -> Result<(f64, Self), ConfigError>;

    /// The new state of `step`, its work counted in `step.statistics`; the stepper checks
    /// it (finite, masses positive) before accepting it.
    fn advance<Sys: VariableMassSystem<N, S>>(&self, step: Step<'_, Sys, S>) -> NewState<S>;

    /// Whether the method can integrate `system` at all; every system by default.
    fn accepts<Sys: VariableMassSystem<N, S>>(_system: &Sys) -> Result<(), ConfigError> {
        Ok(())
    }
}

/// The new state a method computes, or why it could not.
pub type NewState<const S: usize> = Result<SVector<f64, S>, StepError<S>>;

/// One step of size `h` from `(t0, y0)` of `system`, and where its work is counted.
pub struct Step<'s, Sys, const S: usize> {
    /// The system stepped.
    pub system: &'s Sys,
    /// Where the rate and Jacobian evaluations and Newton iterations are counted.
    pub statistics: &'s mut Statistics,
    /// The time the step starts at.
    pub t0: f64,
    /// The state the step starts from.
    pub y0: SVector<f64, S>,
    /// The step size.
    pub h: f64,
}

impl<Sys, const S: usize> Step<'_, Sys, S> {
    /// The state rate at `(time, state)`, counted (`stepper::state_rate`).
    pub fn rate<const N: usize>(&mut self, time: f64, state: &SVector<f64, S>) -> NewState<S>
    where
        Sys: VariableMassSystem<N, S>,
    {
        state_rate(self.system, self.statistics, time, state)
    }
}

/// An explicit method that holds nothing and takes no settings but the step: its
/// [`FixedMethod`] is the formula alone (explicit Euler, classical RK4).
pub trait Explicit<const N: usize, const S: usize>: Default {
    /// The new state of `step` (see [`FixedMethod::advance`]).
    fn formula<Sys: VariableMassSystem<N, S>>(step: Step<'_, Sys, S>) -> NewState<S>;
}

impl<M: Explicit<N, S>, const N: usize, const S: usize> FixedMethod<N, S> for M {
    type Config = FixedStep;

    fn configure(config: FixedStep) -> Result<(f64, Self), ConfigError> {
        Ok((FixedStep::validated(config.step)?, M::default()))
    }

    fn advance<Sys: VariableMassSystem<N, S>>(&self, step: Step<'_, Sys, S>) -> NewState<S> {
        M::formula(step)
    }
}

/// A fixed-step stepper on the state `[q, p, m_s]` taking its steps by the method `M`; use
/// it through [`super::ExplicitEuler`], [`super::ClassicalRk4`],
/// [`super::ImplicitMidpoint`] or [`super::Variational`].
#[derive(Clone, Debug)]
pub struct Fixed<'a, Sys, M, const N: usize, const S: usize> {
    system: &'a Sys,
    progress: Progress<S>,
    step: f64,
    method: M,
}

impl<'a, Sys, M, const N: usize, const S: usize> Fixed<'a, Sys, M, N, S>
where
    Sys: VariableMassSystem<N, S>,
    M: FixedMethod<N, S>,
{
    /// Starts at `(time, state)`; the state is checked (finite, masses positive), then the
    /// settings.
    pub fn new(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        config: M::Config,
    ) -> Result<Self, StepError<S>> {
        let progress = Progress::new(system, time, state)?;
        M::accepts(system).map_err(|e| e.at(time, &state))?;
        let (step, method) = M::configure(config).map_err(|e| e.at(time, &state))?;
        Ok(Self {
            system,
            progress,
            step,
            method,
        })
    }
}

impl<Sys, M, const N: usize, const S: usize> Stepper<N, S> for Fixed<'_, Sys, M, N, S>
where
    Sys: VariableMassSystem<N, S>,
    M: FixedMethod<N, S>,
{
    type System = Sys;

    fn parts(&self) -> (&Sys, &Progress<S>) {
        (self.system, &self.progress)
    }

    fn parts_mut(&mut self) -> ProgressMut<'_, Sys, S> {
        ProgressMut::new(self.system, &mut self.progress)
    }

    fn step(&mut self) -> Result<StepOutcome, StepError<S>> {
        let (h, reaches_stop) = self.progress.next_step(self.step)?;
        let step = Step {
            system: self.system,
            t0: self.progress.time(),
            y0: *self.progress.state(),
            statistics: &mut self.progress.statistics,
            h,
        };
        let y1 = self.method.advance(step)?;
        self.progress.accept(self.system, h, reaches_stop, y1)
    }
}
