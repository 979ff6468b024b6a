//! DOP853: Dormand & Prince's explicit Runge–Kutta pair of order 8 with a fifth- and a
//! third-order error estimate and a seventh-order continuous extension (HNW I, II.10; the
//! coefficients and the step logic follow Hairer & Wanner's `dop853.f`, see
//! `dop853/coefficients.rs`).
//!
//! Twelve stages per step, the FSAL rate f(t₁, y₁) becoming the first stage of the next step.
//! The error estimate combines the two embedded solutions as in `dop853.f`:
//! err = |h| ε₅² / √(S (ε₅² + 0.01 ε₃²)), with ε₅, ε₃ the RMS of the scaled estimates
//! times √S, so that it behaves like an eighth-order estimate for small h.
//! The dense output needs three more stages per step; a stepper built
//! [`without_dense_output`](Dop853::without_dense_output) skips them (runs then interpolate
//! by cubic Hermite, enough for output but not for events to 1e-10).
//! Hairer's stiffness test (stages 12 and 13, both at t₀ + h; bound h|λ| = 6.1) sets
//! [`Statistics::stiffness_detected`].

mod coefficients;

use nalgebra::SVector;

use self::coefficients::*;
use super::adaptive::{Adaptive, AdaptiveMethod, ExplicitAttempt};
use super::control::{AdaptiveControl, Mode};
use super::explicit::{self, Counted};
use super::stiffness::StiffnessTest;
use crate::error::{StepError, StepErrorKind};
use crate::math::{powf, sqrt};
use crate::stepper::{state_rate, Checked, Statistics, StepOutcome};
use crate::system::VariableMassSystem;
use crate::tolerance::Tolerance;

/// h|λ| beyond which DOP853's stiffness test counts a step as stiff (`dop853.f`).
const STIFFNESS_BOUND: f64 = 6.1;

/// The DOP853 stepper on the state `[q, p, m_s]`.
pub type Dop853<'a, Sys, const N: usize, const S: usize> = Adaptive<'a, Sys, Dop853State<S>, N, S>;

/// What DOP853 carries from one step to the next ([`Adaptive`]'s method).
#[derive(Clone, Debug)]
pub struct Dop853State<const S: usize> {
    /// Whether the three extra stages of the dense output are computed.
    dense: bool,
    /// The coefficients of the dense output over the last accepted step (`CONT` of
    /// `dop853.f`).
    continuous: [SVector<f64, S>; 8],
    /// Hairer's stiffness test (on stage 12 and the rate at the new state, both at t₀ + h).
    stiffness: StiffnessTest,
}

impl<const S: usize> Default for Dop853State<S> {
    /// With the dense output.
    fn default() -> Self {
        Self {
            stiffness: StiffnessTest::default(),
            dense: true,
            continuous: [SVector::zeros(); 8],
        }
    }
}

impl<const N: usize, const S: usize> AdaptiveMethod<N, S> for Dop853State<S> {
    fn step<Sys: VariableMassSystem<N, S>>(
        stepper: &mut Dop853<'_, Sys, N, S>,
    ) -> Result<StepOutcome, StepError<S>> {
        let (t0, y0, k1) = stepper.core.begin::<N>(8)?;
        let Mode::Adaptive(control, tolerance) = stepper.core.mode else {
            let (h, reaches_stop) = stepper
                .core
                .progress
                .next_step(stepper.core.memory.next_step)?;
            let attempt = attempt(stepper.core.rates(), (t0, &y0), &k1, h, None)?;
            let completion = stepper.complete((t0, &y0), h, &attempt)?;
            return stepper.accept(h, reaches_stop, &attempt, completion);
        };
        loop {
            let (h, reaches_stop) = stepper.core.attempt_size((t0, &y0))?;
            let tolerance = Some(&tolerance);
            let trial = attempt(stepper.core.rates(), (t0, &y0), &k1, h, tolerance);
            let step = ((t0, &y0), h, reaches_stop);
            if let Some(outcome) = stepper.control(&control, step, trial)? {
                return Ok(outcome);
            }
        }
    }

