//! Common factors pulled out of sums ([`ExprPool::factor_out`]): the greedy choice on small
//! sums written out by hand, the value unchanged, and fewer operations.

mod expr_support;

use expr_support::build;
use varmass_symbolic::expr::{ExprPool, Identity, SymbolKind};

fn pool() -> ExprPool {
    let mut pool = ExprPool::new();
    for name in ["a", "b"] {
        pool.symbols_mut().add_coordinate(name);
    }
    for name in ["k", "w", "x", "y", "z", "m"] {
        pool.symbols_mut().add(name, SymbolKind::Parameter);
    }
    pool
}

/// `input` factors to exactly `expected` (same canonical node), the two are identical in
/// value, and the factored form takes fewer operations (`saving` fewer).
#[track_caller]
fn factors(input: &str, expected: &str, saving: usize) {
    let mut p = pool();
    let e = build(&mut p, input);
    let want = build(&mut p, expected);
    let got = p.factor_out(e);
    assert_eq!(
        got,
        want,
        "{input} factored to {}, expected {}",
        p.display(got),
        p.display(want)
    );
    assert!(matches!(
        p.identical(e, got),
        Identity::Proven | Identity::Numerical { .. }
    ));
    assert_eq!(
        p.operation_count(&[e]) - p.operation_count(&[got]),
        saving,
        "{input}"
    );
}

#[test]
fn the_most_shared_factor_goes_first_then_inside_and_among_the_rest() {
    // k is in all three terms, x in two of what k multiplies: k (x (y + z) + w).
    // 2 + 2 + 1 multiplications and 2 additions (7) become 2 and 2 (4).
    factors("k*x*y + k*x*z + k*w", "k*(x*(y + z) + w)", 3);
    // Terms without the factor stay beside it: x (y + z) + w m (5 → 4 operations).
    factors("x*y + x*z + w*m", "x*(y + z) + w*m", 1);
}

#[test]
fn powers_give_their_base_once_per_round_and_coefficients_stay_in_the_terms() {
    // x² y + x z: x comes out once, leaving x y + z (4 → 3 operations, x² counted once).
    factors("x^2*y + x*z", "x*(x*y + z)", 1);
    // −2 k x + 3 k y: the coefficients stay with their terms, k (−2 x + 3 y).
    factors("-2*k*x + 3*k*y", "k*(-2*x + 3*y)", 1);
    // Functions and reciprocals are factors as a whole: sin(a) (k + m/x).
    factors("k*sin(a) + m*sin(a)/x", "sin(a)*(k + m/x)", 1);
}

#[test]
fn sums_without_a_shared_factor_are_left_as_they_are() {
    for input in ["x*y + z*w", "k + x", "x", "2*x*y + 3"] {
        let mut p = pool();
        let e = build(&mut p, input);
        assert_eq!(p.factor_out(e), e, "{input}");
    }
}
