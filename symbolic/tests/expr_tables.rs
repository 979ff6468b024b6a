//! Table calls in the expression engine (docs/tables.md#a-table-call-in-the-expression-engine):
//! the chain rule through the interpolant's own derivative, evaluation under the table's
//! `Outside` rule on a tape, extrapolation for the checks, and printing.
//!
//! The data, by hand: knots 0, 1, 2, 4 with values 0, 2, 3, 1. Linear: on [1, 2] the chord
//! F(x) = 2 + (x − 1), slope 1; on [2, 4] F(x) = 3 − (x − 2), slope (1 − 3)/2 = −1;
//! extrapolating the last piece, F(6) = 3 − 4 = −1.

use varmass_symbolic::expr::{ExprPool, Func, Node, SymbolKind};
use varmass_table::{Interpolation, Outside, Points, Table};

fn table(interpolation: Interpolation, outside: Outside) -> Table {
    let points = Points::new(vec![0.0, 1.0, 2.0, 4.0], vec![0.0, 2.0, 3.0, 1.0]).unwrap();
    Table::new(&points, interpolation, outside)
}

#[test]
fn the_derivative_of_a_call_is_the_derivative_table_times_the_arguments() {
    let mut pool = ExprPool::new();
    let x = pool.symbols_mut().add_coordinate("x");
    let t = pool.symbols_mut().add("t", SymbolKind::Time);
    let f = pool
        .add_table("F", table(Interpolation::Linear, Outside::Error))
        .unwrap();
    let (xs, ts, two) = (pool.sym(x), pool.sym(t), pool.int(2));
    let two_t = pool.mul(&[two, ts]);
    let argument = pool.add(&[two_t, xs]);
    let call = pool.table_call(f, 0, argument);

    // ∂F(2t + x)/∂x = F'(2t + x), ∂/∂t = 2 F'(2t + x): structurally.
    let slope = pool.table_call(f, 1, argument);
    assert_eq!(pool.diff(call, x), slope);
    let twice = pool.mul(&[two, slope]);
    assert_eq!(pool.diff(call, t), twice);
    assert!(matches!(
        pool.node(slope),
        Node::Call(Func::Table { order: 1, .. }, _)
    ));

    // At t = 0.25, x = 1 the argument is 1.5: F = 2.5, F' = 1 (the chord on [1, 2]).
    let mut env = vec![0.0; pool.symbols().len()];
    env[x.index()] = 1.0;
    env[t.index()] = 0.25;
    assert_eq!(pool.eval(call, &env), 2.5);
    let dx = pool.diff(call, x);
    assert_eq!(pool.eval(dx, &env), 1.0);
    // On [2, 4] (argument 3) the slope is −1, so ∂/∂t = −2, exactly.
    env[x.index()] = 2.5;
    let dt = pool.diff(call, t);
    assert_eq!(pool.eval(dt, &env), -2.0);
}

#[test]
fn second_derivatives_are_the_second_derivative_table() {
    // d²/dx² F(3x) = 9 F''(3x); the natural spline has F'' = 0 at both ends.
    let mut pool = ExprPool::new();
    let x = pool.symbols_mut().add_coordinate("x");
    let f = pool
        .add_table("F", table(Interpolation::Spline, Outside::Error))
        .unwrap();
    let (xs, three) = (pool.sym(x), pool.int(3));
    let argument = pool.mul(&[three, xs]);
    let call = pool.table_call(f, 0, argument);
    let first = pool.diff(call, x);
    let second = pool.diff(first, x);
    let curvature = pool.table_call(f, 2, argument);
    let nine = pool.int(9);
    assert_eq!(second, pool.mul(&[nine, curvature]));

    let mut env = vec![0.0; pool.symbols().len()];
    for at in [0.0, 4.0 / 3.0] {
        env[x.index()] = at;
        assert!(pool.eval(second, &env).abs() < 1e-12, "at x = {at}");
    }
    // Inside, F'' against a central difference of the engine's own F' (cubic pieces: the
    // difference is exact up to rounding; measured 3e-10 at h = 1e-5, bound 1e-8).
    let h = 1e-5;
    env[x.index()] = 0.5;
    let at = pool.eval(second, &env);
    env[x.index()] = 0.5 + h;
    let right = pool.eval(first, &env);
    env[x.index()] = 0.5 - h;
    let left = pool.eval(first, &env);
    let difference = (right - left) / (2.0 * h);
    assert!(
        (at - difference).abs() < 1e-8,
        "F'' {at} against {difference}"
    );
}

