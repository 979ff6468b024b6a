//! Error tolerances and the weighted RMS norm every error control measures with.
//!
//! A tolerance gives each component i the weight wᵢ = atol + rtol·mᵢ, mᵢ a magnitude of that
//! component (|y₀ᵢ|, max(|y₀ᵢ|, |y₁ᵢ|), |zᵢ|, … as the method chooses), and an error vector e
//! meets it when the weighted RMS √(Σ (eᵢ/wᵢ)² / D) is at most 1 (Hairer–Nørsett–Wanner I,
//! II.4). Dormand–Prince (its step-size control and its first step), DOP853 (through
//! [`Tolerance::mean_squares_pair`]) and the Newton iteration of the implicit steppers all
//! measure with [`weighted_rms`]'s rule; their configurations are checked
//! by [`Tolerance::new`]. The Taylor stepper's order and step come from a [`Tolerance`] too
//! (Jorba & Zou's rule, `steppers/taylor.rs`).
//!
//! **The floor is the method's.** A relative tolerance finer than the method's arithmetic
//! can honour only shrinks the steps (or raises the order) without lowering the error, so
//! each method refuses one below its [`Floor`], the finest at which the achieved error
//! still follows the tolerance, measured on Kepler (e = 0.5, three orbits, against the
//! exact orbit; `tests/kepler_floor.rs::tolerance_floor_table`) and the sled
//! (`tests/tolerance_floor.rs::tolerance_floor_table`). The one rule: [`Tolerance::new`]
//! checks against [`Floor::ErrorEstimate`], [`Tolerance::for_floor`] against the floor it
//! is given, and each stepper refuses a tolerance below its own floor.

use nalgebra::SVector;

use crate::error::ConfigError;
use crate::math::sqrt;

/// The root mean square of `values[i] / weight(i)` over all D components:
/// √(Σᵢ (vᵢ / wᵢ)² / D).
///
/// The 0/0 rule: a component whose value is exactly zero contributes 0, whatever its weight.
/// With a purely relative tolerance (atol = 0) a component that is exactly zero has weight 0,
/// and a zero error there meets any tolerance; without the rule 0/0 = NaN would poison the
/// norm and fail every test against it. A non-zero value over a zero weight still gives an
/// infinite norm: an error where no error is tolerated.
///
/// The sum runs over i = 0, 1, …, D − 1 in that order, so the result is reproducible to the
/// last bit.
pub fn weighted_rms<const D: usize>(
    values: &SVector<f64, D>,
    weight: impl Fn(usize) -> f64,
) -> f64 {
    let sum: f64 = (0..D)
        .map(|i| scaled_square(values[i], |v| v / weight(i)))
        .sum();
    sqrt(sum / D as f64)
}

/// scale(value)², scale dividing by the weight, with the 0/0 rule of [`weighted_rms`]: an
/// exact zero counts 0 whatever its weight; a non-zero value over a zero weight is ∞.
/// (The caller chooses how to divide: `v / w`, or `v * (1/w)` when one inverse serves two
/// vectors.)
fn scaled_square(value: f64, scale: impl FnOnce(f64) -> f64) -> f64 {
    if value == 0.0 {
        0.0
    } else {
        let scaled = scale(value);
        scaled * scaled
    }
}

