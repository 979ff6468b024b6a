//! The one step controller of the adaptive steppers — the explicit pairs Dormand–Prince and
//! DOP853 and the diagonally implicit stepper of SDIRK4 and ESDIRK4(3): their settings
//! ([`StepControl`], [`AdaptiveControl`]) and their checked form ([`Mode`]), the first step
//! ([`initial_step`]), what they carry from one step to the next ([`ControlState`]) and the
//! bookkeeping they do the same way: the rate at the start of a step, a rejection, the PI
//! controller's step after an acceptance (Dormand–Prince and DOP853; the DIRK stepper keeps
//! `sdirk4.f`'s formula and leaves the PI memory unused), a restart.

use nalgebra::SVector;

use super::explicit::Counted;
use super::stiffness::StiffnessTest;
use super::FixedStep;
use crate::error::{ConfigError, StepError, StepErrorKind};
use crate::math::powf;
use crate::stepper::{state_rate, Progress, StepOutcome};
use crate::system::VariableMassSystem;
use crate::tolerance::Tolerance;

/// The error-control settings of the adaptive mode. Defaults are those of Hairer's `dopri5`
/// with tolerances 1e-6 (relative) and 1e-9 (absolute); [`AdaptiveControl::dop853`] and
/// [`AdaptiveControl::sdirk4`] give those of `dop853.f` and `sdirk4.f`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveControl {
    /// Relative tolerance per component.
    pub relative_tolerance: f64,
    /// Absolute tolerance per component.
    pub absolute_tolerance: f64,
    /// The first step; `None` chooses it from the problem (HNW I, II.4).
    pub initial_step: Option<f64>,
    /// The largest step allowed.
    pub max_step: f64,
    /// Safety factor on the optimal step, in (0, 1].
    pub safety: f64,
    /// Smallest factor by which one step may shrink the next, in (0, 1].
    pub min_factor: f64,
    /// Largest factor by which one step may grow the next, ≥ 1.
    pub max_factor: f64,
    /// The PI controller's weight β on the previous error (0 gives the classical I
    /// controller).
    pub beta: f64,
}

impl Default for AdaptiveControl {
    fn default() -> Self {
        Self {
            relative_tolerance: 1e-6,
            absolute_tolerance: 1e-9,
            initial_step: None,
            max_step: f64::INFINITY,
            safety: 0.9,
            min_factor: 0.2,
            max_factor: 10.0,
            beta: 0.04,
        }
    }
}

impl AdaptiveControl {
    /// The adaptive control with the defaults of `dop853.f`, for [`super::Dop853`]:
    /// tolerances as [`AdaptiveControl::default`], safety 0.9, step factors in [1/3, 6],
    /// β = 0.
    pub fn dop853() -> Self {
        Self {
            min_factor: 1.0 / 3.0,
            max_factor: 6.0,
            beta: 0.0,
            ..Self::default()
        }
    }

    /// The adaptive control with the defaults of `sdirk4.f`, for [`super::Sdirk4`] and
    /// [`super::Esdirk43`]: tolerances as [`AdaptiveControl::default`], safety 0.9, step
    /// factors in [1/4, 4], no PI term.
    pub fn sdirk4() -> Self {
        Self {
            min_factor: 0.25,
            max_factor: 4.0,
            beta: 0.0,
            ..Self::default()
        }
    }

    /// Checks the settings and returns the tolerance they give.
    pub(crate) fn validated(&self) -> Result<Tolerance, ConfigError> {
        // Tolerance::new's own reason: "not finite …" and "finer than f64 can honour" differ.
        let tolerance = Tolerance::new(self.relative_tolerance, self.absolute_tolerance)?;
        let initial_ok = self.initial_step.is_none_or(|h| h.is_finite() && h > 0.0);
        let factors_ok = self.safety > 0.0
            && self.safety <= 1.0
            && self.min_factor > 0.0
            && self.min_factor <= 1.0
            && self.max_factor >= 1.0
            && self.max_factor.is_finite()
            && (0.0..0.2).contains(&self.beta)
            && self.max_step > 0.0;
        if initial_ok && factors_ok {
            Ok(tolerance)
        } else {
            Err(ConfigError {
                reason: "adaptive control: steps must be positive, safety and min_factor in \
                         (0, 1], max_factor ≥ 1, beta in [0, 0.2)",
            })
        }
    }
}

/// How an adaptive pair (Dormand–Prince, DOP853, SDIRK4, ESDIRK4(3)) chooses its steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepControl {
    /// Error-controlled steps.
    Adaptive(AdaptiveControl),
    /// Every step of the same size, accepted without error control (e.g. to measure the
    /// order of convergence).
    Fixed(FixedStep),
}

