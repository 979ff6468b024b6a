//! The Taylor recurrences generated code calls (`emit = [..., "taylor"]`): coefficient `k`
//! of one operation from the coefficients 0..=k of its operands and 0..k of its result,
//! each array holding the normalized coefficients u\[j\] = u⁽ʲ⁾/j!. At k = 0 each returns the
//! function's value (the value tape's semantics); for k ≥ 1 each calls the rule of
//! `varmass_table::recurrence`, the one the run-time tapes (`varmass_symbolic::expr::TaylorTape`)
//! call too, so the two cannot differ (`tests/taylor_emitted.rs` checks the values at order
//! 0 and the whole series).
//!
//! Each function is generic over the [`Coefficient`]: `f64` for the scalar Taylor stepper,
//! [`Lanes<W>`](crate::lanes::Lanes) for W members at once (`emit = [..., "taylor",
//! "lanes"]`), [`Tangent<W>`](crate::tangent::Tangent) for the sensitivities (`emit = [...,
//! "taylor", "sensitivities"]`: a function's value at order 0 by the chain rule,
//! [`Coefficient::map`]; `abs`, `sign`, `min` and `max` go lane by lane and would be wrong
//! over tangents, which the emitter never gives them). The arithmetic rules run over the coefficient as it is (lane by lane, each
//! lane the `f64` operation); a function's value at order 0 and the selection rules (abs,
//! min, max), which branch, are the `f64` ones applied to each lane in turn. So a lane's
//! coefficients are the scalar expansion's, bit for bit (`tests/taylor_lanes.rs`).

use core::ops::Mul;

use nalgebra::{ComplexField, RealField};

use crate::cholesky::{factor as cholesky, substitute};
use crate::math::{powf, sqrt};
use varmass_table::recurrence as rule;

/// The recurrences' sums, in four chains: one function for generated code and the tapes
/// (`varmass-table` is the crate both depend on).
pub use varmass_table::sum;

/// The scratch and the arrays' length, where generated code has always named them (they
/// live below the trait, which names the scratch, in `crate::scratch`).
pub use crate::scratch::{Scratch, LEN};

/// The number a Taylor coefficient is: `f64`, or W of them side by side
/// ([`Lanes<W>`](crate::lanes::Lanes)), each lane read and written as an `f64`.
pub trait Coefficient: rule::Scalar + Mul<f64, Output = Self> + PartialEq {
    /// How many `f64`s it holds.
    const WIDTH: usize;
    /// Lane `i`.
    fn lane(self, i: usize) -> f64;
    /// Lane `i` is `f(i)`.
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    /// Sets lane `i` to `x`.
    fn set_lane(&mut self, i: usize, x: f64);
    /// Whether a non-finite velocity at order 0 ends the expansion with a singular mass
    /// matrix (the scalar code's check, when the state is finite). Never for lanes: a lane's
    /// non-finite coefficient is found by the caller, which expands that member alone
    /// again for the scalar error.
    fn singular(velocity: Self, state: &[Self]) -> bool;

    /// f(x) at order 0, lane by lane, where f′(x) = `slope`(x, f(x)): the lanes' and
    /// `f64`'s value ignores the slope; a tangent's derivatives follow it (the chain rule,
    /// [`Tangent`](crate::tangent::Tangent)).
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64, slope: impl Fn(f64, f64) -> f64) -> Self {
        let _ = slope;
        Self::from_fn(|i| f(self.lane(i)))
    }

    /// atan2(y, x) at order 0, lane by lane.
    #[inline(always)]
    fn map_atan2(y: Self, x: Self) -> Self {
        Self::from_fn(|i| RealField::atan2(y.lane(i), x.lane(i)))
    }

    /// xᵅ at order 0 as the value tape computes it (`power`: `powi` for integer exponents,
    /// √ for ½), lane by lane.
    #[inline(always)]
    fn map_power(self, alpha: Self) -> Self {
        Self::from_fn(|i| power(self.lane(i), alpha.lane(i)))
    }

    /// (sin x, cos x), or (sinh x, cosh x) for `hyperbolic`, at order 0, lane by lane.
    #[inline(always)]
    fn map_sin_cos(self, hyperbolic: bool) -> (Self, Self) {
        let each = |i| {
            let x = self.lane(i);
            if hyperbolic {
                (ComplexField::sinh(x), ComplexField::cosh(x))
            } else {
                ComplexField::sin_cos(x)
            }
        };
        let mut cosine = Self::splat(0.0);
        let sine = Self::from_fn(|i| {
            let (sine, cos) = each(i);
            cosine.set_lane(i, cos);
            sine
        });
        (sine, cosine)
    }
}