/// The finest relative tolerance a method honours: below it the achieved error stops
/// following the tolerance (the module docs say where each was measured).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Floor {
    /// The error-estimating steppers (Dormand–Prince, DOP853, SDIRK4, ESDIRK4(3)):
    /// 100 machine epsilons, ≈ 2.2e-14. The rounding of one step's own arithmetic (a few ε
    /// per stage, times the stages, times the magnitude of the state) is already of that
    /// size, and their error estimates see only rounding below it. Hairer's codes refuse
    /// such tolerances for the same reason (DOPRI5 and DOP853 stop with "tolerances are
    /// too small" below 10·uround; 100 ε leaves the margin the estimates need). Measured:
    /// DOP853 on Kepler ends 7.6e-13 off at 100 ε, 9.4e-14 at 1e-14, 1.0e-13 at 1e-15 and
    /// 9.9e-14 at 1e-16 (run below the floor for the measurement): it stops following at
    /// about 1e-14, and 100 ε keeps a factor 2 to spare.
    ErrorEstimate,
    /// The Taylor stepper in double: 1e-15 (≈ 4.5 ε). Down to it the error follows the
    /// tolerance where truncation dominates: the sled's closed form over 1 s is met to
    /// 2.7e-16 at 1e-14 and 1.3e-16 (one ulp) at 1e-15, Kepler over ¾ orbit to 9.6e-16 at
    /// 1e-15 (`core/tests/taylor.rs`). Below it only the order grows, and the error is the
    /// rounding of the first two coefficients at every step: Kepler over three orbits ends
    /// 2.0e-14 rms over 16 starts at 1e-14 and at 1e-15 (6.7e-14 at 100 ε), and no lower
    /// than 1.0e-14 at any finer tolerance.
    Taylor,
    /// The Taylor stepper with its double-double head (`Taylor::with_head`): one machine
    /// epsilon, ≈ 2.2e-16. On Kepler's start 5.2e-16 at 1e-15, 2.4e-16 at 2e-16 and
    /// 1e-16, 4.3e-16 at 1e-17: the state's own storage (half an ulp of θ ≈ 6π) is all
    /// that is left.
    TaylorHead,
}

impl Floor {
    /// The finest relative tolerance.
    pub const fn relative(self) -> f64 {
        match self {
            Self::ErrorEstimate => 100.0 * f64::EPSILON,
            Self::Taylor => 1e-15,
            Self::TaylorHead => f64::EPSILON,
        }
    }

    /// Why a finer relative tolerance is refused, with the number (a constant string, as
    /// [`ConfigError`] carries one).
    const fn refusal(self) -> &'static str {
        match self {
            Self::ErrorEstimate => {
                "the relative tolerance is below 100 machine epsilons (2.2e-14), the floor of \
                 the error-estimating steppers: finer than f64 can honour"
            }
            Self::Taylor => {
                "the relative tolerance is below 1e-15, the Taylor stepper's floor in double \
                 (its double-double head honours down to 2.2e-16)"
            }
            Self::TaylorHead => {
                "the relative tolerance is below one machine epsilon (2.2e-16), the floor of \
                 the Taylor stepper with its double-double head"
            }
        }
    }

    /// `relative` against this floor: refused (with the floor in the reason) when it is
    /// positive and finer.
    pub fn check(self, relative: f64) -> Result<(), ConfigError> {
        if relative > 0.0 && relative < self.relative() {
            Err(ConfigError {
                reason: self.refusal(),
            })
        } else {
            Ok(())
        }
    }
}

/// A relative and an absolute tolerance, checked: both finite and non-negative, not both
/// zero, and a relative tolerance, when there is one, no finer than the method's
/// [`Floor`] ([`Tolerance::MIN_RELATIVE`] for [`Tolerance::new`]). Component i of an error
/// is weighed against [`Tolerance::weight`]: atol + rtol·mᵢ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    relative: f64,
    absolute: f64,
    /// How many leading components an error norm weighs ([`Tolerance::controlling`]).
    entries: usize,
}

impl Tolerance {
    /// The finest relative tolerance of the error-estimating steppers, 100 machine
    /// epsilons (≈ 2.2e-14): [`Floor::ErrorEstimate`]'s.
    pub const MIN_RELATIVE: f64 = Floor::ErrorEstimate.relative();

    /// A tolerance of `relative` (rtol) and `absolute` (atol) for the error-estimating
    /// steppers: [`Tolerance::for_floor`] at [`Floor::ErrorEstimate`].
    pub fn new(relative: f64, absolute: f64) -> Result<Self, ConfigError> {
        Self::for_floor(relative, absolute, Floor::ErrorEstimate)
    }

