//! A piecewise polynomial in local power form, the one representation of every interpolant:
//! its derivative is again one (a degree lower), so a table can be differentiated as often as
//! the derivation asks, and the macro can embed any of them as two static arrays.

use alloc::borrow::Cow;
use alloc::vec::Vec;

/// A piecewise polynomial of one degree d on every interval: on interval i, from knot xᵢ to
/// xᵢ₊₁,
///
/// p(x) = Σₖ cᵢₖ (x − xᵢ)ᵏ,  k = 0 … d,
///
/// with the coefficients stored interval after interval, lowest power first (SciPy's `PPoly`
/// stores the same numbers, highest power first).
///
/// Intervals are closed on the left, as SciPy's: a knot belongs to the interval it starts, and
/// the last knot to the last interval. A curve whose slope jumps at a knot (a linear table)
/// therefore gives there the slope on the right, the one a forward integration uses from
/// that knot on.
///
/// Invariants (checked by the constructors): at least two knots, strictly increasing;
/// `coefficients.len() == (knots.len() − 1)·(degree + 1)`. Knots and coefficients are
/// `Cow`s so that generated code can build one over `static` arrays without allocating.
#[derive(Clone, Debug, PartialEq)]
pub struct Piecewise {
    knots: Cow<'static, [f64]>,
    coefficients: Cow<'static, [f64]>,
    degree: usize,
}

impl Piecewise {
    /// A piecewise polynomial over borrowed static data (what the macro emits).
    ///
    /// # Panics
    /// If the data break the invariants above (in a `const`, at compile time).
    pub const fn from_static(
        knots: &'static [f64],
        coefficients: &'static [f64],
        degree: usize,
    ) -> Self {
        assert!(knots.len() >= 2, "a piecewise polynomial needs two knots");
        let mut i = 1;
        while i < knots.len() {
            assert!(
                knots[i - 1].is_finite() && knots[i].is_finite() && knots[i - 1] < knots[i],
                "knots finite and strictly increasing"
            );
            i += 1;
        }
        assert!(
            coefficients.len() == (knots.len() - 1) * (degree + 1),
            "one set of degree + 1 coefficients per interval"
        );
        Self {
            knots: Cow::Borrowed(knots),
            coefficients: Cow::Borrowed(coefficients),
            degree,
        }
    }

    /// A piecewise polynomial over owned data, from checked knots (crate-internal).
    pub(crate) fn from_parts(knots: Vec<f64>, coefficients: Vec<f64>, degree: usize) -> Self {
        debug_assert!(knots.len() >= 2);
        debug_assert_eq!(coefficients.len(), (knots.len() - 1) * (degree + 1));
        Self {
            knots: Cow::Owned(knots),
            coefficients: Cow::Owned(coefficients),
            degree,
        }
    }

    /// The knots, strictly increasing: where the curve may be non-smooth (later: stop times
    /// of the steppers, switching functions).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The coefficients, interval after interval, lowest power first.
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// The degree d of every piece (1 linear, 3 pchip and spline, less for derivatives).
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The first and the last knot.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// Number of intervals (knots − 1).
    pub fn intervals(&self) -> usize {
        self.knots.len() - 1
    }

    /// The interval holding `x`, trying `hint` and the interval after it before a binary
    /// search: an integration asks for nearly the same argument call after call. Arguments
    /// below the first knot give interval 0 and above the last the last interval (their
    /// polynomials extrapolate); a NaN gives 0.
    #[inline]
    pub fn interval(&self, x: f64, hint: usize) -> usize {
        let knots = &*self.knots;
        let contains = |i: usize| i + 1 < knots.len() && knots[i] <= x && x < knots[i + 1];
        if contains(hint) {
            hint
        } else if contains(hint + 1) {
            hint + 1
        } else {
            // The number of interior knots at or below x is the interval's index.
            knots[1..knots.len() - 1].partition_point(|&knot| knot <= x)
        }
    }

    /// p(x) on interval `interval`, summed by powers as SciPy's `PPoly` sums (rather than by
    /// Horner's rule), so that the cubics agree with SciPy's to the last bit where their
    /// coefficients do (pchip's do: `tests/scipy.rs`).
    #[inline]
    pub fn value_on(&self, interval: usize, x: f64) -> f64 {
        let s = x - self.knots[interval];
        match *self.piece(interval) {
            // The table's own degrees written out (the same operations as the loop).
            [c0, c1] => c0 + c1 * s,
            [c0, c1, c2, c3] => c0 + c1 * s + c2 * (s * s) + c3 * (s * s * s),
            ref piece => {
                let mut z = 1.0;
                let mut sum = 0.0;
                for &c in piece {
                    sum += c * z;
                    z *= s;
                }
                sum
            }
        }
    }