    fn dense_output<Sys: VariableMassSystem<N, S>>(
        stepper: &Dop853<'_, Sys, N, S>,
        time: f64,
    ) -> Option<SVector<f64, S>> {
        stepper.interpolate(time)
    }
}

impl<Sys, const N: usize, const S: usize> Dop853<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// The same stepper without the dense output: three rate evaluations fewer per step
    /// (12 instead of 15), and [`Stepper::dense_output`](crate::stepper::Stepper::dense_output) returns `None`.
    pub fn without_dense_output(mut self) -> Self {
        self.method.dense = false;
        self
    }

    /// The seventh-order dense output over the last accepted step at `time` (`CONTD8`),
    /// or `None` without dense output. Before the first step it returns the current state.
    pub fn interpolate(&self, time: f64) -> Option<SVector<f64, S>> {
        if !self.method.dense {
            return None;
        }
        let h = self.core.memory.last_step;
        if h <= 0.0 {
            return Some(*self.core.progress.state());
        }
        let c = &self.method.continuous;
        let s = (time - self.core.progress.previous_time()) / h;
        let s1 = 1.0 - s;
        let inner = c[4] + (c[5] + (c[6] + c[7] * s) * s1) * s;
        Some(c[0] + (c[1] + (c[2] + (c[3] + inner * s1) * s) * s1) * s)
    }
}

/// The eleven new stages and the new state of a step of size `h` from `(t0, y0)`: the
/// explicit core's stages 2–12 over [`STAGE_ROWS`], the new state from b.
fn attempt<Sys, const N: usize, const S: usize>(
    mut rates: Counted<'_, Sys, N>,
    (t0, y0): (f64, &SVector<f64, S>),
    k1: &SVector<f64, S>,
    h: f64,
    tolerance: Option<&Tolerance>,
) -> Result<ExplicitAttempt<S, 12>, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let mut k = [*k1; 12];
    let stage_12_state = explicit::stages(&STAGE_ROWS, (t0, y0), h, &mut k, &mut [], &mut rates)?;
    // b's increment Σ bⱼ kⱼ serves the new state and the third-order estimate.
    let increment = explicit::weighted_sum(WEIGHTS, &k);
    let y1 = y0 + increment * h;
    rates.system.check_state(t0 + h, &y1)?;
    let error = match tolerance {
        None => 0.0,
        Some(tolerance) => {
            let [k1, _, _, _, _, _, _, _, k9, _, _, k12] = k;
            let fifth = explicit::weighted_sum(ERROR_WEIGHTS, &k);
            let third = increment - k1 * BHH1 - k9 * BHH2 - k12 * BHH3;
            error_norm(&fifth, &third, (y0, &y1), tolerance, h)
        }
    };
    Ok(ExplicitAttempt {
        state: y1,
        stages: k,
        stiffness_state: stage_12_state,
        error,
    })
}

/// err^(1/8 − 0.2β). With β = 0 (`dop853.f`'s default) the eighth root is three square
/// roots: within a few ulps of `powf` (see the test) and a fraction of its cost, which is
/// felt on small systems, where the step control is a good part of a step.
fn step_factor_power(error: f64, beta: f64) -> f64 {
    if beta == 0.0 {
        sqrt(sqrt(sqrt(error)))
    } else {
        powf(error, 0.125 - 0.2 * beta)
    }
}

