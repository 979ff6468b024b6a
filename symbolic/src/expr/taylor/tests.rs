//! The recurrences against a second formulation: each function's series composed from its
//! known power series in the increment d = u − u(t₀) (exp, ln, binomial, sin/cos,
//! sinh/cosh) or integrated from its derivative (atan, asin, acos, atan2), with series
//! products and quotients done by plain truncated polynomial arithmetic. None of it shares
//! code with the recurrences.

use super::super::{ExprPool, Func, Id, Rational, Symbol};
use super::{TaylorJet, TaylorTape};

#[path = "reference.rs"]
mod reference;

use reference::{call as reference, exp, ln, mul, power as binomial, Series, ORDER};

/// A pool with inputs x and y and a parameter c, and arguments' series: x and y are given
/// as smooth series with coefficients of mixed signs and sizes.
struct Bench {
    pool: ExprPool,
    x: Symbol,
    y: Symbol,
    c: Symbol,
    xs: Series,
    ys: Series,
}

impl Bench {
    fn new(x0: f64, y0: f64) -> Bench {
        let mut pool = ExprPool::new();
        let x = pool
            .symbols_mut()
            .add("x", super::super::SymbolKind::Parameter);
        let y = pool
            .symbols_mut()
            .add("y", super::super::SymbolKind::Parameter);
        let c = pool
            .symbols_mut()
            .add("c", super::super::SymbolKind::Parameter);
        // Coefficients decay like 0.6^k with alternating, irregular signs (radius ≈ 1.7).
        let series = |x0: f64, phase: f64| -> Series {
            (0..=ORDER)
                .map(|k| match k {
                    0 => x0,
                    _ => 0.6f64.powi(k as i32) * (1.3 * k as f64 + phase).cos() * 0.5,
                })
                .collect()
        };
        Bench {
            xs: series(x0, 0.3),
            ys: series(y0, 1.9),
            pool,
            x,
            y,
            c,
        }
    }

    /// The tape's coefficients of `root`, with x and y as inputs and c = 1.7.
    fn taylor(&self, root: Id) -> Series {
        self.run(&self.pool.compile_taylor(&[root], &[self.x, self.y]))
    }

    /// The coefficients of `tape`'s first output, its inputs x and y, with c = 1.7.
    fn run(&self, tape: &TaylorTape) -> Series {
        let mut jet = TaylorJet::new();
        let mut env = vec![f64::NAN; self.pool.symbols().len()];
        env[self.c.index()] = 1.7;
        tape.begin(&mut jet, ORDER, &env);
        (0..=ORDER)
            .map(|k| {
                tape.set_input(&mut jet, 0, k, self.xs[k]);
                tape.set_input(&mut jet, 1, k, self.ys[k]);
                tape.advance(&mut jet, k);
                tape.output(&jet, 0, k)
            })
            .collect()
    }
}

/// Largest |a − b| over the coefficients, relative to the largest |b|.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let size = b.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / size
}

#[test]
fn every_function_matches_its_composed_series_to_order_20() {
    // x(t₀) = 0.4 and y(t₀) = 0.7 keep asin, acos, ln and the powers on their domains.
    for (x0, y0) in [(0.4, 0.7), (-0.3, 1.2)] {
        let mut b = Bench::new(x0, y0);
        let (x, y) = (b.pool.sym(b.x), b.pool.sym(b.y));
        for f in Func::ALL {
            if f == Func::Ln && x0 < 0.0 || matches!(f, Func::Asin | Func::Acos) && x0.abs() > 1.0 {
                continue;
            }
            let args: Vec<Id> = if f.arity() == 2 { vec![x, y] } else { vec![x] };
            let root = b.pool.call(f, &args);
            let series = [b.xs.clone(), b.ys.clone()];
            let expected = reference(f, &series[..f.arity()]);
            let got = b.taylor(root);
            let error = relative_difference(&got, &expected);
            // Measured ≤ 1.8e-16 (tan at x0 = −0.3); 1e-14 leaves rounding room over 20 orders.
            assert!(
                error < 1e-14,
                "{f:?} at x0 = {x0}: relative error {error:e}"
            );
        }
    }
}

