//! SDIRK4: Hairer & Wanner's L-stable singly diagonally implicit Runge–Kutta method of
//! order 4 with an embedded third-order solution (HNW II, IV.6, Table 6.5, γ = 1/4; the
//! coefficients and the step logic follow `sdirk4.f`, see `sdirk4/coefficients.rs`).
//!
//! Each of the five stages solves Zᵢ = Σ_{j<i} αᵢⱼ Zⱼ + hγ f(t₀ + cᵢh, y₀ + Zᵢ) by simplified
//! Newton with the one matrix I − hγJ, J = [`VariableMassSystem::jacobian`] at the start of
//! a step, kept over the following steps while Newton contracts fast (rate ≤
//! [`Sdirk4Newton::jacobian_reuse_rate`]) and refreshed when it does not. The method is
//! stiffly accurate: y₁ = y₀ + Z₅. The error estimate is `sdirk4.f`'s filtered difference
//! (I − hγJ)⁻¹(y₁ − ŷ₁), which stays bounded on stiff components; the step size follows
//! err^(−1/4) with the safety factor lowered when Newton needed many iterations.
//! The dense output is the cubic-in-increments polynomial of `sdirk4.f` (order 3).
//!
//! A Newton iteration that diverges or contracts too slowly is retried with a fresh
//! Jacobian, then with half the step; when the step can shrink no further the step fails
//! with a [`StepError`] of kind [`NewtonDivergence`](crate::StepErrorKind::NewtonDivergence) at its start time.

mod coefficients;

use nalgebra::{SMatrix, SVector};

use self::coefficients::*;
use super::dormand_prince::{initial_step, resolvable, AdaptiveControl};
use super::newton::Lu;
use super::StepControl;
use crate::error::{StepError, StepErrorKind};
use crate::math::powf;
use crate::stepper::{check_state, state_rate, Progress, Statistics, StepOutcome, Stepper};
use crate::system::VariableMassSystem;
use crate::tolerance::{weighted_rms, Tolerance};

/// The Newton settings of [`Sdirk4`] (defaults of `sdirk4.f`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sdirk4Newton {
    /// Iterations allowed per stage (`NIT`, default 7).
    pub max_iterations: usize,
    /// The iteration stops when its estimated remaining error is below this fraction of
    /// the error tolerance (`FNEWT`, default 0.03).
    pub tolerance_fraction: f64,
    /// The Jacobian is kept for the next step when Newton's contraction rate stayed below
    /// this (`THET`, default 0.001; larger values reuse it more).
    pub jacobian_reuse_rate: f64,
}

impl Default for Sdirk4Newton {
    fn default() -> Self {
        Self {
            max_iterations: 7,
            tolerance_fraction: 0.03,
            jacobian_reuse_rate: 0.001,
        }
    }
}

impl AdaptiveControl {
    /// The adaptive control with the defaults of `sdirk4.f`: tolerances as
    /// [`AdaptiveControl::default`], safety 0.9, step factors in [1/4, 4], no PI term.
    pub fn sdirk4() -> Self {
        Self {
            min_factor: 0.25,
            max_factor: 4.0,
            beta: 0.0,
            ..Self::default()
        }
    }
}

/// The error weights of fixed-step mode, where there is no tolerance: Newton then
/// iterates to about 3e-12 relative.
const FIXED_MODE_TOLERANCE: f64 = 1e-10;

/// The SDIRK4 stepper on the state `[q, p, m_s]`.
#[derive(Clone, Debug)]
pub struct Sdirk4<'a, Sys, const N: usize, const S: usize> {
    system: &'a Sys,
    progress: Progress<S>,
    control: StepControl,
    /// The checked tolerance of the adaptive mode.
    tolerance: Option<Tolerance>,
    newton: Sdirk4Newton,
    /// The size of the next step to try (0 until the first step chooses it).
    next_step: f64,
    /// The size of the last accepted step, for the dense output.
    last_step: f64,
    /// The stage increments Z₁…Z₅ of the last accepted step.
    increments: [SVector<f64, S>; 5],
    /// The Jacobian in use, and whether it was evaluated at the current state.
    jacobian: Option<(SMatrix<f64, S, S>, bool)>,
    /// Hairer's `FACCO`: the last contraction factor θ/(1 − θ) of each stage's Newton
    /// iteration, which lets a fast-converging iteration stop after one update.
    contraction: [f64; 5],
    /// Whether the last attempt was rejected, so the next step may not grow.
    last_rejected: bool,
}

