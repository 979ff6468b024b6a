//! Double-double numbers and dual numbers over them: the arithmetic of the Taylor stepper's
//! head (`emit = [..., "head"]`, [`Taylor::with_head`](crate::steppers::Taylor::with_head)).
//!
//! A [`Dd`] is an unevaluated sum hi + lo of two doubles with |lo| ≤ ½ ulp(hi): about 106
//! bits. Its operations are built from error-free transformations: Knuth's two-sum
//! (s + e = a + b exactly), Dekker's fast two-sum (for |a| ≥ |b|) and the exact product
//! p + e = a·b, by a fused multiply-add where the target has one and by Dekker's split
//! otherwise (Dekker 1971, *A floating-point technique for extending the available
//! precision*; Shewchuk 1997; the algorithms are those of Hida, Li & Bailey's QD library,
//! its "accurate" addition and division). Error bounds (QD): + and − about 2 ulp of the
//! 106-bit result (2⁻¹⁰⁴ relative), × and ÷ a few.
//!
//! A [`Dual`] is v + d ε with ε² = 0: evaluating f at (y + ε ẏ) gives f(y) + ε f′(y)·ẏ,
//! which is how the head gets the Taylor coefficients c₁ = f(y) and c₂ = ½ d f/dt from one
//! evaluation of the state rate's code (t + ε as the time).
//!
//! What has a form here: + − × ÷ (with an `f64` or, for duals, a [`Dd`] on either side),
//! negation, `sqrt`, `cbrt` and `powi`. Generated code needing anything else (sin, exp, ln, tables …) does not compile
//! for the head: the macro refuses it with a message naming the function.

use core::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::ComplexField;

/// hi + lo, |lo| ≤ ½ ulp(hi).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dd {
    /// The leading double.
    pub hi: f64,
    /// The trailing double.
    pub lo: f64,
}

/// Knuth's two-sum: `(s, e)` with s = fl(a + b) and s + e = a + b exactly.
#[inline(always)]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let b_virtual = s - a;
    (s, (a - (s - b_virtual)) + (b - b_virtual))
}

/// Dekker's fast two-sum, exact when |a| ≥ |b| (or a = 0).
#[inline(always)]
pub fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// The exact product: `(p, e)` with p = fl(a b) and p + e = a b (barring overflow and
/// underflow). With a hardware fused multiply-add, e = fma(a, b, −p); otherwise Dekker's
/// split of each factor into two 26-bit halves. Both give the same, exact, e.
#[inline(always)]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if cfg!(target_feature = "fma") {
        (p, <f64 as ComplexField>::mul_add(a, b, -p))
    } else {
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
}

/// Veltkamp's split: a = hi + lo with hi and lo of 26 significant bits each.
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let t = SPLITTER * a;
    let hi = t - (t - a);
    (hi, a - hi)
}

impl Dd {
    /// Zero.
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };

    /// x exactly.
    #[inline(always)]
    pub const fn new(x: f64) -> Self {
        Dd { hi: x, lo: 0.0 }
    }

    /// hi + lo renormalised (|lo| ≤ ½ ulp of the new hi), for |hi| ≥ |lo|.
    #[inline(always)]
    fn normalised(hi: f64, lo: f64) -> Self {
        let (hi, lo) = quick_two_sum(hi, lo);
        Dd { hi, lo }
    }

    /// The square root: the double root y, corrected by one Newton step in double-double,
    /// y + (a − y²)/(2y) (QD's `sqrt`, Karp & Markstein's form).
    pub fn sqrt(self) -> Self {
        if self.hi <= 0.0 {
            // 0 stays 0; a negative or NaN argument gives NaN, as `f64::sqrt`.
            return Dd::new(<f64 as ComplexField>::sqrt(self.hi));
        }
        let y = <f64 as ComplexField>::sqrt(self.hi);
        let residual = self - Dd::from(two_prod(y, y));
        Dd::new(y) + residual.hi / (2.0 * y)
    }

    /// The cube root: the double root y and one Newton step, y + (a − y³)/(3y²).
    pub fn cbrt(self) -> Self {
        if self.hi == 0.0 || !self.hi.is_finite() {
            return Dd::new(<f64 as ComplexField>::cbrt(self.hi));
        }
        let y = <f64 as ComplexField>::cbrt(self.hi);
        let y = Dd::new(y);
        let residual = self - y * y * y;
        y + residual.hi / (3.0 * y.hi * y.hi)
    }

    /// xⁿ by binary powering (a negative n through the reciprocal of x⁻ⁿ).
    pub fn powi(self, n: i32) -> Self {
        let mut result: Option<Dd> = None;
        let mut base = self;
        let mut e = n.unsigned_abs();
        while e > 0 {
            if e & 1 == 1 {
                result = Some(result.map_or(base, |r| r * base));
            }
            e >>= 1;
            if e > 0 {
                base = base * base;
            }
        }
        let result = result.unwrap_or(Dd::new(1.0));
        if n < 0 {
            Dd::new(1.0) / result
        } else {
            result
        }
    }

    /// Whether both parts are finite.
    pub fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }
}

