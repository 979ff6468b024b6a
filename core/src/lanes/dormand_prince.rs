//! Dormand–Prince 5(4) over lanes: W members at once, each with its own step size, its own
//! error control and its own events, each lane giving bit for bit what
//! [`DormandPrince`](crate::steppers::DormandPrince) driven by [`run`](crate::run::run)
//! gives that member alone.
//!
//! The design is heyoka's batch mode's (Biscani & Izzo 2021, per-lane step sizes and
//! times: one integrator in scalar and batch form), reduced to what keeps the scalar path's
//! arithmetic. Nothing of the method is written here: the stages, the new state and the
//! error estimate with its weighted RMS are the explicit core's (`steppers/explicit.rs`)
//! over Dormand–Prince's tableau (`steppers/dp_tableau.rs`), with [`Lanes`] as the
//! component instead of `f64`; the step-size rule is `steppers/step_size.rs`'s (its two
//! `powf` per step one scalar call per lane, skipped where the clamp decides alone); a
//! failed attempt follows the one rejection policy (`Controlled::shrink_or_fail`); the
//! dense output located on by the events (`lanes/events.rs`) is `DormandPrince`'s. The
//! arithmetic runs in lanes compiled for AVX where the CPU has it (chosen at run time;
//! never FMA), each operation the scalar one lane by lane. Each lane then decides on its
//! own, in scalar code, exactly as the scalar stepper does: the shared controller
//! (`Controlled`: first step, stop time), acceptance or rejection, the flow check of every
//! point and the events. An accepted lane's next attempt starts from the new state and its
//! rate (FSAL) where the lanes hold them. A lane whose member is done is refilled with the
//! next job at once (`lanes/member.rs`), so the lanes stay busy while members take
//! different numbers of steps. Hairer's stiffness test (statistics only) is not run.
//!
//! Every operation is the scalar stepper's in the same order: that is what makes the lanes
//! bit-identical, and `tests/lanes_dispersion.rs` holds it.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::events::after_step;
use super::member::{start, Last, Member};
pub use super::member::{LaneEnd, LaneJob};
use super::taylor::run_taylor;
use super::{lane, set_lane, LaneState, LaneSystem, Lanes};
use crate::error::{is_finite, StepError, StepErrorKind};
use crate::run::RunConfig;
use crate::stepper::Checked;
use crate::steppers::control::{AdaptiveControl, Controlled, Mode, StepControl};
use crate::steppers::dormand_prince::Dense;
use crate::steppers::dp_tableau::{ERROR_WEIGHTS, STAGE_ROWS, WEIGHTS};
use crate::steppers::explicit::{self, Rates};
use crate::steppers::step_size::{step_after_acceptance, ClampedErrors};
use crate::steppers::TaylorControl;
use crate::tolerance::Tolerance;

/// The inputs of one attempt in every lane, and the stages it computes.
pub(super) struct Attempt<const S: usize, const W: usize> {
    t0: Lanes<W>,
    h: Lanes<W>,
    /// Whether the attempt was cut to land on the stop time.
    reaches_stop: [bool; W],
    y0: LaneState<S, W>,
    /// k₁ … k₇; k₁ is the rate at y₀ (FSAL).
    pub(super) k: [LaneState<S, W>; 7],
    /// The stage states y₂ … y₆ and y₁ (the new state), for the checks.
    y: [LaneState<S, W>; 6],
    /// The new state y₁ of each lane as the scalar code's vector (`rows`).
    new_states: [SVector<f64, S>; W],
    /// Whether every stage state and the new state of the lane are finite.
    finite: [bool; W],
    /// The scaled error of each lane.
    error: Lanes<W>,
}

/// Runs every job to its first stopping event or `config.end_time`, W members at a time,
/// and returns each member's end in job order: lane by lane what the scalar run ends with
/// (its last point), or its error. The method is the control's: a [`StepControl`] flies
/// Dormand–Prince, lane by lane `run(&mut DormandPrince::new(&job.system, job.time,
/// job.state, control)?, config, job.events)`; a [`TaylorControl`] flies Taylor's method
/// (`emit = [..., "taylor", "lanes"]`), lane by lane `run(&mut Taylor::new(..)?, ..)`
/// (see `lanes/taylor.rs`).
///
/// Only what that needs is supported: an adaptive control (Dormand–Prince), nothing
/// recorded, no energy guard, and systems without switches or stop times (a member that has them fails with a
/// configuration error: run it on the scalar path).
///
/// The lanes' arithmetic runs with AVX where the CPU has it (x86-64 with `std`), otherwise
/// with what the build targets; both give the same bits.
pub fn run_lanes<Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &[LaneJob<'_, Sys, S>],
    control: impl Into<LaneMethod>,
    config: &RunConfig,
) -> Vec<Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    run_lanes_with(jobs, control, config, LaneKernel::Detected)
}

