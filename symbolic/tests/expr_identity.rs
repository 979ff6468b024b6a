//! Identities: proven by canonical form or expansion, else decided numerically.

mod expr_support;

use expr_support::{build, sled_pool};
use std::collections::HashMap;
use varmass_symbolic::expr::{ExprPool, Identity, SymbolKind};

fn verdict(p: &mut ExprPool, a: &str, b: &str) -> Identity {
    let (ia, ib) = (build(p, a), build(p, b));
    p.identical(ia, ib)
}

#[test]
fn proven_by_canonical_form_or_expansion() {
    let mut p = sled_pool();
    for (a, b) in [
        ("m*x'", "x'*m"),
        ("x*(g + 1)", "x*g + x"),
        ("(x + g)^2", "x^2 + 2*x*g + g^2"),
        ("(x + g)*(x - g)", "x^2 - g^2"),
        ("(m0 + c*x)^3/(m0 + c*x)", "(m0 + c*x)^2"),
        ("sin((x + 1)*(x - 1))", "sin(x^2 - 1)"),
        ("1/(x + g)^2", "1/(x^2 + 2*x*g + g^2)"),
    ] {
        assert_eq!(verdict(&mut p, a, b), Identity::Proven, "{a} = {b}");
    }
}

#[test]
fn the_sled_identity_is_proven() {
    // The frozen-mass rule (docs/mechanics.md#the-frozen-mass-rule): substituting m = m0 + c x before differentiating adds c(½ẋ² + g x sin θ).
    let mut p = sled_pool();
    let l = build(&mut p, "1/2*m*x'^2 + m*g*x*sin(theta)");
    let (x, m) = (
        p.symbols().lookup("x").unwrap(),
        p.symbols().lookup("m").unwrap(),
    );
    let law = build(&mut p, "m0 + c*x");
    let ordinary = {
        let lq = p.substitute(l, &HashMap::from([(m, law)]));
        p.diff(lq, x)
    };
    let frozen_term = build(&mut p, "(m0 + c*x)*g*sin(theta)");
    let lhs = p.sub(ordinary, frozen_term);
    let rhs = build(&mut p, "c*(1/2*x'^2 + g*x*sin(theta))");
    assert_eq!(p.identical(lhs, rhs), Identity::Proven);
    // The frozen derivative alone misses the term.
    let frozen = p.diff(l, x);
    let frozen = p.substitute(frozen, &HashMap::from([(m, law)]));
    assert!(matches!(
        p.identical(ordinary, frozen),
        Identity::Refuted { .. }
    ));
}

#[test]
fn trigonometric_identities_are_numerical() {
    let mut p = sled_pool();
    for (a, b) in [
        ("sin(x)^2 + cos(x)^2", "1"),
        ("sin(2*x)", "2*sin(x)*cos(x)"),
        ("exp(x + g)", "exp(x)*exp(g)"),
        ("ln(x*g)", "ln(x) + ln(g)"),
        ("cosh(x)^2 - sinh(x)^2", "1"),
        ("atan2(g, x)", "atan(g/x)"),
        // Points are drawn from [0.3, 1.7] (masses, lengths, angles of a slope), where
        // |x| = x: sampling cannot see the difference, symbolic rules must not claim it.
        ("(x^2)^(1/2)", "x"),
    ] {
        match verdict(&mut p, a, b) {
            Identity::Numerical { points } => assert_eq!(points, 32, "{a} = {b}"),
            other => panic!("{a} = {b}: {other:?}"),
        }
    }
}

#[test]
fn cancellation_does_not_fool_the_tolerance() {
    // Both sides are ~1e8 in every term but differ in the result by far less than that:
    // agreement is judged against the size of the terms, not of the (cancelled) result.
    let mut p = sled_pool();
    let v = verdict(
        &mut p,
        "100000000*sin(x) - 100000000*sin(x)*cos(g)^2",
        "100000000*sin(x)*sin(g)^2",
    );
    assert!(matches!(v, Identity::Numerical { .. }), "{v:?}");
    // A genuine difference of one part in a thousand is caught.
    let v = verdict(&mut p, "sin(x)^2 + cos(x)^2", "1001/1000");
    assert!(matches!(v, Identity::Refuted { .. }), "{v:?}");
}

#[test]
fn refutation_names_the_point() {
    let mut p = sled_pool();
    let Identity::Refuted { env, lhs, rhs } = verdict(&mut p, "x + g", "x*g") else {
        panic!("x + g = x g refuted");
    };
    let t = p.symbols();
    let names: Vec<&str> = env.iter().map(|(s, _)| t.name(*s)).collect();
    assert_eq!(names, ["x", "g"]);
    let (xv, gv) = (env[0].1, env[1].1);
    assert!((0.3..=1.7).contains(&xv) && (0.3..=1.7).contains(&gv));
    assert_eq!(lhs, xv + gv);
    assert_eq!(rhs, xv * gv);
}

#[test]
fn nowhere_defined_is_undecided() {
    let mut p = sled_pool();
    // sqrt of a negative number is NaN at every point.
    assert_eq!(
        verdict(&mut p, "sqrt(-1 - x^2)", "sqrt(-2 - x^2)"),
        Identity::Undecided
    );
}

#[test]
fn definitions_are_inlined_before_deciding() {
    let mut p = sled_pool();
    let value = build(&mut p, "m*x'");
    let p_def = p.define("momentum", value);
    let momentum = p.sym(p_def);
    let v2 = build(&mut p, "x'*m");
    assert_eq!(p.identical(momentum, v2), Identity::Proven);
}

#[test]
fn expansion_past_its_size_limit_keeps_every_factor() {
    // (a+b+c+d)^32 exceeds the 5000-term limit of `expand` on the way; the factors not yet
    // distributed must stay, or S^32 and S^25 would both become S^19 and compare equal.
    let mut p = ExprPool::new();
    let s: Vec<_> = ["a", "b", "c", "d"]
        .iter()
        .map(|n| {
            let sym = p.symbols_mut().add(n, SymbolKind::Parameter);
            p.sym(sym)
        })
        .collect();
    let sum = p.add(&s);
    let (e32, e25) = (p.int(32), p.int(25));
    let (high, low) = (p.pow(sum, e32), p.pow(sum, e25));
    assert!(
        !matches!(
            p.identical(high, low),
            Identity::Proven | Identity::Numerical { .. }
        ),
        "S^32 and S^25 must differ"
    );
    // And expansion preserves value.
    let expanded = p.expand(high);
    let env = vec![0.4; p.symbols().len()];
    let (a, b) = (p.eval(high, &env), p.eval(expanded, &env));
    assert!((a - b).abs() <= 1e-12 * a.abs(), "{a} vs {b}");
}
