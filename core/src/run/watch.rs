//! The events a run watches: g at the end of every step, the sign changes located on the
//! interpolated state, the hits recorded in time order up to the first stopping one.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::point::Point;
use crate::error::StepError;
use crate::events::{locate_root, Event, EventAction, EventHit};
use crate::system::VariableMassSystem;

/// The error of an event whose function is not a number where it is read: it could never
/// change sign, so the run would pass its crossing silently (a rail's event on a system
/// without a rail, a quantity of the model that cannot be evaluated there).
pub const EVENT_NOT_A_NUMBER: &str = "an event's function is not a number here, so its crossing \
     could never be found (a rail's event on a system without a rail, or a quantity that \
     cannot be evaluated)";

/// g of `event` at `(time, state)`, or the run's error there if it is not a number (the
/// lanes read their members' events through it too).
pub(crate) fn read<Sys, const N: usize, const S: usize>(
    event: &Event<'_, S>,
    system: &Sys,
    (time, state): (f64, &SVector<f64, S>),
) -> Result<f64, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let g = event.value(system, time, state);
    match g.is_nan() {
        true => Err(StepError::invalid_configuration(
            time,
            *state,
            EVENT_NOT_A_NUMBER,
        )),
        false => Ok(g),
    }
}

/// The run's events with g at the last point, and room for the hits of one step.
pub(crate) struct EventWatch<'e, 'a, const S: usize> {
    events: &'e [Event<'a, S>],
    /// g of each event at the last point.
    values: Vec<f64>,
    /// (located time, event index) of the hits within the current step.
    pending: Vec<(f64, usize)>,
}

impl<'e, 'a, const S: usize> EventWatch<'e, 'a, S> {
    /// Starts watching `events` from `start`; an event whose g is not a number there is
    /// the run's error ([`EVENT_NOT_A_NUMBER`]).
    pub(crate) fn start<Sys, const N: usize>(
        events: &'e [Event<'a, S>],
        system: &Sys,
        start: &Point<S>,
    ) -> Result<Self, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let values = events
            .iter()
            .map(|event| read(event, system, (start.time, &start.state)))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            events,
            values,
            pending: Vec::with_capacity(events.len()),
        })
    }

    /// Checks the step from `start` to `end`: locates every event that triggered to within
    /// `tolerance` in t, on the states given by `interpolate`, and appends the hits to `hits`
    /// in time order up to and including the first whose action is
    /// [`EventAction::Stop`], which it returns. A g that is not a number at the step's end
    /// is the run's error there.
    pub(crate) fn check_step<Sys, const N: usize>(
        &mut self,
        system: &Sys,
        (start, end): (&Point<S>, &Point<S>),
        interpolate: &impl Fn(f64) -> SVector<f64, S>,
        tolerance: f64,
        hits: &mut Vec<EventHit<S>>,
    ) -> Result<Option<EventHit<S>>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        self.pending.clear();
        for (index, (event, before)) in self.events.iter().zip(&mut self.values).enumerate() {
            let after = read(event, system, (end.time, &end.state))?;
            if event.triggered(*before, after) {
                let time = locate_root(
                    |time| event.value(system, time, &interpolate(time)),
                    (start.time, *before),
                    (end.time, after),
                    tolerance,
                );
                self.pending.push((time, index));
            }
            *before = after;
        }
        self.pending.sort_by(|a, b| a.0.total_cmp(&b.0));
        for &(time, index) in &self.pending {
            let hit = EventHit {
                index,
                time,
                state: interpolate(time),
            };
            hits.push(hit);
            if self.events.get(index).map(|event| event.action) == Some(EventAction::Stop) {
                return Ok(Some(hit));
            }
        }
        Ok(None)
    }
}
