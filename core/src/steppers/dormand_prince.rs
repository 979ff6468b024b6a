//! The Dormand–Prince 5(4) pair: adaptive fifth-order steps with a fourth-order error
//! estimate, a PI step-size controller and a fourth-order continuous extension.
//!
//! Butcher tableau (Dormand & Prince, *A family of embedded Runge–Kutta formulae*, J. Comp.
//! Appl. Math. 6, 1980; Hairer–Nørsett–Wanner I, II.5, Table 5.2). The method is FSAL: the
//! last stage is the rate at the new state and becomes the first stage of the next step.
//!
//! ```text
//!  0    |
//!  1/5  | 1/5
//!  3/10 | 3/40        9/40
//!  4/5  | 44/45      −56/15       32/9
//!  8/9  | 19372/6561 −25360/2187  64448/6561  −212/729
//!  1    | 9017/3168  −355/33      46732/5247   49/176   −5103/18656
//!  1    | 35/384      0           500/1113     125/192  −2187/6784    11/84
//! ------+----------------------------------------------------------------------------
//!  y₁   | 35/384      0           500/1113     125/192  −2187/6784    11/84     0
//!  ŷ₁   | 5179/57600  0           7571/16695   393/640  −92097/339200 187/2100  1/40
//! ```
//!
//! The error estimate is y₁ − ŷ₁ = h Σ eⱼ kⱼ with e = b − b̂. Dense output is Hairer's
//! `CONTD5` (HNW I, II.6, and the `dopri5` code): a quartic in θ = (t − t₀)/h through y₀ and
//! y₁ with the end slopes k₁ and k₇ and one more combination of the stages (coefficients dⱼ).
//! The step-size controller is Gustafsson's PI controller (HNW II, IV.2) as in Hairer's
//! `dopri5`: β = 0.04, safety 0.9, factor in [0.2, 10]. Hairer's stiffness test (stages 6
//! and 7, both at t₀ + h; bound h|λ| = 3.25) sets [`Statistics::stiffness_detected`].

use nalgebra::SVector;

use super::adaptive::{Adaptive, AdaptiveMethod, ExplicitAttempt};
use super::control::{resolvable, AdaptiveControl, Mode};
use super::stiffness::StiffnessTest;
use crate::error::StepError;
use crate::math::powf;
use crate::stepper::{state_rate, Checked, Statistics, StepOutcome};
use crate::system::VariableMassSystem;
use crate::tolerance::Tolerance;

/// h|λ| beyond which the stiffness test counts a step as stiff (`dopri5.f`).
const STIFFNESS_BOUND: f64 = 3.25;

use super::dp_tableau::*;

/// The Dormand–Prince 5(4) stepper on the state `[q, p, m_s]`.
pub type DormandPrince<'a, Sys, const N: usize, const S: usize> =
    Adaptive<'a, Sys, DormandPrinceState<S>, N, S>;

/// What Dormand–Prince carries from one step to the next ([`Adaptive`]'s method).
#[derive(Clone, Debug)]
pub struct DormandPrinceState<const S: usize> {
    /// The stages k₁…k₇ of the last accepted step.
    stages: [SVector<f64, S>; 7],
    /// Hairer's stiffness test (on stages 6 and 7, both at t₀ + h).
    stiffness: StiffnessTest,
}

impl<const S: usize> Default for DormandPrinceState<S> {
    fn default() -> Self {
        Self {
            stages: [SVector::zeros(); 7],
            stiffness: StiffnessTest::default(),
        }
    }
}

impl<const N: usize, const S: usize> AdaptiveMethod<N, S> for DormandPrinceState<S> {
    fn step<Sys: VariableMassSystem<N, S>>(
        stepper: &mut DormandPrince<'_, Sys, N, S>,
    ) -> Result<StepOutcome, StepError<S>> {
        let (t0, y0, k1) = stepper.core.begin::<N>(5)?;
        loop {
            let (h, reaches_stop) = stepper.core.attempt_size((t0, &y0))?;
            let tolerance = match &stepper.core.mode {
                Mode::Adaptive(_, tolerance) => Some(tolerance),
                Mode::Fixed(_) => None,
            };
            let attempt = DormandPrince::attempt(
                stepper.core.system,
                &mut stepper.core.progress.statistics,
                t0,
                &y0,
                &k1,
                h,
                tolerance,
            );
            let Mode::Adaptive(control, _) = stepper.core.mode else {
                return stepper.accept(h, reaches_stop, attempt?);
            };
            if let Some(outcome) = stepper.control(&control, h, reaches_stop, attempt)? {
                return Ok(outcome);
            }
        }
    }

    fn dense_output<Sys: VariableMassSystem<N, S>>(
        stepper: &DormandPrince<'_, Sys, N, S>,
        time: f64,
    ) -> Option<SVector<f64, S>> {
        Some(stepper.interpolate(time))
    }
}

