//! A progress bar for long runs: a [`Stepper`] adapter that forwards every call to the
//! wrapped stepper and moves an `indicatif` bar on stderr after each step, with the steps
//! taken per second. The bar appears only once the run has lasted about a second, and never
//! when stderr is not a terminal.
//!
//! The same adapter enforces what the tool checks after every step and the core's run does
//! not: the wall-clock limit (`--max-seconds`). (The flows' rates, which must stay
//! non-negative, are the core's check: `VariableMassSystem::flow_rate`.)

use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use varmass::core::nalgebra::SVector;
use varmass::core::stepper::{ProgressMut, Restarting};
use varmass::core::{Progress, StepError, StepErrorKind, StepOutcome, Stepper};

/// How long a run goes before its bar is shown.
const QUIET_FOR: Duration = Duration::from_secs(1);
/// The bar's resolution.
const TICKS: u64 = 1000;

/// A stepper with a progress bar over `[from, until]` and a wall-clock limit.
pub struct Watched<St> {
    inner: St,
    /// `None` for a library caller's run (see [`Watched::quiet`]).
    bar: Option<ProgressBar>,
    started: Instant,
    shown: bool,
    from: f64,
    until: f64,
    steps: u64,
    max_seconds: Option<f64>,
}

impl<St> Watched<St> {
    /// Wraps `inner` for a run from `from` to `until`, with no limit.
    pub fn new(inner: St, from: f64, until: f64) -> Self {
        let bar = ProgressBar::with_draw_target(Some(TICKS), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template("{bar:40} {msg} [{elapsed}, eta {eta}]") {
            bar.set_style(style);
        }
        Self::with_bar(inner, from, until, Some(bar))
    }

    /// [`Watched::new`] without a progress bar: for a library caller (the Python package,
    /// an ensemble's members), where the bar's bookkeeping at every step (a clock read and
    /// its atomics) is a cost with nothing to show, and so is making it (parsing its
    /// template and dropping it cost a 50 µs run 4 %).
    pub fn quiet(inner: St, from: f64, until: f64) -> Self {
        Self::with_bar(inner, from, until, None)
    }

    fn with_bar(inner: St, from: f64, until: f64, bar: Option<ProgressBar>) -> Self {
        Self {
            inner,
            bar,
            started: Instant::now(),
            shown: false,
            from,
            until,
            steps: 0,
            max_seconds: None,
        }
    }

    /// Fails the run with [`StepErrorKind::WallClockExceeded`] after `seconds`.
    pub fn with_time_limit(mut self, seconds: Option<f64>) -> Self {
        self.max_seconds = seconds;
        self
    }

    /// What is wrong after a step, if anything: the time limit passed.
    fn check(&self) -> Result<(), StepErrorKind> {
        match self.max_seconds {
            Some(seconds) if self.started.elapsed().as_secs_f64() > seconds => {
                Err(StepErrorKind::WallClockExceeded { seconds })
            }
            _ => Ok(()),
        }
    }

    fn tick(&mut self, time: f64) {
        let Some(bar) = &self.bar else {
            return;
        };
        if !self.shown && self.started.elapsed() >= QUIET_FOR {
            // Draws nothing when stderr is not a terminal.
            bar.set_draw_target(ProgressDrawTarget::stderr());
            self.shown = true;
        }
        let span = self.until - self.from;
        let fraction = if span > 0.0 {
            ((time - self.from) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        bar.set_position((fraction * TICKS as f64) as u64);
        self.steps += 1;
        // The message is only drawn once shown; formatting it costs more than a small step.
        if self.shown {
            let rate = self.steps as f64 / self.started.elapsed().as_secs_f64().max(1e-9);
            bar.set_message(format!(
                "t = {time:.6e}, {} steps, {rate:.0} steps/s",
                self.steps
            ));
        }
    }
}

impl<St> Drop for Watched<St> {
    fn drop(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

impl<St, const N: usize, const S: usize> Stepper<N, S> for Watched<St>
where
    St: Stepper<N, S>,
{
    type System = St::System;

    fn parts(&self) -> (&Self::System, &Progress<S>) {
        self.inner.parts()
    }

    fn parts_mut(&mut self) -> ProgressMut<'_, Self::System, S> {
        self.inner.parts_mut()
    }

    fn forget_history(&mut self, restarting: Restarting) {
        self.inner.forget_history(restarting);
    }

    fn step(&mut self) -> Result<StepOutcome, StepError<S>> {
        let outcome = self.inner.step()?;
        let (time, state) = (self.inner.time(), *self.inner.state());
        self.tick(time);
        self.check()
            .map_err(|kind| StepError::new(time, state, kind))?;
        Ok(outcome)
    }

    fn dense_output(&self, time: f64) -> Option<SVector<f64, S>> {
        self.inner.dense_output(time)
    }
}

#[cfg(test)]
mod tests {
    use varmass::core::steppers::{DormandPrince, StepControl};
    use varmass::core::{run, RunConfig};
    use varmass::interpret::{Program, TapeSystem};
    use varmass::symbolic::{derive_source, mechanics::Parameters};

    use super::*;

    /// The bar only watches: a run through it is the bare stepper's run, bit for bit.
    #[test]
    fn a_watched_run_is_the_bare_run() {
        let source = "coordinates y; mass m = m0; body b: mass m, position [y]; potential m*g*y";
        let derivation = derive_source(source, Parameters::Inferred).expect("derives");
        let program = Program::new(derivation, &[("m0", 2.0), ("g", 9.81)]).expect("fits");
        let system = TapeSystem::<1, 2>::new(program).expect("sizes");
        let start = SVector::<f64, 2>::new(0.0, 10.0);
        let stepper = || DormandPrince::new(&system, 0.0, start, StepControl::default());
        let config = RunConfig::until(3.0);
        let bare = run(&mut stepper().expect("starts"), &config, &[]).expect("runs");
        let mut watched = Watched::new(stepper().expect("starts"), 0.0, 3.0);
        let seen = run(&mut watched, &config, &[]).expect("runs");
        assert_eq!(bare, seen);
        assert_eq!(watched.bar.as_ref().map(ProgressBar::position), Some(TICKS));
        // Without the bar the run is the same run.
        let mut quiet = Watched::quiet(stepper().expect("starts"), 0.0, 3.0);
        assert_eq!(run(&mut quiet, &config, &[]).expect("runs"), bare);
        assert!(quiet.bar.is_none());
    }

    fn falling_body() -> TapeSystem<1, 2> {
        let source = "coordinates y; mass m = m0; body b: mass m, position [y]; potential m*g*y";
        let derivation = derive_source(source, Parameters::Inferred).expect("derives");
        let program = Program::new(derivation, &[("m0", 2.0), ("g", 9.81)]).expect("fits");
        TapeSystem::<1, 2>::new(program).expect("sizes")
    }

    /// A wall-clock limit of 0 s is past after the first step, which it then ends.
    #[test]
    fn the_time_limit_ends_the_run_after_a_step() {
        let system = falling_body();
        let start = SVector::<f64, 2>::new(0.0, 0.0);
        let stepper =
            DormandPrince::new(&system, 0.0, start, StepControl::default()).expect("starts");
        let mut watched = Watched::new(stepper, 0.0, 3.0).with_time_limit(Some(0.0));
        let error = run(&mut watched, &RunConfig::until(3.0), &[]).unwrap_err();
        assert_eq!(
            error.kind,
            StepErrorKind::WallClockExceeded { seconds: 0.0 }
        );
        assert_eq!(watched.steps, 1);
        assert!(error.time > 0.0 && error.time < 3.0, "{}", error.time);
    }
}
