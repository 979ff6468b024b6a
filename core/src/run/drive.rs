//! The run's loop: one pass takes a step and decides what it means — a switch crossed or
//! to be landed on, a stop time reached, an event, the end — and the progress guard counts
//! the passes that do not move the run ([`super::stall`]).

use nalgebra::SVector;

use super::interpolation::{hermite, over_last_step};
use super::point::{Needs, Point};
use super::record::Recorder;
use super::stall::ProgressGuard;
use super::switching::{Crossing, SwitchWatch};
use super::watch::EventWatch;
use super::{
    cross_past, next_target, reach_end, record_step, sample_point, Crossed, RunConfig, Sampled,
};
use crate::error::{StepError, StepErrorKind, SystemError};
use crate::input::Sampling;
use crate::solution::StopReason;
use crate::stepper::{StepOutcome, Stepper};
use crate::system::VariableMassSystem;

/// A run between its start and its stop: the stepper, what is watched and recorded, the
/// last point kept, and the time after which a step was refused for a mass.
pub(super) struct Running<'r, 'e, 'a, St, const N: usize, const S: usize> {
    pub(super) stepper: &'r mut St,
    pub(super) config: &'r RunConfig,
    pub(super) needs: Needs,
    pub(super) recorder: &'r mut Recorder<N, S>,
    pub(super) watch: EventWatch<'e, 'a, S>,
    pub(super) switches: Option<SwitchWatch>,
    /// The last point kept (the stepper stands on it between passes).
    pub(super) previous: Point<S>,
    /// The earliest refusal of a step for a non-positive mass (its time and state): the
    /// run lands halfway there until an event shows up or the gap is a rounding.
    pub(super) refused: Option<StepError<S>>,
}

