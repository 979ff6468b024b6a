//! An ensemble whose members are flown in chunks — W at a time in SIMD lanes by
//! [`run_lanes`](crate::lanes::run_lanes) — with the same members, the same random streams
//! and the same statistics in index order as [`Ensemble`](super::Ensemble): when the chunk
//! function gives each member what the member function gives it (the lanes are
//! bit-identical to the scalar path), the two [`Partial`]s are equal.

use alloc::vec::Vec;
use core::ops::Range;

use super::{check_finite, collect_parallel, Ensemble, Failure, MemberError, MemberRng, Partial};

/// Members per call of the chunk function by default: enough for every lane to be
/// refilled many times (members take different numbers of steps), few enough that the
/// chunks of a batch spread over the threads.
pub const DEFAULT_CHUNK_SIZE: usize = 64;

/// A reproducible ensemble whose members are evaluated a chunk at a time (see the module
/// docs): `chunk` receives the parameters of consecutive members and returns their results
/// in the same order.
pub struct LaneEnsemble<const K: usize, Sample, Chunk> {
    /// The seed, the observables, the sampler and the batching, held as an [`Ensemble`]
    /// whose member function is the chunk function: the settings and their builder methods
    /// are [`Ensemble`]'s, written once.
    ensemble: Ensemble<K, Sample, Chunk>,
    chunk_size: usize,
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
            ensemble: Ensemble::from_parts(seed, observables, sample, chunk),
            chunk_size: DEFAULT_CHUNK_SIZE,
        }
    }

    /// Members per call of the chunk function (at least 1).
    pub fn chunk_size(self, chunk_size: usize) -> Self {
        Self {
            chunk_size: chunk_size.max(1),
            ..self
        }
    }

    /// Members per batch (as [`Ensemble::batch_size`]).
    pub fn batch_size(self, batch_size: u64) -> Self {
        let ensemble = self.ensemble.batch_size(batch_size);
        Self { ensemble, ..self }
    }

    /// Runs on the calling thread only (as [`Ensemble::serial`]).
    pub fn serial(self) -> Self {
        let ensemble = self.ensemble.serial();
        Self { ensemble, ..self }
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
        let ensemble = &self.ensemble;
        let mut partial = Partial::empty(ensemble.seed, &ensemble.observables);
        for batch in ensemble.batches(members) {
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
        let outcomes: Vec<Vec<_>> = if self.ensemble.parallel {
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
        let params: Vec<P> = chunk.clone().map(|i| self.ensemble.params(i)).collect();
        let results = (self.ensemble.member)(&params);
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
