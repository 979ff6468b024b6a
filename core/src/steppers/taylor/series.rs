//! The Taylor recurrences generated code calls (`emit = [..., "taylor"]`): coefficient `k`
//! of one operation from the coefficients 0..=k of its operands and 0..k of its result,
//! each array holding the normalized coefficients u\[j\] = u⁽ʲ⁾/j!. At k = 0 each returns the
//! function's value (the value tape's semantics); for k ≥ 1 each calls the rule of
//! `varmass_table::recurrence`, the one the run-time tapes (`varmass_symbolic::expr::TaylorTape`)
//! call too, so the two cannot differ (`tests/taylor_emitted.rs` checks the values at order
//! 0 and the whole series).

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

/// Coefficient arrays of several subexpressions (rows of M, offsets, momenta).
pub type Arrays<'a> = &'a [&'a [f64; LEN]];

/// w = Σ terms (coefficient k of each, left to right).
pub use varmass_table::recurrence::add;

/// w = c a for a constant c.
#[inline(always)]
pub fn scale(c: &[f64; LEN], a: &[f64; LEN], k: usize) -> f64 {
    let k = k.min(LEN - 1);
    rule::scale(|j| c[j], |j| a[j], k)
}

/// w = offset + scale·a.
#[inline(always)]
pub fn affine(a: &[f64; LEN], k: usize, (scale, offset): (f64, f64)) -> f64 {
    let k = k.min(LEN - 1);
    rule::affine(|j| a[j], k, (scale, offset))
}

/// w = a b.
#[inline(always)]
pub fn mul(a: &[f64; LEN], b: &[f64; LEN], k: usize) -> f64 {
    let k = k.min(LEN - 1);
    rule::mul(|j| a[j], |j| b[j], k)
}

/// w = a b for a of degree at most `da` in t and b at most `db` ([`rule::mul_bounded`]).
#[inline(always)]
pub fn mul_bounded(a: &[f64; LEN], b: &[f64; LEN], k: usize, bounds: (usize, usize)) -> f64 {
    let k = k.min(LEN - 1);
    rule::mul_bounded(|j| a[j], |j| b[j], k, bounds)
}

/// w = a².
#[inline(always)]
pub fn square(a: &[f64; LEN], k: usize) -> f64 {
    let k = k.min(LEN - 1);
    rule::square(|j| a[j], k)
}

/// w a = 1 (times w\[0\] = 1/a\[0\], [`rule::recip`] says why).
#[inline(always)]
pub fn recip(a: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return 1.0 / a[0];
    }
    let k = k.min(LEN - 1);
    rule::recip(|j| a[j], |j| w[j], k)
}

/// w d = a, times 1/d\[0\] as `recip` multiplies: one sum where 1/d and a product took two.
#[inline(always)]
pub fn div(a: &[f64; LEN], d: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    let inverse = 1.0 / d[0];
    if k == 0 {
        return a[0] * inverse;
    }
    let k = k.min(LEN - 1);
    rule::div(|j| a[j], |j| d[j], |j| w[j], k, inverse)
}

/// [`div`] for d of degree at most `dd` in t ([`rule::div_bounded`]).
#[inline(always)]
pub fn div_bounded(a: &[f64; LEN], d: &[f64; LEN], w: &[f64; LEN], k: usize, dd: usize) -> f64 {
    let inverse = 1.0 / d[0];
    if k == 0 {
        return a[0] * inverse;
    }
    let k = k.min(LEN - 1);
    rule::div_bounded(|j| a[j], |j| d[j], |j| w[j], k, inverse, dd)
}

/// w² = a.
#[inline(always)]
pub fn sqrt_of(a: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return sqrt(a[0]);
    }
    let k = k.min(LEN - 1);
    rule::sqrt(|j| a[j], |j| w[j], k)
}

/// w = a^α for the constant α = e\[0\].
#[inline(always)]
pub fn pow(a: &[f64; LEN], e: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    let alpha = e[0];
    if k == 0 {
        return power(a[0], alpha);
    }
    let k = k.min(LEN - 1);
    rule::pow(|j| a[j], alpha, |j| w[j], k)
}

/// bᵉ as the value tape computes it: `powi` for integer exponents, √ for ½.
fn power(b: f64, e: f64) -> f64 {
    if e == 0.5 {
        sqrt(b)
    } else if e == (e as i32) as f64 {
        ComplexField::powi(b, e as i32)
    } else {
        powf(b, e)
    }
}

/// w = eᵃ.
#[inline(always)]
pub fn exp(a: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return crate::math::exp(a[0]);
    }
    let k = k.min(LEN - 1);
    rule::exp(|j| a[j], |j| w[j], k)
}

/// (sin a, cos a), or (sinh a, cosh a) for `hyperbolic`.
#[inline(always)]
pub fn sin_cos(a: &[f64; LEN], s: &mut [f64; LEN], c: &mut [f64; LEN], k: usize, hyperbolic: bool) {
    if k == 0 {
        (s[0], c[0]) = if hyperbolic {
            (ComplexField::sinh(a[0]), ComplexField::cosh(a[0]))
        } else {
            ComplexField::sin_cos(a[0])
        };
        return;
    }
    let k = k.min(LEN - 1);
    let sign = if hyperbolic { 1.0 } else { -1.0 };
    (s[k], c[k]) = rule::sin_cos(|j| a[j], (|j| s[j], |j| c[j]), k, sign);
}

/// tan (or tanh for `hyperbolic`) into w, and v = 1 ± w² beside it.
#[inline(always)]
pub fn tan(a: &[f64; LEN], w: &mut [f64; LEN], v: &mut [f64; LEN], k: usize, hyperbolic: bool) {
    w[k] = if k == 0 {
        if hyperbolic {
            ComplexField::tanh(a[0])
        } else {
            ComplexField::tan(a[0])
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
/// `value` = f(a\[0\]) at k = 0.
#[inline(always)]
pub fn quotient(
    a: &[f64; LEN],
    d: &[f64; LEN],
    w: &[f64; LEN],
    k: usize,
    (sign, value): (f64, f64),
) -> f64 {
    if k == 0 {
        return value;
    }
    let k = k.min(LEN - 1);
    rule::quotient(|j| a[j], |j| d[j], |j| w[j], k, sign)
}

/// w = atan2(y, x), with d = x² + y².
#[inline(always)]
pub fn atan2(y: &[f64; LEN], x: &[f64; LEN], d: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return RealField::atan2(y[0], x[0]);
    }
    let k = k.min(LEN - 1);
    rule::atan2((|j| y[j], |j| x[j]), |j| d[j], |j| w[j], k)
}

/// |a| on the branch of a\[0\]'s sign (at 0: of a's first non-zero coefficient).
#[inline(always)]
pub fn abs(a: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return ComplexField::abs(a[0]);
    }
    let k = k.min(LEN - 1);
    rule::abs(|j| a[j], k)
}

/// sign a\[0\], constant over the step.
#[inline(always)]
pub fn sign(a: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        crate::math::sign(a[0])
    } else {
        0.0
    }
}

/// The smaller (`larger` false) or larger argument at order 0, NaN-propagating there.
#[inline(always)]
pub fn min_max(a: &[f64; LEN], b: &[f64; LEN], k: usize, larger: bool) -> f64 {
    let k = k.min(LEN - 1);
    rule::min_max(|j| a[j], |j| b[j], k, larger)
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