impl Default for StepControl {
    fn default() -> Self {
        Self::Adaptive(AdaptiveControl::default())
    }
}

impl StepControl {
    /// Checks the settings: the check every stepper with a [`StepControl`] makes at
    /// construction.
    pub(crate) fn validated(self) -> Result<Mode, ConfigError> {
        match self {
            Self::Adaptive(control) => control
                .validated()
                .map(|tolerance| Mode::Adaptive(control, tolerance)),
            Self::Fixed(fixed) => FixedStep::validated(fixed.step).map(Mode::Fixed),
        }
    }
}

/// A checked [`StepControl`], as the steppers hold it: the fixed step, or the adaptive
/// settings with the tolerance they give (so adaptive steps always have one).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Mode {
    Fixed(f64),
    Adaptive(AdaptiveControl, Tolerance),
}

impl Mode {
    /// The size of the first step: the fixed step, the adaptive control's initial step, or
    /// one chosen from the problem by [`initial_step`] for a method of `order`, from the
    /// rate at the start (`rate`, evaluated only then).
    pub(crate) fn first_step<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        progress: &mut Progress<S>,
        rate: impl FnOnce(&mut Progress<S>) -> Result<SVector<f64, S>, StepError<S>>,
        order: u32,
    ) -> Result<f64, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        Ok(match self {
            Self::Fixed(step) => *step,
            Self::Adaptive(control, tolerance) => match control.initial_step {
                Some(h) => h.min(control.max_step),
                None => {
                    let rate = rate(progress)?;
                    initial_step(system, progress, &rate, (control, tolerance), order)
                }
            },
        })
    }
}

/// The PI controller's memory of the last accepted error before any step, and its floor.
pub(crate) const ERROR_FLOOR: f64 = 1e-4;

/// The adaptive-control state of an embedded pair.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ControlState<const S: usize> {
    /// The size of the next step to try (0 until the first step chooses it).
    pub(crate) next_step: f64,
    /// The size of the last accepted step, for the dense output (0 before any).
    pub(crate) last_step: f64,
    /// The PI controller's memory of the last accepted error (at least 1e-4).
    pub(crate) previous_error: f64,
    /// Whether the last attempt was rejected, so the next step may not grow.
    pub(crate) last_rejected: bool,
    /// The rate at the current state (FSAL), if known.
    pub(crate) current_rate: Option<SVector<f64, S>>,
}

impl<const S: usize> ControlState<S> {
    /// The state before the first step.
    pub(crate) fn new() -> Self {
        Self {
            next_step: 0.0,
            last_step: 0.0,
            previous_error: ERROR_FLOOR,
            last_rejected: false,
            current_rate: None,
        }
    }

    /// Forgets what belongs to the old initial value (the FSAL rate, the last step, the
    /// controller's memory); the proposed next step is kept.
    pub(crate) fn restart(&mut self) {
        *self = Self {
            next_step: self.next_step,
            ..Self::new()
        };
    }

    /// The rate at the current state: the last stage of the previous step (FSAL), or
    /// evaluated once after a start or restart.
    pub(crate) fn rate_at_start<Sys, const N: usize>(
        &mut self,
        system: &Sys,
        progress: &mut Progress<S>,
    ) -> Result<SVector<f64, S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if let Some(rate) = self.current_rate {
            return Ok(rate);
        }
        let (time, state) = (progress.time(), *progress.state());
        let rate = state_rate(system, &mut progress.statistics, time, &state)?;
        self.current_rate = Some(rate);
        Ok(rate)
    }

    /// Records a rejected attempt (counted in `progress`): the next attempt has size `next`.
    pub(crate) fn reject(&mut self, next: f64, progress: &mut Progress<S>) {
        self.next_step = next;
        self.last_rejected = true;
        progress.statistics.rejected_steps += 1;
    }

    /// The controller's proposal `next` after an accepted step of size `h` with `error`,
    /// not growing right after a rejection; remembers the error for the PI term.
    pub(crate) fn after_acceptance(&mut self, h: f64, next: f64, error: f64) -> f64 {
        let next = if self.last_rejected {
            next.min(h)
        } else {
            next
        };
        self.previous_error = error.max(ERROR_FLOOR);
        self.last_rejected = false;
        next
    }

    /// The PI controller's next step after accepting a step of size `h` with `error` (HNW II,
    /// IV.2): h·err^(−α)·err_old^β / safety within the factor limits, not growing right after
    /// a rejection. `error_power` is err^α, which each pair computes its own way (α = 1/5 −
    /// 0.75β for Dormand–Prince, 1/8 − 0.2β for DOP853); β = 0 needs no second power.
    pub(crate) fn pi_after_acceptance(
        &mut self,
        control: &AdaptiveControl,
        h: f64,
        error: f64,
        error_power: f64,
    ) -> f64 {
        let previous = if control.beta == 0.0 {
            1.0
        } else {
            powf(self.previous_error, control.beta)
        };
        let factor = error_power / previous / control.safety;
        let factor = factor.clamp(1.0 / control.max_factor, 1.0 / control.min_factor);
        self.after_acceptance(h, h / factor, error)
    }

    /// Takes `next` (at most `max_step`) as the next step to try, unless the accepted step
    /// was cut short to land on the stop time and the step already proposed is longer.
    pub(crate) fn propose(&mut self, next: f64, reaches_stop: bool, max_step: f64) {
        if !reaches_stop || next > self.next_step {
            self.next_step = next.min(max_step);
        }
    }

    /// Records an accepted step of size `h` whose last rate is `rate` (FSAL).
    pub(crate) fn accepted(&mut self, h: f64, rate: SVector<f64, S>) {
        self.current_rate = Some(rate);
        self.last_step = h;
    }
}

