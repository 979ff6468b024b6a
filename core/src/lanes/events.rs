//! A lane's run after an accepted step — the flow check of the new point, its events, its
//! end — as the scalar run's (`run`'s `drive` and `EventWatch`): g at the new point, a
//! sign change located (`locate_root`) on the lane's dense output, read out of the lanes
//! only then.

use alloc::vec::Vec;

use super::member::{end_at, LaneEnd, Member};
use super::{lane, LaneState, LaneSystem};
use crate::error::{StepError, StepErrorKind};
use crate::events::{locate_root, Event, EventAction, EventCondition};
use crate::run::RunConfig;
use crate::stepper::{Checked, StepOutcome};
use crate::steppers::dormand_prince::Dense;
use crate::system::VariableMassSystem;

/// The run's bookkeeping after an accepted step (`run`'s `drive` and `EventWatch`): the flow
/// check of the new point, the events located on the lane's dense output, the end time.
/// `Ok(None)` while the run goes on.
#[inline]
pub(super) fn after_step<Sys, const N: usize, const S: usize, const W: usize>(
    member: &mut Member<'_, '_, Sys, S>,
    stages: &[LaneState<S, W>; 7],
    index: usize,
    outcome: StepOutcome,
    config: &RunConfig,
) -> Result<Option<LaneEnd<S>>, StepError<S>>
where
    Sys: LaneSystem<N, S, W>,
{
    let core = &member.core;
    let system = core.system;
    let (time, state) = (core.progress.time(), *core.progress.state());
    system.check_flows(time, &state)?;
    // The events whose g changed sign, with g before.
    let mut changed: Vec<(usize, f64)> = Vec::new();
    for (event_index, (event, before)) in member.events.iter().zip(&mut member.values).enumerate() {
        let after = event.value(system, time, &state);
        if event.triggered(*before, after) {
            changed.push((event_index, *before));
        }
        *before = after;
    }
    if !changed.is_empty() {
        // The lane's stages read out of the lanes only now, for `DormandPrince`'s dense
        // output over its last step.
        let k = core::array::from_fn(|i| lane(&stages[i], index));
        let start = (
            core.progress.previous_time(),
            core.progress.previous_state(),
        );
        let dense = Dense::new(start, &state, core.memory.last_step, &k);
        if let Some((hit, event_index)) = first_stop(member, &changed, &dense, config) {
            let hit_state = dense.at(hit);
            system.check_flows(hit, &hit_state)?;
            return Ok(Some(end_at(core, hit, hit_state, Some(event_index))));
        }
    }
    member.steps += 1;
    if outcome == StepOutcome::ReachedStopTime && time >= config.end_time {
        return Ok(Some(end_at(core, time, state, None)));
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
fn first_stop<Sys, const N: usize, const S: usize, const W: usize>(
    member: &Member<'_, '_, Sys, S>,
    changed: &[(usize, f64)],
    dense: &Dense<S>,
    config: &RunConfig,
) -> Option<(f64, usize)>
where
    Sys: LaneSystem<N, S, W>,
{
    let core = &member.core;
    let (system, time) = (core.system, core.progress.time());
    let start_time = core.progress.previous_time();
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
