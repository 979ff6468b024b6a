//! The double-double operations against exact integer arithmetic and against values
//! computed by mpmath at 300 bits, rounded to (hi, lo) pairs by this script:
//!
//! ```python
//! from mpmath import mp, mpf, sqrt, cbrt
//! mp.prec = 300
//! def dd(x):
//!     hi = float(x); lo = float(x - mpf(hi)); return hi, lo
//! for v in [mpf(1)/3, sqrt(2), cbrt(10), (mpf(7)/3)**5, (mpf(3)/7)**-3]:
//!     print(dd(v))
//! x = mpf(2)
//! print(dd((x**3 + 2)/sqrt(x)), dd(3*x**2/sqrt(x) - (x**3 + 2)/(2*x**mpf(1.5))))
//! ```

use super::*;

/// |got − expected| / |expected|, in double-double.
fn relative(got: Dd, expected: (f64, f64)) -> f64 {
    let expected = Dd::from(expected);
    ((got - expected).hi / expected.hi).abs()
}

/// Two-sum and two-product are exact: checked in 128-bit integers on integer-valued
/// doubles whose sums and products need more than 53 bits.
#[test]
fn the_error_free_transformations_are_exact() {
    let (a, b) = (9_007_199_254_740_991.0f64, 9_007_199_254_740_989.0f64); // 2^53 − 1, 2^53 − 3
    let (p, e) = two_prod(a, b);
    assert_eq!(p as i128 + e as i128, (a as i128) * (b as i128));
    assert_ne!(e, 0.0, "the product needs 106 bits");
    let (s, e) = two_sum(a, 0.75);
    assert_eq!((s as i128) * 4 + (e * 4.0) as i128, (a as i128) * 4 + 3);
    let (s, e) = quick_two_sum(1e300, -1.0);
    assert_eq!((s, e), (1e300, -1.0));
}

/// ÷, √, ∛ and powi against mpmath. Measured (run with --nocapture): 1/3 and ∛10 0 (the
/// correctly rounded pair), √2 8.7e-33, (7/3)⁵ 2.9e-32 (five multiplications and a
/// division), (3/7)⁻³ 7.8e-33 relative; bound 1e-31, 3.5× the largest, about two units of
/// 2⁻¹⁰⁴ ≈ 4.9e-32.
#[test]
fn quotients_roots_and_powers_match_mpmath() {
    let cases = [
        (
            "1/3",
            Dd::new(1.0) / Dd::new(3.0),
            (0.3333333333333333, 1.850371707708594e-17),
        ),
        (
            "sqrt 2",
            Dd::new(2.0).sqrt(),
            (core::f64::consts::SQRT_2, -9.667293313452913e-17),
        ),
        (
            "cbrt 10",
            Dd::new(10.0).cbrt(),
            (2.154434690031884, -9.273902111110189e-17),
        ),
        (
            "(7/3)^5",
            (Dd::new(7.0) / 3.0).powi(5),
            (69.16460905349794, 1.6374647408463215e-15),
        ),
        (
            "(3/7)^-3",
            (3.0 / Dd::new(7.0)).powi(-3),
            (12.703703703703704, -4.605369583630279e-16),
        ),
    ];
    for (name, got, expected) in cases {
        let error = relative(got, expected);
        eprintln!("{name}: {error:e}");
        assert!(error <= 1e-31, "{name}: {error:e}");
    }
}

/// The dual numbers differentiate: f(x) = (x³ + 2)/√x at x = 2 + ε gives f(2) and f′(2) =
/// 3x²/√x − (x³ + 2)/(2 x^{3/2}) (hand-derived; values from mpmath above). Measured
/// 7.0e-33 and 1.8e-33 relative (6.8e-33 for the second function); bound 1e-31.
#[test]
fn duals_give_the_value_and_the_derivative_in_double_double() {
    let x = Dual::new(Dd::new(2.0), Dd::new(1.0));
    let f = (x.powi(3) + 2.0) / x.sqrt();
    let value = relative(f.v, (7.0710678118654755, -2.6132006074761434e-16));
    let slope = relative(f.d, (6.7175144212722016, -7.061837377020858e-17));
    eprintln!("value {value:e}, derivative {slope:e}");
    assert!(value <= 1e-31 && slope <= 1e-31, "{value:e} {slope:e}");
    // The other operators at the same point, against the product and quotient rules
    // written out in double-double.
    let g = (1.0 - x) * x / (x - 3.0) * x.cbrt() - (-x) * 0.5;
    let (v, c) = (Dd::new(2.0), Dd::new(2.0).cbrt());
    // g = (x − x²)/(x − 3) · ∛x + x/2; g′ = [(1 − 2x)(x − 3) − (x − x²)]/(x − 3)² ∛x
    //      + (x − x²)/(x − 3) · ∛x/(3x) + 1/2.
    let u = (v - v * v) / (v - 3.0);
    let du = ((1.0 - v * 2.0) * (v - 3.0) - (v - v * v)) / ((v - 3.0) * (v - 3.0));
    let expected = du * c + u * c / (v * 3.0) + 0.5;
    let error = ((g.d - expected).hi / expected.hi).abs();
    eprintln!("second function's derivative {error:e}");
    assert!(error <= 1e-31, "{error:e}");
    assert_eq!(g.v.hi, (u * c + v * 0.5).hi);
}

/// Non-finite and edge inputs stay visible: √ of a negative is NaN, of 0 is 0, a zero
/// divisor gives a non-finite result (the stepper checks finiteness).
#[test]
fn edge_inputs_are_not_hidden() {
    assert!(Dd::new(-1.0).sqrt().hi.is_nan());
    assert_eq!(Dd::new(0.0).sqrt(), Dd::ZERO);
    assert!(!(Dd::new(1.0) / Dd::ZERO).is_finite());
    assert_eq!(Dd::new(5.0).powi(0), Dd::new(1.0));
}

/// `Dd × Dd` is commutative to the bit, which lets `c / Dual` be written once for an `f64`
/// and a `Dd` constant (`dual_with_constant!`): for a `Dd` it computes 1/b · c where it
/// computed c · 1/b before. Checked on 400 pairs of quotients of half-integers (never 0) of
/// both signs, of magnitudes 1e-100 to 1e100 (products stay normal; most are full 106-bit
/// pairs, lo ≠ 0), and `c / Dual` against the quotient rule written with c first: equal
/// bits, not a tolerance.
#[test]
fn a_double_double_product_does_not_depend_on_the_order() {
    let value = |i: i32| {
        let scale = 10f64.powi((i % 5 - 2) * 50);
        let numerator = f64::from(i * 37 % 101) - 50.5;
        Dd::new(numerator * scale) / Dd::new(f64::from(i % 13 + 3))
    };
    let mut checked = 0;
    for i in 1..=20 {
        for j in 1..=20 {
            let (a, b) = (value(i), value(j + 100));
            assert_eq!((a * b).hi.to_bits(), (b * a).hi.to_bits(), "{a:?} {b:?}");
            assert_eq!((a * b).lo.to_bits(), (b * a).lo.to_bits(), "{a:?} {b:?}");
            let dual = Dual::new(b, a);
            let reciprocal = Dd::new(1.0) / b;
            let q = a * reciprocal;
            let by_rule = Dual::new(q, -(q * dual.d) * reciprocal);
            let got = a / dual;
            let bits = |x: Dual| [x.v.hi, x.v.lo, x.d.hi, x.d.lo].map(f64::to_bits);
            assert_eq!(bits(got), bits(by_rule), "{a:?} / {dual:?}");
            checked += 1;
        }
    }
    assert_eq!(checked, 400);
}
