//! Hairer's stiffness detection for explicit Runge–Kutta pairs (HNW II, IV.2, and the
//! `NSTIFF` logic of `dopri5` and `dop853`).
//!
//! Two stages evaluated at the same time t₀ + h, at states Y and Y′, give an estimate of
//! the dominant eigenvalue of the Jacobian: |λ| ≈ ‖f(Y) − f(Y′)‖ / ‖Y − Y′‖. When h|λ| sits
//! near the boundary of the method's stability region (3.25 for Dormand–Prince 5(4), 6.1 for
//! DOP853), the step size is limited by stability, not accuracy: the scene is stiff. The
//! test runs every 1000 accepted steps, and on every step once it has been positive; 15
//! positive results (without 6 negative ones in a row in between) declare stiffness.

use nalgebra::SVector;

/// Accepted steps between two tests while the scene does not look stiff.
const TEST_INTERVAL: usize = 1000;
/// Positive tests that declare the scene stiff.
const POSITIVE_TO_DECLARE: usize = 15;
/// Negative tests in a row that clear the positive ones.
const NEGATIVE_TO_CLEAR: usize = 6;

/// The counters of the test.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct StiffnessTest {
    positive: usize,
    negative: usize,
}

impl StiffnessTest {
    /// Observes an accepted step (the `accepted_steps`-th) whose two same-time stages are
    /// `(state, rate)` and `(other_state, other_rate)`; returns whether the scene has just
    /// been declared stiff. `threshold` is the method's h|λ| bound.
    pub(crate) fn observe<const S: usize>(
        &mut self,
        accepted_steps: usize,
        step: f64,
        (state, rate): (&SVector<f64, S>, &SVector<f64, S>),
        (other_state, other_rate): (&SVector<f64, S>, &SVector<f64, S>),
        threshold: f64,
    ) -> bool {
        if !accepted_steps.is_multiple_of(TEST_INTERVAL) && self.positive == 0 {
            return false;
        }
        let denominator = (state - other_state).norm_squared();
        let h_lambda = if denominator > 0.0 {
            step.abs() * crate::math::sqrt((rate - other_rate).norm_squared() / denominator)
        } else {
            0.0
        };
        if h_lambda > threshold {
            self.negative = 0;
            self.positive += 1;
            self.positive == POSITIVE_TO_DECLARE
        } else {
            self.negative += 1;
            if self.negative == NEGATIVE_TO_CLEAR {
                self.positive = 0;
            }
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector1;

    /// y′ = λy with the two stages one unit apart: h|λ| is exactly |h λ|.
    fn observe(test: &mut StiffnessTest, accepted: usize, h_lambda: f64) -> bool {
        let (y, other) = (Vector1::new(1.0), Vector1::new(0.0));
        test.observe(
            accepted,
            1.0,
            (&y, &Vector1::new(-h_lambda)),
            (&other, &Vector1::new(0.0)),
            3.25,
        )
    }

    #[test]
    fn fifteen_positive_tests_declare_stiffness_and_six_negative_ones_clear_them() {
        let mut test = StiffnessTest::default();
        // Off the test interval, nothing is tested.
        assert!(!observe(&mut test, 999, 100.0));
        assert_eq!(test, StiffnessTest::default());
        // The first positive test, then every step is tested.
        assert!(!observe(&mut test, 1000, 3.3));
        let declared: Vec<bool> = (1001..1015).map(|n| observe(&mut test, n, 4.0)).collect();
        assert_eq!(declared.iter().filter(|&&d| d).count(), 1);
        assert!(declared[13], "the 15th positive test declares stiffness");

        let mut test = StiffnessTest::default();
        for n in 1000..1014 {
            assert!(!observe(&mut test, n, 4.0));
        }
        for n in 1014..1020 {
            assert!(!observe(&mut test, n, 1.0));
        }
        // Six negatives cleared the fourteen positives: not tested until the next interval.
        assert!(!observe(&mut test, 1020, 4.0));
        assert_eq!(test.positive, 0);
    }
}
