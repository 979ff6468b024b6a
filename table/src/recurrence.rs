//! The Taylor recurrences, written once: coefficient k ≥ 1 of one operation's result from
//! the coefficients 0..=k of its operands and 0..k of the result, all normalized
//! (u\[j\] = u⁽ʲ⁾/j!), each derived from a first-order identity between the result w and its
//! argument a (named beside each rule; Jorba & Zou 2005, *A software package for the
//! numerical integration of ODEs by means of high-order Taylor methods*, Exp. Math. 14, §2;
//! Biscani & Izzo 2021, MNRAS 504, appendix A).
//!
//! Generated code (through `varmass_core::steppers::taylor::series`, its arrays) and the
//! run-time tapes (`varmass_symbolic::expr::TaylorTape`, its jet) both call these functions,
//! each reading coefficients through a closure `|j| …`, so their coefficients are
//! bit-identical by construction: a rule cannot be changed in one of them only. Here because
//! both crates depend on this one (symbolic must not depend on core). Order 0 is not here:
//! it is the function's value, which each caller computes with its own math library (the
//! value tape's and the runtime's `libm`-capable functions), or, where the rule needs no
//! function, given to these rules at k = 0 by the caller as well.
//!
//! The arithmetic rules are generic over the [`Scalar`] of a coefficient (`f64` today; a
//! batch of lanes later), at no cost: every function is `#[inline(always)]` and monomorphized.
//! The selection rules (abs, min, max) branch on the coefficients' values: they take a
//! [`Value`] (`f64`, or a value with derivatives), never lanes (each lane branches alone).

use core::ops::{Add, Div, Mul, Neg, Sub};

/// The number a coefficient is: `f64`, or a batch of them evaluated lane by lane.
pub trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// −0, the identity of addition (x + (−0) = x for every x, −0 included).
    const NEG_ZERO: Self;
    /// The constant `x` in every lane.
    fn splat(x: f64) -> Self;
}

impl Scalar for f64 {
    const NEG_ZERO: f64 = -0.0;
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
}

/// The number a run-time tape's coefficient is (`varmass_symbolic::expr::TaylorTape`): `f64`,
/// or a value with its derivatives in some directions (`varmass_core::tangent::Tangent`, for
/// Taylor sensitivities of a model read at run time). One value, so a selection (abs, min,
/// max, a table's piece) branches on it; a function's value at order 0 comes from the
/// caller's `f64` function, and a value with derivatives moves them by the slopes given
/// beside it (the chain rule). Not for lanes: each lane would branch on its own value.
pub trait Value: Scalar + PartialEq {
    /// The value, which selections branch on.
    fn lead(self) -> f64;
    /// f(x) where f′(x) = `slope(x, f(x))`.
    fn map(self, f: impl Fn(f64) -> f64, slope: impl Fn(f64, f64) -> f64) -> Self;
    /// f(self, x) where (∂f/∂self, ∂f/∂x) = `slopes(self, x, f)`; a slope of a direction
    /// that moves neither argument is never read (it may be NaN, as ∂xᵉ/∂e at x ≤ 0).
    fn map2(
        self,
        x: Self,
        f: impl Fn(f64, f64) -> f64,
        slopes: impl Fn(f64, f64, f64) -> (f64, f64),
    ) -> Self;
    /// The argument whose value `choose(self, other)` returns (min, max): `self` unless the
    /// choice is `other`'s value and not `self`'s; the choice itself for `f64`.
    fn pick(self, other: Self, choose: impl Fn(f64, f64) -> f64) -> Self;
}

impl Value for f64 {
    #[inline(always)]
    fn lead(self) -> f64 {
        self
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64, _: impl Fn(f64, f64) -> f64) -> f64 {
        f(self)
    }
    #[inline(always)]
    fn map2(
        self,
        x: f64,
        f: impl Fn(f64, f64) -> f64,
        _: impl Fn(f64, f64, f64) -> (f64, f64),
    ) -> f64 {
        f(self, x)
    }
    #[inline(always)]
    fn pick(self, other: f64, choose: impl Fn(f64, f64) -> f64) -> f64 {
        choose(self, other)
    }
}

