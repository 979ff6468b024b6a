//! A member of a run in lanes: its job (system, initial value, events), the checks of its
//! start (the scalar run's), its bookkeeping between steps and its end.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::LaneSystem;
use crate::error::{StepError, StepErrorKind};
use crate::events::Event;
use crate::run::RunConfig;
use crate::solution::Record;
use crate::stepper::{Checked, Statistics};
use crate::steppers::control::{Controlled, Mode, StepControl};

/// One member's run: its system, its initial value and the events that end it (as
/// [`run`](crate::run::run)'s `events`).
#[derive(Clone, Copy, Debug)]
pub struct LaneJob<'e, Sys, const S: usize> {
    /// The member's system (its parameters go into its lane).
    pub system: Sys,
    /// The initial time.
    pub time: f64,
    /// The initial state `[q, p, m_s]`.
    pub state: SVector<f64, S>,
    /// The events watched; the first [`EventAction::Stop`](crate::events::EventAction::Stop) hit ends the run.
    pub events: &'e [Event<'e, S>],
}

/// Where a member's run ended: the last point of the scalar run's solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneEnd<const S: usize> {
    /// The time of the last point: the located event, or the end time.
    pub time: f64,
    /// The state there.
    pub state: SVector<f64, S>,
    /// The index of the stopping event, `None` when the run reached the end time.
    pub event: Option<usize>,
    /// The work counters (rate evaluations counted six per attempt and one at the start;
    /// the stiffness flag is never set).
    pub statistics: Statistics,
}

/// A member in its lane: the scalar controller and the run's bookkeeping.
pub(super) struct Member<'s, 'e, Sys, const S: usize> {
    pub(super) job: usize,
    pub(super) core: Controlled<'s, Sys, S>,
    pub(super) events: &'e [Event<'e, S>],
    /// g of each event at the last point.
    pub(super) values: Vec<f64>,
    pub(super) steps: usize,
    /// How the member's last attempt ended, which says where its next one starts.
    pub(super) last: Last,
}

/// How a member's last attempt ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Last {
    /// None yet: the attempt starts from the member's initial value.
    Started,
    /// Accepted: the next starts from its new state and last stage (FSAL), which are in the
    /// lanes already.
    Accepted,
    /// Rejected: the next starts where it did, from what the lane holds still.
    Rejected,
}

/// A member at the start of its run, with the scalar run's checks; `Err` holds the member's
/// result when it ends before any step (a failed check, or a run of zero length).
#[allow(clippy::type_complexity)]
pub(super) fn start<'s, 'e, Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &'s [LaneJob<'e, Sys, S>],
    job: usize,
    control: StepControl,
    config: &RunConfig,
) -> Result<Member<'s, 'e, Sys, S>, Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    let LaneJob {
        system,
        time,
        state,
        events,
    } = &jobs[job];
    let mut core = Controlled::new::<N>(system, *time, *state, control).map_err(Err)?;
    let invalid = |reason| Err(StepError::invalid_configuration(*time, *state, reason));
    if !matches!(core.mode, Mode::Adaptive(..)) {
        return Err(invalid("lanes: only adaptive steps run in lanes"));
    }
    let supported = config.record == Record::default()
        && config.energy_tolerance.is_none()
        && !config.event_tolerance.is_nan()
        && config.event_tolerance >= 0.0;
    if !supported {
        return Err(invalid(
            "lanes: a run in lanes records nothing and guards no energy; the event \
             tolerance must be non-negative",
        ));
    }
    if system.switch_count() > 0 || system.next_stop_time(*time).is_some() {
        return Err(invalid(
            "lanes: a system with switches or stop times runs on the scalar path",
        ));
    }
    for event in *events {
        event
            .validate::<Sys, N>()
            .map_err(|error| invalid(error.reason))?;
    }
    core.progress.set_stop_time(config.end_time).map_err(Err)?;
    system.check_flows(*time, state).map_err(Err)?;
    if config.end_time == *time {
        return Err(Ok(end_at(&core, *time, *state, None)));
    }
    if config.max_steps == 0 {
        let kind = StepErrorKind::TooManySteps { max_steps: 0 };
        return Err(Err(StepError::new(*time, *state, kind)));
    }
    let values = events
        .iter()
        .map(|event| event.value(system, *time, state))
        .collect();
    Ok(Member {
        job,
        core,
        events,
        values,
        steps: 0,
        last: Last::Started,
    })
}

/// The member's end at `(time, state)`, stopped by `event` (`None`: at the end time).
pub(super) fn end_at<Sys, const S: usize>(
    core: &Controlled<'_, Sys, S>,
    time: f64,
    state: SVector<f64, S>,
    event: Option<usize>,
) -> LaneEnd<S> {
    LaneEnd {
        time,
        state,
        event,
        statistics: *core.progress.statistics(),
    }
}
