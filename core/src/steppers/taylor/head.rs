//! The Taylor stepper's head: the first two coefficients in double-double, from the
//! system's state rate over dual numbers ([`VariableMassSystem::taylor_head`]), and the
//! increment added to the state in double-double.
//!
//! Why (`tests/kepler_floor.rs`): with every coefficient in double, each step rounds
//! c₁ = f(y) and c₂ = ½ (J f + ∂f/∂t) to a few ulps, and over many steps that rounding
//! walks the solution off (Kepler's floor, 1.3e-14 at tolerance 1e-16); the coefficients
//! from c₃ on are multiplied by h³ and more, so their rounding is far below the state's
//! ulp. With c₁, c₂ and the sum in double-double, what is left is truncation.

use nalgebra::SVector;

use super::Taylor;
use crate::dd::{Dd, Dual};
use crate::error::{StepError, StepErrorKind};
use crate::system::VariableMassSystem;

impl<Sys, const N: usize, const S: usize> Taylor<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// c₁ and c₂ in double-double at (t₀, y_hi + y_lo), y_lo the compensation: the head
    /// evaluated twice, in double-double for c₁ = f(y) (`taylor_head_rate`), then over
    /// dual numbers at y + ε c₁ with the time t₀ + ε for c₂ = ½ d f/dt (its derivative
    /// part). One evaluation along the double expansion's c₁ instead would leave
    /// ½ J (c₁ − fl(c₁)) in c₂, an error of the size of c₂'s own rounding: tried, Kepler
    /// ended 7.6e-15 off at tolerance 1e-15 (5.2e-16 with two evaluations,
    /// `tests/kepler_floor.rs`).
    fn head_coefficients(&mut self) -> Result<([Dd; S], [Dd; S]), StepError<S>> {
        let (t0, y0) = (self.progress.time(), *self.progress.state());
        let y: [Dd; S] = core::array::from_fn(|i| Dd::from((y0[i], self.compensation[i])));
        let missing = || {
            let reason = "the system stopped providing its double-double head";
            StepError::invalid_configuration(t0, y0, reason)
        };
        let c1 = self.system.taylor_head_rate(t0, &y).ok_or_else(missing)?;
        let along: [Dual; S] = core::array::from_fn(|i| Dual::new(y[i], c1[i]));
        let time = Dual::new(Dd::new(t0), Dd::new(1.0));
        let derivative = self.system.taylor_head(time, &along).ok_or_else(missing)?;
        let c2 = derivative.map(|r| r.d * 0.5);
        self.progress.statistics.rate_evaluations += 2;
        let finite = c1.iter().chain(&c2).all(|c| c.is_finite());
        if finite {
            Ok((c1, c2))
        } else {
            Err(StepError::new(t0, y0, StepErrorKind::NonFiniteState))
        }
    }

    /// y_hi + y_lo + c₁h + c₂h² + Σₖ₌₃ cₖhᵏ with c₁, c₂ from the head, the tail
    /// Σₖ₌₃ cₖhᵏ⁻² by Horner's rule in double and the rest in double-double; the new state
    /// and its low part (the next step's compensation). c₁ and c₂ rounded to double replace
    /// the expansion's, for the dense output.
    pub(super) fn head_sum(
        &mut self,
        order: usize,
        h: f64,
    ) -> Result<(SVector<f64, S>, SVector<f64, S>), StepError<S>> {
        let (c1, c2) = self.head_coefficients()?;
        let y0 = *self.progress.state();
        let mut state = SVector::zeros();
        let mut low = SVector::zeros();
        for i in 0..S {
            let mut tail = 0.0;
            for c in self.coefficients[3.min(order + 1)..=order].iter().rev() {
                tail = (tail + c[i]) * h;
            }
            let second = if order >= 2 { c2[i] } else { Dd::ZERO };
            let increment = (c1[i] + (second + tail) * h) * h;
            let sum = Dd::from((y0[i], self.compensation[i])) + increment;
            state[i] = sum.hi;
            low[i] = sum.lo;
            self.coefficients[1][i] = c1[i].hi;
            if order >= 2 {
                self.coefficients[2][i] = c2[i].hi;
            }
        }
        Ok((state, low))
    }
}