/// `dop853.f`'s scaled error from the fifth- and third-order estimates (per unit step),
/// each weighed by wᵢ = atol + rtol·max(|y₀ᵢ|, |y₁ᵢ|): with the mean squares m₅, m₃ of the
/// weighted estimates ([`Tolerance::mean_squares_pair`]: the 0/0 rule of
/// [`crate::tolerance::weighted_rms`], one pass), err = |h| m₅ / √(m₅ + 0.01 m₃).
fn error_norm<const S: usize>(
    fifth: &SVector<f64, S>,
    third: &SVector<f64, S>,
    (y0, y1): (&SVector<f64, S>, &SVector<f64, S>),
    tolerance: &Tolerance,
    h: f64,
) -> f64 {
    let magnitude = |i: usize| y0[i].abs().max(y1[i].abs());
    let (mean_fifth, mean_third) = tolerance.mean_squares_pair(fifth, third, magnitude);
    let denominator = mean_fifth + 0.01 * mean_third;
    let denominator = if denominator > 0.0 { denominator } else { 1.0 };
    h.abs() * mean_fifth / sqrt(denominator)
}

/// The coefficients of the dense output of an accepted step (the `CONT` array of
/// `dop853.f`): three more stages, 14–16, from the twelve and k₁₃ = f(t₀ + h, y₁).
fn dense_coefficients<Sys, const N: usize, const S: usize>(
    system: &Sys,
    statistics: &mut Statistics,
    (t0, y0): (f64, &SVector<f64, S>),
    h: f64,
    attempt: &ExplicitAttempt<S, 12>,
    k13: &SVector<f64, S>,
) -> Result<[SVector<f64, S>; 8], StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let [k1, _, _, _, _, k6, k7, k8, k9, k10, k11, k12] = attempt.stages;
    let k13 = *k13;
    // f(t₀ + c h, y₀ + h Σⱼ aⱼ kⱼ), the sum taken term by term in the row's order.
    let mut stage = |c: f64, k: [SVector<f64, S>; 8], a: [f64; 8]| {
        let sum = (1..8).fold(k[0] * a[0], |sum, j| sum + k[j] * a[j]);
        state_rate(system, statistics, t0 + c * h, &(y0 + sum * h))
    };
    let k14 = stage(
        C14,
        [k1, k7, k8, k9, k10, k11, k12, k13],
        [A141, A147, A148, A149, A1410, A1411, A1412, A1413],
    )?;
    let k15 = stage(
        C15,
        [k1, k6, k7, k8, k11, k12, k13, k14],
        [A151, A156, A157, A158, A1511, A1512, A1513, A1514],
    )?;
    let k16 = stage(
        C16,
        [k1, k6, k7, k8, k9, k13, k14, k15],
        [A161, A166, A167, A168, A169, A1613, A1614, A1615],
    )?;
    let stages = [k1, k6, k7, k8, k9, k10, k11, k12, k13, k14, k15, k16];
    let row = |d: [f64; 12]| {
        stages
            .iter()
            .zip(d)
            .map(|(k, d)| k * d)
            .sum::<SVector<f64, S>>()
            * h
    };
    let difference = attempt.state - y0;
    let first = k1 * h - difference;
    Ok([
        *y0,
        difference,
        first,
        difference - k13 * h - first,
        row(DENSE_ROWS[0]),
        row(DENSE_ROWS[1]),
        row(DENSE_ROWS[2]),
        row(DENSE_ROWS[3]),
    ])
}

/// What an accepted step adds to its attempt: the FSAL rate and the dense output.
struct Completion<const S: usize> {
    rate: SVector<f64, S>,
    continuous: Option<[SVector<f64, S>; 8]>,
}