/// The method [`run_lanes`] flies the members with, and its control.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LaneMethod {
    /// Dormand–Prince 5(4), adaptive.
    DormandPrince(StepControl),
    /// Taylor's method (the system's `emit = [..., "taylor", "lanes"]`).
    Taylor(TaylorControl),
}

impl From<StepControl> for LaneMethod {
    fn from(control: StepControl) -> Self {
        Self::DormandPrince(control)
    }
}

impl From<TaylorControl> for LaneMethod {
    fn from(control: TaylorControl) -> Self {
        Self::Taylor(control)
    }
}

/// Which compilation of the lanes' arithmetic [`run_lanes_with`] runs: for tests of the
/// portable path on a CPU that has AVX.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LaneKernel {
    /// AVX where the CPU has it, otherwise the build's target (what [`run_lanes`] runs).
    Detected,
    /// The build's target only (SSE2 in a default x86-64 build), never AVX.
    Portable,
}

/// Which compilation of the lanes' arithmetic runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kernel {
    /// For the build's target (SSE2 in a default x86-64 build: two lanes per instruction).
    Portable,
    /// For AVX (four lanes per instruction), which the CPU was found to have.
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    Avx,
}

impl Kernel {
    /// AVX where the CPU has it and `asked` allows, otherwise the build's target.
    fn detect(asked: LaneKernel) -> Self {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        if asked == LaneKernel::Detected && std::is_x86_feature_detected!("avx") {
            return Self::Avx;
        }
        let _ = asked;
        Self::Portable
    }
}

/// [`run_lanes`] with the lanes' arithmetic compiled as `kernel` says.
#[doc(hidden)]
pub fn run_lanes_with<Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &[LaneJob<'_, Sys, S>],
    control: impl Into<LaneMethod>,
    config: &RunConfig,
    kernel: LaneKernel,
) -> Vec<Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    const { assert!(W >= 1, "a lane job needs at least one lane") };
    let kernel = Kernel::detect(kernel);
    match control.into() {
        LaneMethod::DormandPrince(control) => run_dormand_prince(jobs, control, config, kernel),
        LaneMethod::Taylor(control) => run_taylor(jobs, control, config, kernel),
    }
}

/// [`run_lanes`] with Dormand–Prince.
fn run_dormand_prince<Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &[LaneJob<'_, Sys, S>],
    control: StepControl,
    config: &RunConfig,
    kernel: Kernel,
) -> Vec<Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    let mut results: Vec<Option<Result<LaneEnd<S>, StepError<S>>>> =
        (0..jobs.len()).map(|_| None).collect();
    let Some(first) = jobs.first() else {
        return Vec::new();
    };
    let Ok(Mode::Adaptive(adaptive, tolerance)) = control.validated() else {
        // Every member reports why, as it would on the scalar path.
        return (0..jobs.len())
            .map(
                |job| match start::<Sys, N, S, W>(jobs, job, control, config) {
                    Err(done) => done,
                    Ok(_) => Err(unfinished()),
                },
            )
            .collect();
    };
    let clamped = ClampedErrors::dormand_prince(&adaptive);
    let mut parameters = Sys::splat(&first.system);
    let mut lanes: [Option<Member<'_, '_, Sys, S>>; W] = core::array::from_fn(|_| None);
    let mut queue = 0..jobs.len();
    let mut attempt = Attempt::<S, W>::new();
    loop {
        let accepted = lanes
            .each_ref()
            .map(|slot| slot.as_ref().is_some_and(|m| m.last == Last::Accepted));
        attempt.carry(accepted);
        let pool = (&mut lanes, &mut queue, &mut results[..]);
        fill_lanes(pool, &mut parameters, &mut attempt, (jobs, control, config));
        let Some(busy) = lanes.iter().position(Option::is_some) else {
            if queue.is_empty() {
                break;
            }
            continue;
        };
        for (index, slot) in lanes.iter().enumerate() {
            if slot.is_none() {
                attempt.copy_lane(busy, index);
            }
        }
        attempt.kernel::<Sys, N>(kernel, &parameters, &tolerance);
        attempt.rows();
        conclude_lanes(
            &mut lanes,
            &mut results,
            &attempt,
            (&adaptive, &clamped),
            config,
        );
    }
    results
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err(unfinished())))
        .collect()
}