/// Why the stages of an attempt could not be solved.
enum StageFailure<const S: usize> {
    /// Newton diverged or converged too slowly after this many iterations; `shrink` is
    /// the factor `sdirk4.f` proposes for the next try.
    Newton { iterations: usize, shrink: f64 },
    /// A rate could not be evaluated (a trial state outside the domain).
    Rate(StepError<S>),
}

/// One attempted step: the increments, the new state, the scaled error and the Newton
/// work of its last stage (for the step-size safety factor).
struct Attempt<const S: usize> {
    increments: [SVector<f64, S>; 5],
    state: SVector<f64, S>,
    error: f64,
    last_iterations: usize,
    slowest_rate: f64,
}

impl<'a, Sys, const N: usize, const S: usize> Sdirk4<'a, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// Starts at `(time, state)`; the state and the control are checked. See
    /// [`AdaptiveControl::sdirk4`] for the settings of `sdirk4.f`.
    pub fn new(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        control: StepControl,
    ) -> Result<Self, StepError<S>> {
        let tolerance = control
            .checked_tolerance()
            .map_err(|e| e.at(time, &state))?;
        Ok(Self {
            system,
            progress: Progress::new(system, time, state)?,
            control,
            tolerance,
            newton: Sdirk4Newton::default(),
            next_step: 0.0,
            last_step: 0.0,
            increments: [SVector::zeros(); 5],
            jacobian: None,
            contraction: [1.0; 5],
            last_rejected: false,
        })
    }

    /// The same stepper with other Newton settings (checked).
    pub fn with_newton(self, newton: Sdirk4Newton) -> Result<Self, StepError<S>> {
        let valid = newton.max_iterations >= 2
            && newton.tolerance_fraction > 0.0
            && newton.tolerance_fraction < 1.0
            && (0.0..1.0).contains(&newton.jacobian_reuse_rate);
        if !valid {
            let reason = "SDIRK4 Newton: at least 2 iterations, tolerance fraction in (0, 1), \
                          Jacobian reuse rate in [0, 1)";
            let kind = StepErrorKind::InvalidConfiguration { reason };
            return Err(StepError::new(self.time(), *self.state(), kind));
        }
        Ok(Self { newton, ..self })
    }

    /// The third-order dense output over the last accepted step at `time` (meant for
    /// `time` within the step; outside it extrapolates). Before the first step it returns
    /// the current state.
    pub fn interpolate(&self, time: f64) -> SVector<f64, S> {
        let h = self.last_step;
        if h <= 0.0 {
            return *self.progress.state();
        }
        let z = &self.increments;
        let row = |d: [f64; 5]| z[0] * d[0] + z[1] * d[1] + z[2] * d[2] + z[3] * d[3] + z[4] * d[4];
        let s = (time - self.progress.previous_time()) / h;
        let c1 = row([D11, D12, D13, D14, D15]);
        let c2 = row([D21, D22, D23, D24, D25]);
        let c3 = row([D31, D32, D33, D34, D35]);
        let c4 = row([D41, D42, D43, D44, D45]);
        self.progress.previous_state() + (c1 + (c2 + (c3 + c4 * s) * s) * s) * s
    }

    /// The size of the step the stepper will try next (0 before the first step).
    pub fn proposed_step(&self) -> f64 {
        self.next_step
    }

    /// The error weights atol + rtol·|y| (fixed mode: [`FIXED_MODE_TOLERANCE`]).
    fn weights(&self, y: &SVector<f64, S>) -> SVector<f64, S> {
        let (atol, rtol) = match &self.control {
            StepControl::Adaptive(c) => (c.absolute_tolerance, c.relative_tolerance),
            StepControl::Fixed(_) => (FIXED_MODE_TOLERANCE, FIXED_MODE_TOLERANCE),
        };
        y.map(|yi| atol + rtol * yi.abs())
    }

    /// The Jacobian at the current state if the one in hand is stale or missing.
    fn refresh_jacobian(&mut self, force: bool) -> Result<SMatrix<f64, S, S>, StepError<S>> {
        match self.jacobian {
            Some((jacobian, fresh)) if fresh || !force => Ok(jacobian),
            _ => {
                let (t0, y0) = (self.progress.time(), *self.progress.state());
                self.progress.statistics.jacobian_evaluations += 1;
                let jacobian = self
                    .system
                    .jacobian(t0, &y0)
                    .map_err(|error| StepError::from_system(self.system, error, t0, &y0))?;
                if !jacobian.iter().all(|x| x.is_finite()) {
                    return Err(StepError::new(t0, y0, StepErrorKind::NonFiniteState));
                }
                self.jacobian = Some((jacobian, true));
                Ok(jacobian)
            }
        }
    }
}

