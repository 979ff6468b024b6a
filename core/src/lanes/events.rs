//! A lane's run after an accepted step — the flow check of the new point, its events, its
//! end — as the scalar run's (`run`'s `drive` and `EventWatch`): g at the new point, a
//! sign change located (`locate_root`) on the lane's dense output, read out of the lanes
//! only then.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::dormand_prince::{end_at, Attempt, LaneEnd, Member};
use super::{lane, LaneSystem};
use crate::error::{StepError, StepErrorKind};
use crate::events::{locate_root, Event, EventAction, EventCondition};
use crate::run::RunConfig;
use crate::stepper::{Checked, StepOutcome};
use crate::steppers::control::Controlled;
use crate::steppers::dp_tableau::{D1, D3, D4, D5, D6, D7};
use crate::system::VariableMassSystem;

/// The run's bookkeeping after an accepted step (`run`'s `drive` and `EventWatch`): the flow
/// check of the new point, the events located on the lane's dense output, the end time.
/// `Ok(None)` while the run goes on.
#[inline]
pub(super) fn after_step<Sys, const N: usize, const S: usize, const W: usize>(
    member: &mut Member<'_, '_, Sys, S>,
    attempt: &Attempt<S, W>,
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
        let dense = Dense::new(attempt, index, core);
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

/// The dense output over a lane's last accepted step: `DormandPrince::interpolate`.
/// Its four vectors are the interpolant's coefficients, which do not depend on the time:
/// computed once, with `interpolate`'s operations, for the several times root finding asks.
struct Dense<const S: usize> {
    y0: SVector<f64, S>,
    y1: SVector<f64, S>,
    difference: SVector<f64, S>,
    first: SVector<f64, S>,
    second: SVector<f64, S>,
    third: SVector<f64, S>,
    h: f64,
    t0: f64,
}

impl<const S: usize> Dense<S> {
    fn new<Sys, const W: usize>(
        attempt: &Attempt<S, W>,
        index: usize,
        core: &Controlled<'_, Sys, S>,
    ) -> Self {
        let k: [SVector<f64, S>; 7] = core::array::from_fn(|i| lane(&attempt.k[i], index));
        let (y0, y1) = (*core.progress.previous_state(), *core.progress.state());
        let h = core.memory.last_step;
        let difference = y1 - y0;
        let first = k[0] * h - difference;
        let second = difference - k[6] * h - first;
        let third = (k[0] * D1 + k[2] * D3 + k[3] * D4 + k[4] * D5 + k[5] * D6 + k[6] * D7) * h;
        Self {
            y0,
            y1,
            difference,
            first,
            second,
            third,
            h,
            t0: core.progress.previous_time(),
        }
    }

    /// Component `j` of [`Self::at`], with its operations (each component of `at` is
    /// computed on its own, so the two agree to the bit).
    fn component_at(&self, j: usize, time: f64) -> f64 {
        let h = self.h;
        if h <= 0.0 {
            return self.y1[j];
        }
        let theta = (time - self.t0) / h;
        let theta1 = 1.0 - theta;
        let (difference, first, second) = (self.difference[j], self.first[j], self.second[j]);
        self.y0[j]
            + (difference + (first + (second + self.third[j] * theta1) * theta) * theta1) * theta
    }

    fn at(&self, time: f64) -> SVector<f64, S> {
        let h = self.h;
        if h <= 0.0 {
            return self.y1;
        }
        let theta = (time - self.t0) / h;
        let theta1 = 1.0 - theta;
        let (difference, first, second) = (self.difference, self.first, self.second);
        self.y0 + (difference + (first + (second + self.third * theta1) * theta) * theta1) * theta
    }
}