/// A member's end, or its error, by job.
type Ends<const S: usize> = [Option<Result<LaneEnd<S>, StepError<S>>>];

/// The lanes, the jobs not yet started and the ends by job.
type Pool<'p, 's, 'e, Sys, const S: usize, const W: usize> = (
    &'p mut [Option<Member<'s, 'e, Sys, S>>; W],
    &'p mut core::ops::Range<usize>,
    &'p mut Ends<S>,
);

/// Gives each empty lane the next job that starts (its parameters into the lane; a job that
/// ends at its start goes to the ends) and loads each occupied lane's attempt (a member that
/// fails there leaves its lane). An empty lane is left to repeat an occupied one's attempt.
#[inline(always)]
fn fill_lanes<'s, 'e, Sys, const N: usize, const S: usize, const W: usize>(
    (lanes, queue, results): Pool<'_, 's, 'e, Sys, S, W>,
    parameters: &mut Sys::Parameters,
    attempt: &mut Attempt<S, W>,
    (jobs, control, config): (&'s [LaneJob<'e, Sys, S>], StepControl, &RunConfig),
) where
    Sys: LaneSystem<N, S, W>,
{
    for (index, slot) in lanes.iter_mut().enumerate() {
        while slot.is_none() {
            let Some(job) = queue.next() else { break };
            match start(jobs, job, control, config) {
                Ok(member) => {
                    Sys::set_lane(parameters, index, &jobs[job].system);
                    *slot = Some(member);
                }
                Err(done) => results[job] = Some(done),
            }
        }
        if let Some(member) = slot {
            if let Err(error) = attempt.load(index, member) {
                results[member.job] = Some(Err(error));
                *slot = None;
            }
        }
    }
}

/// The verdict on the attempt in each occupied lane (`conclude`), with the step its
/// controller proposes should it be accepted; a member whose run ended leaves its lane and
/// its end goes to `results`.
#[inline]
fn conclude_lanes<Sys, const N: usize, const S: usize, const W: usize>(
    lanes: &mut [Option<Member<'_, '_, Sys, S>>; W],
    results: &mut Ends<S>,
    attempt: &Attempt<S, W>,
    (adaptive, clamped): (&AdaptiveControl, &ClampedErrors),
    config: &RunConfig,
) where
    Sys: LaneSystem<N, S, W>,
{
    // An empty lane's error is NaN here, so that its proposal costs no `powf`.
    let previous = Lanes::from_fn(|i| {
        lanes[i]
            .as_ref()
            .map_or(1.0, |member| member.core.memory.previous_error)
    });
    let busy = lanes.each_ref().map(Option::is_some);
    let error = Lanes::select(busy, attempt.error, Lanes::splat(f64::NAN));
    let proposals = step_after_acceptance(adaptive, clamped, attempt.h, error, previous);
    for (index, slot) in lanes.iter_mut().enumerate() {
        let Some(member) = slot else { continue };
        let verdict = Verdict {
            index,
            control: adaptive,
            clamped,
            proposal: proposals.0[index],
        };
        match conclude(member, attempt, verdict, config) {
            Ok(None) => {}
            Ok(Some(end)) => {
                results[member.job] = Some(Ok(end));
                *slot = None;
            }
            Err(error) => {
                results[member.job] = Some(Err(error));
                *slot = None;
            }
        }
    }
}

/// The error of a job the loop never finished (it cannot happen: every job is started,
/// and a started member ends with a result).
fn unfinished<const S: usize>() -> StepError<S> {
    StepError::invalid_configuration(f64::NAN, SVector::zeros(), "a lane job never finished")
}

