//! An ensemble whose members are flown in chunks — W at a time in SIMD lanes by
//! [`run_lanes`](crate::lanes::run_lanes) — with the same members, the same random streams
//! and the same statistics in index order as [`Ensemble`](super::Ensemble): when the chunk
//! function gives each member what the member function gives it (the lanes are
//! bit-identical to the scalar path), the two [`Partial`]s are equal.

use alloc::vec::Vec;
use core::ops::Range;

use super::{
    check_finite, collect_parallel, member_rng, Failure, MemberError, MemberRng, Partial,
    DEFAULT_BATCH_SIZE,
};

/// Members per call of the chunk function by default: enough for every lane to be
/// refilled many times (members take different numbers of steps), few enough that the
/// chunks of a batch spread over the threads.
pub const DEFAULT_CHUNK_SIZE: usize = 64;

/// A reproducible ensemble whose members are evaluated a chunk at a time (see the module
/// docs): `chunk` receives the parameters of consecutive members and returns their results
/// in the same order.
pub struct LaneEnsemble<const K: usize, Sample, Chunk> {
    seed: u64,
    observables: [&'static str; K],
    sample: Sample,
    chunk: Chunk,
    chunk_size: usize,
    batch_size: u64,
    parallel: bool,
}

impl<const K: usize, Sample, Chunk> LaneEnsemble<K, Sample, Chunk> {
    /// An ensemble of members drawn by `sample` from (seed, index) and evaluated by
    /// `chunk`, [`DEFAULT_CHUNK_SIZE`] members per call, in parallel when the `parallel`
    /// feature is on.
    pub fn new<P, E>(
        seed: u64,
        observables: [&'static str; K],
        sample: Sample,
        chunk: Chunk,
    ) -> Self
    where
        Sample: Fn(&mut MemberRng) -> P,
        Chunk: Fn(&[P]) -> Vec<Result<[f64; K], E>>,
    {
        Self {
            seed,
            observables,
            sample,
            chunk,
            chunk_size: DEFAULT_CHUNK_SIZE,
            batch_size: DEFAULT_BATCH_SIZE,
            parallel: cfg!(feature = "parallel"),
        }
    }

    /// Members per call of the chunk function (at least 1).
    pub fn chunk_size(self, chunk_size: usize) -> Self {
        Self {
            chunk_size: chunk_size.max(1),
            ..self
        }
    }

    /// Members per batch (as [`Ensemble::batch_size`](super::Ensemble::batch_size)).
    pub fn batch_size(self, batch_size: u64) -> Self {
        Self {
            batch_size: batch_size.max(1),
            ..self
        }
    }

    /// Runs on the calling thread only.
    pub fn serial(self) -> Self {
        Self {
            parallel: false,
            ..self
        }
    }
}

impl<const K: usize, P, E, Sample, Chunk> LaneEnsemble<K, Sample, Chunk>
where
    Sample: Fn(&mut MemberRng) -> P + Sync,
    Chunk: Fn(&[P]) -> Vec<Result<[f64; K], E>> + Sync,
    P: Send,
    E: Send,
{
    /// Runs members `members`, batch by batch, into a [`Partial`] in index order.
    ///
    /// # Panics
    ///
    /// If the chunk function returns other than one result per member it was given (a
    /// bug in that function, which no result could stand for).
    pub fn run(&self, members: Range<u64>) -> Partial<P, E> {
        let mut partial = Partial::empty(self.seed, &self.observables);
        let size = usize::try_from(self.batch_size).unwrap_or(usize::MAX);
        for start in (members.start..members.end).step_by(size) {
            let batch = start..start.saturating_add(self.batch_size).min(members.end);
            self.run_batch(batch, &mut partial);
        }
        partial
    }

    fn run_batch(&self, batch: Range<u64>, partial: &mut Partial<P, E>) {
        let chunk_size = self.chunk_size as u64;
        let chunks: Vec<Range<u64>> = (batch.start..batch.end)
            .step_by(self.chunk_size)
            .map(|start| start..(start + chunk_size).min(batch.end))
            .collect();
        let outcomes: Vec<Vec<_>> = if self.parallel {
            collect_parallel(0..chunks.len() as u64, &|i| {
                self.run_chunk(&chunks[i as usize])
            })
        } else {
            chunks.iter().map(|chunk| self.run_chunk(chunk)).collect()
        };
        for (index, outcome) in batch.zip(outcomes.into_iter().flatten()) {
            partial.push(index, outcome);
        }
    }

    /// The members of `chunk`, sampled and flown, as the scalar ensemble records them.
    #[allow(clippy::type_complexity)]
    fn run_chunk(&self, chunk: &Range<u64>) -> Vec<Result<[f64; K], Failure<P, E>>> {
        let params: Vec<P> = chunk
            .clone()
            .map(|index| (self.sample)(&mut member_rng(self.seed, index)))
            .collect();
        let results = (self.chunk)(&params);
        // The chunk function's contract, as `Iterator::zip` would hide its breach.
        assert_eq!(
            results.len(),
            params.len(),
            "a LaneEnsemble's chunk function must return one result per member"
        );
        chunk
            .clone()
            .zip(params)
            .zip(results)
            .map(|((index, params), result)| {
                let result = result.map_err(MemberError::Run).and_then(check_finite);
                result.map_err(|error| Failure {
                    index,
                    params,
                    error,
                })
            })
            .collect()
    }
}
