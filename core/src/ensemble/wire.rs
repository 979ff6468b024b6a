//! A [`Partial`] read back from a file is checked before use: a partial that was edited or
//! truncated is refused at deserialization, instead of merging into wrong statistics.

use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;
use core::ops::Range;

use super::partial::Partial;
use super::report::Failure;

/// The fields of a [`Partial`] as they are serialized, not yet checked.
#[derive(serde::Deserialize)]
pub(super) struct PartialData<P, E> {
    seed: u64,
    observables: Vec<String>,
    covered: Vec<Range<u64>>,
    indices: Vec<u64>,
    values: Vec<Vec<f64>>,
    failures: Vec<Failure<P, E>>,
}

/// Why serialized data is not a partial.
#[derive(Debug)]
pub(super) struct Inconsistent(&'static str);

impl fmt::Display for Inconsistent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "inconsistent partial ensemble result: {}", self.0)
    }
}

impl<P, E> TryFrom<PartialData<P, E>> for Partial<P, E> {
    type Error = Inconsistent;

    fn try_from(data: PartialData<P, E>) -> Result<Self, Inconsistent> {
        if data.values.len() != data.observables.len() {
            return Err(Inconsistent("one column of values per observable"));
        }
        if data.values.iter().any(|c| c.len() != data.indices.len()) {
            return Err(Inconsistent("one value per completed member"));
        }
        if data.values.iter().flatten().any(|v| !v.is_finite()) {
            return Err(Inconsistent("a value is not finite"));
        }
        let ranges_ordered = data.covered.iter().all(|r| r.start < r.end)
            && data.covered.windows(2).all(|w| w[0].end < w[1].start);
        if !ranges_ordered {
            return Err(Inconsistent(
                "covered ranges sorted, disjoint and not empty",
            ));
        }
        let failed: Vec<u64> = data.failures.iter().map(|f| f.index).collect();
        if !accounts_for(&data.covered, &data.indices, &failed) {
            return Err(Inconsistent(
                "every covered member is completed or failed, once, in order",
            ));
        }
        Ok(Self {
            seed: data.seed,
            observables: data.observables,
            covered: data.covered,
            indices: data.indices,
            values: data.values,
            failures: data.failures,
        })
    }
}

/// Whether `completed` and `failed` (each ascending) together list every member of
/// `covered` exactly once.
fn accounts_for(covered: &[Range<u64>], completed: &[u64], failed: &[u64]) -> bool {
    let total: u64 = covered.iter().map(|r| r.end - r.start).sum();
    if total != (completed.len() + failed.len()) as u64 {
        return false;
    }
    let (mut i, mut j) = (0, 0);
    for member in covered.iter().flat_map(Clone::clone) {
        if completed.get(i) == Some(&member) {
            i += 1;
        } else if failed.get(j) == Some(&member) {
            j += 1;
        } else {
            return false;
        }
    }
    true
}