#[test]
fn powers_products_and_quotients_match_the_binomial_series() {
    let mut b = Bench::new(0.8, -1.1);
    let (x, y, c) = (b.pool.sym(b.x), b.pool.sym(b.y), b.pool.sym(b.c));
    let (xs, ys) = (b.xs.clone(), b.ys.clone());
    let cases: Vec<(Rational, Series)> = [
        (2, 1),
        (3, 1),
        (7, 1),
        (-1, 1),
        (-3, 1),
        (1, 2),
        (-3, 2),
        (5, 3),
    ]
    .into_iter()
    .map(|(n, d)| {
        let r = Rational::new(n, d).unwrap();
        (r, binomial(&xs, r.to_f64()))
    })
    .collect();
    for (exponent, expected) in cases {
        let e = b.pool.rational(exponent);
        let root = b.pool.pow(x, e);
        let error = relative_difference(&b.taylor(root), &expected);
        // Measured ≤ 2e-16.
        assert!(error < 1e-14, "x^{exponent:?}: {error:e}");
    }
    // A real exponent (a parameter, c = 1.7) and a varying one: y^2 x^c / y and x^y.
    let power = b.pool.pow(x, c);
    let y2 = b.pool.int(2);
    let y_squared = b.pool.pow(y, y2);
    let minus_one = b.pool.int(-1);
    let inverse = b.pool.pow(y, minus_one);
    let root = b.pool.mul(&[y_squared, power, inverse]);
    let expected = mul(
        &mul(&mul(&ys, &ys), &binomial(&xs, 1.7)),
        &binomial(&ys, -1.0),
    );
    let error = relative_difference(&b.taylor(root), &expected);
    assert!(error < 1e-14, "y² x^c / y: {error:e}");
    let root = b.pool.pow(x, y);
    let expected = exp(&mul(&ys, &ln(&xs)));
    let error = relative_difference(&b.taylor(root), &expected);
    assert!(error < 1e-14, "x^y: {error:e}");
}

#[test]
fn order_zero_is_the_value_tape_and_constants_have_no_higher_coefficients() {
    let mut b = Bench::new(0.4, 0.7);
    let (x, y, c) = (b.pool.sym(b.x), b.pool.sym(b.y), b.pool.sym(b.c));
    let sin_c = b.pool.call(Func::Sin, &[c]);
    let three = b.pool.int(3);
    let cube = b.pool.pow(x, three);
    let quotient = b.pool.call(Func::Atan2, &[y, cube]);
    let root = b.pool.add(&[sin_c, quotient]);
    let taylor = b.taylor(root);
    let mut env = vec![f64::NAN; b.pool.symbols().len()];
    env[b.x.index()] = 0.4;
    env[b.y.index()] = 0.7;
    env[b.c.index()] = 1.7;
    let mut value = [0.0];
    b.pool.compile(&[root]).eval(&env, &mut value);
    assert_eq!(taylor[0].to_bits(), value[0].to_bits());
    let constant_only = b.taylor(sin_c);
    assert_eq!(constant_only[0], 1.7f64.sin());
    assert!(constant_only[1..].iter().all(|x| *x == 0.0));
}

