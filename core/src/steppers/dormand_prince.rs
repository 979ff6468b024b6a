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
//! The stages, the new state and the error estimate are the explicit core's
//! (`explicit.rs`) over `STAGE_ROWS`, `WEIGHTS` and `ERROR_WEIGHTS` (`dp_tableau.rs`):
//! the error estimate is y₁ − ŷ₁ = h Σ eⱼ kⱼ with e = b − b̂. Dense output is Hairer's
//! `CONTD5` (HNW I, II.6, and the `dopri5` code): a quartic in θ = (t − t₀)/h through y₀ and
//! y₁ with the end slopes k₁ and k₇ and one more combination of the stages (coefficients dⱼ).
//! The step-size controller is Gustafsson's PI controller (HNW II, IV.2) as in Hairer's
//! `dopri5`: β = 0.04, safety 0.9, factor in [0.2, 10]. Hairer's stiffness test (stages 6
//! and 7, both at t₀ + h; bound h|λ| = 3.25) sets `Statistics::stiffness_detected`.

use nalgebra::SVector;

use super::adaptive::{Adaptive, AdaptiveMethod, ExplicitAttempt};
use super::control::{AdaptiveControl, Mode};
use super::explicit::{self, Counted, Rates};
use super::step_size::{step_after_acceptance, ClampedErrors};
use super::stiffness::StiffnessTest;
use crate::error::StepError;
use crate::lanes::Lanes;
use crate::stepper::{Checked, StepOutcome};
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
    /// The errors at which the step factor is its clamp's, for the control (computed at the
    /// first adaptive step: the control does not change).
    clamped: Option<ClampedErrors>,
}

impl<const S: usize> Default for DormandPrinceState<S> {
    fn default() -> Self {
        Self {
            stages: [SVector::zeros(); 7],
            stiffness: StiffnessTest::default(),
            clamped: None,
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
            let tolerance = match stepper.core.mode {
                Mode::Adaptive(_, tolerance) => Some(tolerance),
                Mode::Fixed(_) => None,
            };
            let rates = stepper.core.rates();
            let attempt = attempt(rates, (t0, &y0), &k1, h, tolerance.as_ref());
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

/// The six new stages and the new state of a step of size `h` from `(t0, y0)`: the explicit
/// core's stages 2–6, the new state from b, checked, and its rate k₇ (FSAL).
fn attempt<Sys, const N: usize, const S: usize>(
    mut rates: Counted<'_, Sys, N>,
    (t0, y0): (f64, &SVector<f64, S>),
    k1: &SVector<f64, S>,
    h: f64,
    tolerance: Option<&Tolerance>,
) -> Result<ExplicitAttempt<S, 7>, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let mut k = [*k1; 7];
    let stage_6 = explicit::stages(STAGE_ROWS, (t0, y0), h, &mut k, &mut [], &mut rates)?;
    let y1 = explicit::solution(WEIGHTS, y0, &k, h);
    rates.system.check_state(t0 + h, &y1)?;
    k[6] = rates.rate(t0 + h, &y1)?;
    let error = match tolerance {
        None => 0.0,
        Some(tolerance) => {
            let estimate = explicit::combination(ERROR_WEIGHTS, &k, h);
            explicit::error_norm(tolerance, &estimate, (y0, &y1))
        }
    };
    Ok(ExplicitAttempt {
        state: y1,
        stages: k,
        stiffness_state: stage_6,
        error,
    })
}

/// Dormand–Prince's continuous extension over one step (Hairer's `CONTD5`): its
/// coefficients, which do not depend on the time, computed once for the times asked. The
/// scalar stepper's [`DormandPrince::interpolate`] and the lanes' events use it.
pub(crate) struct Dense<const S: usize> {
    y0: SVector<f64, S>,
    y1: SVector<f64, S>,
    difference: SVector<f64, S>,
    first: SVector<f64, S>,
    second: SVector<f64, S>,
    third: SVector<f64, S>,
    h: f64,
    t0: f64,
}

impl<const S: usize> Dense<S> {
    /// The extension over the step of size `h` from `(t0, y0)` to `y1` with stages `k`.
    pub(crate) fn new(
        (t0, y0): (f64, &SVector<f64, S>),
        y1: &SVector<f64, S>,
        h: f64,
        k: &[SVector<f64, S>; 7],
    ) -> Self {
        let difference = y1 - y0;
        let first = k[0] * h - difference;
        let second = difference - k[6] * h - first;
        let third = (k[0] * D1 + k[2] * D3 + k[3] * D4 + k[4] * D5 + k[5] * D6 + k[6] * D7) * h;
        Self {
            y0: *y0,
            y1: *y1,
            difference,
            first,
            second,
            third,
            h,
            t0,
        }
    }

    /// The quartic at `time` (meant for `time` within the step; outside it extrapolates);
    /// the new state for a step of no length.
    pub(crate) fn at(&self, time: f64) -> SVector<f64, S> {
        SVector::from_fn(|j, _| self.component_at(j, time))
    }

    /// Component `j` of [`Self::at`].
    #[inline]
    pub(crate) fn component_at(&self, j: usize, time: f64) -> f64 {
        let h = self.h;
        if h <= 0.0 {
            return self.y1[j];
        }
        let theta = (time - self.t0) / h;
        let theta1 = 1.0 - theta;
        let (difference, first, second) = (self.difference[j], self.first[j], self.second[j]);
        self.y0[j]
            + (difference + (first + (second + self.third[j] * theta1) * theta) * theta1) * theta
    }
}

impl<Sys, const N: usize, const S: usize> DormandPrince<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// The dense output over the last accepted step: the fourth-order continuous extension
    /// (`Dense`), evaluated at `time` (meant for `time` within the step; outside it
    /// extrapolates). Before the first step it returns the current state.
    pub fn interpolate(&self, time: f64) -> SVector<f64, S> {
        let progress = &self.core.progress;
        let start = (progress.previous_time(), progress.previous_state());
        let h = self.core.memory.last_step;
        Dense::new(start, progress.state(), h, &self.method.stages).at(time)
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
        let clamped = *self
            .method
            .clamped
            .get_or_insert_with(|| ClampedErrors::dormand_prince(control));
        match attempt {
            Ok(attempt) if attempt.error <= 1.0 => {
                // The PI controller (HNW II, IV.2), as the lanes compute it.
                let (error, previous) = (attempt.error, self.core.memory.previous_error);
                let proposal = step_after_acceptance(
                    control,
                    &clamped,
                    Lanes([h]),
                    Lanes([error]),
                    Lanes([previous]),
                );
                let next = self.core.memory.after_acceptance(h, proposal.0[0], error);
                let outcome = self.accept(h, reaches_stop, attempt)?;
                self.core
                    .memory
                    .propose(next, reaches_stop, control.max_step);
                Ok(Some(outcome))
            }
            Ok(attempt) => {
                let factor = clamped.rejection_factor(control, attempt.error);
                self.core.memory.reject(h / factor, &mut self.core.progress);
                Ok(None)
            }
            // A trial state outside the domain (non-finite, a mass ≤ 0, a singular mass
            // matrix) is a step too long, not yet a failure.
            Err(error) => self
                .core
                .shrink_or_fail(h * control.min_factor, error)
                .map(|()| None),
        }
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
