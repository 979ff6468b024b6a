//! Ensembles: many runs of one model with sampled parameters, in parallel, reproducible and
//! shardable (feature `ensemble`; `parallel` runs the members over all cores with rayon,
//! `serde` makes partial results serialize).
//!
//! An [`Ensemble`] has a seed, the names of `K` observables, a *sampler* that draws a member's
//! parameters from the member's own random stream ([`member_rng`]: a function of the seed and
//! the member index only), and a *member* closure that builds the system, stepper, initial
//! state and events from the parameters, runs them (with [`run`](crate::run::run), or several
//! runs for several phases) and returns the `K` observables of the solution. (A stepper
//! borrows its system and an event may borrow a closure, so both are built inside the member
//! closure, with the stepper settings and events the caller chose: nothing is dropped.)
//!
//! * [`Ensemble::run`] runs a range of members in batches and returns a [`Partial`]: every
//!   completed member's observables and every [`Failure`] (index, parameters, typed error).
//!   A failed member never aborts the ensemble.
//! * [`Ensemble::run_until`] stops at the first batch boundary where a [`StopRule`] is met.
//! * [`Shard`] `i` of `n` runs a slice; [`Partial::merge`] joins partials (also across
//!   machines, through serde), exactly. With JSON, enable `serde_json`'s `float_roundtrip`
//!   feature: without it a float read back can be one ulp off and the merge is no longer
//!   bit-identical. A partial read back is checked (every member once, one value per
//!   observable) and refused if inconsistent.
//! * [`Partial::summary`] gives count, mean, standard deviation, extremes, quantiles and a
//!   confidence interval of the mean.
//!
//! Results and statistics are bit-identical for 1 thread, many threads, the serial build and
//! any split into shards: a member depends only on (seed, index), and every statistic is
//! computed from the values in member-index order. With `parallel`, members run on rayon's
//! global pool (`RAYON_NUM_THREADS` sets its size; or call inside `ThreadPool::install`).
//!
//! ```
//! use varmass_core::ensemble::{rand::RngExt, Ensemble, SummaryConfig};
//!
//! // Observable: x², x ~ Uniform(0, 1); E[x²] = 1/3.
//! let ensemble = Ensemble::new(42, ["square"], |rng| rng.random_range(0.0..1.0), |x: &f64| {
//!     Ok::<_, varmass_core::StepError<3>>([x * x])
//! });
//! let partial = ensemble.run(0..4000);
//! let summary = partial.summary("square", &SummaryConfig::default())?;
//! assert!(summary.confidence_interval.0 < 1.0 / 3.0 && 1.0 / 3.0 < summary.confidence_interval.1);
//! # Ok::<(), varmass_core::ensemble::StatisticsError>(())
//! ```

mod lanes;
mod partial;
mod report;
mod sampler;
mod shard;
mod statistics;
mod stop;
#[cfg(feature = "serde")]
mod wire;

use alloc::vec::Vec;
use core::ops::Range;

pub use lanes::{LaneEnsemble, DEFAULT_CHUNK_SIZE};
pub use partial::{MergeError, Partial};
pub use report::{ErrorRecord, Failure, MemberError, NonFinite};
pub use sampler::{member_rng, MemberRng};
pub use shard::{Shard, ShardError};
pub use statistics::{
    standard_normal_quantile, summarize, StatisticsError, Summary, SummaryConfig,
};
pub use stop::{StopRule, StopRuleError};

/// `rand`, re-exported so samplers use the version [`MemberRng`] implements.
pub use rand;
/// `rayon`, re-exported to build a thread pool of a chosen size for [`Ensemble::run`].
#[cfg(feature = "parallel")]
pub use rayon;

/// Members run between checks of a stop rule, unless set with [`Ensemble::batch_size`].
pub const DEFAULT_BATCH_SIZE: u64 = 1024;

