//! Validated data: knots strictly increasing, values finite, at least two points.

use alloc::vec::Vec;

/// The points of a table: arguments (knots) strictly increasing, all values finite, at least
/// two points. Every reader and every constructor checks this, so an interpolant never sees
/// a repeated knot (a division by zero) or a NaN.
#[derive(Clone, Debug, PartialEq)]
pub struct Points {
    arguments: Vec<f64>,
    values: Vec<f64>,
}

/// Why [`Points::new`] refused its data; `index` is the offending point's, 0-based.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum InvalidPoints {
    /// The two vectors differ in length.
    #[error("{arguments} arguments but {values} values")]
    LengthMismatch {
        /// Number of arguments.
        arguments: usize,
        /// Number of values.
        values: usize,
    },
    /// Fewer than two points.
    #[error("{found} point(s); a table needs at least two")]
    TooFewPoints {
        /// Number of points given.
        found: usize,
    },
    /// An argument or value is infinite or NaN.
    #[error("point {index} is not finite")]
    NotFinite {
        /// The point's index.
        index: usize,
    },
    /// The slope from the previous point overflows (values near ±1.8e308, or knots a
    /// subnormal apart): the interpolant there would be ±∞ or NaN.
    #[error("the slope from point {} to point {index} is not finite", index - 1)]
    SlopeNotFinite {
        /// The point's index.
        index: usize,
    },
    /// The distance from the previous point's argument (or the first point's) overflows
    /// (knots near ±1.8e308 of opposite signs): the interpolant there would divide by ∞ and
    /// read zero everywhere.
    #[error("the distance from point {from} to point {index} is not finite")]
    SpacingNotFinite {
        /// The earlier point's index (the previous one, or the first).
        from: usize,
        /// The point's index.
        index: usize,
    },
    /// The interpolant's piece from the previous point to this one overflows, though the
    /// slope between them does not: its cubic coefficients (3·δ/h, …) or their sum over the
    /// interval, or its derivative's, are not finite (values near ±1.8e308; pchip and
    /// spline tables, [`Interpolation::checked`](crate::Interpolation::checked)). Lookups
    /// there would be ±∞ or NaN.
    #[error("the interpolant from point {} to point {index} is not finite", index - 1)]
    InterpolantNotFinite {
        /// The point's index (the piece's right end).
        index: usize,
    },
    /// An argument does not increase on the previous one.
    #[error("the argument of point {index} does not increase on the previous one")]
    NotIncreasing {
        /// The point's index.
        index: usize,
    },
}

impl Points {
    /// Checks and takes the data.
    pub fn new(arguments: Vec<f64>, values: Vec<f64>) -> Result<Self, InvalidPoints> {
        if arguments.len() != values.len() {
            return Err(InvalidPoints::LengthMismatch {
                arguments: arguments.len(),
                values: values.len(),
            });
        }
        if arguments.len() < 2 {
            return Err(InvalidPoints::TooFewPoints {
                found: arguments.len(),
            });
        }
        for (index, (x, y)) in arguments.iter().zip(&values).enumerate() {
            if !x.is_finite() || !y.is_finite() {
                return Err(InvalidPoints::NotFinite { index });
            }
            if index > 0 && arguments[index - 1] >= *x {
                return Err(InvalidPoints::NotIncreasing { index });
            }
            if let Some(from) = overflowing_spacing(&arguments, index) {
                return Err(InvalidPoints::SpacingNotFinite { from, index });
            }
            if index > 0 && !((y - values[index - 1]) / (x - arguments[index - 1])).is_finite() {
                return Err(InvalidPoints::SlopeNotFinite { index });
            }
        }
        Ok(Self { arguments, values })
    }

    /// The same curve stretched: every argument times `argument_factor`, every value times
    /// `value_factor` (an ensemble dispersing a thrust curve: a slower burn, a weaker motor).
    /// Checked again, so a factor that is not positive and finite is an error, not a table.
    pub fn stretched(
        &self,
        argument_factor: f64,
        value_factor: f64,
    ) -> Result<Self, InvalidPoints> {
        let arguments = self.arguments.iter().map(|x| x * argument_factor).collect();
        let values = self.values.iter().map(|y| y * value_factor).collect();
        // A factor ≤ 0 reverses or collapses the knots, one not finite makes them so:
        // `new` refuses both.
        Self::new(arguments, values)
    }

    /// The arguments (knots), strictly increasing.
    pub fn arguments(&self) -> &[f64] {
        &self.arguments
    }

    /// The values at the knots.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Number of points (at least two).
    pub fn len(&self) -> usize {
        self.arguments.len()
    }

    /// Always false: there are at least two points (for clippy's `len_without_is_empty`).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// ∫ of the piecewise-linear curve through the points, by exact trapezoids (a motor's
    /// total impulse).
    pub fn trapezoid_integral(&self) -> f64 {
        let x = &self.arguments;
        let y = &self.values;
        (1..x.len())
            .map(|i| 0.5 * (y[i] + y[i - 1]) * (x[i] - x[i - 1]))
            .sum()
    }
}

/// The earlier point whose distance to point `index` overflows, if one does: the previous
/// point, or else the first (a span wider than f64 makes the lookups' slack infinite,
/// docs/tables.md#outside-the-data). 1/∞ = 0 would pass the slope check and the
/// interpolant would read zero.
fn overflowing_spacing(arguments: &[f64], index: usize) -> Option<usize> {
    let x = arguments[index];
    [index.checked_sub(1), Some(0)]
        .into_iter()
        .flatten()
        .find(|&from| from < index && !(x - arguments[from]).is_finite())
}