impl From<f64> for Dd {
    #[inline(always)]
    fn from(x: f64) -> Self {
        Dd::new(x)
    }
}

impl From<(f64, f64)> for Dd {
    /// An unnormalised pair, e.g. the result of [`two_sum`] or [`two_prod`].
    #[inline(always)]
    fn from((hi, lo): (f64, f64)) -> Self {
        Dd { hi, lo }
    }
}

impl Add for Dd {
    type Output = Dd;
    /// QD's accurate addition (two two-sums, then renormalisation).
    #[inline(always)]
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = quick_two_sum(s, e + t);
        Dd::normalised(s, e + f)
    }
}

impl Add<f64> for Dd {
    type Output = Dd;
    #[inline(always)]
    fn add(self, o: f64) -> Dd {
        let (s, e) = two_sum(self.hi, o);
        Dd::normalised(s, e + self.lo)
    }
}

impl Neg for Dd {
    type Output = Dd;
    #[inline(always)]
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for Dd {
    type Output = Dd;
    #[inline(always)]
    fn sub(self, o: Dd) -> Dd {
        self + (-o)
    }
}

impl Sub<f64> for Dd {
    type Output = Dd;
    #[inline(always)]
    fn sub(self, o: f64) -> Dd {
        self + (-o)
    }
}

impl Mul for Dd {
    type Output = Dd;
    /// The exact product of the leading parts plus the cross terms (QD's `*`).
    #[inline(always)]
    fn mul(self, o: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, o.hi);
        Dd::normalised(p, e + (self.hi * o.lo + self.lo * o.hi))
    }
}

impl Mul<f64> for Dd {
    type Output = Dd;
    #[inline(always)]
    fn mul(self, o: f64) -> Dd {
        let (p, e) = two_prod(self.hi, o);
        Dd::normalised(p, e + self.lo * o)
    }
}

impl Div for Dd {
    type Output = Dd;
    /// QD's accurate division: three quotient digits, each from the remainder so far.
    #[inline(always)]
    fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self - o * q1;
        let q2 = r.hi / o.hi;
        let r = r - o * q2;
        let q3 = r.hi / o.hi;
        Dd::normalised(q1, q2) + q3
    }
}

impl Div<f64> for Dd {
    type Output = Dd;
    #[inline(always)]
    fn div(self, o: f64) -> Dd {
        self / Dd::new(o)
    }
}

/// `f64 ∘ Dd` for the operators generated code writes with a literal first.
macro_rules! f64_first {
    ($($Op:ident $op:ident),*) => {$(
        impl $Op<Dd> for f64 {
            type Output = Dd;
            #[inline(always)]
            fn $op(self, o: Dd) -> Dd {
                Dd::new(self).$op(o)
            }
        }
    )*};
}
f64_first!(Add add, Sub sub, Mul mul, Div div);

/// v + d ε with ε² = 0 (forward-mode automatic differentiation of first order).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dual {
    /// The value.
    pub v: Dd,
    /// The derivative along ε.
    pub d: Dd,
}

impl Dual {
    /// v + d ε.
    #[inline(always)]
    pub const fn new(v: Dd, d: Dd) -> Self {
        Dual { v, d }
    }

    /// √x: √v + ε d/(2√v).
    pub fn sqrt(self) -> Self {
        let root = self.v.sqrt();
        Dual::new(root, self.d / (root * 2.0))
    }

    /// ∛x: ∛v + ε d/(3∛v²).
    pub fn cbrt(self) -> Self {
        let root = self.v.cbrt();
        Dual::new(root, self.d / (root * root * 3.0))
    }

    /// xⁿ: vⁿ + ε n vⁿ⁻¹ d.
    pub fn powi(self, n: i32) -> Self {
        if n == 0 {
            return Dual::from(1.0);
        }
        let below = self.v.powi(n - 1);
        Dual::new(below * self.v, below * self.d * f64::from(n))
    }
}

