//! The solution a run fills: every point with the extras asked for, the event hits, and at
//! the end why the run stopped and what it cost.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::energy::EnergyBudget;
use super::point::Point;
use super::RunConfig;
use crate::error::StepError;
use crate::events::EventHit;
use crate::solution::{Record, Solution, StopReason};
use crate::stepper::Stepper;
use crate::system::VariableMassSystem;

/// The solution so far, what to record, and the energy budget when one is kept.
pub(crate) struct Recorder<const N: usize, const S: usize> {
    solution: Solution<N, S>,
    record: Record,
    energy: Option<EnergyBudget>,
}

impl<const N: usize, const S: usize> Recorder<N, S> {
    /// A solution holding `start`, with an energy budget from there if `config` needs one
    /// (then `start` must carry its energy terms).
    pub(crate) fn start<Sys>(
        system: &Sys,
        config: &RunConfig,
        start: &Point<S>,
    ) -> Result<Self, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let energy = config
            .needs_energy()
            .then(|| EnergyBudget::start(start, config.energy_tolerance));
        let mut recorder = Self {
            solution: Solution::new(),
            record: config.record,
            energy,
        };
        recorder.push(system, start)?;
        Ok(recorder)
    }

    /// Where a run appends the events it finds.
    pub(crate) fn hits(&mut self) -> &mut Vec<EventHit<S>> {
        &mut self.solution.events
    }

    /// Records the step from `start` to `end`: adds it to the energy budget if one is kept,
    /// applies the energy guard at `end` if `guarded` and the run has one, and appends `end`.
    pub(crate) fn step_to<Sys>(
        &mut self,
        system: &Sys,
        (start, end): (&Point<S>, &Point<S>),
        interpolate: &impl Fn(f64) -> SVector<f64, S>,
        guarded: bool,
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if let Some(budget) = &mut self.energy {
            budget.add_step(system, start, end, interpolate)?;
        }
        if guarded {
            self.guard(system, end)?;
        }
        self.push(system, end)
    }

    /// Applies the energy guard at `point`, if the run has one.
    pub(crate) fn guard<Sys>(&mut self, system: &Sys, point: &Point<S>) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        match &mut self.energy {
            Some(budget) => budget.check(system, point),
            None => Ok(()),
        }
    }

    /// Appends `point` with the extras asked for.
    pub(crate) fn push<Sys>(&mut self, system: &Sys, point: &Point<S>) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let energy = self.energy.as_ref().and_then(|budget| budget.at(point));
        self.solution
            .push(system, &self.record, point.time, point.state, energy)
    }

    /// The solution, ended for `stop` with the stepper's statistics.
    pub(crate) fn finish<St>(self, stepper: &St, stop: StopReason) -> Solution<N, S>
    where
        St: Stepper<N, S>,
    {
        let mut solution = self.solution;
        solution.stop = stop;
        solution.statistics = *stepper.statistics();
        solution
    }
}
