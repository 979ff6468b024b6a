//! A member of a run in lanes: its job (system, initial value, events), the checks of its
//! start (the scalar run's), its bookkeeping between steps and its end, over the scalar
//! stepper state of its method (its [`LaneCore`]: Dormand–Prince's controller, or a
//! `Taylor` stepper).

use alloc::vec::Vec;
use core::marker::PhantomData;

use nalgebra::SVector;

use super::LaneSystem;
use crate::error::{StepError, StepErrorKind};
use crate::events::Event;
use crate::run::RunConfig;
use crate::solution::Record;
use crate::stepper::{Checked, Progress, Statistics, Stepper};
use crate::steppers::control::{Controlled, Mode, StepControl};
use crate::steppers::Taylor;
use crate::system::VariableMassSystem;

/// What a member's method keeps of its run: the system and the progress (time, state,
/// statistics, stop time).
pub(super) trait LaneCore<Sys, const S: usize> {
    /// The system and the progress.
    fn parts(&self) -> (&Sys, &Progress<S>);
    /// Lands the method's steps on `time`.
    fn set_stop_time(&mut self, time: f64) -> Result<(), StepError<S>>;
}

impl<Sys, const S: usize> LaneCore<Sys, S> for Controlled<'_, Sys, S> {
    fn parts(&self) -> (&Sys, &Progress<S>) {
        (self.system, &self.progress)
    }
    fn set_stop_time(&mut self, time: f64) -> Result<(), StepError<S>> {
        self.progress.set_stop_time(time)
    }
}

impl<Sys, const N: usize, const S: usize> LaneCore<Sys, S> for Taylor<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    fn parts(&self) -> (&Sys, &Progress<S>) {
        Stepper::parts(self)
    }
    fn set_stop_time(&mut self, time: f64) -> Result<(), StepError<S>> {
        Stepper::set_stop_time(self, time)
    }
}

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

/// A member in its lane: its method's scalar state (`core`) and the run's bookkeeping.
pub(super) struct Member<'s, 'e, Sys, const S: usize, C = Controlled<'s, Sys, S>> {
    pub(super) job: usize,
    pub(super) core: C,
    pub(super) events: &'e [Event<'e, S>],
    /// g of each event at the last point.
    pub(super) values: Vec<f64>,
    pub(super) steps: usize,
    /// How the member's last attempt ended, which says where its next one starts.
    pub(super) last: Last,
    /// The system `core` steps (borrowed for `'s`).
    system: PhantomData<&'s Sys>,
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

/// What [`start`] returns: the member, or its result when it ends before any step.
pub(super) type Started<'s, 'e, Sys, const S: usize, C> =
    Result<Member<'s, 'e, Sys, S, C>, Result<LaneEnd<S>, StepError<S>>>;

/// A Dormand–Prince member at the start of its run ([`start_with`]), its control adaptive.
pub(super) fn start<'s, 'e, Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &'s [LaneJob<'e, Sys, S>],
    job: usize,
    control: StepControl,
    config: &RunConfig,
) -> Started<'s, 'e, Sys, S, Controlled<'s, Sys, S>>
where
    Sys: LaneSystem<N, S, W>,
{
    start_with::<Sys, _, N, S, W>(jobs, job, config, |system, time, state| {
        let core = Controlled::new::<N>(system, time, state, control)?;
        if !matches!(core.mode, Mode::Adaptive(..)) {
            let reason = "lanes: only adaptive steps run in lanes";
            return Err(StepError::invalid_configuration(time, state, reason));
        }
        Ok(core)
    })
}

/// A member at the start of its run, its method's state made by `make` (which checks what
/// the scalar stepper's constructor checks), with the scalar run's checks; `Err` holds the
/// member's result when it ends before any step (a failed check, or a run of zero length).
pub(super) fn start_with<'s, 'e, Sys, C, const N: usize, const S: usize, const W: usize>(
    jobs: &'s [LaneJob<'e, Sys, S>],
    job: usize,
    config: &RunConfig,
    make: impl FnOnce(&'s Sys, f64, SVector<f64, S>) -> Result<C, StepError<S>>,
) -> Started<'s, 'e, Sys, S, C>
where
    Sys: LaneSystem<N, S, W>,
    C: LaneCore<Sys, S>,
{
    let LaneJob {
        system,
        time,
        state,
        events,
    } = &jobs[job];
    let mut core = make(system, *time, *state).map_err(Err)?;
    let invalid = |reason| Err(StepError::invalid_configuration(*time, *state, reason));
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
    core.set_stop_time(config.end_time).map_err(Err)?;
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
        .map(|event| crate::run::watch::read(event, system, (*time, state)))
        .collect::<Result<_, _>>()
        .map_err(Err)?;
    Ok(Member {
        job,
        core,
        events,
        values,
        steps: 0,
        last: Last::Started,
        system: PhantomData,
    })
}

/// The member's end at `(time, state)`, stopped by `event` (`None`: at the end time).
pub(super) fn end_at<Sys, const S: usize>(
    core: &impl LaneCore<Sys, S>,
    time: f64,
    state: SVector<f64, S>,
    event: Option<usize>,
) -> LaneEnd<S> {
    LaneEnd {
        time,
        state,
        event,
        statistics: *core.parts().1.statistics(),
    }
}
