//! The diagonally implicit Runge–Kutta stepper shared by [`super::Sdirk4`] (Hairer &
//! Wanner's SDIRK4) and [`super::Esdirk43`] (Kennedy & Carpenter's ESDIRK4(3)6L\[2\]SA):
//! one implementation, two tableaus ([`DirkTableau`], in the stage increment form of
//! `sdirk4.f` extended to an explicit first stage).
//!
//! Each implicit stage solves Zᵢ = Σ_{j<i} αᵢⱼ Wⱼ + hγ f(t₀ + cᵢh, y₀ + Zᵢ) by simplified
//! Newton with the one matrix I − hγJ, J = [`VariableMassSystem::jacobian`] at the start of
//! a step, kept over the following steps while Newton contracts fast (rate ≤
//! [`DirkNewton::jacobian_reuse_rate`]) and refreshed when it does not. Both methods are
//! stiffly accurate: y₁ = y₀ + Z_M. An explicit first stage costs no evaluation after the
//! first step: its rate f(t₀, y₀) is the last stage's rate of the step before (FSAL), read
//! off the converged stage as (Z_M − G_M)/(hγ). The error estimate is `sdirk4.f`'s filtered
//! difference (I − hγJ)⁻¹(y₁ − ŷ₁), which stays bounded on stiff components; the step size
//! follows err^(−1/4) with the safety factor lowered when Newton needed many iterations.
//!
//! A Newton iteration that diverges or contracts too slowly is retried with a fresh
//! Jacobian, then with half the step; when the step can shrink no further the step fails
//! with a [`StepError`] of kind [`NewtonDivergence`](crate::StepErrorKind::NewtonDivergence)
//! at its start time.

mod stage;
mod tableau;

use core::marker::PhantomData;

use nalgebra::{SMatrix, SVector};

use self::stage::{weighted_norm, StepContext};
pub(crate) use self::tableau::{explicit_parts, on_increments, rate_transform};
pub use self::tableau::{DirkMethod, DirkTableau};
use super::adaptive::{Adaptive, AdaptiveMethod};
use super::control::{resolvable, AdaptiveControl, Mode};
use super::newton::Lu;
use crate::error::{StepError, StepErrorKind};
use crate::math::powf;
use crate::stepper::{state_rate, Checked, Progress, StepOutcome};
use crate::system::VariableMassSystem;

/// The Newton settings of the diagonally implicit steppers (defaults of `sdirk4.f`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirkNewton {
    /// Iterations allowed per stage (`NIT`, default 7).
    pub max_iterations: usize,
    /// The iteration stops when its estimated remaining error is below this fraction of
    /// the error tolerance (`FNEWT`, default 0.03).
    pub tolerance_fraction: f64,
    /// The Jacobian is kept for the next step when Newton's contraction rate stayed below
    /// this (`THET`, default 0.001; larger values reuse it more).
    pub jacobian_reuse_rate: f64,
}

impl Default for DirkNewton {
    fn default() -> Self {
        Self {
            max_iterations: 7,
            tolerance_fraction: 0.03,
            jacobian_reuse_rate: 0.001,
        }
    }
}

/// The error weights of fixed-step mode, where there is no tolerance: Newton then
/// iterates to about 3e-12 relative.
const FIXED_MODE_TOLERANCE: f64 = 1e-10;

/// A diagonally implicit stepper with M stages on the state `[q, p, m_s]`; use it through
/// [`super::Sdirk4`] or [`super::Esdirk43`]. There is no stiffness test (it is made for stiff
/// problems), and of the controller's memory the PI term is unused.
pub type Dirk<'a, Sys, T, const N: usize, const S: usize, const M: usize> =
    Adaptive<'a, Sys, DirkState<T, S, M>, N, S>;

/// What the DIRK stepper carries from one step to the next ([`Adaptive`]'s method).
#[derive(Clone, Debug)]
pub struct DirkState<T, const S: usize, const M: usize> {
    /// The Newton settings ([`Dirk::with_newton`]).
    newton: DirkNewton,
    /// The stage vectors W₁…W_M of the last accepted step.
    increments: [SVector<f64, S>; M],
    /// The Jacobian in use, and whether it was evaluated at the current state.
    jacobian: Option<(SMatrix<f64, S, S>, bool)>,
    /// Hairer's `FACCO`: the last contraction factor θ/(1 − θ) of each stage's Newton
    /// iteration, which lets a fast-converging iteration stop after one update.
    contraction: [f64; M],
    tableau: PhantomData<T>,
}