/// What the stages of one step share: the start, the step, the factorised I − hγJ, the
/// error weights and the Newton settings.
struct StepContext<'c, Sys, const S: usize> {
    system: &'c Sys,
    t0: f64,
    y0: SVector<f64, S>,
    h: f64,
    lu: &'c Lu<S>,
    /// Whether the Jacobian was evaluated at y₀ (rather than kept from an earlier step).
    fresh_jacobian: bool,
    weights: SVector<f64, S>,
    newton: &'c Sdirk4Newton,
}

/// The [`weighted_rms`] of v against the weights w.
fn weighted_norm<const S: usize>(v: &SVector<f64, S>, weights: &SVector<f64, S>) -> f64 {
    weighted_rms(v, |i| weights[i])
}

/// A solved stage: its increment, its Newton iterations and slowest contraction rate.
struct Stage<const S: usize> {
    increment: SVector<f64, S>,
    iterations: usize,
    slowest_rate: f64,
}

impl<Sys, const S: usize> StepContext<'_, Sys, S> {
    /// Solves Z = G + hγ f(t₀ + ch, y₀ + Z) from `start` by simplified Newton (`sdirk4.f`'s
    /// loop 40), updating the stage's contraction factor.
    fn solve_stage<const N: usize>(
        &self,
        statistics: &mut Statistics,
        c: f64,
        explicit: &SVector<f64, S>,
        start: SVector<f64, S>,
        contraction: &mut f64,
    ) -> Result<Stage<S>, StageFailure<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (h, newton) = (self.h, self.newton);
        let iterations = newton.max_iterations;
        let mut z = start;
        // `sdirk4.f` starts from the stage's last contraction factor, so that a fast
        // iteration may stop after one update. With a Jacobian kept from an earlier step
        // that factor is not known to hold: it is measured again (≥ 2 iterations unless
        // the first update is already within the tolerance). Without this the error of a
        // single update with a stale Jacobian set a floor (Kepler orbit: 1.2e-9 at a
        // tolerance of 1e-11, against 1.7e-10 with a fresh Jacobian).
        let mut factor = if self.fresh_jacobian {
            powf(contraction.max(f64::EPSILON), 0.8)
        } else {
            1.0
        };
        let (mut previous, mut slowest_rate) = (0.0, 0.0f64);
        let diverged = |iterations| StageFailure::Newton {
            iterations,
            shrink: 0.5,
        };
        for iteration in 1..=iterations {
            let time = self.t0 + c * h;
            let rate = state_rate(self.system, statistics, time, &(self.y0 + z))
                .map_err(StageFailure::Rate)?;
            let delta = self.lu.solve(explicit - z + rate * (h * GAMMA));
            statistics.newton_iterations += 1;
            let norm = weighted_norm(&delta, &self.weights);
            if !norm.is_finite() {
                return Err(diverged(iteration));
            }
            if iteration >= 2 {
                let theta = norm / previous;
                if theta >= 0.99 {
                    return Err(diverged(iteration));
                }
                slowest_rate = slowest_rate.max(theta);
                factor = theta / (1.0 - theta);
                if iteration < iterations {
                    // Will the remaining iterations reach the tolerance at this rate?
                    let exponent = (iterations - 1 - iteration) as i32;
                    let predicted = factor * norm * theta.powi(exponent);
                    let ratio = (predicted / newton.tolerance_fraction).clamp(1e-4, 16.0);
                    if ratio >= 1.0 {
                        let remaining = (iterations - iteration) as f64;
                        let shrink = 0.8 * powf(ratio, -1.0 / remaining);
                        return Err(StageFailure::Newton {
                            iterations: iteration,
                            shrink,
                        });
                    }
                }
            }
            previous = norm;
            z += delta;
            let rounding = self
                .y0
                .zip_map(&z, |y, z| 16.0 * f64::EPSILON * (y + z).abs());
            if factor * norm <= newton.tolerance_fraction || weighted_norm(&delta, &rounding) <= 1.0
            {
                *contraction = factor;
                return Ok(Stage {
                    increment: z,
                    iterations: iteration,
                    slowest_rate,
                });
            }
        }
        Err(diverged(iterations))
    }
}