    /// A tolerance of `relative` (rtol) and `absolute` (atol) for a method of floor
    /// `floor`; fails unless both are finite and non-negative, at least one is positive,
    /// and a positive `relative` is at least the floor (a purely absolute tolerance,
    /// rtol = 0, stays usable).
    pub fn for_floor(relative: f64, absolute: f64, floor: Floor) -> Result<Self, ConfigError> {
        let usable = relative >= 0.0
            && absolute >= 0.0
            && relative.is_finite()
            && absolute.is_finite()
            && relative + absolute > 0.0;
        if !usable {
            return Err(ConfigError {
                reason: "tolerances must be finite, non-negative and not both zero",
            });
        }
        floor.check(relative)?;
        Ok(Self {
            relative,
            absolute,
            entries: usize::MAX,
        })
    }

    /// This tolerance weighing only the first `entries` components of an error (all by
    /// default): forward sensitivities' columns left out of the error control, CVODES's
    /// `errconS = false` (`sensitivity::Sensitive::with_error_control`). At least one.
    pub fn controlling(self, entries: usize) -> Self {
        Self {
            entries: entries.max(1),
            ..self
        }
    }

    /// How many leading components an error norm weighs (of a vector of `len`).
    pub fn entries(&self, len: usize) -> usize {
        self.entries.min(len)
    }

    /// The relative tolerance rtol.
    pub fn relative(&self) -> f64 {
        self.relative
    }

    /// The absolute tolerance atol.
    pub fn absolute(&self) -> f64 {
        self.absolute
    }

    /// The weight atol + rtol·`magnitude` of a component of that magnitude.
    pub fn weight(&self, magnitude: f64) -> f64 {
        self.absolute + self.relative * magnitude
    }

    /// The [`weighted_rms`] of `values` with the weights of components of magnitudes
    /// `magnitude(i)`; at most 1 means the tolerance is met.
    pub fn norm<const D: usize>(
        &self,
        values: &SVector<f64, D>,
        magnitude: impl Fn(usize) -> f64,
    ) -> f64 {
        let entries = self.entries(D);
        if entries == D {
            return weighted_rms(values, |i| self.weight(magnitude(i)));
        }
        let sum: f64 = (0..entries)
            .map(|i| scaled_square(values[i], |v| v / self.weight(magnitude(i))))
            .sum();
        sqrt(sum / entries as f64)
    }