#[test]
fn a_tape_applies_the_outside_rule_and_names_the_table() {
    let mut pool = ExprPool::new();
    let x = pool.symbols_mut().add_coordinate("x");
    let f = pool
        .add_table("F", table(Interpolation::Linear, Outside::Error))
        .unwrap();
    let g = pool
        .add_table("G", table(Interpolation::Linear, Outside::Zero))
        .unwrap();
    let xs = pool.sym(x);
    let (fx, gx) = (pool.table_call(f, 0, xs), pool.table_call(g, 0, xs));
    let slope = pool.diff(fx, x);
    let tape = pool.compile(&[fx, gx, slope]);
    let mut env = vec![0.0; pool.symbols().len()];
    let mut out = [0.0; 3];

    env[x.index()] = 1.5;
    tape.eval(&env, &mut out);
    assert_eq!(out, [2.5, 2.5, 1.0]);
    assert_eq!(tape.outside(), None);

    // Past the data: F (outside error) fails, naming itself and the argument; G is zero.
    env[x.index()] = 6.0;
    tape.eval(&env, &mut out);
    assert!(out[0].is_nan() && out[2].is_nan());
    assert_eq!(out[1], 0.0);
    assert_eq!(tape.outside(), Some(("F", 6.0)));

    // A derivative's failure names the derivative.
    let only_slope = pool.compile(&[slope]);
    let mut one = [0.0];
    only_slope.eval(&env, &mut one);
    assert_eq!(only_slope.outside(), Some(("F'", 6.0)));

    // The checks' evaluation extrapolates the end piece instead: F(6) = 3 − 4 = −1.
    assert_eq!(pool.eval(fx, &env), -1.0);
}

#[test]
fn calls_print_with_the_tables_name_and_primes() {
    let mut pool = ExprPool::new();
    let x = pool.symbols_mut().add_coordinate("x");
    let f = pool
        .add_table("rho", table(Interpolation::Pchip, Outside::Hold))
        .unwrap();
    let xs = pool.sym(x);
    let call = pool.table_call(f, 0, xs);
    let slope = pool.diff(call, x);
    let curvature = pool.diff(slope, x);
    assert_eq!(pool.display(call).to_string(), "rho(x)");
    assert_eq!(pool.display(slope).to_string(), "rho'(x)");
    assert_eq!(pool.display(curvature).to_string(), "rho''(x)");
    // Equal calls are one node; different orders are not.
    assert_eq!(pool.table_call(f, 0, xs), call);
    assert_ne!(slope, call);
}

