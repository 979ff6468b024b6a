//! The trigonometric reduction: each identity applies, nothing else changes, and the value
//! is preserved.

mod expr_support;

use expr_support::build;
use varmass_symbolic::expr::{ExprPool, Identity, SymbolKind};

fn pool() -> ExprPool {
    let mut pool = ExprPool::new();
    for name in ["a", "b"] {
        pool.symbols_mut().add_coordinate(name);
    }
    for name in ["k", "l1", "l2", "m"] {
        pool.symbols_mut().add(name, SymbolKind::Parameter);
    }
    pool
}

/// `input` reduces to exactly `expected` (same canonical node), and the two agree in value.
#[track_caller]
fn reduces(input: &str, expected: &str) {
    let mut p = pool();
    let e = build(&mut p, input);
    let want = build(&mut p, expected);
    let got = p.reduce_trig(e);
    assert_eq!(
        got,
        want,
        "{input} reduced to {}, expected {}",
        p.display(got),
        p.display(want)
    );
    assert!(matches!(
        p.identical(e, got),
        Identity::Proven | Identity::Numerical { .. }
    ));
}

#[test]
fn pythagoras() {
    reduces("k*sin(a)^2 + k*cos(a)^2", "k");
    reduces(
        "m*l1^2*a'^2*sin(a)^2 + m*l1^2*a'^2*cos(a)^2 + b",
        "m*l1^2*a'^2 + b",
    );
}

#[test]
fn angle_differences_and_sums() {
    reduces("k*cos(a)*cos(b) + k*sin(a)*sin(b)", "k*cos(a - b)");
    reduces("k*cos(a)*cos(b) - k*sin(a)*sin(b)", "k*cos(a + b)");
    reduces("k*sin(a)*cos(b) - k*cos(a)*sin(b)", "k*sin(a - b)");
    reduces("k*sin(a)*cos(b) + k*cos(a)*sin(b)", "k*sin(a + b)");
}

#[test]
fn the_double_pendulum_kinetic_energy_takes_its_textbook_form() {
    // ½ m2 |d/dt (l1 sin a + l2 sin b, −l1 cos a − l2 cos b)|²
    reduces(
        "m/2*((l1*a'*cos(a) + l2*b'*cos(b))^2 + (l1*a'*sin(a) + l2*b'*sin(b))^2)",
        "m*l1^2*a'^2/2 + m*l2^2*b'^2/2 + m*l1*l2*a'*b'*cos(a - b)",
    );
}

#[test]
fn unequal_coefficients_and_other_terms_are_left_alone() {
    reduces("k*sin(a)^2 + m*cos(a)^2", "k*sin(a)^2 + m*cos(a)^2");
    reduces(
        "k*cos(a)*cos(b) + m*sin(a)*sin(b)",
        "k*cos(a)*cos(b) + m*sin(a)*sin(b)",
    );
    reduces("sin(a)^2 + cos(b)^2", "sin(a)^2 + cos(b)^2");
    reduces("k*a + l1", "k*a + l1");
}

#[test]
fn arguments_of_two_symbols_expand_back_for_evaluation() {
    let mut p = pool();
    for (input, expected) in [
        ("k*cos(a - b)", "k*(cos(a)*cos(b) + sin(a)*sin(b))"),
        ("sin(a - b)", "sin(a)*cos(b) - cos(a)*sin(b)"),
        (
            "sin(a + b)^2 + cos(a)",
            "(sin(a)*cos(b) + cos(a)*sin(b))^2 + cos(a)",
        ),
        ("cos(a + 2*b)", "cos(a + 2*b)"),
    ] {
        let e = build(&mut p, input);
        let want = build(&mut p, expected);
        let got = p.expand_trig_arguments(e);
        assert_eq!(got, want, "{input} gave {}", p.display(got));
        assert!(matches!(
            p.identical(e, got),
            Identity::Proven | Identity::Numerical { .. }
        ));
    }
}