/// An ensemble: seed, observable names, sampler and member closure (see the module docs).
pub struct Ensemble<const K: usize, Sample, Member> {
    seed: u64,
    observables: [&'static str; K],
    sample: Sample,
    member: Member,
    batch_size: u64,
    parallel: bool,
}

impl<const K: usize, Sample, Member> Ensemble<K, Sample, Member> {
    /// An ensemble with `seed` whose members draw their parameters with `sample` and run
    /// with `member`, which returns the named observables (or the member's error).
    pub fn new<P, E>(
        seed: u64,
        observables: [&'static str; K],
        sample: Sample,
        member: Member,
    ) -> Self
    where
        Sample: Fn(&mut MemberRng) -> P,
        Member: Fn(&P) -> Result<[f64; K], E>,
    {
        Self::from_parts(seed, observables, sample, member)
    }

    /// The ensemble with the default batching, whatever `member` is: the constructor of
    /// [`LaneEnsemble`] too, whose member function takes a chunk.
    fn from_parts(
        seed: u64,
        observables: [&'static str; K],
        sample: Sample,
        member: Member,
    ) -> Self {
        Self {
            seed,
            observables,
            sample,
            member,
            batch_size: DEFAULT_BATCH_SIZE,
            parallel: cfg!(feature = "parallel"),
        }
    }

    /// Members per batch (at least 1): a stop rule is checked after each batch, and each
    /// batch is spread over the threads, so it should be many times the thread count.
    pub fn batch_size(self, batch_size: u64) -> Self {
        Self {
            batch_size: batch_size.max(1),
            ..self
        }
    }

    /// Runs the members one after another on the calling thread even with `parallel`.
    /// The results are the same bits either way.
    pub fn serial(self) -> Self {
        Self {
            parallel: false,
            ..self
        }
    }

    /// The seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// `members` cut into consecutive batches.
    fn batches(&self, members: Range<u64>) -> impl Iterator<Item = Range<u64>> {
        let size = self.batch_size;
        let end = members.end;
        (members.start..end)
            .step_by(usize::try_from(size).unwrap_or(usize::MAX))
            .map(move |start| start..start.saturating_add(size).min(end))
    }

    /// The parameters of member `index`, drawn from its own stream.
    fn params<P>(&self, index: u64) -> P
    where
        Sample: Fn(&mut MemberRng) -> P,
    {
        (self.sample)(&mut member_rng(self.seed, index))
    }
}

impl<const K: usize, P, E, Sample, Member> Ensemble<K, Sample, Member>
where
    Sample: Fn(&mut MemberRng) -> P + Sync,
    Member: Fn(&P) -> Result<[f64; K], E> + Sync,
    P: Send,
    E: Send,
{
    /// Member `index` alone: its parameters and its observables (or why it failed), as in
    /// any run of the ensemble.
    pub fn member(&self, index: u64) -> (P, Result<[f64; K], MemberError<E>>) {
        let params = self.params(index);
        let result = (self.member)(&params)
            .map_err(MemberError::Run)
            .and_then(check_finite);
        (params, result)
    }

    /// Runs `members` and returns their observables and failures.
    pub fn run(&self, members: Range<u64>) -> Partial<P, E> {
        let mut partial = Partial::empty(self.seed, &self.observables);
        for batch in self.batches(members) {
            self.run_batch(batch, &mut partial);
        }
        partial
    }

    /// Runs shard `shard` of an ensemble of `total` members.
    pub fn run_shard(&self, shard: Shard, total: u64) -> Partial<P, E> {
        self.run(shard.members(total))
    }

    /// Runs `members` in batches until `rule` is met after a batch (or the members run out).
    /// The batches start at `members.start`, so the stopping count is the same for any
    /// thread count.
    pub fn run_until(
        &self,
        members: Range<u64>,
        rule: &StopRule,
    ) -> Result<Partial<P, E>, StopRuleError> {
        rule.validate(K)?;
        let mut partial = Partial::empty(self.seed, &self.observables);
        for batch in self.batches(members) {
            self.run_batch(batch, &mut partial);
            if rule.is_met(&partial) {
                break;
            }
        }
        Ok(partial)
    }

    /// Runs one batch (in parallel if enabled) and appends it to `partial` in index order.
    fn run_batch(&self, batch: Range<u64>, partial: &mut Partial<P, E>) {
        let outcome = |index: u64| {
            let (params, result) = self.member(index);
            result.map_err(|error| Failure {
                index,
                params,
                error,
            })
        };
        let outcomes: Vec<_> = if self.parallel {
            collect_parallel(batch.clone(), &outcome)
        } else {
            batch.clone().map(outcome).collect()
        };
        for (index, outcome) in batch.zip(outcomes) {
            partial.push(index, outcome);
        }
    }
}

/// The outcomes of `batch`, computed on rayon's current pool, in index order.
#[cfg(feature = "parallel")]
fn collect_parallel<T: Send>(batch: Range<u64>, outcome: &(impl Fn(u64) -> T + Sync)) -> Vec<T> {
    use rayon::prelude::*;
    batch.into_par_iter().map(outcome).collect()
}

/// Without `parallel`, the serial loop.
#[cfg(not(feature = "parallel"))]
fn collect_parallel<T: Send>(batch: Range<u64>, outcome: &(impl Fn(u64) -> T + Sync)) -> Vec<T> {
    batch.map(outcome).collect()
}

/// The observables if all are finite, else which one is not.
fn check_finite<const K: usize, E>(values: [f64; K]) -> Result<[f64; K], MemberError<E>> {
    match values
        .iter()
        .enumerate()
        .find_map(|(k, &value)| Some((k, NonFinite::of(value)?)))
    {
        Some((observable, value)) => Err(MemberError::NonFiniteObservable { observable, value }),
        None => Ok(values),
    }
}