impl Coefficient for f64 {
    const WIDTH: usize = 1;
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> f64 {
        f(0)
    }
    #[inline(always)]
    fn set_lane(&mut self, _: usize, x: f64) {
        *self = x;
    }
    #[inline(always)]
    fn singular(velocity: f64, state: &[f64]) -> bool {
        !velocity.is_finite() && state.iter().all(|x| x.is_finite())
    }
}

/// `x` in every lane: a constant of generated code.
#[inline(always)]
pub fn splat<T: Coefficient>(x: f64) -> T {
    T::splat(x)
}

/// `f` of each lane of `x`: a function's value at order 0.
#[inline(always)]
pub fn value<T: Coefficient>(x: T, f: impl Fn(f64) -> f64) -> T {
    T::from_fn(|i| f(x.lane(i)))
}

/// `f` of each lane of `y` and `x`: a two-argument function's value at order 0.
#[inline(always)]
pub fn value2<T: Coefficient>(y: T, x: T, f: impl Fn(f64, f64) -> f64) -> T {
    T::from_fn(|i| f(y.lane(i), x.lane(i)))
}

/// atan2(y, x) lane by lane ([`Coefficient::map_atan2`]).
#[inline(always)]
pub fn atan2_value<T: Coefficient>(y: T, x: T) -> T {
    T::map_atan2(y, x)
}