impl<const S: usize, const W: usize> Attempt<S, W> {
    fn new() -> Self {
        let zero = [Lanes::default(); S];
        Self {
            t0: Lanes::default(),
            h: Lanes::default(),
            reaches_stop: [false; W],
            y0: zero,
            k: [zero; 7],
            y: [zero; 6],
            new_states: [SVector::zeros(); W],
            finite: [true; W],
            error: Lanes::default(),
        }
    }

    /// Where the `accepted` lanes' next attempts start: the new state y₁ and its rate k₇
    /// (FSAL) of the attempt just accepted, which the member's progress and controller now
    /// hold too (the same values: `Progress::accept` stores y₁ as given, `accepted` k₇), so
    /// they move within the lanes instead of out and back in.
    fn carry(&mut self, accepted: [bool; W]) {
        for j in 0..S {
            self.y0[j] = Lanes::select(accepted, self.y[5][j], self.y0[j]);
            self.k[0][j] = Lanes::select(accepted, self.k[6][j], self.k[0][j]);
        }
    }

    /// Puts the member's next attempt (t₀, y₀, k₁, h) in lane `index`: the scalar
    /// stepper's start of a step, its first step chosen if none is yet. After an attempt
    /// the lane holds y₀ and k₁ already (`carry`; a rejection leaves them): only t₀ and h
    /// are new.
    fn load<Sys, const N: usize>(
        &mut self,
        index: usize,
        member: &mut Member<'_, '_, Sys, S>,
    ) -> Result<(), StepError<S>>
    where
        Sys: LaneSystem<N, S, W>,
    {
        let (t0, y0) = if member.last == Last::Started {
            let (t0, y0, k1) = member.core.begin::<N>(5)?;
            set_lane(&mut self.y0, index, &y0);
            set_lane(&mut self.k[0], index, &k1);
            (t0, y0)
        } else {
            // `begin` would give the same: the rate is known, the step chosen.
            (member.core.progress.time(), *member.core.progress.state())
        };
        let (h, reaches_stop) = member.core.attempt_size((t0, &y0))?;
        self.t0.0[index] = t0;
        self.h.0[index] = h;
        self.reaches_stop[index] = reaches_stop;
        Ok(())
    }

    /// Reads every lane's new state out of the lanes, all at once right after the kernel:
    /// read lane by lane just before its acceptance, the vector was loaded while its
    /// components were still being stored (a store-to-load forwarding stall, the hottest
    /// spot of the loop in `perf annotate`), where here the `powf`s that follow give the
    /// stores time to land.
    fn rows(&mut self) {
        for (i, row) in self.new_states.iter_mut().enumerate() {
            *row = lane(&self.y[5], i);
        }
    }

    /// Copies the inputs of lane `from` into lane `to`.
    fn copy_lane(&mut self, from: usize, to: usize) {
        self.t0.0[to] = self.t0.0[from];
        self.h.0[to] = self.h.0[from];
        self.reaches_stop[to] = self.reaches_stop[from];
        for j in 0..S {
            self.y0[j].0[to] = self.y0[j].0[from];
            self.k[0][j].0[to] = self.k[0][j].0[from];
        }
    }

    /// The work of an attempt in every lane: the stages, then the error and the finiteness
    /// check. On x86-64 it is compiled twice, for the build's target (SSE2 by default: two
    /// lanes per instruction) and for AVX (four), the AVX one chosen at run time where the
    /// CPU has it (`Kernel::detect`). AVX only, not FMA: a fused multiply-add rounds once
    /// where the scalar path rounds twice, and the lanes would no longer be the scalar
    /// path's bits (`objdump -d` of a build shows no `vfmadd`).
    fn kernel<Sys, const N: usize>(
        &mut self,
        kernel: Kernel,
        parameters: &Sys::Parameters,
        tolerance: &Tolerance,
    ) where
        Sys: LaneSystem<N, S, W>,
    {
        match kernel {
            Kernel::Portable => self.kernel_portable::<Sys, N>(parameters, tolerance),
            // SAFETY: `Kernel::Avx` is only chosen where the CPU has AVX (`Kernel::detect`).
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            Kernel::Avx => unsafe { self.kernel_avx::<Sys, N>(parameters, tolerance) },
        }
    }

