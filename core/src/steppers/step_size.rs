//! The step-size rule of the explicit pairs over lanes (one lane for the scalar stepper):
//! Dormand–Prince's PI controller (HNW II, IV.2; `dopri5`'s α = 1/5 − 0.75β, β, safety and
//! factor limits) after an accepted attempt, [`step_after_acceptance`], and its factor after
//! a rejected one, [`ClampedErrors::rejection_factor`] — each skipping its `powf`s where the
//! clamp decides alone ([`ClampedErrors`]). `steppers/dormand_prince.rs` runs them on one
//! lane, `lanes/dormand_prince.rs` on W.
//!
//! The two powers err^α and err_prev^β stay one scalar `powf` per lane (a vector `pow`
//! would round otherwise), called back to back so that the calls overlap; the three
//! divisions and the clamp that follow are IEEE operations, the same bits lane by lane as
//! the scalar code's, and run vectorized instead of as a chain of scalar divisions per lane.

use super::control::{AdaptiveControl, ERROR_FLOOR};
use crate::lanes::Lanes;
use crate::math::powf;

/// The error norms at which a Dormand–Prince step factor is decided by its clamp alone, so
/// that the controller may skip its `powf`s there and give the same bits (in lanes the two
/// `powf` per step were a fifth of the time).
///
/// Why the result is the same, bit for bit. Write α = 1/5 − 0.75β ∈ (0.05, 0.2] (β ∈ [0, 0.2)),
/// s the safety, lo = 1/max_factor and hi = 1/min_factor. The full controller computes
/// f = fl(fl(pow(e, α) / P) / s) with P = pow(e_prev, β) (1 without β) and clamps: to lo
/// on acceptance, f ≤ lo giving exactly lo; on rejection `f.min(hi)`, f ≥ hi giving exactly
/// hi. Assume only that `pow` is within a relative 1e-9 of xʸ (glibc's and libm's are within
/// 1 ulp, 2.2e-16). Then:
/// - accepted, e ≤ `smallest` = pow(T, 1/α)·(1 − 10⁻⁶) with T = lo·s·P_min·(1 − 10⁻⁶), P_min
///   = pow(10⁻⁴, β)·(1 − 10⁻⁶): e_prev ≥ 10⁻⁴ (the floor), so the computed P ≥ P_min;
///   pow(e, α) ≤ T (the factor (1 − 10⁻⁶)^α ≤ 1 − 5·10⁻⁸ dwarfs every rounding); and correctly
///   rounded division is monotone, so f ≤ fl(fl(T/P_min)/s) ≤ lo: the clamp gives lo;
/// - rejected, finite e ≥ `largest` = pow(hi·s, 1/α)·(1 + 10⁻⁶): pow(e, α) ≥ hi·s·(1 + 4·10⁻⁸),
///   so fl(pow/s) ≥ hi and `min` gives hi.
///
/// And P = pow(10⁻⁴, β) at the floor is `floor_power`, computed once: the same call on the same
/// arguments. Between the bounds the `powf`s are computed as before. The tests below check
/// the bounds against the full formula on both sides of each.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClampedErrors {
    /// An accepted error at most this makes the PI factor lo.
    pub(crate) smallest: f64,
    /// A rejected finite error at least this makes the factor hi.
    pub(crate) largest: f64,
    /// pow(10⁻⁴, β): P when the previous error is at the floor.
    pub(crate) floor_power: f64,
}

/// The relative margin of [`ClampedErrors`]' bounds.
const CLAMP_MARGIN: f64 = 1e-6;

impl ClampedErrors {
    /// Dormand–Prince's α = 1/5 − 0.75β, as its controller computes it.
    pub(crate) fn exponent(control: &AdaptiveControl) -> f64 {
        0.2 - 0.75 * control.beta
    }

    /// The bounds for `control` (checked: β ∈ [0, 0.2), s ∈ (0, 1], factors finite).
    pub(crate) fn dormand_prince(control: &AdaptiveControl) -> Self {
        let alpha = Self::exponent(control);
        let floor_power = powf(ERROR_FLOOR, control.beta);
        let p_min = if control.beta == 0.0 {
            1.0
        } else {
            floor_power * (1.0 - CLAMP_MARGIN)
        };
        let lo = 1.0 / control.max_factor;
        let hi = 1.0 / control.min_factor;
        let target = lo * control.safety * p_min * (1.0 - CLAMP_MARGIN);
        // Subnormal products round absolutely, not relatively: no shortcut then.
        let smallest = if target >= f64::MIN_POSITIVE {
            powf(target, 1.0 / alpha) * (1.0 - CLAMP_MARGIN)
        } else {
            -1.0
        };
        let largest = powf(hi * control.safety, 1.0 / alpha) * (1.0 + CLAMP_MARGIN);
        Self {
            smallest,
            largest,
            floor_power,
        }
    }