/// (∂w/∂x, ∂w/∂e) of w = xᵉ at order 0, for a [`Value`] with derivatives: e xᵉ⁻¹ (0 for
/// e = 0; e w/x below 0 — an integer power or the real cube root — where xᵉ⁻¹ by `powf` is
/// NaN) and w ln x (NaN for x ≤ 0, read only where a direction moves the exponent). `power`
/// and `ln` are the caller's (the value tape's semantics, its math library): the tapes and
/// generated code's tangents take the same slopes.
#[inline(always)]
pub fn power_slopes(
    (x, e, w): (f64, f64, f64),
    power: impl Fn(f64, f64) -> f64,
    ln: impl Fn(f64) -> f64,
) -> (f64, f64) {
    let along_x = match e {
        0.0 => 0.0,
        e if x < 0.0 => e * w / x,
        e => e * power(x, e - 1.0),
    };
    let along_e = match x > 0.0 {
        true => w * ln(x),
        false => f64::NAN,
    };
    (along_x, along_e)
}

/// Σ `term(j)` for j in `start..end`: the terms between the two ends in four interleaved
/// partial sums (term i of them into sum i mod 4) added pairwise, ((s₀ + s₁) + (s₂ + s₃)),
/// then `term(start)`, then `term(end − 1)` (a range of fewer than three terms: all in the
/// partial sums).
///
/// Why the ends last: an expansion is one long chain of dependent orders, and in every
/// rule's convolution Σ aⱼ b₍ₖ₋ⱼ₎ the coefficients computed last sit at the ends of the
/// range (a product's a\[0\] b\[k\] and a\[k\] b\[0\]; a quotient's d\[1\] w\[k−1\] and
/// d\[k\] w\[0\]), while the terms between read coefficients settled orders before. Added
/// last, the newest term waits on one product and one addition, not on a product and the
/// three additions that ended the four partial sums (issue 38: the sled's and the rocket's
/// expansions 4–6 % faster). The four partial sums let the processor overlap the dependent
/// additions of the rest (heyoka sums its recurrences pairwise for the same reason), and
/// the error bound shrinks with the depth. They start at −0 (see [`Scalar::NEG_ZERO`]; not
/// +0: −0 + 0 = +0), so the compiler drops the first addition of each: 9 % of the 3-link
/// pendulum's instructions at 1e-9 (callgrind). `#[inline(always)]`: generated code unrolls
/// it at every order.
#[inline(always)]
pub fn sum<S: Scalar>(start: usize, end: usize, term: impl Fn(usize) -> S) -> S {
    if end >= start + 3 {
        (chains(start + 1, end - 1, &term) + term(start)) + term(end - 1)
    } else {
        chains(start, end, &term)
    }
}

/// Σ `term(j)` for j in `start..end` in four interleaved partial sums ([`sum`]).
#[inline(always)]
fn chains<S: Scalar>(start: usize, end: usize, term: &impl Fn(usize) -> S) -> S {
    let mut s = [S::NEG_ZERO; 4];
    let mut j = start;
    while j + 4 <= end {
        s[0] = s[0] + term(j);
        s[1] = s[1] + term(j + 1);
        s[2] = s[2] + term(j + 2);
        s[3] = s[3] + term(j + 3);
        j += 4;
    }
    let mut i = 0;
    while j < end {
        s[i] = s[i] + term(j);
        i += 1;
        j += 1;
    }
    (s[0] + s[1]) + (s[2] + s[3])
}

/// j as a coefficient, for the factors j and k − j of the rules.
#[inline(always)]
fn int<S: Scalar>(j: usize) -> S {
    S::splat(j as f64)
}

/// 1/k, which depends on no data, so it is computed off the chain of orders (see [`recip`]).
#[inline(always)]
fn inverse<S: Scalar>(k: usize) -> S {
    S::splat(1.0 / k as f64)
}

/// w = Σ terms, every k: coefficient k of each term, added left to right from −0.
#[inline(always)]
pub fn add<S: Scalar>(terms: impl IntoIterator<Item = S>) -> S {
    terms.into_iter().fold(S::NEG_ZERO, |total, x| total + x)
}

/// w = c a for a constant c: w\[k\] = c\[0\] a\[k\], every k.
#[inline(always)]
pub fn scale<S: Scalar>(c: impl Fn(usize) -> S, a: impl Fn(usize) -> S, k: usize) -> S {
    c(0) * a(k)
}

/// w = offset + scale·a, every k: the value at order 0, scale·a\[k\] after it.
#[inline(always)]
pub fn affine<S: Scalar>(a: impl Fn(usize) -> S, k: usize, (scale, offset): (f64, f64)) -> S {
    if k == 0 {
        S::splat(offset) + S::splat(scale) * a(0)
    } else {
        S::splat(scale) * a(k)
    }
}

