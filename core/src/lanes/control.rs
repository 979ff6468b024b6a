//! The step controller's arithmetic over lanes: the PI controller's next step after an
//! accepted attempt (HNW II, IV.2; `ControlState::pi_after_acceptance` with Dormand–Prince's
//! α = 1/5 − 0.75β), for every lane at once.
//!
//! The two powers err^α and err_prev^β stay one scalar `powf` per lane (a vector `pow`
//! would round otherwise), called back to back so that the calls overlap, and skipped where
//! [`ClampedErrors`] shows the clamp decides alone; the three divisions and the clamp that
//! follow are IEEE operations, the same bits lane by lane as the scalar code's, and run
//! vectorized instead of as a chain of scalar divisions per lane.

use super::Lanes;
use crate::math::powf;
use crate::steppers::control::{AdaptiveControl, ClampedErrors, ERROR_FLOOR};

/// The step each lane's controller proposes after accepting an attempt of size `h` with
/// scaled error `error` (≤ 1), its previous accepted error being `previous` (≥ 10⁻⁴):
/// h / clamp(err^α / err_prev^β / s, 1/max_factor, 1/min_factor), before the rule that a
/// step right after a rejection may not grow (`ControlState::after_acceptance`). The value
/// in a lane whose error is above 1 or NaN (a rejection) is not meaningful.
pub(super) fn step_after_acceptance<const W: usize>(
    control: &AdaptiveControl,
    clamped: &ClampedErrors,
    h: Lanes<W>,
    error: Lanes<W>,
    previous: Lanes<W>,
) -> Lanes<W> {
    let alpha = ClampedErrors::exponent(control);
    let smallest = 1.0 / control.max_factor;
    let largest = 1.0 / control.min_factor;
    let mut power = Lanes::splat(1.0);
    let mut previous_power = Lanes::splat(1.0);
    let mut decided = [false; W];
    for (i, &e) in error.0.iter().enumerate() {
        // An error above 1 or NaN is a rejection, whose proposal is not read.
        let accepted = e <= 1.0;
        if !accepted || e <= clamped.smallest {
            decided[i] = true;
            continue;
        }
        power.0[i] = powf(e, alpha);
        previous_power.0[i] = if control.beta == 0.0 {
            1.0
        } else if previous.0[i] == ERROR_FLOOR {
            clamped.floor_power
        } else {
            powf(previous.0[i], control.beta)
        };
    }
    let factor = (power / previous_power / control.safety).map(|f| f.clamp(smallest, largest));
    h / Lanes::select(decided, Lanes::splat(smallest), factor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::steppers::control::tests::controls;
    use crate::steppers::control::ControlState;

    /// Every lane's proposal is the scalar controller's (`pi_after_acceptance` with err^α
    /// by `powf`) to the bit, for errors across the clamp's bound (to a few ulps of it, and
    /// at 0), previous errors at the floor and above it, and the controls of the scalar
    /// controller's tests (Hairer's defaults, no PI term, the largest β, one factor).
    #[test]
    fn lanes_propose_the_scalar_controllers_step() {
        for control in controls() {
            let clamped = ClampedErrors::dormand_prince(&control);
            let alpha = ClampedErrors::exponent(&control);
            let bound = clamped.smallest.to_bits();
            let mut errors: Vec<f64> = (bound - 6..=bound + 6).map(f64::from_bits).collect();
            errors.extend((0..=200).map(|i| 1e-12 * powf(1e12, f64::from(i) / 200.0)));
            errors.extend([0.0, 1.0]);
            for previous in [ERROR_FLOOR, 3e-4, 0.2, 1.0] {
                for chunk in errors.chunks(4) {
                    let e = Lanes::<4>::from_fn(|i| chunk.get(i).copied().unwrap_or(0.5));
                    let h = Lanes::<4>::from_fn(|i| 0.1 + 0.3 * i as f64);
                    let lanes =
                        step_after_acceptance(&control, &clamped, h, e, Lanes::splat(previous));
                    for i in 0..4 {
                        let mut scalar = ControlState::<1>::new();
                        scalar.previous_error = previous;
                        // A step not after a rejection: the proposal itself.
                        let error = e.0[i];
                        let expected =
                            scalar.pi_after_acceptance(&control, h.0[i], error, powf(error, alpha));
                        assert_eq!(
                            lanes.0[i].to_bits(),
                            expected.to_bits(),
                            "{control:?}: error {error:e}, previous {previous:e}"
                        );
                    }
                }
            }
        }
    }
}
