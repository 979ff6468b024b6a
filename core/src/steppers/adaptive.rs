//! The one shape of the adaptive steppers (Dormand–Prince, DOP853, the DIRK stepper of SDIRK4
//! and ESDIRK4(3)), as diffsol and OrdinaryDiffEq split a solver: [`Adaptive`] holds what
//! every method holds — the system, the progress, the checked settings and the controller's
//! memory (`control::Controlled`) — and the method `A` ([`AdaptiveMethod`]) holds what only
//! it carries from one step to the next (its stages, its dense output, its Jacobian) and
//! takes the step. The constructor, the [`Stepper`] accessors and the restart are written
//! here once; users name the steppers by their aliases ([`super::DormandPrince`],
//! [`super::Dop853`], [`super::Sdirk4`], [`super::Esdirk43`]).

use nalgebra::SVector;

use super::control::{Controlled, StepControl};
use crate::error::StepError;
use crate::stepper::{Progress, ProgressMut, Restarting, StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// An adaptive stepper on the state `[q, p, m_s]` taking its steps by the method `A`; use it
/// through [`super::DormandPrince`], [`super::Dop853`], [`super::Sdirk4`] or
/// [`super::Esdirk43`].
#[derive(Clone, Debug)]
pub struct Adaptive<'a, Sys, A, const N: usize, const S: usize> {
    /// The system, the progress, the settings and the controller's memory.
    pub(super) core: Controlled<'a, Sys, S>,
    /// What the method carries from one step to the next.
    pub(super) method: A,
}

/// A method of an [`Adaptive`] stepper: its step, its dense output and what it forgets at a
/// restart; its [`Default`] is what it carries before the first step.
pub trait AdaptiveMethod<const N: usize, const S: usize>: Default {
    /// Takes one accepted step ([`Stepper::step`]).
    fn step<Sys: VariableMassSystem<N, S>>(
        stepper: &mut Adaptive<'_, Sys, Self, N, S>,
    ) -> Result<StepOutcome, StepError<S>>;

    /// The method's continuous extension over the last step ([`Stepper::dense_output`]).
    fn dense_output<Sys: VariableMassSystem<N, S>>(
        stepper: &Adaptive<'_, Sys, Self, N, S>,
        time: f64,
    ) -> Option<SVector<f64, S>>;

    /// Drops what belongs to the old initial value (the controller's memory is dropped by
    /// [`Adaptive`]); nothing by default.
    fn forget_history(&mut self) {}
}

impl<'a, Sys, A, const N: usize, const S: usize> Adaptive<'a, Sys, A, N, S>
where
    Sys: VariableMassSystem<N, S>,
    A: AdaptiveMethod<N, S>,
{
    /// Starts at `(time, state)`; the state and the control are checked. Each method's
    /// reference code has its own defaults: [`AdaptiveControl::default`] (`dopri5`),
    /// [`AdaptiveControl::dop853`] (`dop853.f`), [`AdaptiveControl::sdirk4`] (`sdirk4.f`).
    ///
    /// [`AdaptiveControl::default`]: super::AdaptiveControl::default
    /// [`AdaptiveControl::dop853`]: super::AdaptiveControl::dop853
    /// [`AdaptiveControl::sdirk4`]: super::AdaptiveControl::sdirk4
    pub fn new(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        control: StepControl,
    ) -> Result<Self, StepError<S>> {
        Ok(Self {
            core: Controlled::new::<N>(system, time, state, control)?,
            method: A::default(),
        })
    }

    /// The size of the step the stepper will try next (0 before the first step).
    pub fn proposed_step(&self) -> f64 {
        self.core.memory.next_step
    }
}

impl<Sys, A, const N: usize, const S: usize> Stepper<N, S> for Adaptive<'_, Sys, A, N, S>
where
    Sys: VariableMassSystem<N, S>,
    A: AdaptiveMethod<N, S>,
{
    type System = Sys;

    fn parts(&self) -> (&Sys, &Progress<S>) {
        (self.core.system, &self.core.progress)
    }

    fn parts_mut(&mut self) -> ProgressMut<'_, Sys, S> {
        ProgressMut::new(self.core.system, &mut self.core.progress)
    }

    fn forget_history(&mut self, _: Restarting) {
        self.core.memory.restart();
        self.method.forget_history();
    }

    fn dense_output(&self, time: f64) -> Option<SVector<f64, S>> {
        A::dense_output(self, time)
    }

    fn step(&mut self) -> Result<StepOutcome, StepError<S>> {
        A::step(self)
    }
}

/// One attempted step of an explicit pair with `K` stages: the new state, the stages, the
/// state of the other stage at t₀ + h that the stiffness test pairs with the new state, and
/// the scaled error.
pub(super) struct ExplicitAttempt<const S: usize, const K: usize> {
    pub(super) state: SVector<f64, S>,
    pub(super) stages: [SVector<f64, S>; K],
    pub(super) stiffness_state: SVector<f64, S>,
    pub(super) error: f64,
}
