//! A run that failed: the typed error with the solution computed up to the failure, so a
//! failure never loses the points before it.

use alloc::boxed::Box;
use core::fmt;
use core::ops::Deref;

use crate::error::StepError;
use crate::solution::Solution;

/// The failure of a [`run`](crate::run::run): the [`StepError`] (time, state, kind) and the
/// [`Solution`] up to the last accepted point, its `stop` [`StopReason::Failed`](crate::StopReason::Failed).
///
/// It dereferences to the [`StepError`], so `error.kind`, `error.time` and `error.state`
/// read as before, and `?` turns it into a `StepError` where a function returns one.
/// Displayed as the step error is.
#[derive(Clone, Debug, PartialEq)]
pub struct RunError<const N: usize, const S: usize> {
    /// What went wrong, when and where.
    pub error: StepError<S>,
    /// Every point computed before the failure (empty when the run failed before its first
    /// point, e.g. on an invalid configuration).
    pub partial: Box<Solution<N, S>>,
}

impl<const N: usize, const S: usize> RunError<N, S> {
    /// The error without the points.
    pub fn into_step_error(self) -> StepError<S> {
        self.error
    }
}

impl<const N: usize, const S: usize> Deref for RunError<N, S> {
    type Target = StepError<S>;

    fn deref(&self) -> &StepError<S> {
        &self.error
    }
}

impl<const N: usize, const S: usize> fmt::Display for RunError<N, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.error, f)
    }
}

impl<const N: usize, const S: usize> core::error::Error for RunError<N, S> {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        core::error::Error::source(&self.error)
    }
}

impl<const N: usize, const S: usize> From<RunError<N, S>> for StepError<S> {
    fn from(error: RunError<N, S>) -> Self {
        error.error
    }
}