impl<Sys, const N: usize, const S: usize> Dop853<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// The rate at the new state and, if wanted, the dense output of an attempt that
    /// passed the error test.
    fn complete(
        &mut self,
        (t0, y0): (f64, &SVector<f64, S>),
        h: f64,
        attempt: &ExplicitAttempt<S, 12>,
    ) -> Result<Completion<S>, StepError<S>> {
        let statistics = &mut self.core.progress.statistics;
        let rate = state_rate(self.core.system, statistics, t0 + h, &attempt.state)?;
        let continuous = if self.method.dense {
            let step = (t0, y0);
            Some(dense_coefficients(
                self.core.system,
                statistics,
                step,
                h,
                attempt,
                &rate,
            )?)
        } else {
            None
        };
        Ok(Completion { rate, continuous })
    }

    fn accept(
        &mut self,
        h: f64,
        reaches_stop: bool,
        attempt: &ExplicitAttempt<S, 12>,
        completion: Completion<S>,
    ) -> Result<StepOutcome, StepError<S>> {
        // Stage 12 and the rate at the new state are both at t₀ + h.
        let outcome = self.core.accept_observed::<N>(
            (h, reaches_stop),
            (&attempt.state, &completion.rate),
            (&attempt.stiffness_state, &attempt.stages[11]),
            &mut self.method.stiffness,
            STIFFNESS_BOUND,
        )?;
        if let Some(continuous) = completion.continuous {
            self.method.continuous = continuous;
        }
        Ok(outcome)
    }

    /// The step-size controller's verdict on an attempted step of size `h` (`dop853.f`):
    /// accepted (its outcome) when its error is at most 1 and the rate at its end and its
    /// dense output can be evaluated, otherwise `None` with a shorter next step; an error
    /// once the step would underflow.
    fn control(
        &mut self,
        control: &AdaptiveControl,
        ((t0, y0), h, reaches_stop): ((f64, &SVector<f64, S>), f64, bool),
        trial: Result<ExplicitAttempt<S, 12>, StepError<S>>,
    ) -> Result<Option<StepOutcome>, StepError<S>> {
        // Borrowed, not moved out: a step's stages are a few hundred bytes.
        let attempt = match trial {
            Ok(ref attempt) => attempt,
            // A trial state outside the domain (non-finite, a mass ≤ 0, a singular mass
            // matrix) is a step too long, not yet a failure: shrink and retry.
            Err(error) => {
                return self
                    .core
                    .shrink_or_fail(h * control.min_factor, error)
                    .map(|()| None)
            }
        };
        // `dop853.f`: fac11 = err^(1/8 − 0.2β), bounded by the factor limits.
        let error = attempt.error;
        let fac11 = step_factor_power(error, control.beta);
        if error > 1.0 || !error.is_finite() {
            let factor = if error.is_finite() {
                (control.safety / fac11).max(control.min_factor)
            } else {
                control.min_factor
            };
            let kind = StepErrorKind::StepSizeUnderflow { step: h * factor };
            let underflow = StepError::new(t0, *y0, kind);
            return self
                .core
                .shrink_or_fail(h * factor, underflow)
                .map(|()| None);
        }
        let completion = match self.complete((t0, y0), h, attempt) {
            Ok(completion) => completion,
            Err(error) => {
                return self
                    .core
                    .shrink_or_fail(h * control.min_factor, error)
                    .map(|()| None)
            }
        };
        let next = self
            .core
            .memory
            .pi_after_acceptance(control, h, error, fac11);
        let outcome = self.accept(h, reaches_stop, attempt, completion)?;
        self.core
            .memory
            .propose(next, reaches_stop, control.max_step);
        Ok(Some(outcome))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three square roots against `powf(x, 1/8)` over errors from 1e-300 to 1e300.
    #[test]
    fn the_eighth_root_by_square_roots_matches_powf() {
        let mut worst: f64 = 0.0;
        for k in -3000..=3000 {
            let error = 10f64.powf(f64::from(k) / 10.0) * 1.2345;
            let exact = powf(error, 0.125);
            worst = worst.max((step_factor_power(error, 0.0) - exact).abs() / exact);
        }
        eprintln!("worst relative difference {worst:e}");
        // Measured: at most 1 ulp (2.2e-16) apart.
        assert!(worst <= 2.0 * f64::EPSILON, "{worst:e}");
        assert_eq!(step_factor_power(0.5, 0.04), powf(0.5, 0.125 - 0.2 * 0.04));
    }
}
