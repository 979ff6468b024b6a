//! What an adaptive stepper with FSAL carries from one step to the next (the explicit pairs
//! Dormand–Prince and DOP853 with their PI controllers, and the diagonally implicit
//! stepper of SDIRK4 and ESDIRK4(3), which leaves the PI memory unused), and the
//! bookkeeping they do the same way: the rate at the start of a step, a rejection, the step
//! after an acceptance, a restart. Each stepper keeps its own controller formula (the
//! exponents and factors differ).

use nalgebra::SVector;

use crate::error::StepError;
use crate::stepper::{state_rate, Progress};
use crate::system::VariableMassSystem;

/// The PI controller's memory of the last accepted error before any step, and its floor.
const ERROR_FLOOR: f64 = 1e-4;

/// The adaptive-control state of an embedded pair.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ControlState<const S: usize> {
    /// The size of the next step to try (0 until the first step chooses it).
    pub(crate) next_step: f64,
    /// The size of the last accepted step, for the dense output (0 before any).
    pub(crate) last_step: f64,
    /// The PI controller's memory of the last accepted error (at least 1e-4).
    pub(crate) previous_error: f64,
    /// Whether the last attempt was rejected, so the next step may not grow.
    pub(crate) last_rejected: bool,
    /// The rate at the current state (FSAL), if known.
    pub(crate) current_rate: Option<SVector<f64, S>>,
}

impl<const S: usize> ControlState<S> {
    /// The state before the first step.
    pub(crate) fn new() -> Self {
        Self {
            next_step: 0.0,
            last_step: 0.0,
            previous_error: ERROR_FLOOR,
            last_rejected: false,
            current_rate: None,
        }
    }

    /// Forgets what belongs to the old initial value (the FSAL rate, the last step, the
    /// controller's memory); the proposed next step is kept.
    pub(crate) fn restart(&mut self) {
        *self = Self {
            next_step: self.next_step,
            ..Self::new()
        };
    }

    /// The rate at the current state: the last stage of the previous step (FSAL), or
    /// evaluated once after a start or restart.
    pub(crate) fn rate_at_start<Sys, const N: usize>(
        &mut self,
        system: &Sys,
        progress: &mut Progress<S>,
    ) -> Result<SVector<f64, S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if let Some(rate) = self.current_rate {
            return Ok(rate);
        }
        let (time, state) = (progress.time(), *progress.state());
        let rate = state_rate(system, &mut progress.statistics, time, &state)?;
        self.current_rate = Some(rate);
        Ok(rate)
    }

    /// Records a rejected attempt (counted in `progress`): the next attempt has size `next`.
    pub(crate) fn reject(&mut self, next: f64, progress: &mut Progress<S>) {
        self.next_step = next;
        self.last_rejected = true;
        progress.statistics.rejected_steps += 1;
    }

    /// The controller's proposal `next` after an accepted step of size `h` with `error`,
    /// not growing right after a rejection; remembers the error for the PI term.
    pub(crate) fn after_acceptance(&mut self, h: f64, next: f64, error: f64) -> f64 {
        let next = if self.last_rejected {
            next.min(h)
        } else {
            next
        };
        self.previous_error = error.max(ERROR_FLOOR);
        self.last_rejected = false;
        next
    }

    /// Takes `next` (at most `max_step`) as the next step to try, unless the accepted step
    /// was cut short to land on the stop time and the step already proposed is longer.
    pub(crate) fn propose(&mut self, next: f64, reaches_stop: bool, max_step: f64) {
        if !reaches_stop || next > self.next_step {
            self.next_step = next.min(max_step);
        }
    }

    /// Records an accepted step of size `h` whose last rate is `rate` (FSAL).
    pub(crate) fn accepted(&mut self, h: f64, rate: SVector<f64, S>) {
        self.current_rate = Some(rate);
        self.last_step = h;
    }
}