impl<Sys, const N: usize, const S: usize> Sdirk4<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// The five stages, the new state and the error of a step with the context's `h`.
    /// `extrapolate` starts stage 1 from the last step's dense output.
    fn attempt(
        &mut self,
        context: &StepContext<'_, Sys, S>,
        extrapolate: bool,
    ) -> Result<Attempt<S>, StageFailure<S>> {
        let (t0, y0, h) = (context.t0, context.y0, context.h);
        let start = if extrapolate && self.last_step > 0.0 {
            self.interpolate(t0 + GAMMA * h) - y0
        } else {
            SVector::zeros()
        };
        let statistics = &mut self.progress.statistics;
        let eta = &mut self.contraction;
        let zero = SVector::zeros();
        let s1 = context.solve_stage(statistics, GAMMA, &zero, start, &mut eta[0])?;
        let z1 = s1.increment;
        let g2 = z1 * ALPH21;
        let s2 = context.solve_stage(statistics, C2, &g2, z1 * ETA1, &mut eta[1])?;
        let z2 = s2.increment;
        let g3 = z1 * ALPH31 + z2 * ALPH32;
        let start = z1 * ANU1 + z2 * ANU2;
        let s3 = context.solve_stage(statistics, C3, &g3, start, &mut eta[2])?;
        let z3 = s3.increment;
        let g4 = z1 * ALPH41 + z2 * ALPH42 + z3 * ALPH43;
        let start = z1 * AMU1 + z3 * AMU3;
        let s4 = context.solve_stage(statistics, C4, &g4, start, &mut eta[3])?;
        let z4 = s4.increment;
        let embedded = z1 * E1 + z2 * E2 + z3 * E3 + z4 * E4;
        let g5 = z1 * ALPH51 + z2 * ALPH52 + z3 * ALPH53 + z4 * ALPH54;
        let s5 = context.solve_stage(statistics, 1.0, &g5, embedded, &mut eta[4])?;
        let z5 = s5.increment;
        let state = y0 + z5;
        check_state(self.system, t0 + h, &state).map_err(StageFailure::Rate)?;
        let estimate = context.lu.solve(z5 - embedded);
        let weights = self.weights(&y0.zip_map(&state, |a, b| a.abs().max(b.abs())));
        let slowest_rate = [&s1, &s2, &s3, &s4, &s5]
            .iter()
            .fold(0.0f64, |slowest, s| slowest.max(s.slowest_rate));
        Ok(Attempt {
            increments: [z1, z2, z3, z4, z5],
            state,
            error: weighted_norm(&estimate, &weights).max(1e-10),
            last_iterations: s5.iterations,
            slowest_rate,
        })
    }

    /// The step size `sdirk4.f` proposes after an attempt with this error: err^(−1/4) with
    /// a safety factor lowered when the last stage needed many Newton iterations.
    fn proposed_after(&self, h: f64, attempt: &Attempt<S>, control: &AdaptiveControl) -> f64 {
        let iterations = self.newton.max_iterations as f64;
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
        attempt: Attempt<S>,
    ) -> Result<StepOutcome, StepError<S>> {
        let outcome = self
            .progress
            .accept(self.system, h, reaches_stop, attempt.state)?;
        self.increments = attempt.increments;
        self.last_step = h;
        self.last_rejected = false;
        // Keep the Jacobian (now from an earlier state) while Newton contracts fast.
        self.jacobian = match self.jacobian {
            Some((jacobian, _)) if attempt.slowest_rate <= self.newton.jacobian_reuse_rate => {
                Some((jacobian, false))
            }
            _ => None,
        };
        Ok(outcome)
    }

    /// The first step: the fixed step, the configured one, or HNW's heuristic for order 4.
    fn first_step(&mut self) -> Result<f64, StepError<S>> {
        Ok(match self.control {
            StepControl::Fixed(fixed) => fixed.step,
            StepControl::Adaptive(control) => match control.initial_step {
                Some(h) => h.min(control.max_step),
                None => {
                    let (t0, y0) = (self.progress.time(), *self.progress.state());
                    let statistics = &mut self.progress.statistics;
                    let rate = state_rate(self.system, statistics, t0, &y0)?;
                    let tolerance = self.tolerance.expect("adaptive mode has a tolerance");
                    let settings = (&control, &tolerance);
                    initial_step(self.system, &mut self.progress, &rate, settings, 4)
                }
            },
        })
    }
}

