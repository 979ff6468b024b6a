//! Taylor's method over lanes: W members at once, each with its own order and step, each
//! lane giving bit for bit what [`Taylor`] driven by [`run`](crate::run::run) gives that
//! member alone.
//!
//! Nothing of the method is written here. The expansion is the generated recurrences
//! (`emit = [..., "taylor", "lanes"]`: the one per-order function of the scalar
//! `taylor_coefficients`, instantiated over [`Lanes<W>`]); everything else is each
//! member's own scalar [`Taylor`] stepper: its order (`Taylor::plan`, from the tolerance
//! and its state's norm), then, given its lane of the expansion
//! (`Taylor::expanded_elsewhere`), its step, compensated sum and acceptance
//! (`Taylor::take_step`), and its series as the dense output events are located on
//! (`lanes/events.rs`, the Dormand–Prince lanes' bookkeeping).
//!
//! One order per lane, one expansion for all: the lanes expand to the largest order any
//! of them asks for, and each lane takes its own order's coefficients. Coefficient k reads
//! only coefficients 0..=k, so a lane's truncated expansion is the scalar one to the bit,
//! and its order and step are the scalar stepper's: a shared order would change both
//! (docs/ensembles.md, the measured cost of either). A member whose step fails (a
//! non-finite or non-positive state, a step that makes no progress) is flown again alone
//! on the scalar path from its start: the scalar run's recovery (a step refused for a mass
//! landed on by halves) and typed error, its time and state, are then the member's.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::dormand_prince::Kernel;
use super::events::after_step;
use super::member::{start_with, LaneEnd, LaneJob, Member};
use super::{lane, LaneState, LaneSystem, Lanes};
use crate::error::StepError;
use crate::run::{run, RunConfig};
use crate::scratch::{Scratch, LEN};
use crate::solution::StopReason;
use crate::stepper::Stepper;
use crate::steppers::taylor::{rules, Plan};
use crate::steppers::{Taylor, TaylorControl};

/// A member in its lane, stepped by its own scalar Taylor stepper.
type TaylorMember<'s, 'e, Sys, const N: usize, const S: usize> =
    Member<'s, 'e, Sys, S, Taylor<'s, Sys, N, S>>;

/// A member's end, or its error, by job.
type Ends<const S: usize> = Vec<Option<Result<LaneEnd<S>, StepError<S>>>>;

/// The expansion of every lane: its point and the coefficients, with the scratch the
/// generated recurrences work in.
struct Expansion<const S: usize, const W: usize> {
    t: Lanes<W>,
    y: LaneState<S, W>,
    coefficients: [LaneState<S, W>; LEN],
    scratch: Scratch<Lanes<W>>,
}