impl<T, const S: usize, const M: usize> Default for DirkState<T, S, M> {
    fn default() -> Self {
        Self {
            newton: DirkNewton::default(),
            increments: [SVector::zeros(); M],
            jacobian: None,
            contraction: [1.0; M],
            tableau: PhantomData,
        }
    }
}

impl<T, const N: usize, const S: usize, const M: usize> AdaptiveMethod<N, S> for DirkState<T, S, M>
where
    T: DirkMethod<M>,
{
    fn step<Sys: VariableMassSystem<N, S>>(
        stepper: &mut Dirk<'_, Sys, T, N, S, M>,
    ) -> Result<StepOutcome, StepError<S>> {
        let (t0, y0) = (stepper.core.progress.time(), *stepper.core.progress.state());
        if stepper.core.memory.next_step <= 0.0 {
            // HNW's heuristic for order 4, from the rate at the start (evaluated only then).
            let (system, start) = (stepper.core.system, (t0, &y0));
            let rate = |progress: &mut Progress<S>| {
                state_rate(system, &mut progress.statistics, start.0, start.1)
            };
            stepper.core.memory.next_step =
                stepper
                    .core
                    .mode
                    .first_step(system, &mut stepper.core.progress, rate, 4)?;
        }
        let adaptive = match stepper.core.mode {
            Mode::Adaptive(control, _) => Some(control),
            Mode::Fixed(_) => None,
        };
        let mut extrapolate = true;
        loop {
            let (h, reaches_stop) = stepper.core.attempt_size((t0, &y0))?;
            let (jacobian, fresh) = match stepper.method.jacobian {
                Some(pair) => pair,
                None => (stepper.refresh_jacobian(true)?, true),
            };
            let gamma = T::TABLEAU.gamma;
            let matrix = SMatrix::<f64, S, S>::identity() - jacobian * (h * gamma);
            let failure = match Lu::factor(matrix) {
                Some(lu) => {
                    let newton = stepper.method.newton;
                    let context = StepContext {
                        system: stepper.core.system,
                        t0,
                        y0,
                        h,
                        lu: &lu,
                        fresh_jacobian: fresh,
                        weights: stepper.weights(&y0),
                        newton: &newton,
                        gamma,
                    };
                    match (stepper.attempt(&context, extrapolate), adaptive) {
                        (Ok(attempt), None) => return stepper.accept(h, reaches_stop, attempt),
                        (Ok(attempt), Some(control)) => {
                            let proposed = stepper.proposed_after(h, &attempt, &control);
                            if attempt.error <= 1.0 {
                                let accepted = (h, reaches_stop, attempt);
                                return stepper.accept_controlled(&control, proposed, accepted);
                            }
                            stepper
                                .core
                                .memory
                                .reject(proposed, &mut stepper.core.progress);
                            continue;
                        }
                        (Err(failure), _) => failure,
                    }
                }
                None => StageFailure::Newton {
                    iterations: 0,
                    shrink: 0.5,
                },
            };
            extrapolate = false;
            stepper.core.progress.statistics.rejected_steps += 1;
            stepper.core.memory.last_rejected = true;
            stepper.recover(failure, fresh, (t0, y0), h)?;
        }
    }

    fn dense_output<Sys: VariableMassSystem<N, S>>(
        stepper: &Dirk<'_, Sys, T, N, S, M>,
        time: f64,
    ) -> Option<SVector<f64, S>> {
        Some(stepper.interpolate(time))
    }

    fn forget_history(&mut self) {
        self.jacobian = None;
        self.contraction = [1.0; M];
    }
}

/// Why the stages of an attempt could not be solved.
enum StageFailure<const S: usize> {
    /// Newton diverged or converged too slowly after this many iterations; `shrink` is
    /// the factor `sdirk4.f` proposes for the next try.
    Newton { iterations: usize, shrink: f64 },
    /// A rate could not be evaluated (a trial state outside the domain).
    Rate(StepError<S>),
}

/// One attempted step: the stage vectors, the new state, the last stage's rate (for the
/// next step's explicit stage), the scaled error and the Newton work of the last stage
/// (for the step-size safety factor).
struct Attempt<const S: usize, const M: usize> {
    increments: [SVector<f64, S>; M],
    state: SVector<f64, S>,
    last_rate: SVector<f64, S>,
    error: f64,
    last_iterations: usize,
    slowest_rate: f64,
}

/// Σ_{j<upto} coefficientsⱼ Wⱼ, skipping zero coefficients.
fn combination<const S: usize, const M: usize>(
    coefficients: &[f64; M],
    w: &[SVector<f64, S>; M],
    upto: usize,
) -> SVector<f64, S> {
    let mut sum = SVector::zeros();
    for (coefficient, w) in coefficients.iter().zip(w).take(upto) {
        if *coefficient != 0.0 {
            sum += w * *coefficient;
        }
    }
    sum
}