impl<Sys, const N: usize, const S: usize> Stepper<N, S> for Sdirk4<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    type System = Sys;

    fn system(&self) -> &Sys {
        self.system
    }

    fn progress(&self) -> &Progress<S> {
        &self.progress
    }

    fn set_stop_time(&mut self, stop_time: f64) -> Result<(), StepError<S>> {
        self.progress.set_stop_time(stop_time)
    }

    fn restart(&mut self, time: f64, state: SVector<f64, S>) -> Result<(), StepError<S>> {
        self.progress.restart(self.system, time, state)?;
        self.last_step = 0.0;
        self.jacobian = None;
        self.contraction = [1.0; 5];
        self.last_rejected = false;
        Ok(())
    }

    fn dense_output(&self, time: f64) -> Option<SVector<f64, S>> {
        Some(self.interpolate(time))
    }

    fn step(&mut self) -> Result<StepOutcome, StepError<S>> {
        let (t0, y0) = (self.progress.time(), *self.progress.state());
        if self.next_step <= 0.0 {
            self.next_step = self.first_step()?;
        }
        let adaptive = match self.control {
            StepControl::Adaptive(control) => Some(control),
            StepControl::Fixed(_) => None,
        };
        let mut extrapolate = true;
        loop {
            let (h, reaches_stop) = self.progress.next_step(self.next_step)?;
            if !resolvable(t0, h) {
                let kind = StepErrorKind::StepSizeUnderflow { step: h };
                return Err(StepError::new(t0, y0, kind));
            }
            let (jacobian, fresh) = match self.jacobian {
                Some(pair) => pair,
                None => (self.refresh_jacobian(true)?, true),
            };
            let matrix = SMatrix::<f64, S, S>::identity() - jacobian * (h * GAMMA);
            let failure = match Lu::factor(matrix) {
                Some(lu) => {
                    let newton = self.newton;
                    let context = StepContext {
                        system: self.system,
                        t0,
                        y0,
                        h,
                        lu: &lu,
                        fresh_jacobian: fresh,
                        weights: self.weights(&y0),
                        newton: &newton,
                    };
                    match (self.attempt(&context, extrapolate), adaptive) {
                        (Ok(attempt), None) => return self.accept(h, reaches_stop, attempt),
                        (Ok(attempt), Some(control)) => {
                            let proposed = self.proposed_after(h, &attempt, &control);
                            if attempt.error <= 1.0 {
                                let next = if self.last_rejected {
                                    proposed.min(h)
                                } else {
                                    proposed
                                };
                                let outcome = self.accept(h, reaches_stop, attempt)?;
                                if !reaches_stop || next > self.next_step {
                                    self.next_step = next.min(control.max_step);
                                }
                                return Ok(outcome);
                            }
                            self.next_step = proposed;
                            self.last_rejected = true;
                            self.progress.statistics.rejected_steps += 1;
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
            self.progress.statistics.rejected_steps += 1;
            self.last_rejected = true;
            self.recover(failure, fresh, (t0, y0), h)?;
        }
    }
}

impl<Sys, const N: usize, const S: usize> Sdirk4<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
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
        self.next_step = h * shrink;
        let fixed = matches!(self.control, StepControl::Fixed(_));
        if fixed || !resolvable(t0, self.next_step) {
            return Err(error);
        }
        Ok(())
    }
}