    /// [`Self::kernel`] for the build's target.
    #[inline(always)]
    fn kernel_portable<Sys, const N: usize>(
        &mut self,
        parameters: &Sys::Parameters,
        tolerance: &Tolerance,
    ) where
        Sys: LaneSystem<N, S, W>,
    {
        self.stages::<Sys, N>(parameters);
        self.measure(tolerance);
    }

    /// [`Self::kernel`] compiled for AVX: the same code, inlined into a function with the
    /// feature on (the generated state rate too, being `#[inline]`).
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    fn kernel_avx<Sys, const N: usize>(
        &mut self,
        parameters: &Sys::Parameters,
        tolerance: &Tolerance,
    ) where
        Sys: LaneSystem<N, S, W>,
    {
        self.kernel_portable::<Sys, N>(parameters, tolerance);
    }

    /// The stages k₂ … k₇ and the new state in every lane: the explicit core's, as
    /// `DormandPrince`'s attempt takes them, lane by lane (the same operations, each stage
    /// written out by the compiler: `explicit::stages_written_out`).
    #[inline(always)]
    fn stages<Sys, const N: usize>(&mut self, parameters: &Sys::Parameters)
    where
        Sys: LaneSystem<N, S, W>,
    {
        let (t0, h, y0) = (self.t0, self.h, self.y0);
        let mut rates = LaneRates::<Sys, N, S, W> { parameters };
        // The stage states y₂ … y₆ go straight to where the checks read them.
        let states = &mut self.y[..5];
        match explicit::stages_written_out(
            STAGE_ROWS,
            (t0, &y0),
            h,
            &mut self.k,
            states,
            &mut rates,
        ) {
            Ok(_) => {}
            Err(never) => match never {},
        }
        let y1 = explicit::solution(WEIGHTS, &y0, &self.k, h);
        self.k[6] = Sys::state_rate_lanes(parameters, t0 + h, &y1);
        self.y[5] = y1;
    }

    /// Which lanes' stage states are all finite, and every lane's scaled error: the
    /// explicit core's estimate and norm, as `DormandPrince`'s attempt takes them.
    #[inline(always)]
    fn measure(&mut self, tolerance: &Tolerance) {
        let estimate = explicit::combination(ERROR_WEIGHTS, &self.k, self.h);
        self.error = explicit::error_norm(tolerance, &estimate, (&self.y0, &self.y[5]));
        // 0·x is 0 for a finite x and NaN for ±∞ or NaN: one sum over the stage states
        // tells, lane by lane, whether they were all finite.
        let mut spread = Lanes::<W>::splat(0.0);
        for y in &self.y {
            for component in y {
                spread += *component * 0.0;
            }
        }
        self.finite = spread.0.map(|x| x == 0.0);
    }
}

/// The generated state rate over lanes, for the explicit core (it cannot fail: each lane's
/// input is checked afterwards, `check_stages`).
struct LaneRates<'p, Sys, const N: usize, const S: usize, const W: usize>
where
    Sys: LaneSystem<N, S, W>,
{
    parameters: &'p Sys::Parameters,
}

impl<Sys, const N: usize, const S: usize, const W: usize> Rates<Lanes<W>, LaneState<S, W>>
    for LaneRates<'_, Sys, N, S, W>
where
    Sys: LaneSystem<N, S, W>,
{
    type Error = core::convert::Infallible;
    #[inline(always)]
    fn rate(
        &mut self,
        time: Lanes<W>,
        state: &LaneState<S, W>,
    ) -> Result<LaneState<S, W>, Self::Error> {
        Ok(Sys::state_rate_lanes(self.parameters, time, state))
    }
}

/// What `conclude` needs besides the attempt: the lane, the controller's bounds and the
/// step the controller proposes should the lane's attempt be accepted.
struct Verdict<'c> {
    index: usize,
    /// Every member's control (one `StepControl` for the run).
    control: &'c AdaptiveControl,
    clamped: &'c ClampedErrors,
    proposal: f64,
}

