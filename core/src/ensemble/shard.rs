//! Shards: slice `i` of `n` of an ensemble's members, so that a batch scheduler (a cluster's
//! job array, a CI matrix) can spread one ensemble over machines and merge the partial results.

use core::ops::Range;

/// Slice `index` of `count` equal (±1 member) slices of an ensemble.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Shard {
    index: u64,
    count: u64,
}

/// A shard that cannot exist.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("shard {index} of {count} does not exist (shards are numbered 0..count, count ≥ 1)")]
pub struct ShardError {
    /// The index asked for.
    pub index: u64,
    /// The number of shards asked for.
    pub count: u64,
}

impl Shard {
    /// Shard `index` (from 0) of `count`.
    pub fn new(index: u64, count: u64) -> Result<Self, ShardError> {
        if index >= count {
            return Err(ShardError { index, count });
        }
        Ok(Self { index, count })
    }

    /// Which shard this is, from 0.
    pub fn index(&self) -> u64 {
        self.index
    }

    /// How many shards there are.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The members of this shard out of `total`: `⌊total·i/n⌋ .. ⌊total·(i+1)/n⌋`. The shards
    /// of one `count` cover `0..total` exactly once.
    pub fn members(&self, total: u64) -> Range<u64> {
        let bound = |i: u64| (u128::from(total) * u128::from(i) / u128::from(self.count)) as u64;
        bound(self.index)..bound(self.index + 1)
    }
}
