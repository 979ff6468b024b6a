//! The stop rule: end an ensemble once the confidence interval of one observable's mean is
//! narrow enough. It is checked only at batch boundaries (fixed member counts), on the values
//! in member-index order, so the member count at which it stops is the same for any number
//! of threads.

use super::partial::Partial;
use super::statistics::half_width;

/// Stop once the `confidence` interval of the mean of observable `observable` has a
/// half-width of at most `half_width`, and at least `min_members` members have completed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StopRule {
    /// Index of the observable watched.
    pub observable: usize,
    /// The target half-width z·s/√n.
    pub half_width: f64,
    /// The confidence level of the interval, in (0, 1).
    pub confidence: f64,
    /// Completed members needed before the rule may stop the ensemble (at least 2).
    pub min_members: u64,
}

impl StopRule {
    /// Stop once the 95 % interval of observable `observable` has at most this half-width,
    /// after at least 100 completed members.
    pub fn half_width(observable: usize, half_width: f64) -> Self {
        Self {
            observable,
            half_width,
            confidence: 0.95,
            min_members: 100,
        }
    }

    /// Checks the rule against an ensemble with `observables` observables.
    pub fn validate(&self, observables: usize) -> Result<(), StopRuleError> {
        if self.observable >= observables {
            return Err(StopRuleError::UnknownObservable {
                observable: self.observable,
            });
        }
        if !(self.confidence > 0.0 && self.confidence < 1.0) {
            return Err(StopRuleError::InvalidConfidence {
                confidence: self.confidence,
            });
        }
        if !(self.half_width > 0.0 && self.half_width.is_finite()) {
            return Err(StopRuleError::InvalidHalfWidth {
                half_width: self.half_width,
            });
        }
        Ok(())
    }

    /// Whether `partial` meets the rule. An unknown observable, too few values or an
    /// invalid confidence never meet it.
    pub fn is_met<P, E>(&self, partial: &Partial<P, E>) -> bool {
        let Some(values) = partial.values(self.observable) else {
            return false;
        };
        if (values.len() as u64) < self.min_members {
            return false;
        }
        half_width(values, self.confidence).is_ok_and(|width| width <= self.half_width)
    }
}

/// A stop rule that could never be met.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum StopRuleError {
    /// The observable index is out of range.
    #[error("the stop rule watches observable {observable}, which does not exist")]
    UnknownObservable {
        /// The index given.
        observable: usize,
    },
    /// The confidence level is not in (0, 1).
    #[error("the stop rule's confidence {confidence} is not in (0, 1)")]
    InvalidConfidence {
        /// The level given.
        confidence: f64,
    },
    /// The target half-width is not positive and finite.
    #[error("the stop rule's half-width {half_width} is not positive and finite")]
    InvalidHalfWidth {
        /// The target given.
        half_width: f64,
    },
}
