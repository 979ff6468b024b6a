//! Dormand–Prince 5(4) over lanes: W members at once, each with its own step size, its own
//! error control and its own events, each lane giving bit for bit what
//! [`DormandPrince`](crate::steppers::DormandPrince) driven by [`run`](crate::run::run)
//! gives that member alone.
//!
//! The design is heyoka's batch mode's (Biscani & Izzo 2021, per-lane step sizes and
//! times), reduced to what keeps the scalar path's arithmetic: the stages — six state rates
//! and the combinations between them, the work of an attempt —, the error estimate with the
//! weighted RMS of `Tolerance::norm` and the finiteness of the stage states run in lanes,
//! each operation the scalar one lane by lane, compiled for AVX where the CPU has it (chosen
//! at run time; never FMA). So does the PI controller's arithmetic after the attempt
//! (`lanes/control.rs`): its two `powf` per step stay one scalar call per lane (a vector
//! `pow` would round otherwise), skipped where the clamp decides alone (`ClampedErrors`).
//! Each lane then decides on its own, in scalar code, exactly as the scalar stepper does:
//! the shared controller (`steppers/control.rs`'s `Controlled`: first step, stop time),
//! acceptance or rejection, the flow check of every point and the events located on the
//! lane's own dense output (`locate_root`). An accepted lane's next attempt starts from
//! the new state and its rate (FSAL) where the lanes hold them. A lane whose member is done
//! is refilled with the next job at once, so the lanes stay busy while members take
//! different numbers of steps. Hairer's stiffness test (statistics only) is not run.
//!
//! The tableau and the dense output are the scalar stepper's (`steppers/dormand_prince.rs`,
//! HNW I, II.5, Table 5.2 and `CONTD5`), with every operation in the same order: that is
//! what makes the lanes bit-identical, and `tests/lanes_dispersion.rs` holds it.

use alloc::vec::Vec;

use nalgebra::SVector;

use super::control::step_after_acceptance;
use super::events::after_step;
use super::{lane, set_lane, LaneState, LaneSystem, Lanes};
use crate::error::{is_finite, StepError, StepErrorKind};
use crate::events::Event;
use crate::run::RunConfig;
use crate::solution::Record;
use crate::stepper::{Checked, Statistics};
use crate::steppers::control::{
    resolvable, AdaptiveControl, ClampedErrors, Controlled, Mode, StepControl,
};
use crate::tolerance::Tolerance;

use crate::steppers::dp_tableau::*;

/// One member's run: its system, its initial value and the events that end it (as
/// [`run`](crate::run::run)'s `events`).
#[derive(Clone, Copy, Debug)]
pub struct LaneJob<'e, Sys, const S: usize> {
    /// The member's system (its parameters go into its lane).
    pub system: Sys,
    /// The initial time.
    pub time: f64,
    /// The initial state `[q, p, m_s]`.
    pub state: SVector<f64, S>,
    /// The events watched; the first [`EventAction::Stop`](crate::events::EventAction::Stop) hit ends the run.
    pub events: &'e [Event<'e, S>],
}

/// Where a member's run ended: the last point of the scalar run's solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneEnd<const S: usize> {
    /// The time of the last point: the located event, or the end time.
    pub time: f64,
    /// The state there.
    pub state: SVector<f64, S>,
    /// The index of the stopping event, `None` when the run reached the end time.
    pub event: Option<usize>,
    /// The work counters (rate evaluations counted six per attempt and one at the start;
    /// the stiffness flag is never set).
    pub statistics: Statistics,
}

/// A member in its lane: the scalar controller and the run's bookkeeping.
pub(super) struct Member<'s, 'e, Sys, const S: usize> {
    pub(super) job: usize,
    pub(super) core: Controlled<'s, Sys, S>,
    pub(super) events: &'e [Event<'e, S>],
    /// g of each event at the last point.
    pub(super) values: Vec<f64>,
    pub(super) steps: usize,
    /// How the member's last attempt ended, which says where its next one starts.
    last: Last,
}

/// How a member's last attempt ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Last {
    /// None yet: the attempt starts from the member's initial value.
    Started,
    /// Accepted: the next starts from its new state and last stage (FSAL), which are in the
    /// lanes already.
    Accepted,
    /// Rejected: the next starts where it did, from what the lane holds still.
    Rejected,
}

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