/// The first step of an adaptive method of order `order` (HNW I, II.4, the `hinit` of
/// `dopri5` and `dop853`): a step for which an explicit Euler step would change the state by
/// about 1 % of its size, refined by an estimate of the second derivative.
pub(crate) fn initial_step<Sys, const N: usize, const S: usize>(
    system: &Sys,
    progress: &mut Progress<S>,
    k1: &SVector<f64, S>,
    (control, tolerance): (&AdaptiveControl, &Tolerance),
    order: u32,
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    let t0 = progress.time();
    let y0 = *progress.state();
    // HNW's heuristic (I, II.4) has absolute constants (1e-6, 1e-5) and mixes ‖f‖ ~ 1/t
    // with ‖f′‖ ~ 1/t². Running it in τ = t/T, T the length of the integration, makes
    // the first step independent of the unit of time; T = 1 (HNW's own) without a stop.
    let unit = progress
        .stop_time()
        .map(|stop| stop - t0)
        .filter(|length| *length > 0.0 && length.is_finite())
        .unwrap_or(1.0);
    let weight = |i: usize| tolerance.weight(y0[i].abs());
    // A component without a scale (atol = 0 and y = 0) says nothing about the step size
    // here: it does not vote (its value is taken as 0, which counts 0).
    let norm = |v: &SVector<f64, S>| {
        let voting = SVector::<f64, S>::from_fn(|i, _| if weight(i) > 0.0 { v[i] } else { 0.0 });
        // Over the components the error control weighs (`Tolerance::controlling`).
        tolerance.norm(&voting, |i| y0[i].abs())
    };
    let rate_norm = norm(k1) * unit;
    let state_norm = norm(&y0);
    let mut tau = if rate_norm <= 1e-5 || state_norm <= 1e-5 {
        1e-6
    } else {
        0.01 * state_norm / rate_norm
    };
    // Norms that overflow (a tiny absolute tolerance) give 0 or NaN: fall back to the
    // heuristic's own small default, which the controller then grows.
    if !(tau > 0.0 && tau.is_finite()) {
        tau = 1e-6;
    }
    let h = (tau * unit).min(control.max_step);
    let probe = y0 + k1 * h;
    let Ok(k_probe) = state_rate(system, &mut progress.statistics, t0 + h, &probe) else {
        // The probe left the domain (e.g. a mass went negative): the first guess is
        // already small enough to try; rejections will shrink it further if needed.
        return h;
    };
    let second_derivative = norm(&(k_probe - k1)) / h * unit * unit;
    let scale = second_derivative.max(rate_norm);
    let refined = if scale <= 1e-15 {
        (tau * 1e-3).max(1e-6)
    } else {
        powf(0.01 / scale, 1.0 / f64::from(order))
    };
    let first = ((100.0 * tau).min(refined) * unit).min(control.max_step);
    if first > 0.0 && first.is_finite() {
        first
    } else {
        h
    }
}

/// Whether a step of size `h` from `t0` is positive and moves t at all.
pub(crate) fn resolvable(t0: f64, h: f64) -> bool {
    h > 0.0 && t0 + h != t0
}

