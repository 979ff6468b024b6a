//! The Taylor recurrences generated code calls (`emit = [..., "taylor"]`): coefficient `k`
//! of one operation from the coefficients 0..=k of its operands and 0..k of its result,
//! each array holding the normalized coefficients u\[j\] = u⁽ʲ⁾/j!. At k = 0 each returns the
//! function's value. The formulas are those of the run-time tapes
//! (`varmass_symbolic::expr::TaylorTape`, Jorba & Zou 2005 §2, Biscani & Izzo 2021
//! appendix A), each named beside the identity it comes from; `tests/taylor_emitted.rs`
//! holds the two to the same coefficients.

use core::any::TypeId;

use nalgebra::{ComplexField, RealField};

use crate::cholesky::{factor as cholesky, substitute};
use crate::math::{powf, sqrt};

/// The recurrences' sums, in four chains: one function for generated code and the tapes
/// (`varmass-table` is the crate both depend on).
pub use varmass_table::sum;

/// The length of every coefficient array of generated code: orders 0 … [`super::MAX_ORDER`].
pub const LEN: usize = super::MAX_ORDER + 1;

/// Coefficient arrays of several subexpressions (rows of M, offsets, momenta).
pub type Arrays<'a> = &'a [&'a [f64; LEN]];

/// The working memory of generated `taylor_coefficients`: one coefficient array (a row) per
/// subexpression, and M\[0\]'s factor when q̇ is solved order by order. The caller keeps it
/// between expansions (the [`Taylor`](super::Taylor) stepper owns one), so that an
/// expansion neither allocates nor clears its rows: zeroing every row of a stack buffer of
/// `LEN`-long arrays at each expansion was two thirds of the instructions of the 3-link
/// pendulum's step.
///
/// Why no row needs clearing: generated code writes every row it reads at orders
/// 0 ..= k before reading it at order k, except the rows set at order 0 alone (time, held
/// inputs, constants), whose higher coefficients must read 0. Those it zeroes when the
/// scratch is new to it ([`Scratch::parts`] says so: the scratch remembers which
/// generated code used it last), and nothing writes their higher coefficients afterwards.
/// So what a scratch held before, another system's rows included, never reaches a result
/// (`tests/taylor_emitted.rs` and `tests/taylor_tables.rs` run on scratches filled with
/// NaN, reused).
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    rows: Vec<[f64; LEN]>,
    factor: Vec<f64>,
    /// The generated code that used the rows last (a type of its own, local to it).
    owner: Option<TypeId>,
}

impl Scratch {
    /// An empty scratch; the first expansion sizes it (the only allocation).
    pub fn new() -> Self {
        Self::default()
    }

    /// A scratch of `rows` rows and a factor of `factor` entries, every entry `value`: for
    /// tests that what a scratch held never reaches a result.
    #[doc(hidden)]
    pub fn filled(rows: usize, factor: usize, value: f64) -> Self {
        Self {
            rows: vec![[value; LEN]; rows],
            factor: vec![value; factor],
            owner: None,
        }
    }

    /// The first `F` rows and `factor` entries of the factor, grown if shorter, for the
    /// generated code `owner`; `true` when that code did not use them last (its rows set
    /// at order 0 alone must then be zeroed).
    pub fn parts<const F: usize>(
        &mut self,
        factor: usize,
        owner: TypeId,
    ) -> (&mut [[f64; LEN]; F], &mut [f64], bool) {
        let fresh = self.owner != Some(owner) || self.rows.len() < F;
        if self.rows.len() < F {
            self.rows.resize(F, [0.0; LEN]);
        }
        if self.factor.len() < factor {
            self.factor.resize(factor, 0.0);
        }
        self.owner = Some(owner);
        let rows = self.rows.first_chunk_mut::<F>();
        // `rows` holds at least F rows now.
        let rows = rows.unwrap_or_else(|| unreachable!("the rows were grown to {F}"));
        (rows, &mut self.factor[..factor], fresh)
    }
}

/// w = a b.
#[inline(always)]
pub fn mul(a: &[f64; LEN], b: &[f64; LEN], k: usize) -> f64 {
    let k = k.min(LEN - 1);
    sum(0, k + 1, |j| a[j] * b[k - j])
}

/// w = a².
#[inline(always)]
pub fn square(a: &[f64; LEN], k: usize) -> f64 {
    let k = k.min(LEN - 1);
    let cross = sum(0, k.div_ceil(2), |j| a[j] * a[k - j]);
    let middle = if k.is_multiple_of(2) {
        a[k / 2] * a[k / 2]
    } else {
        -0.0
    };
    2.0 * cross + middle
}