impl From<f64> for Dual {
    #[inline(always)]
    fn from(x: f64) -> Self {
        Dual::new(Dd::new(x), Dd::ZERO)
    }
}

impl Add for Dual {
    type Output = Dual;
    #[inline(always)]
    fn add(self, o: Dual) -> Dual {
        Dual::new(self.v + o.v, self.d + o.d)
    }
}

impl Sub for Dual {
    type Output = Dual;
    #[inline(always)]
    fn sub(self, o: Dual) -> Dual {
        Dual::new(self.v - o.v, self.d - o.d)
    }
}

impl Mul for Dual {
    type Output = Dual;
    #[inline(always)]
    fn mul(self, o: Dual) -> Dual {
        Dual::new(self.v * o.v, self.v * o.d + self.d * o.v)
    }
}

impl Div for Dual {
    type Output = Dual;
    /// (a/b)′ = (a′ − (a/b) b′)/b, both through the reciprocal 1/b: one double-double
    /// division and three products rather than two divisions (a division costs about
    /// three products), a few units of 2⁻¹⁰⁴ either way.
    #[inline(always)]
    fn div(self, o: Dual) -> Dual {
        let reciprocal = Dd::new(1.0) / o.v;
        let q = self.v * reciprocal;
        Dual::new(q, (self.d - q * o.d) * reciprocal)
    }
}

impl Neg for Dual {
    type Output = Dual;
    #[inline(always)]
    fn neg(self) -> Dual {
        Dual::new(-self.v, -self.d)
    }
}

/// `Dual ∘ c` and `c ∘ Dual` for a constant `c` (an `f64` or a [`Dd`], no ε part): the
/// operation on v, and on d by the rules of a constant, (v ± c)′ = v′, (c·v)′ = c v′,
/// (c − v)′ = −v′; the same text for both types, each operation on v and d being the
/// constant's own (`Dd ∘ f64` or `Dd ∘ Dd`).
macro_rules! dual_with_constant {
    ($C:ty) => {
        impl Add<$C> for Dual {
            type Output = Dual;
            #[inline(always)]
            fn add(self, o: $C) -> Dual {
                Dual::new(self.v + o, self.d)
            }
        }

        impl Sub<$C> for Dual {
            type Output = Dual;
            #[inline(always)]
            fn sub(self, o: $C) -> Dual {
                Dual::new(self.v - o, self.d)
            }
        }

        impl Mul<$C> for Dual {
            type Output = Dual;
            #[inline(always)]
            fn mul(self, o: $C) -> Dual {
                Dual::new(self.v * o, self.d * o)
            }
        }

        impl Div<$C> for Dual {
            type Output = Dual;
            #[inline(always)]
            fn div(self, o: $C) -> Dual {
                Dual::new(self.v / o, self.d / o)
            }
        }

        impl Add<Dual> for $C {
            type Output = Dual;
            #[inline(always)]
            fn add(self, o: Dual) -> Dual {
                o + self
            }
        }

        impl Sub<Dual> for $C {
            type Output = Dual;
            #[inline(always)]
            fn sub(self, o: Dual) -> Dual {
                Dual::new(self - o.v, -o.d)
            }
        }

        impl Mul<Dual> for $C {
            type Output = Dual;
            #[inline(always)]
            fn mul(self, o: Dual) -> Dual {
                o * self
            }
        }

        impl Div<Dual> for $C {
            type Output = Dual;
            /// (c/b)′ = −(c/b) b′/b, through the reciprocal 1/b as `Dual / Dual`. The
            /// product 1/b · c is `Dd × f64` for an `f64` (cheaper than widening c), and
            /// for a `Dd` the same bits as c · 1/b: `Dd × Dd` is commutative to the bit
            /// (`two_prod` is exact either way, and the cross terms are one sum of two
            /// products, whose order IEEE addition does not see; `dd_tests.rs` checks it).
            #[inline(always)]
            fn div(self, o: Dual) -> Dual {
                let reciprocal = Dd::new(1.0) / o.v;
                let q = reciprocal * self;
                Dual::new(q, -(q * o.d) * reciprocal)
            }
        }
    };
}
dual_with_constant!(f64);
dual_with_constant!(Dd);

impl From<Dd> for Dual {
    #[inline(always)]
    fn from(x: Dd) -> Self {
        Dual::new(x, Dd::ZERO)
    }
}

#[cfg(test)]
#[path = "dd_tests.rs"]
mod tests;
