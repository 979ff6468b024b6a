//! An independent reference for Taylor coefficients: truncated power series with plain
//! polynomial arithmetic, each elementary function composed from its known power series in
//! the increment d = u − u₀ (exp, ln, the binomial series, sin/cos and sinh/cosh by the
//! addition theorems) or integrated from its derivative (tan, tanh as quotients; atan,
//! asin, acos, atan2 through their derivatives). It shares no code with the recurrences.
//!
//! Test code only, in two places: the recurrences' unit tests (`taylor/tests.rs`) and the
//! workspace's `tests/taylor_support/series.rs` (which adds an evaluator over the pool's
//! nodes) include this one file by path; the includer brings `Func` into scope.

#![allow(dead_code)] // each includer uses its own part

use super::Func;

/// A series truncated after `ORDER`.
pub type Series = Vec<f64>;

pub const ORDER: usize = 20;

pub fn constant(c: f64) -> Series {
    let mut s = vec![0.0; ORDER + 1];
    s[0] = c;
    s
}

pub fn add(a: &[f64], b: &[f64]) -> Series {
    a.iter().zip(b).map(|(x, y)| x + y).collect()
}

pub fn scale(a: &[f64], c: f64) -> Series {
    a.iter().map(|x| x * c).collect()
}

pub fn mul(a: &[f64], b: &[f64]) -> Series {
    (0..=ORDER)
        .map(|k| (0..=k).map(|j| a[j] * b[k - j]).sum())
        .collect()
}

/// Σₙ cₙ dⁿ for d with d\[0\] = 0.
fn compose(d: &[f64], c: impl Fn(usize) -> f64) -> Series {
    let mut total = constant(c(0));
    let mut power = constant(1.0);
    for n in 1..=ORDER {
        power = mul(&power, d);
        total = add(&total, &scale(&power, c(n)));
    }
    total
}

fn increment(a: &[f64]) -> Series {
    let mut d = a.to_vec();
    d[0] = 0.0;
    d
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|i| i as f64).product()
}

/// a^α = a₀^α (1 + d/a₀)^α, the binomial series.
pub fn power(a: &[f64], alpha: f64) -> Series {
    let d = scale(&increment(a), 1.0 / a[0]);
    let mut coefficients = vec![1.0];
    for n in 1..=ORDER {
        let previous = coefficients[n - 1];
        coefficients.push(previous * (alpha - (n - 1) as f64) / n as f64);
    }
    scale(&compose(&d, |n| coefficients[n]), a[0].powf(alpha))
}

pub fn divide(a: &[f64], b: &[f64]) -> Series {
    mul(a, &power(b, -1.0))
}

pub fn exp(a: &[f64]) -> Series {
    scale(&compose(&increment(a), |n| 1.0 / factorial(n)), a[0].exp())
}

pub fn ln(a: &[f64]) -> Series {
    let d = scale(&increment(a), 1.0 / a[0]);
    let term = |n: usize| match n {
        0 => a[0].ln(),
        n if n % 2 == 1 => 1.0 / n as f64,
        n => -1.0 / n as f64,
    };
    compose(&d, term)
}

fn sin_cos(a: &[f64], hyperbolic: bool) -> (Series, Series) {
    let d = increment(a);
    let sign = |n: usize| {
        if hyperbolic || (n / 2).is_multiple_of(2) {
            1.0
        } else {
            -1.0
        }
    };
    let odd = compose(&d, |n| {
        if n % 2 == 1 {
            sign(n) / factorial(n)
        } else {
            0.0
        }
    });
    let even = compose(&d, |n| {
        if n.is_multiple_of(2) {
            sign(n) / factorial(n)
        } else {
            0.0
        }
    });
    let (s0, c0) = if hyperbolic {
        (a[0].sinh(), a[0].cosh())
    } else {
        a[0].sin_cos()
    };
    let flip = if hyperbolic { 1.0 } else { -1.0 };
    (
        add(&scale(&even, s0), &scale(&odd, c0)),
        add(&scale(&even, c0), &scale(&odd, flip * s0)),
    )
}

fn integrate(w0: f64, rate: &[f64]) -> Series {
    let mut w = constant(w0);
    for k in 1..=ORDER {
        w[k] = rate[k - 1] / k as f64;
    }
    w
}

fn derivative(a: &[f64]) -> Series {
    let mut d: Series = (1..=ORDER).map(|k| k as f64 * a[k]).collect();
    d.push(0.0);
    d
}

/// The series of f at its arguments' series (abs, sign, min, max on the branch of the
/// order-0 values).
pub fn call(f: Func, args: &[Series]) -> Series {
    let a = &args[0];
    let one_minus_square = add(&constant(1.0), &scale(&mul(a, a), -1.0));
    match f {
        Func::Sin => sin_cos(a, false).0,
        Func::Cos => sin_cos(a, false).1,
        Func::Sinh => sin_cos(a, true).0,
        Func::Cosh => sin_cos(a, true).1,
        Func::Tan => {
            let (s, c) = sin_cos(a, false);
            divide(&s, &c)
        }
        Func::Tanh => {
            let (s, c) = sin_cos(a, true);
            divide(&s, &c)
        }
        Func::Exp => exp(a),
        Func::Ln => ln(a),
        Func::Asin | Func::Acos => {
            let sign = if f == Func::Asin { 1.0 } else { -1.0 };
            let rate = mul(&derivative(a), &power(&one_minus_square, -0.5));
            integrate(f.apply(&[a[0]]), &scale(&rate, sign))
        }
        Func::Atan => {
            let one_plus_square = add(&constant(1.0), &mul(a, a));
            integrate(a[0].atan(), &divide(&derivative(a), &one_plus_square))
        }
        Func::Atan2 => {
            let (y, x) = (a, &args[1]);
            let cross = add(
                &mul(x, &derivative(y)),
                &scale(&mul(y, &derivative(x)), -1.0),
            );
            let d = add(&mul(x, x), &mul(y, y));
            integrate(y[0].atan2(x[0]), &divide(&cross, &d))
        }
        Func::Abs => scale(a, if a[0] < 0.0 { -1.0 } else { 1.0 }),
        Func::Sign => constant(f.apply(&[a[0]])),
        Func::Min => args[if a[0] <= args[1][0] { 0 } else { 1 }].clone(),
        Func::Max => args[if a[0] >= args[1][0] { 0 } else { 1 }].clone(),
        // No model these tests expand has a table (the tapes give NaN coefficients for one).
        Func::Table { .. } | Func::Input { .. } => vec![f64::NAN; a.len()],
    }
}