    /// p′(x) on interval `interval`, Σ k·cₖ sᵏ⁻¹ summed as in [`Piecewise::value_on`] (no
    /// derivative is built).
    #[inline]
    pub fn slope_on(&self, interval: usize, x: f64) -> f64 {
        let s = x - self.knots[interval];
        let piece = self.piece(interval);
        let mut z = 1.0;
        let mut sum = 0.0;
        for (k, &c) in piece.iter().enumerate().skip(1) {
            sum += c * z * k as f64;
            z *= s;
        }
        sum
    }

    /// p(x), searching the interval from scratch.
    pub fn value(&self, x: f64) -> f64 {
        self.value_on(self.interval(x, 0), x)
    }

    /// The derivative p′, a piecewise polynomial on the same knots one degree lower (of a
    /// constant, the zero constant): the coefficients k·cₖ shifted down a power.
    pub fn derivative(&self) -> Self {
        let degree = self.degree.saturating_sub(1);
        let coefficients = (0..self.intervals())
            .flat_map(|interval| {
                let piece = self.piece(interval);
                (0..=degree).map(move |k| match piece.get(k + 1) {
                    Some(&c) => (k + 1) as f64 * c,
                    None => 0.0,
                })
            })
            .collect();
        Self::from_parts(self.knots.to_vec(), coefficients, degree)
    }

    /// The antiderivative P with P(first knot) = 0, a piecewise polynomial on the same knots
    /// one degree higher: on each piece cₖ/(k+1) shifted up a power, plus the integral of
    /// the pieces before it. Of a linear thrust curve it is the impulse I(t) by exact
    /// trapezoids, so the mass of a motor burning at ṁ = −F/u_e is m₀ − I(t)/u_e.
    pub fn antiderivative(&self) -> Self {
        let width = self.degree + 2;
        let mut coefficients = Vec::with_capacity(self.intervals() * width);
        let mut before = 0.0;
        for interval in 0..self.intervals() {
            let start = coefficients.len();
            coefficients.push(before);
            let piece = self.piece(interval);
            coefficients.extend(piece.iter().enumerate().map(|(k, &c)| c / (k + 1) as f64));
            // The piece's integral over its whole interval carries into the next.
            let h = self.knots[interval + 1] - self.knots[interval];
            before = coefficients[start..]
                .iter()
                .rev()
                .fold(0.0, |sum, &c| sum * h + c);
        }
        Self::from_parts(self.knots.to_vec(), coefficients, self.degree + 1)
    }

    /// The curve scaled by `value_scale` and stretched by `argument_scale`:
    /// q(x) = k·p(x/s) for k = `value_scale`, s = `argument_scale`, on the knots s·xᵢ. On
    /// each piece q(x) = Σₖ (k·cᵢₖ/sᵏ)(x − s·xᵢ)ᵏ, since x/s − xᵢ = (x − s·xᵢ)/s. What an
    /// ensemble disperses a thrust curve with: the total impulse scales by k·s and the burn
    /// time by s. `None` unless k is finite and s finite and positive, or if the new knots
    /// or coefficients are not finite and strictly increasing (an overflow or underflow).
    pub fn transformed(&self, value_scale: f64, argument_scale: f64) -> Option<Self> {
        let (k, s) = (value_scale, argument_scale);
        if !(k.is_finite() && s.is_finite() && s > 0.0) {
            return None;
        }
        let knots: Vec<f64> = self.knots.iter().map(|&x| s * x).collect();
        let increasing = knots.windows(2).all(|w| w[0] < w[1]);
        if !(increasing && knots.iter().all(|x| x.is_finite())) {
            return None;
        }
        let width = self.degree + 1;
        let coefficients: Vec<f64> = self
            .coefficients
            .iter()
            .enumerate()
            .map(|(i, &c)| k * c / s.powi((i % width) as i32))
            .collect();
        if !coefficients.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Self::from_parts(knots, coefficients, self.degree))
    }

    /// The coefficients of interval `interval`.
    #[inline]
    fn piece(&self, interval: usize) -> &[f64] {
        let width = self.degree + 1;
        &self.coefficients[interval * width..(interval + 1) * width]
    }
}