/// w = a b: the Cauchy product (every k, order 0 included).
#[inline(always)]
pub fn mul<S: Scalar>(a: impl Fn(usize) -> S, b: impl Fn(usize) -> S, k: usize) -> S {
    mul_bounded(a, b, k, (usize::MAX, usize::MAX))
}

/// w = a b for a of degree at most `da` in t and b at most `db` (their coefficients above
/// those orders 0, exactly): the Cauchy product with the terms that read such a
/// coefficient left out (an exact −0 in the same sum, so the result is [`mul`]'s bit for
/// bit, but for a zero's sign and for a non-finite coefficient times a known 0). With k,
/// `da` and `db` constants (generated code) the compiler drops those terms.
#[inline(always)]
pub fn mul_bounded<S: Scalar>(
    a: impl Fn(usize) -> S,
    b: impl Fn(usize) -> S,
    k: usize,
    (da, db): (usize, usize),
) -> S {
    sum(0, k + 1, |j| {
        if j <= da && k - j <= db {
            a(j) * b(k - j)
        } else {
            S::NEG_ZERO
        }
    })
}

/// w = a²: the Cauchy product, each cross term once and doubled (every k).
#[inline(always)]
pub fn square<S: Scalar>(a: impl Fn(usize) -> S, k: usize) -> S {
    let cross = sum(0, k.div_ceil(2), |j| a(j) * a(k - j));
    let middle = if k.is_multiple_of(2) {
        a(k / 2) * a(k / 2)
    } else {
        S::NEG_ZERO
    };
    S::splat(2.0) * cross + middle
}

/// w a = 1, k ≥ 1. Times w\[0\] = 1/a\[0\] rather than over a\[0\]: each order's coefficient
/// depends on the last, so the expansion is one long chain of dependent operations, and a
/// division on it costs three to five times a product's latency at every order.
#[inline(always)]
pub fn recip<S: Scalar>(a: impl Fn(usize) -> S, w: impl Fn(usize) -> S, k: usize) -> S {
    -sum(1, k + 1, |j| a(j) * w(k - j)) * w(0)
}

/// w d = a, k ≥ 1, times `inverse` = 1/d\[0\] as [`recip`] multiplies: one sum where 1/d
/// and a product took two.
#[inline(always)]
pub fn div<S: Scalar>(
    a: impl Fn(usize) -> S,
    d: impl Fn(usize) -> S,
    w: impl Fn(usize) -> S,
    k: usize,
    inverse: S,
) -> S {
    div_bounded(a, d, w, k, inverse, usize::MAX)
}

/// [`div`] for d of degree at most `dd` in t: the terms that read a coefficient of d above
/// it (0) left out, as [`mul_bounded`] leaves them.
#[inline(always)]
pub fn div_bounded<S: Scalar>(
    a: impl Fn(usize) -> S,
    d: impl Fn(usize) -> S,
    w: impl Fn(usize) -> S,
    k: usize,
    inverse: S,
    dd: usize,
) -> S {
    let term = |j: usize| {
        if j <= dd {
            d(j) * w(k - j)
        } else {
            S::NEG_ZERO
        }
    };
    (a(k) - sum(1, k + 1, term)) * inverse
}

/// w² = a, k ≥ 1.
#[inline(always)]
pub fn sqrt<S: Scalar>(a: impl Fn(usize) -> S, w: impl Fn(usize) -> S, k: usize) -> S {
    let cross = sum(1, k, |j| w(j) * w(k - j));
    (a(k) - cross) / (S::splat(2.0) * w(0))
}

/// a w′ = α a′ w, w = a^α for the constant α, k ≥ 1 (J&Z eq. 2.6).
#[inline(always)]
pub fn pow<S: Scalar>(a: impl Fn(usize) -> S, alpha: S, w: impl Fn(usize) -> S, k: usize) -> S {
    let total = sum(0, k, |j| (alpha * int(k - j) - int(j)) * a(k - j) * w(j));
    total / (int::<S>(k) * a(0))
}

/// k w\[k\] = Σⱼ₌₁ᵏ j a\[j\] u\[k−j\], coefficient k − 1 of w′ = a′ u, before the 1/k.
#[inline(always)]
fn chain<S: Scalar>(a: impl Fn(usize) -> S, u: impl Fn(usize) -> S, k: usize) -> S {
    sum(1, k + 1, |j| int::<S>(j) * a(j) * u(k - j))
}