/// Runs every job to its first stopping event or `config.end_time` with Dormand–Prince
/// under `control`, W members at a time, and returns each member's end in job order: lane
/// by lane what `run(&mut DormandPrince::new(&job.system, job.time, job.state, control)?,
/// config, job.events)` ends with (its last point), or its error.
///
/// Only what that needs is supported: an adaptive control, nothing recorded, no energy
/// guard, and systems without switches or stop times (a member that has them fails with a
/// configuration error: run it on the scalar path).
///
/// The lanes' arithmetic runs with AVX where the CPU has it (x86-64 with `std`), otherwise
/// with what the build targets; both give the same bits.
pub fn run_lanes<Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &[LaneJob<'_, Sys, S>],
    control: StepControl,
    config: &RunConfig,
) -> Vec<Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    run_lanes_with(jobs, control, config, LaneKernel::Detected)
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
enum Kernel {
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
    control: StepControl,
    config: &RunConfig,
    kernel: LaneKernel,
) -> Vec<Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    let kernel = Kernel::detect(kernel);
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
        for (index, slot) in lanes.iter_mut().enumerate() {
            while slot.is_none() {
                let Some(job) = queue.next() else { break };
                match start(jobs, job, control, config) {
                    Ok(member) => {
                        Sys::set_lane(&mut parameters, index, &jobs[job].system);
                        *slot = Some(member);
                    }
                    Err(done) => results[job] = Some(done),
                }
            }
            // An empty lane repeats the attempt of an occupied one (its results unread).
            if let Some(member) = slot {
                if let Err(error) = attempt.load(index, member) {
                    results[member.job] = Some(Err(error));
                    *slot = None;
                }
            }
        }
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
        // An empty lane's error is NaN here, so that its proposal costs no `powf`.
        let previous = Lanes::from_fn(|i| {
            lanes[i]
                .as_ref()
                .map_or(1.0, |member| member.core.memory.previous_error)
        });
        let busy = lanes.each_ref().map(Option::is_some);
        let error = Lanes::select(busy, attempt.error, Lanes::splat(f64::NAN));
        let proposals = step_after_acceptance(&adaptive, &clamped, attempt.h, error, previous);
        for (index, slot) in lanes.iter_mut().enumerate() {
            let Some(member) = slot else { continue };
            let verdict = Verdict {
                index,
                control: &adaptive,
                clamped: &clamped,
                proposal: proposals.0[index],
            };
            match conclude(member, &attempt, verdict, config) {
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
    results
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err(unfinished())))
        .collect()
}

/// The error of a job the loop never finished (it cannot happen: every job is started,
/// and a started member ends with a result).
fn unfinished<const S: usize>() -> StepError<S> {
    StepError::invalid_configuration(f64::NAN, SVector::zeros(), "a lane job never finished")
}

/// A member at the start of its run, with the scalar run's checks; `Err` holds the member's
/// result when it ends before any step (a failed check, or a run of zero length).
#[allow(clippy::type_complexity)]
fn start<'s, 'e, Sys, const N: usize, const S: usize, const W: usize>(
    jobs: &'s [LaneJob<'e, Sys, S>],
    job: usize,
    control: StepControl,
    config: &RunConfig,
) -> Result<Member<'s, 'e, Sys, S>, Result<LaneEnd<S>, StepError<S>>>
where
    Sys: LaneSystem<N, S, W>,
{
    let LaneJob {
        system,
        time,
        state,
        events,
    } = &jobs[job];
    let mut core = Controlled::new::<N>(system, *time, *state, control).map_err(Err)?;
    let invalid = |reason| Err(StepError::invalid_configuration(*time, *state, reason));
    if !matches!(core.mode, Mode::Adaptive(..)) {
        return Err(invalid("lanes: only adaptive steps run in lanes"));
    }
    let supported = config.record == Record::default()
        && config.energy_tolerance.is_none()
        && !config.event_tolerance.is_nan()
        && config.event_tolerance >= 0.0;
    if !supported {
        return Err(invalid(
            "lanes: a run in lanes records nothing and guards no energy; the event \
             tolerance must be non-negative",
        ));
    }
    if system.switch_count() > 0 || system.next_stop_time(*time).is_some() {
        return Err(invalid(
            "lanes: a system with switches or stop times runs on the scalar path",
        ));
    }
    for event in *events {
        event
            .validate::<Sys, N>()
            .map_err(|error| invalid(error.reason))?;
    }
    core.progress.set_stop_time(config.end_time).map_err(Err)?;
    system.check_flows(*time, state).map_err(Err)?;
    if config.end_time == *time {
        return Err(Ok(end_at(&core, *time, *state, None)));
    }
    if config.max_steps == 0 {
        let kind = StepErrorKind::TooManySteps { max_steps: 0 };
        return Err(Err(StepError::new(*time, *state, kind)));
    }
    let values = events
        .iter()
        .map(|event| event.value(system, *time, state))
        .collect();
    Ok(Member {
        job,
        core,
        events,
        values,
        steps: 0,
        last: Last::Started,
    })
}

/// The member's end at `(time, state)`, stopped by `event` (`None`: at the end time).
pub(super) fn end_at<Sys, const S: usize>(
    core: &Controlled<'_, Sys, S>,
    time: f64,
    state: SVector<f64, S>,
    event: Option<usize>,
) -> LaneEnd<S> {
    LaneEnd {
        time,
        state,
        event,
        statistics: *core.progress.statistics(),
    }
}

