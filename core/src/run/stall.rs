//! The progress guard: a run that goes round without moving t ends with
//! [`StepErrorKind::Stalled`] at the point it stands on, its points kept, instead of
//! looping until [`StepErrorKind::TooManySteps`] (10⁷ passes by default, minutes) or for
//! ever.
//!
//! Passes that do not move the run's last point are normal in small numbers: a redo before
//! a switch restarts at the step's start, a crossing moves t by a few roundings, a sample
//! of the held inputs or a step refused for a mass retried shorter stays where it is. A
//! burst of them is bounded by its own rules (16 crossings of one switch chatter, a
//! refused step halves until it cannot). So a run that takes [`RunConfig::stall_passes`]
//! passes in a row without moving t by more than [`FEW_ROUNDINGS`] roundings from where
//! the burst began has lost its way: before issue 34, a switch standing exactly on a
//! table's knot sent the run back to the same step start 10⁷ times.
//!
//! [`RunConfig::stall_passes`]: super::RunConfig::stall_passes

use super::point::Point;
use crate::error::{StepError, StepErrorKind};

/// How many roundings of t (4 ε · |t|, relative: a run may step at any time scale, 1e-103 s
/// included, so no absolute floor) a run must move to count as progress: more than a
/// crossing's bracket (a few roundings), less than any step a stepper takes on purpose.
pub(crate) const FEW_ROUNDINGS: f64 = 16.0;

/// Counts the run's passes since its last point last moved.
pub(crate) struct ProgressGuard {
    /// Where the current burst of passes began.
    from: f64,
    /// Passes since then.
    idle: usize,
    /// The most passes a burst may take.
    limit: usize,
}

impl ProgressGuard {
    /// A guard for a run starting at `time`, failing after `limit` idle passes.
    pub(crate) fn new(time: f64, limit: usize) -> Self {
        Self {
            from: time,
            idle: 0,
            limit,
        }
    }

    /// Counts one pass that left the run's last point at `point`: progress when it moved
    /// more than a few roundings from where the burst began, else one more idle pass, the
    /// error once there are more than the limit.
    pub(crate) fn check<const S: usize>(&mut self, point: &Point<S>) -> Result<(), StepError<S>> {
        let few = FEW_ROUNDINGS * 4.0 * f64::EPSILON * self.from.abs();
        if (point.time - self.from).abs() > few {
            (self.from, self.idle) = (point.time, 0);
            return Ok(());
        }
        self.idle += 1;
        if self.idle <= self.limit {
            return Ok(());
        }
        let kind = StepErrorKind::Stalled { steps: self.idle };
        Err(StepError::new(point.time, point.state, kind))
    }
}