/// What an adaptive stepper (Dormand–Prince, DOP853, the DIRK stepper; see
/// [`super::adaptive::Adaptive`]) holds besides what its method carries: the system, the
/// progress, the checked settings and the controller's memory. One constructor, the start of a
/// step and the step size to try, written once for all.
#[derive(Clone, Debug)]
pub(crate) struct Controlled<'a, Sys, const S: usize> {
    pub(crate) system: &'a Sys,
    pub(crate) progress: Progress<S>,
    pub(crate) mode: Mode,
    /// Next and last step, the controller's memory, the FSAL rate.
    pub(crate) memory: ControlState<S>,
}

impl<'a, Sys, const S: usize> Controlled<'a, Sys, S> {
    /// Starts at `(time, state)`; the state and the control are checked.
    pub(crate) fn new<const N: usize>(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        control: StepControl,
    ) -> Result<Self, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mode = match control.validated().map_err(|e| e.at(time, &state))? {
            Mode::Adaptive(settings, tolerance) => {
                Mode::Adaptive(settings, tolerance.controlling(system.controlled_entries()))
            }
            fixed => fixed,
        };
        Ok(Self {
            system,
            progress: Progress::new(system, time, state)?,
            mode,
            memory: ControlState::new(),
        })
    }

    /// The start of a step of a method of `order`: its time, its state and the rate there
    /// (FSAL), the first step chosen if none is yet.
    pub(crate) fn begin<const N: usize>(&mut self, order: u32) -> Result<Start<S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let t0 = self.progress.time();
        let y0 = *self.progress.state();
        let k1 = self.memory.rate_at_start(self.system, &mut self.progress)?;
        if self.memory.next_step <= 0.0 {
            let first = self
                .mode
                .first_step(self.system, &mut self.progress, |_| Ok(k1), order);
            self.memory.next_step = first?;
        }
        Ok((t0, y0, k1))
    }

    /// The rate of the system, counted in the progress, for the explicit core.
    pub(crate) fn rates<const N: usize>(&mut self) -> Counted<'_, Sys, N> {
        Counted {
            system: self.system,
            statistics: &mut self.progress.statistics,
        }
    }

    /// The one rejection policy of a failed attempt (a trial state outside the domain:
    /// non-finite, a mass ≤ 0, a singular mass matrix — a step too long, not yet a failure):
    /// the next attempt has size `next`, unless that no longer moves t, when the cause
    /// `error` is returned rather than an underflow.
    pub(crate) fn shrink_or_fail(
        &mut self,
        next: f64,
        error: StepError<S>,
    ) -> Result<(), StepError<S>> {
        self.memory.reject(next, &mut self.progress);
        if resolvable(self.progress.time(), self.memory.next_step) {
            Ok(())
        } else {
            Err(error)
        }
    }

    /// The size of the next attempt from `(t0, y0)` and whether it reaches the stop time; an
    /// underflow error when it no longer moves t.
    pub(crate) fn attempt_size(
        &mut self,
        (t0, y0): (f64, &SVector<f64, S>),
    ) -> Result<(f64, bool), StepError<S>> {
        let (h, reaches_stop) = self.progress.next_step(self.memory.next_step)?;
        if !resolvable(t0, h) {
            let kind = StepErrorKind::StepSizeUnderflow { step: h };
            return Err(StepError::new(t0, *y0, kind));
        }
        Ok((h, reaches_stop))
    }
}

/// A pair's two stages at the same time t₀ + h for the stiffness test: (state, rate).
pub(crate) type StagePair<'v, const S: usize> = (&'v SVector<f64, S>, &'v SVector<f64, S>);

impl<Sys, const S: usize> Controlled<'_, Sys, S> {
    /// Accepts a step of size `h` ending at `end` (the new state and the rate there, which
    /// the next step starts from: FSAL) and runs Hairer's stiffness test `stiffness` on `end`
    /// and `stage`, the other stage at t₀ + h, against the method's h|λ| `bound`.
    pub(crate) fn accept_observed<const N: usize>(
        &mut self,
        (h, reaches_stop): (f64, bool),
        end: StagePair<'_, S>,
        stage: StagePair<'_, S>,
        stiffness: &mut StiffnessTest,
        bound: f64,
    ) -> Result<StepOutcome, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let outcome = self.progress.accept(self.system, h, reaches_stop, *end.0)?;
        let statistics = &mut self.progress.statistics;
        let stiff = stiffness.observe(statistics.accepted_steps, h, end, stage, bound);
        statistics.stiffness_detected |= stiff;
        self.memory.accepted(h, *end.1);
        Ok(outcome)
    }
}

/// The start of a step: t₀, y₀ and the rate there.
pub(crate) type Start<const S: usize> = (f64, SVector<f64, S>, SVector<f64, S>);