/// w′ = a′ w, w = eᵃ, k ≥ 1.
#[inline(always)]
pub fn exp<S: Scalar>(a: impl Fn(usize) -> S, w: impl Fn(usize) -> S, k: usize) -> S {
    chain(a, w, k) * inverse(k)
}

/// (sin a, cos a) for `sign` −1: s′ = a′ c, c′ = −a′ s; (sinh a, cosh a) for +1: both +
/// (J&Z eq. 2.9). k ≥ 1; returns (s\[k\], c\[k\]).
#[inline(always)]
pub fn sin_cos<S: Scalar>(
    a: impl Fn(usize) -> S,
    (s, c): (impl Fn(usize) -> S, impl Fn(usize) -> S),
    k: usize,
    sign: f64,
) -> (S, S) {
    let first = chain(&a, c, k);
    let second = chain(&a, s, k);
    let inverse = inverse::<S>(k);
    (first * inverse, S::splat(sign) * second * inverse)
}

/// tan (`sign` +1) or tanh (−1): w′ = v a′ with v = 1 + sign·w²; w\[k\], k ≥ 1.
#[inline(always)]
pub fn tan<S: Scalar>(a: impl Fn(usize) -> S, v: impl Fn(usize) -> S, k: usize) -> S {
    chain(a, v, k) * inverse(k)
}

/// v\[k\] of v = 1 + sign·w² beside [`tan`], every k, once w\[k\] is known.
#[inline(always)]
pub fn tan_companion<S: Scalar>(w: impl Fn(usize) -> S, k: usize, sign: f64) -> S {
    let one = S::splat(if k == 0 { 1.0 } else { 0.0 });
    one + S::splat(sign) * mul(&w, &w, k)
}

/// w′ d = sign·a′, k ≥ 1 (ln: d = a; asin, acos: d = √(1 − a²), ±1; atan: d = 1 + a²).
#[inline(always)]
pub fn quotient<S: Scalar>(
    a: impl Fn(usize) -> S,
    d: impl Fn(usize) -> S,
    w: impl Fn(usize) -> S,
    k: usize,
    sign: f64,
) -> S {
    let total = sum(1, k, |j| int::<S>(j) * w(j) * d(k - j));
    (S::splat(sign) * a(k) - total / int(k)) / d(0)
}

/// w′ d = x y′ − y x′ with d = x² + y², w = atan2(y, x), k ≥ 1.
#[inline(always)]
pub fn atan2<S: Scalar>(
    (y, x): (impl Fn(usize) -> S, impl Fn(usize) -> S),
    d: impl Fn(usize) -> S,
    w: impl Fn(usize) -> S,
    k: usize,
) -> S {
    let cross = sum(0, k, |j| {
        int::<S>(k - j) * (x(j) * y(k - j) - y(j) * x(k - j))
    });
    let total = sum(1, k, |j| int::<S>(j) * w(j) * d(k - j));
    (cross - total) / (int::<S>(k) * d(0))
}

/// |a|, k ≥ 1: the branch of a\[0\]'s sign; at a\[0\] = 0 (a run restarted on the kink,
/// which events locate) the branch a takes just after: the sign of its first non-zero
/// coefficient up to k (+ when there is none: every coefficient up to k is then 0).
#[inline(always)]
pub fn abs<S: Value>(a: impl Fn(usize) -> S, k: usize) -> S {
    let zero = |_| S::splat(0.0);
    if below(&a, &zero, k) {
        -a(k)
    } else {
        a(k)
    }
}

/// The series of the smaller (`larger` false) or larger argument at order 0, k ≥ 1; NaN
/// when either order-0 value is (no branch is chosen then). At a tie (a run restarted on
/// the kink, which events locate) the branch that holds just after: the first coefficient
/// up to k where the two series differ decides (where none does, a\[k\] = b\[k\] and the
/// branch does not matter). A tie decided by the order of the arguments instead expanded a
/// whole step on the wrong side: `max(H - 47000, 0)` restarted at H - 47000 = 0 with H
/// falling gave the isothermal layer of models/lib/atmosphere_1976.vms a growing factor, and
/// a sphere's fall time 2e-5 off (cli/tests/library.rs).
#[inline(always)]
pub fn min_max<S: Value>(
    a: impl Fn(usize) -> S,
    b: impl Fn(usize) -> S,
    k: usize,
    larger: bool,
) -> S {
    if a(0).lead().is_nan() || b(0).lead().is_nan() {
        return S::splat(f64::NAN);
    }
    let first = if larger {
        !below(&a, &b, k)
    } else {
        !below(&b, &a, k)
    };
    if first {
        a(k)
    } else {
        b(k)
    }
}