impl<'a, Sys, T, const N: usize, const S: usize, const M: usize> Dirk<'a, Sys, T, N, S, M>
where
    Sys: VariableMassSystem<N, S>,
    T: DirkMethod<M>,
{
    /// The same stepper with other Newton settings (checked).
    pub fn with_newton(mut self, newton: DirkNewton) -> Result<Self, StepError<S>> {
        let valid = newton.max_iterations >= 2
            && newton.tolerance_fraction > 0.0
            && newton.tolerance_fraction < 1.0
            && (0.0..1.0).contains(&newton.jacobian_reuse_rate);
        if !valid {
            let reason = "DIRK Newton: at least 2 iterations, tolerance fraction in (0, 1), \
                          Jacobian reuse rate in [0, 1)";
            let kind = StepErrorKind::InvalidConfiguration { reason };
            return Err(StepError::new(
                self.core.progress.time(),
                *self.core.progress.state(),
                kind,
            ));
        }
        self.method.newton = newton;
        Ok(self)
    }

    /// The third-order dense output over the last accepted step at `time` (meant for
    /// `time` within the step; outside it extrapolates). Before the first step it returns
    /// the current state.
    pub fn interpolate(&self, time: f64) -> SVector<f64, S> {
        let h = self.core.memory.last_step;
        if h <= 0.0 {
            return *self.core.progress.state();
        }
        let [d1, d2, d3, d4] = &T::TABLEAU.dense;
        let row = |d| combination(d, &self.method.increments, M);
        let s = (time - self.core.progress.previous_time()) / h;
        let (c1, c2, c3, c4) = (row(d1), row(d2), row(d3), row(d4));
        self.core.progress.previous_state() + (c1 + (c2 + (c3 + c4 * s) * s) * s) * s
    }

    /// The error weights atol + rtol·|y| (fixed mode: [`FIXED_MODE_TOLERANCE`]).
    fn weights(&self, y: &SVector<f64, S>) -> SVector<f64, S> {
        let (atol, rtol) = match &self.core.mode {
            Mode::Adaptive(c, _) => (c.absolute_tolerance, c.relative_tolerance),
            Mode::Fixed(_) => (FIXED_MODE_TOLERANCE, FIXED_MODE_TOLERANCE),
        };
        y.map(|yi| atol + rtol * yi.abs())
    }

    /// The Jacobian at the current state if the one in hand is stale or missing.
    fn refresh_jacobian(&mut self, force: bool) -> Result<SMatrix<f64, S, S>, StepError<S>> {
        match self.method.jacobian {
            Some((jacobian, fresh)) if fresh || !force => Ok(jacobian),
            _ => {
                let (t0, y0) = (self.core.progress.time(), *self.core.progress.state());
                self.core.progress.statistics.jacobian_evaluations += 1;
                let jacobian =
                    self.core.system.jacobian(t0, &y0).map_err(|error| {
                        StepError::from_system(self.core.system, error, t0, &y0)
                    })?;
                if !jacobian.iter().all(|x| x.is_finite()) {
                    return Err(StepError::new(t0, y0, StepErrorKind::NonFiniteState));
                }
                self.method.jacobian = Some((jacobian, true));
                Ok(jacobian)
            }
        }
    }

    /// The stages, the new state and the error of a step with the context's `h`.
    /// `extrapolate` starts the first implicit stage from the last step's dense output.
    fn attempt(
        &mut self,
        context: &StepContext<'_, Sys, S>,
        extrapolate: bool,
    ) -> Result<Attempt<S, M>, StageFailure<S>> {
        let tableau = &T::TABLEAU;
        let (t0, y0, h) = (context.t0, context.y0, context.h);
        let mut w = [SVector::zeros(); M];
        let first = usize::from(tableau.explicit_first);
        if tableau.explicit_first {
            let rate = self
                .core
                .memory
                .rate_at_start(self.core.system, &mut self.core.progress);
            w[0] = rate.map_err(StageFailure::Rate)? * h;
        }
        let (mut explicit, mut last_iterations, mut slowest_rate) = (SVector::zeros(), 0, 0.0f64);
        for i in first..M {
            explicit = combination(&tableau.alpha[i], &w, i);
            let start = if i == first && extrapolate && self.core.memory.last_step > 0.0 {
                self.interpolate(t0 + tableau.c[i] * h) - y0
            } else {
                combination(&tableau.start[i], &w, i)
            };
            let statistics = &mut self.core.progress.statistics;
            let eta = &mut self.method.contraction[i];
            let stage = context.solve_stage(statistics, tableau.c[i], &explicit, start, eta)?;
            w[i] = stage.increment;
            last_iterations = stage.iterations;
            slowest_rate = slowest_rate.max(stage.slowest_rate);
        }
        let state = y0 + w[M - 1];
        self.core
            .system
            .check_state(t0 + h, &state)
            .map_err(StageFailure::Rate)?;
        let embedded = combination(&tableau.embedded, &w, M);
        let estimate = context.lu.solve(w[M - 1] - embedded);
        let magnitudes = y0.zip_map(&state, |a, b| a.abs().max(b.abs()));
        // Adaptive, over the entries the tolerance weighs (`Tolerance::controlling`: a
        // sensitivity run's columns may be left out); the same weights atol + rtol·m.
        let error = match &self.core.mode {
            Mode::Adaptive(_, tolerance) => tolerance.norm(&estimate, |i| magnitudes[i]),
            Mode::Fixed(_) => weighted_norm(&estimate, &self.weights(&magnitudes)),
        };
        Ok(Attempt {
            last_rate: (w[M - 1] - explicit) / (h * tableau.gamma),
            increments: w,
            state,
            error: error.max(1e-10),
            last_iterations,
            slowest_rate,
        })
    }

    /// The step size `sdirk4.f` proposes after an attempt with this error: err^(−1/4) with
    /// a safety factor lowered when the last stage needed many Newton iterations.
    fn proposed_after(&self, h: f64, attempt: &Attempt<S, M>, control: &AdaptiveControl) -> f64 {
        let iterations = self.method.newton.max_iterations as f64;
        let work = control.safety * (1.0 + 2.0 * iterations)
            / (attempt.last_iterations as f64 + 2.0 * iterations);
        let safety = control.safety.min(work);
        let quotient = (powf(attempt.error, 0.25) / safety)
            .clamp(1.0 / control.max_factor, 1.0 / control.min_factor);
        h / quotient
    }

    fn accept(
        &mut self,
        h: f64,
        reaches_stop: bool,
        attempt: Attempt<S, M>,
    ) -> Result<StepOutcome, StepError<S>> {
        let outcome =
            self.core
                .progress
                .accept(self.core.system, h, reaches_stop, attempt.state)?;
        self.method.increments = attempt.increments;
        // The last stage's rate is f at the new state: the next step's explicit first
        // stage (SDIRK4, without one, never reads it).
        self.core.memory.accepted(h, attempt.last_rate);
        // Keep the Jacobian (now from an earlier state) while Newton contracts fast.
        self.method.jacobian = match self.method.jacobian {
            Some((jacobian, _))
                if attempt.slowest_rate <= self.method.newton.jacobian_reuse_rate =>
            {
                Some((jacobian, false))
            }
            _ => None,
        };
        Ok(outcome)
    }

    /// Accepts a step whose error met the tolerance and takes `proposed` as the next step,
    /// not growing right after a rejection nor beyond the maximum step.
    fn accept_controlled(
        &mut self,
        control: &AdaptiveControl,
        proposed: f64,
        (h, reaches_stop, attempt): (f64, bool, Attempt<S, M>),
    ) -> Result<StepOutcome, StepError<S>> {
        let error = attempt.error;
        let outcome = self.accept(h, reaches_stop, attempt)?;
        let next = self.core.memory.after_acceptance(h, proposed, error);
        self.core
            .memory
            .propose(next, reaches_stop, control.max_step);
        Ok(outcome)
    }

    /// After a failed attempt: a fresh Jacobian if the one used was stale, else a shorter
    /// step; an error when neither is possible (fixed steps, or a step that would
    /// underflow).
    fn recover(
        &mut self,
        failure: StageFailure<S>,
        fresh: bool,
        (t0, y0): (f64, SVector<f64, S>),
        h: f64,
    ) -> Result<(), StepError<S>> {
        let (error, shrink) = match failure {
            StageFailure::Newton { iterations, shrink } => {
                if !fresh {
                    self.refresh_jacobian(true)?;
                    return Ok(());
                }
                let kind = StepErrorKind::NewtonDivergence { iterations };
                let error = StepError::new(t0, y0, kind);
                (error, shrink)
            }
            StageFailure::Rate(error) => (error, 0.25),
        };
        self.core.memory.next_step = h * shrink;
        let fixed = matches!(self.core.mode, Mode::Fixed(_));
        if fixed || !resolvable(t0, self.core.memory.next_step) {
            return Err(error);
        }
        Ok(())
    }
}

impl<Sys, T, const N: usize, const S: usize, const M: usize> Dirk<'_, Sys, T, N, S, M>
where
    Sys: VariableMassSystem<N, S>,
    T: DirkMethod<M>,
{
}
