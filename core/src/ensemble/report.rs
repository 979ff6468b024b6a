//! Failed members: which one, with which parameters, and why. A failure is recorded and the
//! ensemble goes on; it never aborts the ensemble or vanishes from its results.

use alloc::string::{String, ToString};

use crate::error::StepError;

/// Why a member produced no observables.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum MemberError<E> {
    /// The member's closure returned an error (typically the [`StepError`] of its run).
    #[error("the run failed: {0}")]
    Run(E),
    /// An observable came out NaN or infinite; it is not mixed into the statistics.
    #[error("observable {observable} is {value:?}")]
    NonFiniteObservable {
        /// Index of the observable.
        observable: usize,
        /// Which non-finite value it was.
        value: NonFinite,
    },
}

/// The kind of a non-finite number (kept as a name, since JSON has no NaN or infinity).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum NonFinite {
    /// Not a number.
    NaN,
    /// +∞.
    PositiveInfinity,
    /// −∞.
    NegativeInfinity,
}

impl NonFinite {
    /// The kind of `value`, or `None` if it is finite.
    pub fn of(value: f64) -> Option<Self> {
        if value.is_nan() {
            Some(Self::NaN)
        } else if value == f64::INFINITY {
            Some(Self::PositiveInfinity)
        } else if value == f64::NEG_INFINITY {
            Some(Self::NegativeInfinity)
        } else {
            None
        }
    }
}

/// A member that failed: its index, the parameters its sampler drew, and the error.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Failure<P, E> {
    /// The member's index.
    pub index: u64,
    /// The parameters it was built from.
    pub params: P,
    /// What went wrong.
    pub error: MemberError<E>,
}

/// A run error reduced to what any format can hold: the time of the failure and its
/// message. Map a [`Partial`](super::Partial)'s errors to it with
/// [`Partial::map_errors`](super::Partial::map_errors) to serialize a partial whose error type
/// cannot be.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[error("{message}")]
pub struct ErrorRecord {
    /// When the run failed.
    pub time: f64,
    /// The error's message.
    pub message: String,
}

impl<const S: usize> From<StepError<S>> for ErrorRecord {
    fn from(error: StepError<S>) -> Self {
        Self {
            time: error.time,
            message: error.to_string(),
        }
    }
}
