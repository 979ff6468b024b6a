//! The few real functions the runtime and generated code need, through `nalgebra::ComplexField` so that they
//! exist without `std` (nalgebra is built with `libm`).

use nalgebra::ComplexField;

/// √x.
pub(crate) fn sqrt(x: f64) -> f64 {
    <f64 as ComplexField>::sqrt(x)
}

/// xʸ.
pub(crate) fn powf(x: f64, y: f64) -> f64 {
    <f64 as ComplexField>::powf(x, y)
}

/// The sign of x as the derivative of |x| needs it: −1, 0 or 1 (and NaN for NaN).
/// `f64::signum` gives 1 at 0, which would make d|x|/dx = 1 at the kink; generated code
/// calls this instead.
#[inline]
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        x * 0.0
    }
}

/// ln x.
pub(crate) fn ln(x: f64) -> f64 {
    <f64 as ComplexField>::ln(x)
}

/// eˣ.
pub(crate) fn exp(x: f64) -> f64 {
    <f64 as ComplexField>::exp(x)
}

/// The least integer ≥ x.
pub(crate) fn ceil(x: f64) -> f64 {
    <f64 as ComplexField>::ceil(x)
}

/// The angle, rad, from the nearest singular attitude (gimbal lock) of Euler sequences given
/// their middle angles and whether each sequence is proper (`zxz`; else Tait–Bryan, `zyx`):
/// the middle angle's distance to π/2 + kπ (Tait–Bryan) or to kπ (proper), where the map
/// from the angles' rates to ω loses rank (det E = cos θ₂, resp. sin θ₂, up to sign). The
/// smallest over `middles`; ∞ for none. Generated code and the interpreter call it.
pub fn singular_attitude_distance(middles: &[(f64, bool)]) -> f64 {
    use core::f64::consts::{FRAC_PI_2, PI};
    middles
        .iter()
        .map(|&(angle, proper)| {
            let offset = if proper { angle } else { angle - FRAC_PI_2 };
            (offset - PI * <f64 as ComplexField>::round(offset / PI)).abs()
        })
        .fold(f64::INFINITY, f64::min)
}