/// Two stages over one set of slots: the second reads what the first computed (sin x and
/// cos x, 1/y) instead of recomputing it, and gives the coefficients its own tape gives,
/// bit for bit. A substituted input (y := c, a constant) turns its products into scalings:
/// the coefficients are those of the expression with c written in y's place.
#[test]
fn stages_share_their_slots_and_substitutions_make_constants() {
    let mut b = Bench::new(0.4, 0.7);
    let (x, y) = (b.pool.sym(b.x), b.pool.sym(b.y));
    let sin = b.pool.call(Func::Sin, &[x]);
    let minus_one = b.pool.int(-1);
    let inverse = b.pool.pow(y, minus_one);
    let first = b.pool.mul(&[sin, inverse]);
    let cos = b.pool.call(Func::Cos, &[x]);
    let second = b.pool.mul(&[cos, inverse]);
    let inputs = [b.x, b.y];
    let stages: [&[Id]; 2] = [&[first], &[second]];
    let tapes = b.pool.compile_taylor_stages(&stages, &inputs, &[]);
    let alone = b.pool.compile_taylor(&[second], &inputs);
    // Alone: the pair and the quotient cos x / y (its reciprocal 1/y pruned, Op::Div);
    // after the first stage, the quotient.
    assert_eq!(alone.series_instructions().len(), 2);
    assert_eq!(tapes[1].series_instructions().len(), 1);
    let mut jet = TaylorJet::new();
    let env = vec![f64::NAN; b.pool.symbols().len()];
    tapes[0].begin(&mut jet, ORDER, &env);
    tapes[1].begin_more(&mut jet, &env);
    let mut staged = Vec::new();
    for k in 0..=ORDER {
        for tape in &tapes {
            tape.set_input(&mut jet, 0, k, b.xs[k]);
            tape.set_input(&mut jet, 1, k, b.ys[k]);
            tape.advance(&mut jet, k);
        }
        staged.push(tapes[1].output(&jet, 0, k));
    }
    let own = b.taylor(second);
    assert!(staged
        .iter()
        .zip(&own)
        .all(|(a, b)| a.to_bits() == b.to_bits()));

    let c = b.pool.sym(b.c);
    let substituted = b
        .pool
        .compile_taylor_substituting(&[second], &inputs, &[(b.y, c)]);
    // The reciprocal of the constant is computed once (fixed); the product is a scaling.
    assert_eq!(substituted.series_instructions().len(), 2);
    let c_inverse = b.pool.pow(c, minus_one);
    let written = b.pool.mul(&[cos, c_inverse]);
    let expected = b.run(&b.pool.compile_taylor(&[written], &inputs));
    assert_eq!(b.run(&substituted), expected);
    assert!(!substituted.output_is_constant(0));
}

/// Products whose series factors are the same but whose constants differ share their
/// Cauchy products: 2·x·y·sin x + c·x·y·sin x + x·y·sin x is two products (x y, then times
/// sin x), three scalings and a sum, not six products (the 3-link pendulum's ṗ holds such
/// terms). The coefficients are the sum's, term by term.
#[test]
fn products_of_the_same_series_factors_are_made_once() {
    let mut b = Bench::new(0.4, 0.7);
    let (x, y, c) = (b.pool.sym(b.x), b.pool.sym(b.y), b.pool.sym(b.c));
    let sin = b.pool.call(Func::Sin, &[x]);
    let two = b.pool.int(2);
    let terms = [
        b.pool.mul(&[two, x, y, sin]),
        b.pool.mul(&[c, x, y, sin]),
        b.pool.mul(&[x, y, sin]),
    ];
    let root = b.pool.add(&terms);
    let tape = b.pool.compile_taylor(&[root], &[b.x, b.y]);
    let products = tape
        .series_instructions()
        .iter()
        .filter(|i| matches!(i.op, super::Op::Mul(..)))
        .count();
    assert_eq!(products, 2);
    // The sin/cos pair, two products, two scalings (the term without a constant is the
    // product itself) and the sum.
    assert_eq!(tape.series_instructions().len(), 6);
    let product = mul(&mul(&b.xs, &b.ys), &reference(Func::Sin, &[b.xs.clone()]));
    let expected: Series = product.iter().map(|p| (2.0 + 1.7 + 1.0) * p).collect();
    let error = relative_difference(&b.taylor(root), &expected);
    // Measured 0 to a few ulps.
    assert!(error < 1e-14, "shared products: {error:e}");
}
