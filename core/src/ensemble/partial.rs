//! The result of running some members of an ensemble: every completed member's observables,
//! every failure, and which members were run. Partials of disjoint members merge exactly.
//!
//! A partial keeps the values themselves (8 bytes per member and observable, plus 8 bytes for
//! the member's index) in member-index order, and computes statistics from them on demand.
//! Merging is therefore an order-preserving interleave: associative, commutative, exact, and
//! the statistics of merged shards are bit-identical to those of one run over all members.

use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::ops::Range;

use super::report::Failure;
use super::statistics::{summarize, StatisticsError, Summary, SummaryConfig};

/// Observables and failures of a set of members of one ensemble (see the module docs).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(try_from = "super::wire::PartialData<P, E>"))]
pub struct Partial<P, E> {
    pub(super) seed: u64,
    pub(super) observables: Vec<String>,
    /// The members run, as sorted, disjoint, non-adjacent ranges.
    pub(super) covered: Vec<Range<u64>>,
    /// Indices of the completed members, ascending.
    pub(super) indices: Vec<u64>,
    /// `values[k][j]`: observable k of member `indices[j]`.
    pub(super) values: Vec<Vec<f64>>,
    /// The failed members, by ascending index.
    pub(super) failures: Vec<Failure<P, E>>,
}

/// Why two partials cannot be merged.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MergeError {
    /// They come from ensembles with different seeds.
    #[error("the partials have different seeds ({left} and {right})")]
    SeedMismatch {
        /// Seed of the left partial.
        left: u64,
        /// Seed of the right partial.
        right: u64,
    },
    /// They observe different quantities.
    #[error("the partials have different observables")]
    ObservableMismatch,
    /// Both ran this member.
    #[error("member {index} is in both partials")]
    Overlap {
        /// The first member found in both.
        index: u64,
    },
}

impl<P, E> Partial<P, E> {
    /// An empty partial of the ensemble with `seed` and these observables.
    pub(crate) fn empty(seed: u64, observables: &[&str]) -> Self {
        Self {
            seed,
            observables: observables.iter().map(|name| name.to_string()).collect(),
            covered: Vec::new(),
            indices: Vec::new(),
            values: observables.iter().map(|_| Vec::new()).collect(),
            failures: Vec::new(),
        }
    }

    /// Appends the outcome of member `index`, which must follow every member already here.
    pub(crate) fn push<const K: usize>(
        &mut self,
        index: u64,
        outcome: Result<[f64; K], Failure<P, E>>,
    ) {
        match outcome {
            Ok(values) => {
                self.indices.push(index);
                for (column, value) in self.values.iter_mut().zip(values) {
                    column.push(value);
                }
            }
            Err(failure) => self.failures.push(failure),
        }
        match self.covered.last_mut() {
            Some(last) if last.end == index => last.end = index + 1,
            _ => self.covered.push(index..index + 1),
        }
    }

    /// The ensemble's seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The observables' names, in the order of the member closure's array.
    pub fn observables(&self) -> &[String] {
        &self.observables
    }

    /// The members run, as sorted, disjoint ranges.
    pub fn covered(&self) -> &[Range<u64>] {
        &self.covered
    }

    /// How many members were run (completed or failed).
    pub fn member_count(&self) -> u64 {
        self.covered
            .iter()
            .map(|range| range.end - range.start)
            .sum()
    }

    /// Indices of the members that completed, ascending.
    pub fn completed(&self) -> &[u64] {
        &self.indices
    }

    /// The values of observable `k` for the completed members, in index order.
    pub fn values(&self, k: usize) -> Option<&[f64]> {
        self.values.get(k).map(Vec::as_slice)
    }

    /// The index of the observable called `name`.
    pub fn observable_index(&self, name: &str) -> Option<usize> {
        self.observables.iter().position(|n| n == name)
    }

    /// The failed members, by ascending index.
    pub fn failures(&self) -> &[Failure<P, E>] {
        &self.failures
    }

    /// The statistics of the observable called `name`.
    pub fn summary(&self, name: &str, config: &SummaryConfig) -> Result<Summary, StatisticsError> {
        let k = self
            .observable_index(name)
            .ok_or(StatisticsError::UnknownObservable)?;
        summarize(&self.values[k], config)
    }

    /// The same partial with every failure's run error mapped by `f` (e.g. to an
    /// [`ErrorRecord`](super::ErrorRecord) that serializes).
    pub fn map_errors<E2>(self, mut f: impl FnMut(E) -> E2) -> Partial<P, E2> {
        use super::report::MemberError;
        let failures = self
            .failures
            .into_iter()
            .map(|failure| Failure {
                index: failure.index,
                params: failure.params,
                error: match failure.error {
                    MemberError::Run(error) => MemberError::Run(f(error)),
                    MemberError::NonFiniteObservable { observable, value } => {
                        MemberError::NonFiniteObservable { observable, value }
                    }
                },
            })
            .collect();
        Partial {
            seed: self.seed,
            observables: self.observables,
            covered: self.covered,
            indices: self.indices,
            values: self.values,
            failures,
        }
    }

    /// The partial of the members of both, which must come from the same ensemble and share
    /// no member. The result depends only on the members, not on the order of merging.
    pub fn merge(self, other: Self) -> Result<Self, MergeError> {
        if self.seed != other.seed {
            return Err(MergeError::SeedMismatch {
                left: self.seed,
                right: other.seed,
            });
        }
        if self.observables != other.observables {
            return Err(MergeError::ObservableMismatch);
        }
        let covered = union(&self.covered, &other.covered)?;
        let (indices, values) = interleave(
            (&self.indices, &self.values),
            (&other.indices, &other.values),
        );
        let mut failures = self.failures;
        failures.extend(other.failures);
        failures.sort_by_key(|failure| failure.index);
        Ok(Self {
            seed: self.seed,
            observables: self.observables,
            covered,
            indices,
            values,
            failures,
        })
    }
}

/// The union of two sorted lists of disjoint ranges, coalescing adjacent ones; an error if
/// they share a member.
fn union(left: &[Range<u64>], right: &[Range<u64>]) -> Result<Vec<Range<u64>>, MergeError> {
    let mut all: Vec<Range<u64>> = left.iter().chain(right).cloned().collect();
    all.sort_by_key(|range| range.start);
    let mut merged: Vec<Range<u64>> = Vec::with_capacity(all.len());
    for range in all {
        match merged.last_mut() {
            Some(last) if range.start < last.end => {
                return Err(MergeError::Overlap { index: range.start })
            }
            Some(last) if range.start == last.end => last.end = range.end,
            _ => merged.push(range),
        }
    }
    Ok(merged)
}

type Columns<'a> = (&'a [u64], &'a [Vec<f64>]);

/// Interleaves two sets of completed members (disjoint, each ascending) into one ascending.
fn interleave(left: Columns<'_>, right: Columns<'_>) -> (Vec<u64>, Vec<Vec<f64>>) {
    let total = left.0.len() + right.0.len();
    let mut indices = Vec::with_capacity(total);
    let mut values: Vec<Vec<f64>> = left.1.iter().map(|_| Vec::with_capacity(total)).collect();
    let (mut i, mut j) = (0, 0);
    while i < left.0.len() || j < right.0.len() {
        let take_left = j == right.0.len() || (i < left.0.len() && left.0[i] < right.0[j]);
        let (source, position) = if take_left { (left, i) } else { (right, j) };
        indices.push(source.0[position]);
        for (column, source_column) in values.iter_mut().zip(source.1) {
            column.push(source_column[position]);
        }
        if take_left {
            i += 1;
        } else {
            j += 1;
        }
    }
    (indices, values)
}