/// [`run_lanes`](super::run_lanes) with a [`TaylorControl`]: every job to its first
/// stopping event or `config.end_time`, W members at a time.
pub(super) fn run_taylor<Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &[LaneJob<'_, Sys, S>],
    control: TaylorControl,
    config: &RunConfig,
    kernel: Kernel,
) -> Vec<Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    let mut results: Ends<S> = (0..jobs.len()).map(|_| None).collect();
    let Some(first) = jobs.first() else {
        return Vec::new();
    };
    let mut parameters = Sys::splat(&first.system);
    let mut expansion = Expansion::<S, W>::new();
    if !expansion.emitted::<Sys, N>(&parameters) {
        return refuse_all(jobs);
    }
    let mut lanes: [Option<TaylorMember<'_, '_, Sys, N, S>>; W] = core::array::from_fn(|_| None);
    let mut queue = 0..jobs.len();
    let rules = rules(control);
    loop {
        for (index, slot) in lanes.iter_mut().enumerate() {
            while slot.is_none() {
                let Some(job) = queue.next() else { break };
                // A run that ends before its first step keeps the probe: its start's
                // error (a singular mass matrix) is then the scalar run's.
                let ends_at_once = config.max_steps == 0 || config.end_time == jobs[job].time;
                let make = |system, time, state| match ends_at_once {
                    true => Taylor::new(system, time, state, control),
                    false => Taylor::in_lanes(system, (time, state), control, rules),
                };
                match start_with::<Sys, _, N, S, W>(jobs, job, config, make) {
                    Ok(member) => {
                        Sys::set_lane(&mut parameters, index, &jobs[job].system);
                        *slot = Some(member);
                    }
                    Err(done) => results[job] = Some(done),
                }
            }
        }
        let plans = lanes
            .each_ref()
            .map(|slot| slot.as_ref().map(|m| m.core.plan()));
        let Some(order) = plans.iter().flatten().map(|plan| plan.order).max() else {
            break;
        };
        expansion.load(&lanes);
        expansion.kernel::<Sys, N>(kernel, &parameters, order);
        for (index, slot) in lanes.iter_mut().enumerate() {
            let (Some(member), Some(plan)) = (slot.as_mut(), plans[index]) else {
                continue;
            };
            let outcome = conclude(member, &expansion, index, plan, config);
            let end = match outcome {
                Ok(None) => continue,
                Ok(Some(end)) => Ok(end),
                Err(Failure::Run(error)) => Err(error),
                Err(Failure::Step) => scalar_run::<Sys, N, S>(&jobs[member.job], control, config),
            };
            results[member.job] = Some(end);
            *slot = None;
        }
    }
    results
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err(unfinished())))
        .collect()
}

/// How a member's step went wrong: its stepper failed (the member is flown again on the
/// scalar path), or the run did after an accepted step (its error stands).
enum Failure<const S: usize> {
    Step,
    Run(StepError<S>),
}

/// Lane `index`'s step for its member: its coefficients handed to its stepper, the step
/// taken, then the run's bookkeeping (flows, events, end). `Ok(Some)` when the run ends.
fn conclude<Sys, const N: usize, const S: usize, const W: usize>(
    member: &mut TaylorMember<'_, '_, Sys, N, S>,
    expansion: &Expansion<S, W>,
    index: usize,
    plan: Plan,
    config: &RunConfig,
) -> Result<Option<LaneEnd<S>>, Failure<S>>
where
    Sys: LaneSystem<N, S, W>,
{
    let coefficient = |k: usize| lane(&expansion.coefficients[k], index);
    let stepper = &mut member.core;
    let stepped = stepper
        .expanded_elsewhere(plan.order, coefficient)
        .and_then(|()| stepper.take_step(plan));
    let Ok(outcome) = stepped else {
        return Err(Failure::Step);
    };
    // The dense output is the stepper's series (`Taylor::interpolate`).
    after_step::<Sys, _, _, N, S, W>(member, |core| core, outcome, config).map_err(Failure::Run)
}

/// The member's run on the scalar path, from its start: what the lanes give a member
/// whose step failed.
fn scalar_run<Sys, const N: usize, const S: usize>(
    job: &LaneJob<'_, Sys, S>,
    control: TaylorControl,
    config: &RunConfig,
) -> Result<LaneEnd<S>, StepError<S>>
where
    Sys: crate::system::VariableMassSystem<N, S>,
{
    let mut stepper = Taylor::new(&job.system, job.time, job.state, control)?;
    let solution = run(&mut stepper, config, job.events).map_err(|failure| failure.error)?;
    let (time, state) = match solution.last() {
        Some((time, state)) => (time, *state),
        None => (job.time, job.state),
    };
    let event = match solution.stop {
        StopReason::EventFound { index } => Some(index),
        _ => None,
    };
    Ok(LaneEnd {
        time,
        state,
        event,
        statistics: solution.statistics,
    })
}

