//! Exact rational constants with checked arithmetic.
//!
//! Every operation that could overflow `i128` returns `None`; the caller then falls back to
//! an inexact `f64` constant or leaves the operation unfolded. Nothing here panics.

use std::cmp::Ordering;
use std::fmt;

/// An exact rational number `num / den`, always reduced, with `den > 0`.
///
/// Because the representation is unique, derived `Eq` and `Hash` are equality of values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rational {
    num: i128,
    den: i128,
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        let r = a % b;
        a = b;
        b = r;
    }
    a
}

/// `10^k` if it fits.
fn pow10(k: u32) -> Option<i128> {
    10i128.checked_pow(k)
}

/// The integer `k`-th root of `n ≥ 0` if `n` is a perfect `k`-th power.
fn exact_integer_root(n: i128, k: u32) -> Option<i128> {
    if n < 0 || k == 0 {
        return None;
    }
    if n < 2 || k == 1 {
        return Some(n);
    }
    // The f64 estimate is within a few units of the true root for every i128; check the
    // neighbours exactly.
    let estimate = (n as f64).powf(1.0 / f64::from(k)).round() as i128;
    (estimate.saturating_sub(2)..=estimate.saturating_add(2))
        .filter(|r| *r >= 0)
        .find(|r| r.checked_pow(k) == Some(n))
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    /// One.
    pub const ONE: Rational = Rational { num: 1, den: 1 };
    /// Minus one.
    pub const MINUS_ONE: Rational = Rational { num: -1, den: 1 };
    /// One half (the exponent of a square root).
    pub const HALF: Rational = Rational { num: 1, den: 2 };
    /// Minus one half (the exponent of an inverse square root).
    pub const MINUS_HALF: Rational = Rational { num: -1, den: 2 };

    /// `num / den` reduced; `None` if `den == 0` or the normalised value does not fit.
    pub fn new(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        let g = gcd(num.unsigned_abs(), den.unsigned_abs());
        // g ≥ 1 since den ≠ 0. Divide in u128 so that i128::MIN is handled.
        let n = num.unsigned_abs() / g;
        let d = den.unsigned_abs() / g;
        let negative = (num < 0) != (den < 0);
        let d = i128::try_from(d).ok()?;
        let n = if negative {
            0i128.checked_sub_unsigned(n)?
        } else {
            i128::try_from(n).ok()?
        };
        Some(Rational { num: n, den: d })
    }

    /// The integer `n`.
    pub const fn integer(n: i128) -> Rational {
        Rational { num: n, den: 1 }
    }

    /// The numerator (carries the sign).
    pub fn numer(self) -> i128 {
        self.num
    }

    /// The denominator (always positive).
    pub fn denom(self) -> i128 {
        self.den
    }

    /// Whether this is zero.
    pub fn is_zero(self) -> bool {
        self.num == 0
    }

    /// Whether this is one.
    pub fn is_one(self) -> bool {
        self.num == 1 && self.den == 1
    }

    /// Whether this is negative.
    pub fn is_negative(self) -> bool {
        self.num < 0
    }

    /// The value as an integer, if it is one.
    pub fn as_integer(self) -> Option<i128> {
        (self.den == 1).then_some(self.num)
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        if self.den == 1 {
            return self.num as f64;
        }
        self.num as f64 / self.den as f64
    }

    /// `-self`.
    pub fn checked_neg(self) -> Option<Rational> {
        Some(Rational {
            num: self.num.checked_neg()?,
            den: self.den,
        })
    }

    /// `|self|`.
    pub fn checked_abs(self) -> Option<Rational> {
        Some(Rational {
            num: self.num.checked_abs()?,
            den: self.den,
        })
    }

    /// `self + other`.
    pub fn checked_add(self, other: Rational) -> Option<Rational> {
        // Integers (most constants) need no gcd: i128 division is slow unoptimized.
        if self.den == 1 && other.den == 1 {
            return Some(Rational::integer(self.num.checked_add(other.num)?));
        }
        let g = i128::try_from(gcd(self.den.unsigned_abs(), other.den.unsigned_abs())).ok()?;
        let left = self.num.checked_mul(other.den / g)?;
        let right = other.num.checked_mul(self.den / g)?;
        Rational::new(
            left.checked_add(right)?,
            (self.den / g).checked_mul(other.den)?,
        )
    }

    /// `self - other`.
    pub fn checked_sub(self, other: Rational) -> Option<Rational> {
        self.checked_add(other.checked_neg()?)
    }

    /// `self * other`.
    pub fn checked_mul(self, other: Rational) -> Option<Rational> {
        if self.den == 1 && other.den == 1 {
            return Some(Rational::integer(self.num.checked_mul(other.num)?));
        }
        // Cross-reduce first so that products that fit are never rejected.
        let g1 = i128::try_from(gcd(self.num.unsigned_abs(), other.den.unsigned_abs())).ok()?;
        let g2 = i128::try_from(gcd(other.num.unsigned_abs(), self.den.unsigned_abs())).ok()?;
        let (g1, g2) = (g1.max(1), g2.max(1));
        let num = (self.num / g1).checked_mul(other.num / g2)?;
        let den = (self.den / g2).checked_mul(other.den / g1)?;
        Rational::new(num, den)
    }

    /// `1 / self`; `None` for zero.
    pub fn checked_recip(self) -> Option<Rational> {
        Rational::new(self.den, self.num)
    }

    /// `self / other`; `None` for division by zero.
    pub fn checked_div(self, other: Rational) -> Option<Rational> {
        self.checked_mul(other.checked_recip()?)
    }

    /// `self^exp` for an integer exponent; `None` on overflow or `0^negative`.
    pub fn checked_pow(self, exp: i128) -> Option<Rational> {
        // Cheap exact answers first, so that huge exponents of 0 and ±1 never loop.
        if exp == 0 {
            return Some(Rational::ONE);
        }
        if self.num == 0 {
            return (exp > 0).then_some(Rational::ZERO);
        }
        if self.den == 1 && self.num.abs() == 1 {
            return Some(if self.num == 1 || exp % 2 == 0 {
                Rational::ONE
            } else {
                Rational::MINUS_ONE
            });
        }
        let base = if exp < 0 { self.checked_recip()? } else { self };
        let mut e = exp.unsigned_abs();
        // |base| ≥ 2 in numerator or denominator, so e > 127 always overflows.
        if e > 127 {
            return None;
        }
        let mut acc = Rational::ONE;
        let mut square = base;
        loop {
            if e & 1 == 1 {
                acc = acc.checked_mul(square)?;
            }
            e >>= 1;
            if e == 0 {
                return Some(acc);
            }
            square = square.checked_mul(square)?;
        }
    }

    /// The exact `k`-th root, if numerator and denominator are perfect `k`-th powers
    /// (a negative value has an odd root only).
    pub fn exact_root(self, k: u32) -> Option<Rational> {
        if k == 0 {
            return None;
        }
        if self.num < 0 {
            if k.is_multiple_of(2) {
                return None;
            }
            return self.checked_neg()?.exact_root(k)?.checked_neg();
        }
        Rational::new(
            exact_integer_root(self.num, k)?,
            exact_integer_root(self.den, k)?,
        )
    }

    /// Parses a decimal literal (`2`, `9.81`, `.5`, `1e-3`, `6.02E23`) exactly; `None` if the
    /// text is not such a literal or the value does not fit in `i128 / i128`.
    pub fn from_decimal(text: &str) -> Option<Rational> {
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], Some(&text[i + 1..])),
            None => (text, None),
        };
        let (int_part, frac_part) = match mantissa.find('.') {
            Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
            None => (mantissa, ""),
        };
        let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
        if int_part.is_empty() && frac_part.is_empty()
            || !all_digits(int_part)
            || !all_digits(frac_part)
        {
            return None;
        }
        let exponent: i64 = match exponent {
            None => 0,
            Some(e) => {
                let digits = e.strip_prefix(['+', '-']).unwrap_or(e);
                if digits.is_empty() || !all_digits(digits) {
                    return None;
                }
                // Any exponent this long cannot give an i128 rational anyway.
                if digits.len() > 6 {
                    return None;
                }
                e.parse().ok()?
            }
        };
        let mut num: i128 = 0;
        for b in int_part.bytes().chain(frac_part.bytes()) {
            num = num.checked_mul(10)?.checked_add(i128::from(b - b'0'))?;
        }
        let scale = exponent - frac_part.len() as i64;
        if num == 0 {
            return Some(Rational::ZERO);
        }
        if scale >= 0 {
            Rational::new(num.checked_mul(pow10(u32::try_from(scale).ok()?)?)?, 1)
        } else {
            Rational::new(num, pow10(u32::try_from(-scale).ok()?)?)
        }
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Rational) -> Ordering {
        if let (Some(l), Some(r)) = (
            self.num.checked_mul(other.den),
            other.num.checked_mul(self.den),
        ) {
            return l.cmp(&r);
        }
        // Overflow: compare by continued fractions, exact and overflow-free.
        let (mut a, mut b, mut c, mut d) = (self.num, self.den, other.num, other.den);
        let mut flipped = false;
        loop {
            let (qa, ra) = (a.div_euclid(b), a.rem_euclid(b));
            let (qc, rc) = (c.div_euclid(d), c.rem_euclid(d));
            let ord = qa.cmp(&qc);
            if ord != Ordering::Equal {
                return if flipped { ord.reverse() } else { ord };
            }
            match (ra == 0, rc == 0) {
                (true, true) => return Ordering::Equal,
                (true, false) => {
                    return if flipped {
                        Ordering::Greater
                    } else {
                        Ordering::Less
                    }
                }
                (false, true) => {
                    return if flipped {
                        Ordering::Less
                    } else {
                        Ordering::Greater
                    }
                }
                (false, false) => {
                    // a/b = qa + ra/b: compare b/ra against d/rc, reversed.
                    (a, b, c, d) = (b, ra, d, rc);
                    flipped = !flipped;
                }
            }
        }
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Rational) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Rational {
        Rational::integer(i128::from(n))
    }
}