/// Whether the series a is below b just after the expansion point: the first of the
/// coefficients 0..=k where they differ is smaller in a (false where none differs).
#[inline(always)]
fn below<S: Value>(a: &impl Fn(usize) -> S, b: &impl Fn(usize) -> S, k: usize) -> bool {
    for j in 0..=k {
        let (x, y) = (a(j).lead(), b(j).lead());
        if x != y {
            return x < y;
        }
    }
    false
}

/// Row `a` of the right side of M\[0\] q̇\[k\] = p\[k\] − b\[k\] − Σⱼ₌₁ᵏ M\[j\] q̇\[k−j\],
/// coefficient k of M q̇ = p − b for n coordinates (q̇ where no closed form was derived):
/// `matrix(a, b, j)` is M\[j\]_ab, `velocity(b, j)` is q̇_b\[j\], and (`momentum`, `offset`)
/// are p_a\[k\] and b_a\[k\]. The sum over j in four chains, over b left to right.
#[inline(always)]
pub fn velocity_right_side<S: Scalar>(
    (n, a, k): (usize, usize, usize),
    matrix: impl Fn(usize, usize, usize) -> S,
    velocity: impl Fn(usize, usize) -> S,
    (momentum, offset): (S, S),
) -> S {
    let coupling = sum(1, k + 1, |j| {
        (0..n).fold(S::NEG_ZERO, |total, b| {
            total + matrix(a, b, j) * velocity(b, k - j)
        })
    });
    (momentum - offset) - coupling
}

#[cfg(test)]
mod tests {
    use super::{exp, sin_cos, sum, Scalar};
    use core::ops::{Add, Div, Mul, Neg, Sub};

    /// The order of the additions, which generated code and the tapes share: the terms
    /// between the ends in four chains, ((s₀ + s₁) + (s₂ + s₃)), then the first term, then
    /// the last. With 2⁵³ and 1 groupings round differently: for [2⁵³, 1, 1, 1, 1, −2⁵³]
    /// the chains give 4 exactly, 2⁵³ + 4 is exact, and − 2⁵³ leaves 4; left to right each
    /// 1 is lost against 2⁵³ (0), and the four chains over all six terms (the order before
    /// issue 38) give s₀ = 2⁵³ + 1 → 2⁵³, s₁ = 1 − 2⁵³ (exact), so 1 + 2 = 3.
    #[test]
    fn adds_in_four_chains_then_pairwise() {
        let big = 2f64.powi(53);
        let terms = [big, 1.0, 1.0, 1.0, 1.0, -big];
        assert_eq!(sum(0, 6, |j| terms[j]), 4.0);
        assert_eq!(terms.iter().fold(0.0, |s, t| s + t), 0.0);
        let (s0, s1) = (terms[0] + terms[4], terms[1] + terms[5]);
        assert_eq!((s0 + s1) + (terms[2] + terms[3]), 3.0);
        // Empty: −0, the identity of addition.
        assert!(sum(3, 3, |_| 1.0).to_bits() == (-0.0f64).to_bits());
    }

    /// Two lanes, each the `f64` arithmetic: what a batch integrator would run.
    #[derive(Clone, Copy, Debug, PartialEq)]
    struct Pair([f64; 2]);

    macro_rules! lanewise {
        ($($trait:ident $method:ident $op:tt),*) => {$(
            impl $trait for Pair {
                type Output = Pair;
                fn $method(self, other: Pair) -> Pair {
                    Pair([self.0[0] $op other.0[0], self.0[1] $op other.0[1]])
                }
            }
        )*};
    }
    lanewise!(Add add +, Sub sub -, Mul mul *, Div div /);

    impl Neg for Pair {
        type Output = Pair;
        fn neg(self) -> Pair {
            Pair([-self.0[0], -self.0[1]])
        }
    }

    impl Scalar for Pair {
        const NEG_ZERO: Pair = Pair([-0.0; 2]);
        fn splat(x: f64) -> Pair {
            Pair([x; 2])
        }
    }