/// Every job's error when the system has no Taylor recurrences over lanes.
fn refuse_all<Sys, const S: usize>(
    jobs: &[LaneJob<'_, Sys, S>],
) -> Vec<Result<LaneEnd<S>, StepError<S>>> {
    let reason = "lanes: the system has no Taylor recurrences over lanes (generate them \
                  with emit = [..., \"taylor\", \"lanes\"])";
    jobs.iter()
        .map(|job| {
            Err(StepError::invalid_configuration(
                job.time, job.state, reason,
            ))
        })
        .collect()
}

/// The error of a job the loop never finished (it cannot happen: every job is started,
/// and a started member ends with a result).
fn unfinished<const S: usize>() -> StepError<S> {
    StepError::invalid_configuration(f64::NAN, SVector::zeros(), "a lane job never finished")
}

impl<const S: usize, const W: usize> Expansion<S, W> {
    fn new() -> Self {
        let zero = [Lanes::default(); S];
        Self {
            t: Lanes::default(),
            y: zero,
            coefficients: [zero; LEN],
            scratch: Scratch::default(),
        }
    }

    /// Whether the system's Taylor recurrences over lanes were generated.
    fn emitted<Sys, const N: usize>(&mut self, parameters: &Sys::Parameters) -> bool
    where
        Sys: LaneSystem<N, S, W>,
    {
        let (t, y) = (self.t, self.y);
        let probe = &mut self.coefficients[..1];
        Sys::taylor_coefficients_lanes(parameters, t, &y, probe, &mut self.scratch).is_some()
    }

    /// Each member's point into its lane; an empty lane repeats an occupied one's point
    /// (its result unread). Its parameters stay those of the member it last held, so its
    /// expansion may leave the domain (a NaN, never read: each lane's stepper reads only its
    /// own lane).
    fn load<Sys, const N: usize>(&mut self, lanes: &[Option<TaylorMember<'_, '_, Sys, N, S>>; W])
    where
        Sys: LaneSystem<N, S, W>,
    {
        let busy = lanes.iter().position(Option::is_some).unwrap_or(0);
        for i in 0..W {
            let Some(member) = lanes[i].as_ref().or(lanes[busy].as_ref()) else {
                continue;
            };
            let progress = member.core.parts().1;
            self.t.0[i] = progress.time();
            for (j, x) in progress.state().iter().enumerate() {
                self.y[j].0[i] = *x;
            }
        }
    }

    /// The expansion of every lane to `order`, called from a frame compiled for AVX where
    /// the CPU has it (as the Dormand–Prince lanes' kernel; never FMA). The generated
    /// `taylor_coefficients_lanes` is not inlined into it, so the expansion itself is
    /// compiled for the default target (SSE2's two lanes) either way: the AVX entry gains
    /// nothing yet (the review of session 39 found no ymm instruction in the bench binary's
    /// expansion).
    fn kernel<Sys, const N: usize>(
        &mut self,
        kernel: Kernel,
        parameters: &Sys::Parameters,
        order: usize,
    ) where
        Sys: LaneSystem<N, S, W>,
    {
        match kernel {
            Kernel::Portable => self.expand::<Sys, N>(parameters, order),
            // SAFETY: `Kernel::Avx` is only chosen where the CPU has AVX (`Kernel::detect`).
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            Kernel::Avx => unsafe { self.expand_avx::<Sys, N>(parameters, order) },
        }
    }

    /// The generated recurrences over lanes, to `order`.
    #[inline(always)]
    fn expand<Sys, const N: usize>(&mut self, parameters: &Sys::Parameters, order: usize)
    where
        Sys: LaneSystem<N, S, W>,
    {
        let coefficients = &mut self.coefficients[..=order];
        // Lanes never fail (a lane's non-finite coefficient is its stepper's to find).
        let _ = Sys::taylor_coefficients_lanes(
            parameters,
            self.t,
            &self.y,
            coefficients,
            &mut self.scratch,
        );
    }

    /// [`Self::expand`] compiled for AVX.
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    fn expand_avx<Sys, const N: usize>(&mut self, parameters: &Sys::Parameters, order: usize)
    where
        Sys: LaneSystem<N, S, W>,
    {
        self.expand::<Sys, N>(parameters, order);
    }
}
