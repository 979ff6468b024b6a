//! The three interpolants, each built as a [`Piecewise`] polynomial: `linear`, `pchip`
//! (Fritsch–Carlson monotone cubic) and `spline` (natural cubic). The two cubics follow
//! SciPy's `PchipInterpolator` and `CubicSpline(bc_type='natural')` operation for operation
//! (SciPy 1.17, `scipy/interpolate/_cubic.py`), so that they agree to rounding.

use alloc::vec::Vec;

use crate::piecewise::Piecewise;
use crate::points::{InvalidPoints, Points};

/// How a table interpolates between its points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Interpolation {
    /// Straight lines between the points (continuous, the slope jumps at knots).
    #[default]
    Linear,
    /// Monotone piecewise cubic Hermite (Fritsch–Carlson, SciPy's `PchipInterpolator`):
    /// C¹, no overshoot, flat wherever the data turn.
    Pchip,
    /// Natural cubic spline (zero second derivative at both ends, SciPy's
    /// `CubicSpline(bc_type='natural')`): C².
    Spline,
}

impl Interpolation {
    /// The interpolant of `points`.
    pub fn interpolate(self, points: &Points) -> Piecewise {
        match self {
            Self::Linear => linear(points),
            Self::Pchip => hermite(points, &pchip_slopes(points)),
            Self::Spline => hermite(points, &natural_spline_slopes(points)),
        }
    }

    /// [`Interpolation::interpolate`], refused where a piece overflows
    /// ([`InvalidPoints::InterpolantNotFinite`] naming its right end): `Points` checks the
    /// chords' slopes, but a cubic's coefficients are up to 3·δ/h (δ the chord's rise), so
    /// values near 1.8e308 with finite slopes can give an interpolant (or its derivative
    /// table) that is ±∞ or NaN between them (before, such a pchip or spline table was taken and the run failed at
    /// its first step with "the state became non-finite").
    pub fn checked(self, points: &Points) -> Result<Piecewise, InvalidPoints> {
        let curve = self.interpolate(points);
        match overflowing_piece(&curve) {
            Some(piece) => Err(InvalidPoints::InterpolantNotFinite { index: piece + 1 }),
            None => Ok(curve),
        }
    }

    /// The interpolation's name in the DSL and the tool: `linear`, `pchip` or `spline`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::Pchip => "pchip",
            Self::Spline => "spline",
        }
    }
}

/// Whether `curve` or one of its derivative tables may overflow where it is evaluated
/// (its interval from the first knot given, as in [`Interpolation::checked`]).
fn overflowing_piece(curve: &Piecewise) -> Option<usize> {
    let mut table = curve.clone();
    loop {
        if let Some(piece) = (0..table.intervals()).find(|&piece| overflows(&table, piece)) {
            return Some(piece);
        }
        if table.degree() == 0 {
            return None;
        }
        table = table.derivative();
    }
}

/// Whether piece `piece` of `curve` may overflow where it is evaluated, as
/// [`Piecewise::value_on`] sums c₀ + c₁s + c₂s² + c₃s³ for s in [0, h]: some sᵏ or cₖhᵏ is
/// not finite, or a partial sum Σₖ≤ⱼ cₖsᵏ may exceed the largest f64. Each partial sum is
/// bounded by its Bernstein coefficients on [0, h] (their largest magnitude; exact for a
/// line, whose are its two end values), computed on the coefficients scaled by 1/8 so that
/// the check itself does not overflow.
fn overflows(curve: &Piecewise, piece: usize) -> bool {
    let knots = curve.knots();
    let width = knots[piece + 1] - knots[piece];
    let per_piece = curve.degree() + 1;
    let coefficients = &curve.coefficients()[piece * per_piece..][..per_piece];
    // bₖ = cₖ hᵏ / 8: the piece in u = s/h ∈ [0, 1], scaled.
    let mut scaled = [0.0; 8];
    let mut power = 1.0;
    for (k, &c) in coefficients.iter().enumerate() {
        if k > 0 {
            power *= width;
        }
        scaled[k.min(7)] = c / 8.0 * power;
        if !(power.is_finite() && (c * power).is_finite()) {
            return true;
        }
    }
    let degree = per_piece.min(8) - 1;
    (1..=degree).any(|j| bernstein_bound(&scaled[..=j]) > f64::MAX / 8.0)
}

/// max |βᵢ| over the Bernstein coefficients βᵢ = Σₖ≤ᵢ C(i,k)/C(j,k)·bₖ of Σₖ≤ⱼ bₖuᵏ on
/// [0, 1]: a bound on its magnitude there (the convex hull property).
fn bernstein_bound(b: &[f64]) -> f64 {
    let j = b.len() - 1;
    let binomial =
        |n: usize, k: usize| (0..k).fold(1.0, |c, m| c * (n - m) as f64 / (m + 1) as f64);
    (0..=j)
        .map(|i| {
            abs((0..=i)
                .map(|k| binomial(i, k) / binomial(j, k) * b[k])
                .sum::<f64>())
        })
        .fold(0.0, |largest: f64, beta| {
            if beta > largest || beta.is_nan() {
                beta
            } else {
                largest
            }
        })
}

/// yᵢ + mᵢ (x − xᵢ) with mᵢ the slope of the chord.
fn linear(points: &Points) -> Piecewise {
    let (x, y) = (points.arguments(), points.values());
    let coefficients = (0..x.len() - 1)
        .flat_map(|i| [y[i], (y[i + 1] - y[i]) / (x[i + 1] - x[i])])
        .collect();
    Piecewise::from_parts(x.to_vec(), coefficients, 1)
}