/// The verdict on lane `index`'s attempt for its member, as the scalar stepper and run
/// reach it: rejected (`Ok(None)`, the next attempt shorter), accepted and the run goes on
/// (`Ok(None)`), accepted and the run ends (`Ok(Some)`), or failed.
fn conclude<Sys, const N: usize, const S: usize, const W: usize>(
    member: &mut Member<'_, '_, Sys, S>,
    attempt: &Attempt<S, W>,
    verdict: Verdict<'_>,
    config: &RunConfig,
) -> Result<Option<LaneEnd<S>>, StepError<S>>
where
    Sys: LaneSystem<N, S, W>,
{
    let (index, control) = (verdict.index, verdict.control);
    let (h, reaches_stop) = (attempt.h.0[index], attempt.reaches_stop[index]);
    member.core.progress.statistics.rate_evaluations += 6;
    member.last = Last::Rejected;
    let (error, finite) = (attempt.error.0[index], attempt.finite[index]);
    let accepting = error <= 1.0;
    // The scalar stepper checks the new state twice: in its attempt (a failure there is a
    // step too long) and on accepting it (`Progress::accept`: the same check at the same
    // time, t₀ + h, unless the step lands on the stop time). Where the two are one, the
    // check on accepting serves both.
    if !finite || !accepting || reaches_stop {
        if let Err(error) = check_stages(member.core.system, attempt, index, finite) {
            return too_long(member, h, control, error);
        }
    }
    if !accepting {
        // `DormandPrince::control`'s factor, its `powf` skipped where the clamp decides.
        let factor = verdict.clamped.rejection_factor(control, error);
        let memory = &mut member.core.memory;
        memory.reject(h / factor, &mut member.core.progress);
        return Ok(None);
    }
    let y1 = attempt.new_states[index];
    let progress = &mut member.core.progress;
    let outcome = match progress.accept(member.core.system, h, reaches_stop, y1) {
        Ok(outcome) => outcome,
        // Unchecked before: the attempt's own check failed.
        Err(error) if !reaches_stop => return too_long(member, h, control, error),
        Err(error) => return Err(error),
    };
    let memory = &mut member.core.memory;
    let next = memory.after_acceptance(h, verdict.proposal, error);
    // `accepted(h, k₇)` but for the FSAL rate k₇, which stays in the lane (`carry`): only a
    // member's first attempt asks the controller for its rate (`load`).
    memory.last_step = h;
    memory.propose(next, reaches_stop, control.max_step);
    member.last = Last::Accepted;
    // The lane's stages read out of the lanes only if an event needs them, for
    // `DormandPrince`'s dense output over its last step.
    let dense = |core: &Controlled<'_, Sys, S>| {
        let k = core::array::from_fn(|i| lane(&attempt.k[i], index));
        let start = (
            core.progress.previous_time(),
            core.progress.previous_state(),
        );
        Dense::new(start, core.progress.state(), core.memory.last_step, &k)
    };
    after_step::<Sys, _, _, N, S, W>(member, dense, outcome, config)
}

/// A trial state outside the domain (non-finite, a mass not positive): a step too long,
/// shrunk by `min_factor` and retried, unless it can shrink no more (the one rejection
/// policy, `Controlled::shrink_or_fail`).
fn too_long<Sys, const S: usize>(
    member: &mut Member<'_, '_, Sys, S>,
    h: f64,
    control: &AdaptiveControl,
    error: StepError<S>,
) -> Result<Option<LaneEnd<S>>, StepError<S>> {
    member
        .core
        .shrink_or_fail(h * control.min_factor, error)
        .map(|()| None)
}

/// Scalar `state_rate`'s check of each stage state (finite) and `Checked::check_state` of the new
/// state, in the scalar stepper's order.
fn check_stages<Sys, const N: usize, const S: usize, const W: usize>(
    system: &Sys,
    attempt: &Attempt<S, W>,
    index: usize,
    finite: bool,
) -> Result<(), StepError<S>>
where
    Sys: LaneSystem<N, S, W>,
{
    let (t0, h) = (attempt.t0.0[index], attempt.h.0[index]);
    if finite {
        return system.check_state(t0 + h, &attempt.new_states[index]);
    }
    for (y, &(c, _)) in attempt.y[..5].iter().zip(STAGE_ROWS) {
        let y = lane(y, index);
        if !is_finite(&y) {
            let time = if c == 1.0 { t0 + h } else { t0 + c * h };
            return Err(StepError::new(time, y, StepErrorKind::NonFiniteState));
        }
    }
    system.check_state(t0 + h, &attempt.new_states[index])
}