    /// The series of e^{λt} and (sin ωt, cos ωt) about t = 0 from a = λt (a\[1\] = λ):
    /// w\[k\] = λᵏ/k!, and sin: ωᵏ/k! (−1)^((k−1)/2) for odd k, 0 for even; cos the other
    /// way. Each lane of a [`Pair`] (λ = 0.7 and −1.3, ω = 2 and 0.5) must give the closed
    /// form (measured: ≤ 4.0e-16 relative at k ≤ 12; asserted 1e-15, a 2.5× margin) and the
    /// `f64` rule's bits exactly: the generic rules are the scalar ones, lane by lane.
    #[test]
    fn rules_match_closed_forms_in_every_lane() {
        const K: usize = 12;
        let rate = [0.7, -1.3];
        let a = |j: usize| Pair(if j == 1 { rate } else { [0.0; 2] });
        let mut w = [Pair([1.0; 2]); K + 1];
        let mut factorial = 1.0;
        for k in 1..=K {
            w[k] = exp(a, |j| w[j], k);
            factorial *= k as f64;
            for (lane, rate) in rate.iter().enumerate() {
                let closed = rate.powi(k as i32) / factorial;
                assert!(
                    (w[k].0[lane] - closed).abs() <= 1e-15 * closed.abs(),
                    "exp k={k}"
                );
                let scalar = exp(|j| a(j).0[lane], |j| w[j].0[lane], k);
                assert_eq!(scalar.to_bits(), w[k].0[lane].to_bits());
            }
        }
        let omega = [2.0, 0.5];
        let a = |j: usize| Pair(if j == 1 { omega } else { [0.0; 2] });
        let (mut s, mut c) = ([Pair([0.0; 2]); K + 1], [Pair([1.0; 2]); K + 1]);
        let mut factorial = 1.0;
        for k in 1..=K {
            (s[k], c[k]) = sin_cos(a, (|j| s[j], |j| c[j]), k, -1.0);
            factorial *= k as f64;
            for (lane, omega) in omega.iter().enumerate() {
                let magnitude = omega.powi(k as i32) / factorial;
                let sign = if (k / 2) % 2 == 0 { 1.0 } else { -1.0 };
                let (sin, cos) = if k % 2 == 1 {
                    (sign * magnitude, 0.0)
                } else {
                    (0.0, sign * magnitude)
                };
                assert!((s[k].0[lane] - sin).abs() <= 1e-15 * magnitude, "sin k={k}");
                assert!((c[k].0[lane] - cos).abs() <= 1e-15 * magnitude, "cos k={k}");
            }
        }
    }

    #[test]
    fn a_tie_takes_the_branch_that_holds_just_after() {
        use super::{abs, min_max};
        // a(t) = t - t², b(t) = 0: tied at t = 0, a above just after (its slope 1 > 0).
        let a = [0.0, 1.0, -1.0, 0.0];
        let b = [0.0; 4];
        let (ra, rb) = (|j: usize| a[j], |j: usize| b[j]);
        for k in 1..4 {
            assert_eq!(min_max(ra, rb, k, true), a[k], "max k={k}");
            assert_eq!(min_max(ra, rb, k, false), b[k], "min k={k}");
            // Arguments swapped: the same branches (the order decided before).
            assert_eq!(min_max(rb, ra, k, true), a[k], "max swapped k={k}");
            assert_eq!(min_max(rb, ra, k, false), b[k], "min swapped k={k}");
        }
        // -t + t²: |.| = t - t² just after 0, the minus branch.
        let c = [0.0, -1.0, 1.0, 0.0];
        for k in 1..4 {
            assert_eq!(abs(|j| c[j], k), -c[k], "abs k={k}");
        }
        // Equal slopes, the second coefficient decides: a = t + t², b = t.
        let (p, q) = ([0.0, 1.0, 1.0], [0.0, 1.0, 0.0]);
        assert_eq!(min_max(|j| p[j], |j| q[j], 2, false), q[2]);
        assert_eq!(min_max(|j| q[j], |j| p[j], 2, true), p[2]);
        // Apart at order 0: order 0 decides, as before.
        let (low, high) = ([1.0, 5.0], [2.0, -5.0]);
        assert_eq!(min_max(|j| low[j], |j| high[j], 1, false), 5.0);
        assert_eq!(min_max(|j| high[j], |j| low[j], 1, true), -5.0);
    }
}
