//! A lane's run after an accepted step — the flow check of the new point, its events, its
//! end — as the scalar run's (`run`'s `drive` and `EventWatch`): g at the new point, a
//! sign change located (`locate_root`) on the lane's dense output (the method's: made only
//! then, for Dormand–Prince out of the lanes).

use alloc::vec::Vec;

use nalgebra::SVector;

use super::member::{end_at, LaneCore, LaneEnd, Member};
use super::LaneSystem;
use crate::error::{StepError, StepErrorKind};
use crate::events::{locate_root, Event, EventAction, EventCondition};
use crate::run::RunConfig;
use crate::stepper::{Checked, StepOutcome};
use crate::steppers::dormand_prince::Dense;
use crate::steppers::Taylor;
use crate::system::VariableMassSystem;

/// A method's dense output over its last step, as the scalar run reads it.
pub(super) trait Interpolant<const S: usize> {
    /// The state at `time`.
    fn at(&self, time: f64) -> SVector<f64, S>;
    /// Component `j` of the state at `time` (the bits of `at(time)[j]`).
    fn component_at(&self, j: usize, time: f64) -> f64;
}

impl<const S: usize> Interpolant<S> for Dense<S> {
    fn at(&self, time: f64) -> SVector<f64, S> {
        Dense::at(self, time)
    }
    fn component_at(&self, j: usize, time: f64) -> f64 {
        Dense::component_at(self, j, time)
    }
}

/// The Taylor stepper's series, the dense output the scalar run locates events on.
impl<Sys, const N: usize, const S: usize> Interpolant<S> for &Taylor<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    fn at(&self, time: f64) -> SVector<f64, S> {
        self.interpolate(time)
    }
    fn component_at(&self, j: usize, time: f64) -> f64 {
        self.interpolate(time)[j]
    }
}

/// The run's bookkeeping after an accepted step (`run`'s `drive` and `EventWatch`): the flow
/// check of the new point, the events located on the lane's dense output, the end time.
/// `Ok(None)` while the run goes on.
/// `dense` makes the method's dense output of the step, only when an event needs it.
#[inline]
pub(super) fn after_step<'c, Sys, C, D, const N: usize, const S: usize, const W: usize>(
    member: &'c mut Member<'_, '_, Sys, S, C>,
    dense: impl FnOnce(&'c C) -> D,
    outcome: StepOutcome,
    config: &RunConfig,
) -> Result<Option<LaneEnd<S>>, StepError<S>>
where
    Sys: LaneSystem<N, S, W>,
    C: LaneCore<Sys, S>,
    D: Interpolant<S>,
{
    let (time, state) = {
        let progress = member.core.parts().1;
        (progress.time(), *progress.state())
    };
    member.core.parts().0.check_flows(time, &state)?;
    // The events whose g changed sign, with g before.
    let mut changed: Vec<(usize, f64)> = Vec::new();
    let system = member.core.parts().0;
    for (event_index, (event, before)) in member.events.iter().zip(&mut member.values).enumerate() {
        // A g that is not a number is the scalar run's error too (`run::watch`).
        let after = crate::run::watch::read(event, system, (time, &state))?;
        if event.triggered(*before, after) {
            changed.push((event_index, *before));
        }
        *before = after;
    }
    // Counted before the events are located: a stop there ends the member anyway.
    member.steps += 1;
    let member: &'c Member<'_, '_, Sys, S, C> = member;
    if !changed.is_empty() {
        let dense = dense(&member.core);
        if let Some((hit, event_index)) = first_stop(member, &changed, &dense, config) {
            let hit_state = dense.at(hit);
            system.check_flows(hit, &hit_state)?;
            return Ok(Some(end_at(
                &member.core,
                hit,
                hit_state,
                Some(event_index),
            )));
        }
    }
    if outcome == StepOutcome::ReachedStopTime && time >= config.end_time {
        return Ok(Some(end_at(&member.core, time, state, None)));
    }
    if member.steps >= config.max_steps {
        let kind = StepErrorKind::TooManySteps {
            max_steps: config.max_steps,
        };
        return Err(StepError::new(time, state, kind));
    }
    Ok(None)
}

/// The earliest located stopping event among the `changed` ones (index, g before), each
/// located in place: `EventWatch::check_step`'s choice.
fn first_stop<Sys, C, const N: usize, const S: usize, const W: usize>(
    member: &Member<'_, '_, Sys, S, C>,
    changed: &[(usize, f64)],
    dense: &impl Interpolant<S>,
    config: &RunConfig,
) -> Option<(f64, usize)>
where
    Sys: LaneSystem<N, S, W>,
    C: LaneCore<Sys, S>,
{
    let (system, progress) = member.core.parts();
    let time = progress.time();
    let start_time = progress.previous_time();
    let mut located: Vec<(f64, usize)> = changed
        .iter()
        .map(|&(event_index, before)| {
            let event = &member.events[event_index];
            let after = member.values[event_index];
            let one = component_of::<Sys, N, S>(event);
            let hit = locate_root(
                |t| match one {
                    Some((component, value)) => dense.component_at(component, t) - value,
                    None => event.value(system, t, &dense.at(t)),
                },
                (start_time, before),
                (time, after),
                config.event_tolerance,
            );
            (hit, event_index)
        })
        .collect();
    located.sort_by(|a, b| a.0.total_cmp(&b.0));
    located
        .into_iter()
        .find(|(_, i)| member.events.get(*i).map(|e| e.action) == Some(EventAction::Stop))
}

/// The state component j and the value v of an event whose g is x_j − v: a state
/// component's, or a state mass's (component 2N + k: [`LaneSystem`]'s `mass` reads it
/// as it is), so that it needs one component of the interpolant only. `None` for others.
#[inline]
fn component_of<Sys, const N: usize, const S: usize>(event: &Event<'_, S>) -> Option<(usize, f64)>
where
    Sys: VariableMassSystem<N, S>,
{
    match event.condition {
        EventCondition::StateComponent { index, value } if index < S => Some((index, value)),
        EventCondition::Mass { index, threshold } if index < Sys::STATE_MASSES => {
            Some((2 * N + index, threshold))
        }
        _ => None,
    }
}