    /// The mean squares Σᵢ (aᵢ/wᵢ)²/D and Σᵢ (bᵢ/wᵢ)²/D of two vectors against the same
    /// weights (the squares of their [`Tolerance::norm`]s), in one pass with one division per
    /// component: for an error estimate measured twice, as DOP853's.
    pub fn mean_squares_pair<const D: usize>(
        &self,
        a: &SVector<f64, D>,
        b: &SVector<f64, D>,
        magnitude: impl Fn(usize) -> f64,
    ) -> (f64, f64) {
        let (mut sum_a, mut sum_b) = (0.0, 0.0);
        let entries = self.entries(D);
        for i in 0..entries {
            let inverse = 1.0 / self.weight(magnitude(i));
            sum_a += scaled_square(a[i], |v| v * inverse);
            sum_b += scaled_square(b[i], |v| v * inverse);
        }
        (sum_a / entries as f64, sum_b / entries as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (3/1, 4/2) has mean square (9 + 4)/2: exact in binary, so compared exactly.
    #[test]
    fn weighted_rms_of_a_hand_computed_vector() {
        let values = SVector::<f64, 2>::new(3.0, 4.0);
        let weights = [1.0, 2.0];
        assert_eq!(weighted_rms(&values, |i| weights[i]), sqrt(6.5));
    }

    /// The 0/0 rule: a zero value over a zero weight counts 0; a non-zero one is infinite.
    #[test]
    fn zero_over_zero_counts_zero_and_only_that() {
        let weights = [0.0, 1.0];
        let zero_first = SVector::<f64, 2>::new(0.0, 2.0);
        assert_eq!(weighted_rms(&zero_first, |i| weights[i]), sqrt(2.0));
        let nonzero_first = SVector::<f64, 2>::new(1e-300, 2.0);
        assert_eq!(weighted_rms(&nonzero_first, |i| weights[i]), f64::INFINITY);
    }

    #[test]
    fn tolerance_weights_and_norm() {
        let tolerance = Tolerance::new(0.5, 0.25).unwrap();
        assert_eq!(tolerance.weight(2.0), 1.25);
        let values = SVector::<f64, 1>::new(2.5);
        assert_eq!(tolerance.norm(&values, |_| 2.0), 2.0);
        assert_eq!((tolerance.relative(), tolerance.absolute()), (0.5, 0.25));
    }

    /// The pair is the two squared norms, the 0/0 rule included.
    #[test]
    fn mean_squares_pair_is_the_two_squared_norms() {
        let tolerance = Tolerance::new(0.5, 0.0).unwrap();
        let magnitudes = [0.0, 2.0, 4.0];
        let a = SVector::<f64, 3>::new(0.0, 3.0, 1.0);
        let b = SVector::<f64, 3>::new(0.0, 1.0, 6.0);
        // Weights 0, 1, 2: a gives (0 + 9 + 0.25)/3, b (0 + 1 + 9)/3, exact in binary up to
        // the division by 3, which both sides do alike.
        let (ma, mb) = tolerance.mean_squares_pair(&a, &b, |i| magnitudes[i]);
        assert_eq!((ma, mb), (9.25 / 3.0, 10.0 / 3.0));
        let norm_a = tolerance.norm(&a, |i| magnitudes[i]);
        assert!((norm_a * norm_a - ma).abs() <= 4.0 * f64::EPSILON * ma);
    }

    #[test]
    fn unusable_tolerances_are_rejected() {
        for (relative, absolute) in [
            (0.0, 0.0),
            (-1e-6, 1e-9),
            (1e-6, -1e-9),
            (f64::NAN, 1e-9),
            (1e-6, f64::INFINITY),
        ] {
            let error = Tolerance::new(relative, absolute).unwrap_err();
            assert!(error.reason.contains("tolerances"), "{relative} {absolute}");
        }
        // Finer than f64 can honour: refused with the reason; exactly the limit is usable.
        let error = Tolerance::new(1e-15, 1e-15).unwrap_err();
        assert!(
            error.reason.contains("100 machine epsilons"),
            "{}",
            error.reason
        );
        assert!(Tolerance::new(Tolerance::MIN_RELATIVE, 0.0).is_ok());
        // Each floor refuses below itself, naming its number, and takes itself.
        for (floor, named) in [
            (Floor::ErrorEstimate, "2.2e-14"),
            (Floor::Taylor, "1e-15"),
            (Floor::TaylorHead, "2.2e-16"),
        ] {
            let below = floor.relative() * (1.0 - f64::EPSILON);
            let error = Tolerance::for_floor(below, 0.0, floor).unwrap_err();
            assert!(error.reason.contains(named), "{floor:?}: {}", error.reason);
            assert!(Tolerance::for_floor(floor.relative(), 0.0, floor).is_ok());
        }
        // 1e-16 is finer than the double Taylor stepper's floor, not than its head's; 1e-15
        // than the error-estimating steppers', not than Taylor's.
        assert!(Tolerance::for_floor(5e-16, 5e-16, Floor::Taylor).is_err());
        assert!(Tolerance::for_floor(5e-16, 5e-16, Floor::TaylorHead).is_ok());
        assert!(Tolerance::new(1e-15, 1e-15).is_err());
        assert!(Tolerance::for_floor(1e-15, 1e-15, Floor::Taylor).is_ok());
        // Either alone is usable.
        assert_eq!(Tolerance::new(1e-6, 0.0).map(|t| t.weight(2.0)), Ok(2e-6));
        assert_eq!(Tolerance::new(0.0, 1e-9).map(|t| t.weight(2.0)), Ok(1e-9));
    }
}