    /// The factor h/h_new after a rejected error `error` (> 1 or NaN): pow(e, α)/s, at most
    /// hi; hi for a non-finite error (`dopri5`'s), without its `powf` where the clamp
    /// decides.
    pub(crate) fn rejection_factor(&self, control: &AdaptiveControl, error: f64) -> f64 {
        let hi = 1.0 / control.min_factor;
        if !error.is_finite() || error >= self.largest {
            return hi;
        }
        (powf(error, Self::exponent(control)) / control.safety).min(hi)
    }
}

/// The step each lane's controller proposes after accepting an attempt of size `h` with
/// scaled error `error` (≤ 1), its previous accepted error being `previous` (≥ 10⁻⁴):
/// h / clamp(err^α / err_prev^β / s, 1/max_factor, 1/min_factor), before the rule that a
/// step right after a rejection may not grow (`ControlState::after_acceptance`). The value
/// in a lane whose error is above 1 or NaN (a rejection) is not meaningful.
pub(crate) fn step_after_acceptance<const W: usize>(
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
    use crate::steppers::control::ControlState;

    /// The controls the bounds are tried on : Hairer's
    /// defaults, no PI term, the largest β with a safety of 1 and a narrower factor range,
    /// and a factor range of one point.
    fn controls() -> [AdaptiveControl; 4] {
        let default = AdaptiveControl::default();
        [
            default,
            AdaptiveControl {
                beta: 0.0,
                ..AdaptiveControl::dop853()
            },
            AdaptiveControl {
                beta: 0.199,
                safety: 1.0,
                max_factor: 3.0,
                ..default
            },
            AdaptiveControl {
                min_factor: 1.0,
                max_factor: 1.0,
                ..default
            },
        ]
    }

    /// Errors spread geometrically over `[low, high]`, and the neighbours of `around` to
    /// a few ulps.
    fn errors(low: f64, high: f64, around: f64) -> Vec<f64> {
        let mut errors: Vec<f64> = (0..=400)
            .map(|i| low * powf(high / low, f64::from(i) / 400.0))
            .collect();
        let bits = around.to_bits();
        errors.extend((bits - 4..=bits + 4).map(f64::from_bits));
        errors
    }

    /// After a rejection the factor with the shortcut equals the full formula's
    /// (pow(e, α)/s at most hi, hi for a non-finite error) to the bit, across the bound;
    /// both bounds are within 10⁻⁴ of the exact thresholds (tight: the shortcut covers
    /// nearly all of the clamp's range).
    #[test]
    fn the_rejection_shortcut_gives_the_full_controllers_factor() {
        for control in controls() {
            let clamped = ClampedErrors::dormand_prince(&control);
            let alpha = ClampedErrors::exponent(&control);
            let hi = 1.0 / control.min_factor;
            let top = clamped.largest * 1e3;
            let mut checked = errors(1.0, top, clamped.largest);
            checked.extend([f64::INFINITY, f64::NAN]);
            for error in checked {
                let expected = if error.is_finite() {
                    (powf(error, alpha) / control.safety).min(hi)
                } else {
                    hi
                };
                let got = clamped.rejection_factor(&control, error);
                assert_eq!(got.to_bits(), expected.to_bits(), "{control:?} {error:e}");
            }
            let exact = powf(hi * control.safety, 1.0 / alpha);
            let gap = (clamped.largest - exact) / exact;
            assert!(gap > 0.0 && gap < 1e-4, "{control:?}: gap {gap:e}");
            // The acceptance bound against the exact threshold with the smallest P (the
            // previous error at the floor), e^α = lo·s·P_min: measured 1.3e-5 below it for
            // β = 0.04 (the margins, raised to 1/α). Its bits: the next test.
            let p_min = powf(ERROR_FLOOR, control.beta);
            let exact = powf(p_min * control.safety / control.max_factor, 1.0 / alpha);
            let gap = (exact - clamped.smallest) / exact;
            assert!(gap > 0.0 && gap < 1e-4, "{control:?}: gap {gap:e}");
        }
    }

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
