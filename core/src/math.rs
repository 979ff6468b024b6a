//! The few real functions the runtime needs, through `nalgebra::ComplexField` so that they
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