/// Coefficient arrays of several subexpressions (rows of M, offsets, momenta).
pub type Arrays<'a> = &'a [&'a [f64; LEN]];

/// w = Σ terms (coefficient k of each, left to right).
pub use varmass_table::recurrence::add;

/// w = c a for a constant c.
#[inline(always)]
pub fn scale<T: Coefficient>(c: &[T; LEN], a: &[T; LEN], k: usize) -> T {
    let k = k.min(LEN - 1);
    rule::scale(|j| c[j], |j| a[j], k)
}

/// w = offset + scale·a.
#[inline(always)]
pub fn affine<T: Coefficient>(a: &[T; LEN], k: usize, (scale, offset): (f64, f64)) -> T {
    let k = k.min(LEN - 1);
    rule::affine(|j| a[j], k, (scale, offset))
}

/// w = a b.
#[inline(always)]
pub fn mul<T: Coefficient>(a: &[T; LEN], b: &[T; LEN], k: usize) -> T {
    let k = k.min(LEN - 1);
    rule::mul(|j| a[j], |j| b[j], k)
}

/// w = a b for a of degree at most `da` in t and b at most `db` ([`rule::mul_bounded`]).
#[inline(always)]
pub fn mul_bounded<T: Coefficient>(
    a: &[T; LEN],
    b: &[T; LEN],
    k: usize,
    bounds: (usize, usize),
) -> T {
    let k = k.min(LEN - 1);
    rule::mul_bounded(|j| a[j], |j| b[j], k, bounds)
}

/// w = a².
#[inline(always)]
pub fn square<T: Coefficient>(a: &[T; LEN], k: usize) -> T {
    let k = k.min(LEN - 1);
    rule::square(|j| a[j], k)
}

/// w a = 1 (times w\[0\] = 1/a\[0\], [`rule::recip`] says why).
#[inline(always)]
pub fn recip<T: Coefficient>(a: &[T; LEN], w: &[T; LEN], k: usize) -> T {
    if k == 0 {
        return T::splat(1.0) / a[0];
    }
    let k = k.min(LEN - 1);
    rule::recip(|j| a[j], |j| w[j], k)
}

/// w d = a, times 1/d\[0\] as `recip` multiplies: one sum where 1/d and a product took two.
#[inline(always)]
pub fn div<T: Coefficient>(a: &[T; LEN], d: &[T; LEN], w: &[T; LEN], k: usize) -> T {
    let inverse = T::splat(1.0) / d[0];
    if k == 0 {
        return a[0] * inverse;
    }
    let k = k.min(LEN - 1);
    rule::div(|j| a[j], |j| d[j], |j| w[j], k, inverse)
}

/// [`div`] for d of degree at most `dd` in t ([`rule::div_bounded`]).
#[inline(always)]
pub fn div_bounded<T: Coefficient>(
    a: &[T; LEN],
    d: &[T; LEN],
    w: &[T; LEN],
    k: usize,
    dd: usize,
) -> T {
    let inverse = T::splat(1.0) / d[0];
    if k == 0 {
        return a[0] * inverse;
    }
    let k = k.min(LEN - 1);
    rule::div_bounded(|j| a[j], |j| d[j], |j| w[j], k, inverse, dd)
}

/// w² = a.
#[inline(always)]
pub fn sqrt_of<T: Coefficient>(a: &[T; LEN], w: &[T; LEN], k: usize) -> T {
    if k == 0 {
        return a[0].map(sqrt, |_, w| 0.5 / w);
    }
    let k = k.min(LEN - 1);
    rule::sqrt(|j| a[j], |j| w[j], k)
}

/// w = a^α for the constant α = e\[0\].
#[inline(always)]
pub fn pow<T: Coefficient>(a: &[T; LEN], e: &[T; LEN], w: &[T; LEN], k: usize) -> T {
    let alpha = e[0];
    if k == 0 {
        return a[0].map_power(alpha);
    }
    let k = k.min(LEN - 1);
    rule::pow(|j| a[j], alpha, |j| w[j], k)
}

/// bᵉ as the value tape computes it: `powi` for integer exponents, √ for ½, the real cube
/// root for ⅓ (the printed state rate's `.cbrt()`).
pub(crate) fn power(b: f64, e: f64) -> f64 {
    if e == 0.5 {
        sqrt(b)
    } else if e == 1.0 / 3.0 {
        ComplexField::cbrt(b)
    } else if e == (e as i32) as f64 {
        ComplexField::powi(b, e as i32)
    } else {
        powf(b, e)
    }
}

/// w = eᵃ.
#[inline(always)]
pub fn exp<T: Coefficient>(a: &[T; LEN], w: &[T; LEN], k: usize) -> T {
    if k == 0 {
        return a[0].map(crate::math::exp, |_, w| w);
    }
    let k = k.min(LEN - 1);
    rule::exp(|j| a[j], |j| w[j], k)
}

/// (sin a, cos a), or (sinh a, cosh a) for `hyperbolic`.
#[inline(always)]
pub fn sin_cos<T: Coefficient>(
    a: &[T; LEN],
    s: &mut [T; LEN],
    c: &mut [T; LEN],
    k: usize,
    hyperbolic: bool,
) {
    if k == 0 {
        (s[0], c[0]) = a[0].map_sin_cos(hyperbolic);
        return;
    }
    let k = k.min(LEN - 1);
    let sign = if hyperbolic { 1.0 } else { -1.0 };
    (s[k], c[k]) = rule::sin_cos(|j| a[j], (|j| s[j], |j| c[j]), k, sign);
}

/// tan (or tanh for `hyperbolic`) into w, and v = 1 ± w² beside it.
#[inline(always)]
pub fn tan<T: Coefficient>(
    a: &[T; LEN],
    w: &mut [T; LEN],
    v: &mut [T; LEN],
    k: usize,
    hyperbolic: bool,
) {
    w[k] = if k == 0 {
        if hyperbolic {
            a[0].map(ComplexField::tanh, |_, w| 1.0 - w * w)
        } else {
            a[0].map(ComplexField::tan, |_, w| 1.0 + w * w)
        }
    } else {
        let k = k.min(LEN - 1);
        rule::tan(|j| a[j], |j| v[j], k)
    };
    let sign = if hyperbolic { -1.0 } else { 1.0 };
    let k = k.min(LEN - 1);
    v[k] = rule::tan_companion(|j| w[j], k, sign);
}

/// w′ d = sign·a′ for k ≥ 1 (ln: d = a; asin, acos: d = √(1 − a²); atan: d = 1 + a²);
/// at k = 0 `f`(a\[0\]) lane by lane, with f′(x) = `slope`(x, f(x)) for a tangent's
/// derivatives. The slope is the function's own, not sign/d: the tape also writes a call
/// of a constant (sin θ of a parameter) as this op with d = a, whose recurrence is never
/// run (its higher coefficients are 0) but whose derivative at order 0 is f′, not 1/a.
#[inline(always)]
pub fn quotient<T: Coefficient>(
    a: &[T; LEN],
    d: &[T; LEN],
    w: &[T; LEN],
    k: usize,
    (sign, f, slope): (f64, impl Fn(f64) -> f64, impl Fn(f64, f64) -> f64),
) -> T {
    if k == 0 {
        return a[0].map(f, slope);
    }
    let k = k.min(LEN - 1);
    rule::quotient(|j| a[j], |j| d[j], |j| w[j], k, sign)
}

/// w = atan2(y, x), with d = x² + y².
#[inline(always)]
pub fn atan2<T: Coefficient>(
    y: &[T; LEN],
    x: &[T; LEN],
    d: &[T; LEN],
    w: &[T; LEN],
    k: usize,
) -> T {
    if k == 0 {
        return atan2_value(y[0], x[0]);
    }
    let k = k.min(LEN - 1);
    rule::atan2((|j| y[j], |j| x[j]), |j| d[j], |j| w[j], k)
}

/// |a| on the branch of a\[0\]'s sign (at 0: of a's first non-zero coefficient).
#[inline(always)]
pub fn abs<T: Coefficient>(a: &[T; LEN], k: usize) -> T {
    if k == 0 {
        return value(a[0], ComplexField::abs);
    }
    let k = k.min(LEN - 1);
    T::from_fn(|i| rule::abs(|j| a[j].lane(i), k))
}

/// sign a\[0\], constant over the step.
#[inline(always)]
pub fn sign<T: Coefficient>(a: &[T; LEN], k: usize) -> T {
    if k == 0 {
        value(a[0], crate::math::sign)
    } else {
        T::splat(0.0)
    }
}

/// The smaller (`larger` false) or larger argument at order 0, NaN-propagating there.
#[inline(always)]
pub fn min_max<T: Coefficient>(a: &[T; LEN], b: &[T; LEN], k: usize, larger: bool) -> T {
    let k = k.min(LEN - 1);
    T::from_fn(|i| rule::min_max(|j| a[j].lane(i), |j| b[j].lane(i), k, larger))
}

/// Coefficient k of q̇ from M q̇ = p − b, n coordinates: M\[0\] q̇\[k\] = p\[k\] − b\[k\] −
/// Σⱼ₌₁ᵏ M\[j\] q̇\[k−j\], with M\[0\] factored (Cholesky, row-major in `factor`) at k = 0.
/// `false` when M\[0\] is not positive definite or a result is not finite.
#[inline(always)]
pub fn solve_velocities(
    n: usize,
    (matrix, offset, momenta): (Arrays<'_>, Arrays<'_>, Arrays<'_>),
    velocities: &mut [&mut [f64; LEN]],
    factor: &mut [f64],
    k: usize,
) -> bool {
    if k == 0 {
        for (e, f) in factor.iter_mut().enumerate().take(n * n) {
            *f = matrix[e][0];
        }
        if !cholesky(factor, n) {
            return false;
        }
    }
    let k = k.min(LEN - 1);
    let mut rhs = [0.0; 16];
    for a in 0..n.min(16) {
        rhs[a] = rule::velocity_right_side(
            (n, a, k),
            |a, b, j| matrix[a * n + b][j],
            |b, j| velocities[b][j],
            (momenta[a][k], offset[a][k]),
        );
    }
    substitute(factor, &mut rhs, n);
    for (a, v) in velocities.iter_mut().enumerate().take(n) {
        v[k] = rhs[a];
    }
    rhs.iter().take(n).all(|x| x.is_finite())
}