/// w a = 1. Times w\[0\] = 1/a\[0\] rather than over a\[0\]: each order's coefficient
/// depends on the last, so the expansion is one long chain of dependent operations, and a
/// division on it costs three to five times a product's latency at every order.
#[inline(always)]
pub fn recip(a: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return 1.0 / a[0];
    }
    let k = k.min(LEN - 1);
    -sum(1, k + 1, |j| a[j] * w[k - j]) * w[0]
}

/// w d = a, times 1/d\[0\] as `recip` multiplies: one sum where 1/d and a product took two.
#[inline(always)]
pub fn div(a: &[f64; LEN], d: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    let inverse = 1.0 / d[0];
    if k == 0 {
        return a[0] * inverse;
    }
    let k = k.min(LEN - 1);
    (a[k] - sum(1, k + 1, |j| d[j] * w[k - j])) * inverse
}

/// w² = a.
#[inline(always)]
pub fn sqrt_of(a: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return sqrt(a[0]);
    }
    let k = k.min(LEN - 1);
    let cross = sum(1, k, |j| w[j] * w[k - j]);
    (a[k] - cross) / (2.0 * w[0])
}

/// a w′ = α a′ w, w = a^α for the constant α = e\[0\].
#[inline(always)]
pub fn pow(a: &[f64; LEN], e: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    let alpha = e[0];
    if k == 0 {
        return power(a[0], alpha);
    }
    let k = k.min(LEN - 1);
    let total = sum(0, k, |j| {
        (alpha * (k - j) as f64 - j as f64) * a[k - j] * w[j]
    });
    total / (k as f64 * a[0])
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

/// w′ = a′ w.
#[inline(always)]
pub fn exp(a: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return crate::math::exp(a[0]);
    }
    let k = k.min(LEN - 1);
    // Times 1/k, which depends on no data, so it is computed off the chain (see `recip`).
    sum(1, k + 1, |j| j as f64 * a[j] * w[k - j]) * (1.0 / k as f64)
}

/// (sin a, cos a): s′ = a′ c, c′ = −a′ s; for `hyperbolic`, (sinh, cosh) with both +.
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
    let first = sum(1, k + 1, |j| j as f64 * a[j] * c[k - j]);
    let second = sum(1, k + 1, |j| j as f64 * a[j] * s[k - j]);
    let sign = if hyperbolic { 1.0 } else { -1.0 };
    let inverse = 1.0 / k as f64;
    s[k] = first * inverse;
    c[k] = sign * second * inverse;
}

/// tan (or tanh for `hyperbolic`): w′ = v a′ with v = 1 ± w².
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
        sum(1, k + 1, |j| j as f64 * a[j] * v[k - j]) * (1.0 / k as f64)
    };
    let sign = if hyperbolic { -1.0 } else { 1.0 };
    let one = if k == 0 { 1.0 } else { 0.0 };
    v[k] = one + sign * mul(w, w, k);
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
    let total = sum(1, k, |j| j as f64 * w[j] * d[k - j]);
    (sign * a[k] - total / k as f64) / d[0]
}

/// w′ d = x y′ − y x′ with d = x² + y², w = atan2(y, x).
#[inline(always)]
pub fn atan2(y: &[f64; LEN], x: &[f64; LEN], d: &[f64; LEN], w: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        return RealField::atan2(y[0], x[0]);
    }
    let k = k.min(LEN - 1);
    let cross = sum(0, k, |j| {
        (k - j) as f64 * (x[j] * y[k - j] - y[j] * x[k - j])
    });
    let total = sum(1, k, |j| j as f64 * w[j] * d[k - j]);
    (cross - total) / (k as f64 * d[0])
}

/// |a| on the branch of a\[0\]'s sign.
#[inline(always)]
pub fn abs(a: &[f64; LEN], k: usize) -> f64 {
    if k == 0 {
        ComplexField::abs(a[0])
    } else if a[0] < 0.0 {
        -a[k]
    } else {
        a[k]
    }
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
    if a[0].is_nan() || b[0].is_nan() {
        return f64::NAN;
    }
    let first = if larger { a[0] >= b[0] } else { a[0] <= b[0] };
    if first {
        a[k]
    } else {
        b[k]
    }
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
        // Σⱼ₌₁ᵏ (Σ_b M[j]_ab q̇_b[k−j]): the sum over j in four chains, as the tapes add it.
        let coupling = sum(1, k + 1, |j| {
            (0..n).fold(-0.0, |total, b| {
                total + matrix[a * n + b][j] * velocities[b][k - j]
            })
        });
        rhs[a] = (momenta[a][k] - offset[a][k]) - coupling;
    }
    substitute(factor, &mut rhs, n);
    for (a, v) in velocities.iter_mut().enumerate().take(n) {
        v[k] = rhs[a];
    }
    rhs.iter().take(n).all(|x| x.is_finite())
}