/// The cubic Hermite interpolant through `points` with slopes `d` at the knots, with
/// SciPy's `CubicHermiteSpline` coefficients: t = (dᵢ + dᵢ₊₁ − 2mᵢ)/hᵢ, then
/// c₃ = t/hᵢ, c₂ = (mᵢ − dᵢ)/hᵢ − t, c₁ = dᵢ, c₀ = yᵢ.
fn hermite(points: &Points, d: &[f64]) -> Piecewise {
    let (x, y) = (points.arguments(), points.values());
    let coefficients = (0..x.len() - 1)
        .flat_map(|i| {
            let h = x[i + 1] - x[i];
            let slope = (y[i + 1] - y[i]) / h;
            let t = (d[i] + d[i + 1] - 2.0 * slope) / h;
            [y[i], d[i], (slope - d[i]) / h - t, t / h]
        })
        .collect();
    Piecewise::from_parts(x.to_vec(), coefficients, 3)
}

/// The sign as NumPy's `sign`: −1, 0 or 1 (only finite values reach here).
fn sign(v: f64) -> i8 {
    (v > 0.0) as i8 - (v < 0.0) as i8
}

/// |v| without `std` (`f64::abs` is not in `core` at our minimum Rust).
fn abs(v: f64) -> f64 {
    if v < 0.0 {
        -v
    } else {
        v
    }
}

/// The number of knots n, the interval widths hᵢ = xᵢ₊₁ − xᵢ and the chord slopes
/// mᵢ = (yᵢ₊₁ − yᵢ)/hᵢ, i < n − 1: what both slope rules start from.
fn chords(points: &Points) -> (usize, Vec<f64>, Vec<f64>) {
    let (x, y) = (points.arguments(), points.values());
    let n = x.len();
    let h: Vec<f64> = (0..n - 1).map(|i| x[i + 1] - x[i]).collect();
    let m: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    (n, h, m)
}

/// PCHIP's slopes at the knots (Fritsch–Carlson, 1980, with Brodlie's weights): zero where
/// the chords on either side differ in sign or one is flat, else the weighted harmonic mean
/// of the two chords; at the ends the shape-preserving three-point formula (Moler,
/// *Numerical Computing with MATLAB*, §3.6).
fn pchip_slopes(points: &Points) -> Vec<f64> {
    let (n, h, m) = chords(points);
    if n == 2 {
        return alloc::vec![m[0]; 2];
    }
    let mut d = alloc::vec![0.0; n];
    for k in 1..n - 1 {
        let turns = sign(m[k]) != sign(m[k - 1]) || m[k] == 0.0 || m[k - 1] == 0.0;
        if !turns {
            let w1 = 2.0 * h[k] + h[k - 1];
            let w2 = h[k] + 2.0 * h[k - 1];
            let harmonic_mean = (w1 / m[k - 1] + w2 / m[k]) / (w1 + w2);
            d[k] = 1.0 / harmonic_mean;
        }
    }
    d[0] = pchip_end_slope(h[0], h[1], m[0], m[1]);
    d[n - 1] = pchip_end_slope(h[n - 2], h[n - 3], m[n - 2], m[n - 3]);
    d
}

/// The one-sided three-point slope at an end, from the end interval (h0, m0) and its
/// neighbour (h1, m1); zero if it points against the end chord, 3·m0 if the chords turn and
/// it is steeper than that (which keeps the end piece monotone).
fn pchip_end_slope(h0: f64, h1: f64, m0: f64, m1: f64) -> f64 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if sign(d) != sign(m0) {
        0.0
    } else if sign(m0) != sign(m1) && abs(d) > 3.0 * abs(m0) {
        3.0 * m0
    } else {
        d
    }
}

/// The natural cubic spline's slopes sᵢ at the knots: C² continuity at interior knots,
///
/// hᵢ sᵢ₋₁ + 2(hᵢ₋₁ + hᵢ) sᵢ + hᵢ₋₁ sᵢ₊₁ = 3(hᵢ mᵢ₋₁ + hᵢ₋₁ mᵢ),
///
/// and zero second derivative at the ends, 2h₀s₀ + h₀s₁ = 3(y₁ − y₀) and its mirror image
/// (the rows of SciPy's banded system). The matrix is strictly diagonally dominant, so the
/// Thomas algorithm needs no pivoting.
fn natural_spline_slopes(points: &Points) -> Vec<f64> {
    let (n, h, m) = chords(points);
    let y = points.values();
    // Row i: lower[i]·s[i−1] + diagonal[i]·s[i] + upper[i]·s[i+1] = rhs[i].
    let row = |i: usize| -> (f64, f64, f64, f64) {
        if i == 0 {
            (0.0, 2.0 * h[0], h[0], 3.0 * (y[1] - y[0]))
        } else if i == n - 1 {
            (h[n - 2], 2.0 * h[n - 2], 0.0, 3.0 * (y[n - 1] - y[n - 2]))
        } else {
            let rhs = 3.0 * (h[i] * m[i - 1] + h[i - 1] * m[i]);
            (h[i], 2.0 * (h[i - 1] + h[i]), h[i - 1], rhs)
        }
    };
    // Forward elimination: upper′ and rhs′ of the unit-diagonal system.
    let mut upper = Vec::with_capacity(n);
    let mut rhs = Vec::with_capacity(n);
    for i in 0..n {
        let (l, diagonal, u, r) = row(i);
        let (previous_upper, previous_rhs) = if i == 0 {
            (0.0, 0.0)
        } else {
            (upper[i - 1], rhs[i - 1])
        };
        let pivot = diagonal - l * previous_upper;
        upper.push(u / pivot);
        rhs.push((r - l * previous_rhs) / pivot);
    }
    // Back substitution.
    let mut s = rhs;
    for i in (0..n - 1).rev() {
        s[i] -= upper[i] * s[i + 1];
    }
    s
}