/// The Taylor series of F(t²) (docs/tables.md#taylor-series) against the chain rule through
/// the derivative tables, by hand (Faà di Bruno with only a′ = 2t and a″ = 2 nonzero, and
/// F⁗ = 0 inside a cubic piece: the terms n!/(m₁! m₂! 2^m₂) F^(m₁+m₂) a′^m₁ a″^m₂ with
/// m₁ + 2m₂ = n):
///   w₁ = F′ a′,  w₂ = (F″ a′² + F′ a″)/2,  w₃ = (F‴ a′³ + 3 F″ a′ a″)/6,
///   w₄ = (6 F‴ a′² a″ + 3 F″ a″²)/24,  w₅ = 15 F‴ a′ a″²/120,  w₆ = 15 F‴ a″³/720,
/// every derivative at a(t₀). The argument t² is not affine, so this is a true composition
/// (F(t²) is a polynomial of degree 6 in t on the piece: w₇ = 0).
#[test]
fn the_taylor_series_of_a_table_call_is_the_chain_rule_through_its_derivative_tables() {
    use varmass_symbolic::expr::TaylorJet;
    for interpolation in [
        Interpolation::Linear,
        Interpolation::Pchip,
        Interpolation::Spline,
    ] {
        let mut pool = ExprPool::new();
        let t = pool.symbols_mut().add("t", SymbolKind::Time);
        let f = pool
            .add_table("F", table(interpolation, Outside::Error))
            .unwrap();
        let ts = pool.sym(t);
        let square = pool.mul(&[ts, ts]);
        let call = pool.table_call(f, 0, square);
        // The derivative tables, built in the pool up to order 3.
        pool.table_call(f, 3, square);
        let tape = pool.compile_taylor(&[call], &[t]);
        let env = vec![0.0; pool.symbols().len()];
        for t0 in [0.3, 1.3, 1.9] {
            let mut jet = TaylorJet::new();
            tape.begin(&mut jet, 7, &env);
            for k in 0..=7 {
                let tk = match k {
                    0 => t0,
                    1 => 1.0,
                    _ => 0.0,
                };
                tape.set_input(&mut jet, 0, k, tk);
                tape.advance(&mut jet, k);
            }
            let a = t0 * t0;
            let d = |order: u8| pool.table(f, order).unwrap().value(a).unwrap();
            let (a1, a2) = (2.0 * t0, 2.0);
            let expected = [
                d(0),
                d(1) * a1,
                (d(2) * a1 * a1 + d(1) * a2) / 2.0,
                (d(3) * a1.powi(3) + 3.0 * d(2) * a1 * a2) / 6.0,
                (6.0 * d(3) * a1 * a1 * a2 + 3.0 * d(2) * a2 * a2) / 24.0,
                15.0 * d(3) * a1 * a2 * a2 / 120.0,
                15.0 * d(3) * a2.powi(3) / 720.0,
                0.0,
            ];
            for (k, want) in expected.iter().enumerate() {
                let got = tape.output(&jet, 0, k);
                // Measured ≤ 4.4e-16 relative to max(|w_k|, 1); bound 1e-14.
                let error = (got - want).abs() / want.abs().max(1.0);
                assert!(
                    error <= 1e-14,
                    "{interpolation:?} t0 {t0} k {k}: {got} vs {want}"
                );
            }
        }
    }
}

/// Outside the data under `outside error` the series is NaN (a typed non-finite error in a
/// Taylor run), under `outside zero` zero at every order.
#[test]
fn the_taylor_series_outside_the_data_follows_the_rule() {
    use varmass_symbolic::expr::TaylorJet;
    for (outside, nan) in [(Outside::Error, true), (Outside::Zero, false)] {
        let mut pool = ExprPool::new();
        let t = pool.symbols_mut().add("t", SymbolKind::Time);
        let f = pool
            .add_table("F", table(Interpolation::Spline, outside))
            .unwrap();
        let ts = pool.sym(t);
        let call = pool.table_call(f, 0, ts);
        let tape = pool.compile_taylor(&[call], &[t]);
        let mut jet = TaylorJet::new();
        tape.begin(&mut jet, 3, &[0.0]);
        for (k, tk) in [5.0, 1.0, 0.0, 0.0].into_iter().enumerate() {
            tape.set_input(&mut jet, 0, k, tk);
            tape.advance(&mut jet, k);
            let w = tape.output(&jet, 0, k);
            assert_eq!(w.is_nan(), nan, "{outside:?} k {k}: {w}");
            if !nan {
                assert_eq!(w, 0.0);
            }
        }
    }
}