/// y₀ + δ(j) in every component j, δ written out in place: a closure would be compiled on
/// its own, without the AVX of the kernel it serves.
macro_rules! stage {
    ($y0:expr, |$j:ident| $delta:expr) => {{
        let mut out = $y0;
        for ($j, component) in out.iter_mut().enumerate() {
            *component += $delta;
        }
        out
    }};
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

    /// The stages k₂ … k₇ and the new state in every lane: `DormandPrince::attempt`'s
    /// operations, in its order, lane by lane.
    #[inline(always)]
    fn stages<Sys, const N: usize>(&mut self, parameters: &Sys::Parameters)
    where
        Sys: LaneSystem<N, S, W>,
    {
        let (t0, h, y0) = (self.t0, self.h, self.y0);
        // Called directly and the stages written out (`stage!`), with no closure: a closure
        // is compiled on its own, without the AVX of the kernel that calls it.
        let rate = Sys::state_rate_lanes;
        let k1 = self.k[0];
        let y2 = stage!(y0, |j| k1[j] * (A21 * h));
        let k2 = rate(parameters, t0 + C2 * h, &y2);
        let y3 = stage!(y0, |j| (k1[j] * A31 + k2[j] * A32) * h);
        let k3 = rate(parameters, t0 + C3 * h, &y3);
        let y4 = stage!(y0, |j| (k1[j] * A41 + k2[j] * A42 + k3[j] * A43) * h);
        let k4 = rate(parameters, t0 + C4 * h, &y4);
        let y5 = stage!(y0, |j| {
            (k1[j] * A51 + k2[j] * A52 + k3[j] * A53 + k4[j] * A54) * h
        });
        let k5 = rate(parameters, t0 + C5 * h, &y5);
        let y6 = stage!(y0, |j| {
            (k1[j] * A61 + k2[j] * A62 + k3[j] * A63 + k4[j] * A64 + k5[j] * A65) * h
        });
        let k6 = rate(parameters, t0 + h, &y6);
        let y1 = stage!(y0, |j| {
            (k1[j] * B1 + k3[j] * B3 + k4[j] * B4 + k5[j] * B5 + k6[j] * B6) * h
        });
        let k7 = rate(parameters, t0 + h, &y1);
        self.k = [k1, k2, k3, k4, k5, k6, k7];
        self.y = [y2, y3, y4, y5, y6, y1];
    }

    /// Which lanes' stage states are all finite, and every lane's scaled error:
    /// `DormandPrince::attempt`'s estimate and [`Tolerance::norm`]'s weighted RMS (weights
    /// atol + rtol·max(|y₀ᵢ|, |y₁ᵢ|), an exact zero counting 0, the squares summed in
    /// component order), lane by lane.
    #[inline(always)]
    fn measure(&mut self, tolerance: &Tolerance) {
        let (k, h, y1) = (&self.k, self.h, &self.y[5]);
        let absolute = Lanes::<W>::splat(tolerance.absolute());
        let relative = Lanes::<W>::splat(tolerance.relative());
        let mut sum = Lanes::<W>::splat(0.0);
        for j in 0..S {
            let estimate = (k[0][j] * E1
                + k[2][j] * E3
                + k[3][j] * E4
                + k[4][j] * E5
                + k[5][j] * E6
                + k[6][j] * E7)
                * h;
            let magnitude = self.y0[j].abs().max(y1[j].abs());
            // `Tolerance::weight`: atol + rtol·m.
            let weight = absolute + relative * magnitude;
            let scaled = estimate / weight;
            let square = Lanes::select(
                estimate.0.map(|e| e == 0.0),
                Lanes::splat(0.0),
                scaled * scaled,
            );
            sum += square;
        }
        self.error = (sum / S as f64).sqrt();
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
    after_step(member, attempt, index, outcome, config)
}

/// A trial state outside the domain (non-finite, a mass not positive): a step too long,
/// shrunk by `min_factor` and retried, unless it can shrink no more
/// (`DormandPrince::control`).
fn too_long<Sys, const S: usize>(
    member: &mut Member<'_, '_, Sys, S>,
    h: f64,
    control: &AdaptiveControl,
    error: StepError<S>,
) -> Result<Option<LaneEnd<S>>, StepError<S>> {
    let core = &mut member.core;
    core.memory
        .reject(h * control.min_factor, &mut core.progress);
    if resolvable(core.progress.time(), core.memory.next_step) {
        Ok(None)
    } else {
        Err(error)
    }
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
    for (y, c) in attempt.y[..5].iter().zip([C2, C3, C4, C5, 1.0]) {
        let y = lane(y, index);
        if !is_finite(&y) {
            let time = if c == 1.0 { t0 + h } else { t0 + c * h };
            return Err(StepError::new(time, y, StepErrorKind::NonFiniteState));
        }
    }
    system.check_state(t0 + h, &attempt.new_states[index])
}