impl<Sys, const N: usize, const S: usize> DormandPrince<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// The dense output over the last accepted step: the fourth-order continuous extension,
    /// evaluated at `time` (meant for `time` within the step; outside it extrapolates).
    /// Before the first step it returns the current state.
    pub fn interpolate(&self, time: f64) -> SVector<f64, S> {
        let h = self.core.memory.last_step;
        let y0 = self.core.progress.previous_state();
        let y1 = self.core.progress.state();
        if h <= 0.0 {
            return *y1;
        }
        let k = &self.method.stages;
        let theta = (time - self.core.progress.previous_time()) / h;
        let theta1 = 1.0 - theta;
        let difference = y1 - y0;
        let first = k[0] * h - difference;
        let second = difference - k[6] * h - first;
        let third = (k[0] * D1 + k[2] * D3 + k[3] * D4 + k[4] * D5 + k[5] * D6 + k[6] * D7) * h;
        y0 + (difference + (first + (second + third * theta1) * theta) * theta1) * theta
    }

    /// The six new stages and the new state of a step of size `h` from `(t0, y0)`.
    fn attempt(
        system: &Sys,
        statistics: &mut Statistics,
        t0: f64,
        y0: &SVector<f64, S>,
        k1: &SVector<f64, S>,
        h: f64,
        tolerance: Option<&Tolerance>,
    ) -> Result<ExplicitAttempt<S, 7>, StepError<S>> {
        let k1 = *k1;
        let k2 = state_rate(system, statistics, t0 + C2 * h, &(y0 + k1 * (A21 * h)))?;
        let y3 = y0 + (k1 * A31 + k2 * A32) * h;
        let k3 = state_rate(system, statistics, t0 + C3 * h, &y3)?;
        let y4 = y0 + (k1 * A41 + k2 * A42 + k3 * A43) * h;
        let k4 = state_rate(system, statistics, t0 + C4 * h, &y4)?;
        let y5 = y0 + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h;
        let k5 = state_rate(system, statistics, t0 + C5 * h, &y5)?;
        let y6 = y0 + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h;
        let k6 = state_rate(system, statistics, t0 + h, &y6)?;
        let y1 = y0 + (k1 * B1 + k3 * B3 + k4 * B4 + k5 * B5 + k6 * B6) * h;
        system.check_state(t0 + h, &y1)?;
        let k7 = state_rate(system, statistics, t0 + h, &y1)?;
        // Each component weighed by atol + rtol·max(|y₀ᵢ|, |y₁ᵢ|).
        let error = match tolerance {
            None => 0.0,
            Some(tolerance) => {
                let estimate = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
                tolerance.norm(&estimate, |i| y0[i].abs().max(y1[i].abs()))
            }
        };
        Ok(ExplicitAttempt {
            state: y1,
            stages: [k1, k2, k3, k4, k5, k6, k7],
            stiffness_state: y6,
            error,
        })
    }

    /// The step-size controller's verdict on an attempted step of size `h`: accepted (its
    /// outcome) when its error is at most 1, otherwise `None` with a shorter next step. A
    /// failed attempt is a step too long as well, unless the step cannot shrink any more.
    fn control(
        &mut self,
        control: &AdaptiveControl,
        h: f64,
        reaches_stop: bool,
        attempt: Result<ExplicitAttempt<S, 7>, StepError<S>>,
    ) -> Result<Option<StepOutcome>, StepError<S>> {
        match attempt {
            Ok(attempt) if attempt.error <= 1.0 => self
                .accept_controlled(control, h, reaches_stop, attempt)
                .map(Some),
            Ok(attempt) => {
                let factor = powf(attempt.error, 0.2 - 0.75 * control.beta) / control.safety;
                // A non-finite error estimate (overflowing stages) shrinks the most.
                let factor = if attempt.error.is_finite() {
                    factor.min(1.0 / control.min_factor)
                } else {
                    1.0 / control.min_factor
                };
                self.reject(h / factor);
                Ok(None)
            }
            Err(error) => {
                // A trial state outside the domain (non-finite, a mass ≤ 0, a singular mass
                // matrix) is a step too long, not yet a failure: shrink and retry. If the
                // step underflows, report the cause rather than the underflow.
                self.reject(h * control.min_factor);
                if resolvable(self.core.progress.time(), self.core.memory.next_step) {
                    Ok(None)
                } else {
                    Err(error)
                }
            }
        }
    }

    /// Accepts a step whose error met the tolerance and chooses the next step by the PI
    /// controller (HNW II, IV.2): h_new = h·err^(−α)·err_old^β with α = 1/5 − 0.75β, within
    /// the factor limits, not growing right after a rejection.
    fn accept_controlled(
        &mut self,
        control: &AdaptiveControl,
        h: f64,
        reaches_stop: bool,
        attempt: ExplicitAttempt<S, 7>,
    ) -> Result<StepOutcome, StepError<S>> {
        let error_power = powf(attempt.error, 0.2 - 0.75 * control.beta);
        let next = self
            .core
            .memory
            .pi_after_acceptance(control, h, attempt.error, error_power);
        let outcome = self.accept(h, reaches_stop, attempt)?;
        self.core
            .memory
            .propose(next, reaches_stop, control.max_step);
        Ok(outcome)
    }

    /// Rejects an attempt: the next attempt has size `next`.
    fn reject(&mut self, next: f64) {
        self.core.memory.reject(next, &mut self.core.progress);
    }

    fn accept(
        &mut self,
        h: f64,
        reaches_stop: bool,
        attempt: ExplicitAttempt<S, 7>,
    ) -> Result<StepOutcome, StepError<S>> {
        // Stages 6 and 7 are both at t₀ + h; stage 7 is the rate at the new state.
        let outcome = self.core.accept_observed::<N>(
            (h, reaches_stop),
            (&attempt.state, &attempt.stages[6]),
            (&attempt.stiffness_state, &attempt.stages[5]),
            &mut self.method.stiffness,
            STIFFNESS_BOUND,
        )?;
        self.method.stages = attempt.stages;
        Ok(outcome)
    }
}