impl<St, const N: usize, const S: usize> Running<'_, '_, '_, St, N, S>
where
    St: Stepper<N, S>,
{
    /// Passes until a stop, the step limit, or a run that stalls.
    pub(super) fn go(&mut self) -> Result<StopReason, StepError<S>> {
        if let Some(stop) = self.leave_zero()? {
            return Ok(stop);
        }
        let mut guard = ProgressGuard::new(self.previous.time, self.config.stall_passes);
        for _ in 0..self.config.max_steps {
            if let Some(stop) = self.pass()? {
                return Ok(stop);
            }
            guard.check(&self.previous)?;
        }
        let kind = StepErrorKind::TooManySteps {
            max_steps: self.config.max_steps,
        };
        Err(StepError::new(
            self.stepper.time(),
            *self.stepper.state(),
            kind,
        ))
    }

    /// Crosses off a switch standing on zero at the run's start
    /// ([`SwitchWatch::leave_zero`]); the reason to stop, if the sliver meets one.
    fn leave_zero(&mut self) -> Result<Option<StopReason>, StepError<S>> {
        let system = self.stepper.system();
        let crossing = match &mut self.switches {
            Some(switches) => switches.leave_zero(system, &self.previous)?,
            None => None,
        };
        match crossing {
            Some(Crossing::Cross { time, state }) => self.cross(self.previous.time, (time, state)),
            _ => Ok(None),
        }
    }

    /// One step and what follows from it; the reason to stop, if the run stops.
    fn pass(&mut self) -> Result<Option<StopReason>, StepError<S>> {
        let outcome = match self.stepper.step() {
            Ok(outcome) => outcome,
            Err(error) => return self.refuse(error),
        };
        let system = self.stepper.system();
        let current = Point::at(
            system,
            self.stepper.time(),
            *self.stepper.state(),
            self.needs,
        )?;
        let step_start = self.previous.time;
        if let Some(switches) = &mut self.switches {
            let interpolate = |time| over_last_step(&*self.stepper, &self.previous, &current, time);
            let step = (&self.previous, &current);
            match switches.check_step(system, step, &interpolate)? {
                Crossing::None => {}
                Crossing::Redo { near } => return self.redo(step_start, near),
                Crossing::Cross { time, state } => return self.cross(step_start, (time, state)),
            }
        }
        let interpolate = |time| over_last_step(&*self.stepper, &self.previous, &current, time);
        let watches = (&mut *self.recorder, &mut self.watch, self.config);
        let step = (&self.previous, &current);
        if let Some(stop) = record_step(system, watches, step, &interpolate)? {
            return Ok(Some(stop));
        }
        self.previous = current;
        match outcome {
            StepOutcome::ReachedStopTime => self.landed(step_start),
            _ => Ok(None),
        }
    }

    /// The stepper landed on its stop time (the previous point): the end, the near end of
    /// a switch's bracket, or a stop time of the system.
    fn landed(&mut self, step_start: f64) -> Result<Option<StopReason>, StepError<S>> {
        let time = self.stepper.time();
        let system = self.stepper.system();
        let crossing = match &mut self.switches {
            // The end first: a switch landed on at the end is not crossed past it.
            _ if time >= self.config.end_time => {
                let stop = reach_end(self.stepper, self.recorder, &self.previous, self.needs)?;
                return Ok(Some(stop));
            }
            Some(switches) if switches.landed(time) => {
                switches.cross_from(system, &self.previous)?
            }
            _ => Crossing::None,
        };
        match crossing {
            Crossing::Cross { time, state } => return self.cross(step_start, (time, state)),
            // The crossing is still ahead: land nearer.
            Crossing::Redo { near } => return self.redo(time, near),
            // A stop time of the system, or a crossing not there after all: restart here
            // (the rate may have a kink in t), sample the held inputs whose grid holds it
            // (a knot of a table of t, or another input's sample, samples none), and aim at
            // the next.
            Crossing::None => {
                let watches = (&mut *self.recorder, &mut self.watch, self.switches.as_mut());
                let previous = &mut self.previous;
                match sample_point(self.stepper, watches, previous, Sampling::Due, self.needs)? {
                    Sampled::Unchanged => self.stepper.restart(time, previous.state)?,
                    Sampled::Changed => {}
                    Sampled::Stopped(stop) => return Ok(Some(stop)),
                }
            }
        }
        self.aim()
    }

    /// Integrates again from the point kept (at `from`) to `near`, before a switch.
    fn redo(&mut self, from: f64, near: f64) -> Result<Option<StopReason>, StepError<S>> {
        self.stepper.restart(from, self.previous.state)?;
        self.stepper.set_stop_time(near)?;
        Ok(None)
    }

    /// Crosses a switch to `past` by its Euler sliver and restarts there, a few roundings
    /// past the switch, maybe past a sample time: the inputs with a sample since the step's
    /// start (`step_start`) are sampled at the restart. Then aims at the next stop.
    fn cross(
        &mut self,
        step_start: f64,
        past: (f64, SVector<f64, S>),
    ) -> Result<Option<StopReason>, StepError<S>> {
        let sliver = (&mut *self.recorder, &mut self.watch, self.config);
        self.previous = match cross_past(self.stepper, sliver, &self.previous, past, self.needs)? {
            Crossed::Past(point) => point,
            Crossed::Stopped(stop) => return Ok(Some(stop)),
        };
        let watches = (&mut *self.recorder, &mut self.watch, self.switches.as_mut());
        let which = Sampling::Since(step_start);
        let previous = &mut self.previous;
        if let Sampled::Stopped(stop) =
            sample_point(self.stepper, watches, previous, which, self.needs)?
        {
            return Ok(Some(stop));
        }
        self.aim()
    }

    /// Sets the stepper's stop time to the next time it must land on: the system's next
    /// stop time or the end, or halfway to a time a step was refused at. A stop time of the
    /// system a few roundings ahead ([`is_sliver`]) is crossed by one Euler step instead.
    fn aim(&mut self) -> Result<Option<StopReason>, StepError<S>> {
        let time = self.stepper.time();
        let mut target = next_target(self.stepper.system(), time, self.config.end_time);
        if let Some(refused) = self.refused {
            let halfway = time + 0.5 * (refused.time - time);
            if halfway > time && halfway < target {
                target = halfway;
            }
        }
        let system_stop = target < self.config.end_time && self.refused.is_none();
        if system_stop && self.previous.time == time && is_sliver(time, target) {
            return self.step_sliver(target);
        }
        self.stepper.set_stop_time(target)?;
        Ok(None)
    }

    /// Crosses the sliver from the point kept to the system's stop time `target` (the T₁ → T₂
    /// of a knot whose order read jumps, `core::table::next_knot_time_read`) by one Euler
    /// step, recorded as a switch's sliver is. The step controller could not take it: its
    /// stages read both sides of the jump, so its error estimate is the jump times a few
    /// roundings, above an absolute tolerance where the state is near 0, and no shorter
    /// step helps (review of session 33: a force switched on at t = 500 failed with a step
    /// underflow by DOP853 at 1e-12). The Euler step errs by the same few roundings times
    /// the jump, the knot's documented error.
    fn step_sliver(&mut self, target: f64) -> Result<Option<StopReason>, StepError<S>> {
        let system = self.stepper.system();
        let from = &self.previous;
        let rate = match from.rate {
            Some(rate) => rate,
            None => system
                .state_rate(from.time, &from.state)
                .map_err(|error| StepError::from_system(system, error, from.time, &from.state))?,
        };
        let state = from.state + rate * (target - from.time);
        self.cross(from.time, (target, state))
    }

    /// A step the stepper refused. One refused for a mass that the step would make
    /// non-positive (at `error.time`, after the point kept) is not yet the run's end: an
    /// event, a stop condition or a phase change may come before the mass runs out (a
    /// burn to exactly zero propellant). The run lands halfway there, again and again
    /// (a bisection in t, each landing's step checked for events as any), until the gap
    /// is a rounding of t or the stepper's own step underflows on the way (an adaptive
    /// stepper shrinks a step refused for a mass itself); then an event whose function
    /// changes sign between the last point and the refused state stops the run at that
    /// last point, located to the gap. Otherwise, and for every other failure, the error
    /// stands.
    fn refuse(&mut self, error: StepError<S>) -> Result<Option<StopReason>, StepError<S>> {
        let from = self.previous.time;
        let underflow = match error.kind {
            StepErrorKind::System(SystemError::NonPositiveMass { .. }) if error.time > from => {
                false
            }
            // Only a refusal still ahead makes an underflow part of its bisection; after the
            // run got past it, the underflow is the run's own failure and is reported as such.
            StepErrorKind::StepSizeUnderflow { .. }
                if self.refused.is_some_and(|r| r.time > from) =>
            {
                true
            }
            _ => return Err(error),
        };
        let earliest = match self.refused {
            Some(refused) if underflow || refused.time <= error.time => refused,
            _ => error,
        };
        // A refusal the run has since passed (a mass that depends on the path, near a
        // singular motion: shorter steps got past where a longer one was refused) ends it
        // there, rather than integrate on through the singularity.
        if earliest.time <= from {
            return Err(earliest);
        }
        self.refused = Some(earliest);
        let halfway = from + 0.5 * (earliest.time - from);
        if !underflow && halfway > from && halfway < earliest.time {
            self.stepper.set_stop_time(halfway)?;
            return Ok(None);
        }
        self.event_before(earliest)
    }

    /// The stopping event between the last point and the state a step was refused at
    /// (`refused`, a few roundings after it), on the line between them: the run stops at
    /// the last point for it, or the refusal stands. The hits of that gap are recorded at
    /// the last point, the event's row: located on the line they stand a rounding later,
    /// past the refusal's mass (−1.1e-13 kg of propellant in `tests/burn_to_zero.rs`), a
    /// state no row may hold (a phase entered there would start with a negative mass).
    /// Before (review of issue 33) they kept that located time, which no row had.
    fn event_before(&mut self, refused: StepError<S>) -> Result<Option<StopReason>, StepError<S>> {
        let past = Point {
            time: refused.time,
            state: refused.state,
            rate: None,
            energy: None,
        };
        let line = |time| hermite(&self.previous, &past, time);
        let system = self.stepper.system();
        let hits = self.recorder.hits();
        let before = hits.len();
        let step = (&self.previous, &past);
        let Some(hit) = self.watch.check_step(system, step, &line, 0.0, hits)? else {
            return Err(refused);
        };
        for gap_hit in &mut hits[before..] {
            (gap_hit.time, gap_hit.state) = (self.previous.time, self.previous.state);
        }
        Ok(Some(StopReason::EventFound { index: hit.index }))
    }
}

/// Whether `target` is within a few roundings of t after `time` (64 ulps of the larger):
/// a sliver, which only the stop times around a knot make.
fn is_sliver(time: f64, target: f64) -> bool {
    let gap = target - time;
    gap > 0.0 && gap <= 64.0 * f64::EPSILON * time.abs().max(target.abs())
}
