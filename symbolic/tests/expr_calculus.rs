//! The frozen-mass calculus, substitution, definitions, degree — against closed forms and
//! finite differences.

mod expr_support;

use expr_support::{build, sled_pool};
use std::collections::HashMap;
use varmass_symbolic::expr::{ExprPool, Symbol, SymbolKind};

fn sym(pool: &ExprPool, name: &str) -> Symbol {
    pool.symbols().lookup(name).unwrap()
}

/// An environment for the sled pool: every symbol gets a distinct value in [0.3, 1.7].
fn sled_env(pool: &ExprPool) -> Vec<f64> {
    (0..pool.symbols().len())
        .map(|i| 0.3 + 1.4 * ((i * 7 + 3) % 11) as f64 / 11.0)
        .collect()
}

#[test]
fn the_sled_under_the_frozen_mass_rule() {
    // Paper §4, eq. 20: L = ½ m ẋ² + m g x sin θ with m frozen.
    let mut p = sled_pool();
    let l = build(&mut p, "1/2*m*x'^2 + m*g*x*sin(theta)");
    let (x, v) = (sym(&p, "x"), sym(&p, "x'"));
    let dl_dx = p.diff(l, x);
    let dl_dv = p.diff(l, v);
    assert_eq!(dl_dx, build(&mut p, "m*g*sin(theta)"));
    assert_eq!(dl_dv, build(&mut p, "m*x'"), "p = m ẋ (eq. 8)");
    // d*/dt ∂*L/∂ẋ = m ẍ: the mass is frozen even though m = m0 + c x.
    let dp_dt = p.time_derivative(dl_dv).unwrap();
    assert_eq!(dp_dt, build(&mut p, "m*x''"));

    // Substituting the mass law first gives the ordinary derivative, which differs from
    // the frozen one by exactly c(½ẋ² + g x sin θ).
    let m = sym(&p, "m");
    let law = build(&mut p, "m0 + c*x");
    let lq = p.substitute(l, &HashMap::from([(m, law)]));
    let ordinary = p.diff(lq, x);
    let frozen = p.substitute(dl_dx, &HashMap::from([(m, law)]));
    let gap = p.sub(ordinary, frozen);
    assert_eq!(gap, build(&mut p, "1/2*c*x'^2 + c*g*x*sin(theta)"));
    // The factored form agrees numerically (it is not expanded by construction).
    let factored = build(&mut p, "c*(1/2*x'^2 + g*x*sin(theta))");
    let env = sled_env(&p);
    let (a, b) = (p.eval(gap, &env), p.eval(factored, &env));
    assert!((a - b).abs() <= 1e-14 * a.abs().max(1.0), "{a} vs {b}");
}

#[test]
fn time_derivative_follows_the_coordinates() {
    let mut p = sled_pool();
    let cases = [
        ("x", "x'"),
        ("x'", "x''"),
        ("t", "1"),
        ("m*g + theta", "0"),
        ("sin(x)", "cos(x)*x'"),
        ("x'^2*t", "2*x'*x''*t + x'^2"),
        ("m*x'*t^2", "m*x''*t^2 + 2*m*x'*t"),
    ];
    for (e, want) in cases {
        let id = build(&mut p, e);
        let d = p.time_derivative(id).unwrap();
        assert_eq!(d, build(&mut p, want), "d/dt {e}");
    }
}

#[test]
fn time_derivative_refuses_accelerations_and_momenta() {
    let mut p = sled_pool();
    for (text, name) in [("x''*m", "x''"), ("p_x^2/m", "p_x")] {
        let e = build(&mut p, text);
        let err = p.time_derivative(e).unwrap_err();
        assert_eq!(err.name, name);
        assert_eq!(err.symbol, sym(&p, name));
        assert!(err.to_string().contains(name));
    }
    // ∂ is total even there.
    let e = build(&mut p, "x''*m");
    let d = p.diff(e, sym(&p, "x''"));
    assert_eq!(d, build(&mut p, "m"));
}

#[test]
fn diff_with_respect_to_a_frozen_mass_is_one_on_itself() {
    // The true momentum rate (docs/mechanics.md#true-momentum-rate) needs ∂*p/∂m: it is ẋ for p = m ẋ.
    let mut p = sled_pool();
    let e = build(&mut p, "m*x'");
    let d = p.diff(e, sym(&p, "m"));
    assert_eq!(d, build(&mut p, "x'"));
}

/// Central difference of `e` along symbol `s` at `env`.
fn central_difference(p: &ExprPool, e: varmass_symbolic::expr::Id, s: Symbol, env: &[f64]) -> f64 {
    // h = 1e-5: truncation ~ h² f'''/6 ≈ 1e-11 and rounding ~ 1e-16/h ≈ 1e-11 for O(1)
    // values, so 1e-7 relative is a comfortable bound.
    let h = 1e-5;
    let mut up = env.to_vec();
    let mut down = env.to_vec();
    up[s.index()] += h;
    down[s.index()] -= h;
    (p.eval(e, &up) - p.eval(e, &down)) / (2.0 * h)
}

#[test]
fn every_function_differentiates_like_finite_differences() {
    let mut p = ExprPool::new();
    for n in ["x", "y"] {
        p.symbols_mut().add(n, SymbolKind::Parameter);
    }
    let (x, y) = (sym(&p, "x"), sym(&p, "y"));
    let cases = [
        "sin(x*y)",
        "cos(x^2)",
        "tan(x/2)",
        "exp(-x*y)",
        "ln(x + y)",
        "abs(x - 2*y)",
        "sign(x - y)*x",
        "tanh(x*y)",
        "sinh(x - y)",
        "cosh(2*x)",
        "asin(x/3)",
        "acos(y/2 - x/4)",
        "atan(x*y)",
        "atan2(y, x)",
        "atan2(x - 2, y)",
        "min(x, 2*y)",
        "max(x^2, y)",
        "x^y",
        "(x + y)^(3/2)",
        "2^(x*y)",
        "sqrt(x^2 + y^2)",
        "x^-3*y",
    ];
    // Points away from the kinks of abs/sign/min/max and the singularities of ln, asin.
    let env = [0.7, 1.3];
    for text in cases {
        let e = build(&mut p, text);
        for s in [x, y] {
            let d = p.diff(e, s);
            let exact = p.eval(d, &env);
            let approx = central_difference(&p, e, s, &env);
            assert!(
                (exact - approx).abs() <= 1e-7 * exact.abs().max(1.0),
                "∂({text})/∂{}: {exact} vs finite difference {approx}",
                p.symbols().name(s)
            );
        }
    }
}

#[test]
fn substitution_is_simultaneous_and_canonical() {
    let mut p = ExprPool::new();
    for n in ["x", "y"] {
        p.symbols_mut().add(n, SymbolKind::Parameter);
    }
    let (x, y) = (sym(&p, "x"), sym(&p, "y"));
    let e = build(&mut p, "x - 2*y");
    let (xs, ys) = (p.sym(x), p.sym(y));
    let swapped = p.substitute(e, &HashMap::from([(x, ys), (y, xs)]));
    assert_eq!(swapped, build(&mut p, "y - 2*x"));
    let e = build(&mut p, "x^2 + x*y");
    let zero = p.int(0);
    let at_zero = p.substitute(e, &HashMap::from([(x, zero)]));
    assert!(p.is_zero(at_zero));
    let e = build(&mut p, "sin(x)^2");
    let minus_y = build(&mut p, "-y");
    let odd = p.substitute(e, &HashMap::from([(x, minus_y)]));
    assert_eq!(odd, build(&mut p, "sin(y)^2"));
}

#[test]
fn definitions_are_looked_through() {
    let mut p = sled_pool();
    let value = build(&mut p, "x^2*g");
    let w = p.define("w", value);
    assert_eq!(p.definition(w), Some(value));
    assert_eq!(p.symbols().kind(w), SymbolKind::Definition);
    let e = build(&mut p, "w*x'");
    let x = sym(&p, "x");
    assert_eq!(p.diff(e, x), build(&mut p, "2*x*g*x'"));
    assert_eq!(
        p.time_derivative(e).unwrap(),
        build(&mut p, "2*x*g*x'^2 + w*x''")
    );
    assert_eq!(p.inline_definitions(e), build(&mut p, "x^2*g*x'"));
    let env = sled_env(&p);
    let xv = env[x.index()];
    let want = xv * xv * env[sym(&p, "g").index()] * env[sym(&p, "x'").index()];
    assert!((p.eval(e, &env) - want).abs() < 1e-14);
    // With respect to itself, a defined symbol is a variable like any other.
    assert_eq!(p.diff(e, w), build(&mut p, "x'"));
    // Contains and degree see through it; a redefinition does not rebind.
    assert!(p.contains(e, x));
    assert!(p.free_symbols(e).contains(&w));
    let other = p.int(3);
    assert_eq!(p.try_define("w", other), Err(w));
    assert_eq!(p.definition(w), Some(value));
    // Substituting into the definition's value inlines it.
    let g = sym(&p, "g");
    let two = p.int(2);
    let s = p.substitute(e, &HashMap::from([(g, two)]));
    assert_eq!(s, build(&mut p, "2*x^2*x'"));
    let unaffected = p.substitute(e, &HashMap::from([(sym(&p, "theta"), two)]));
    assert_eq!(unaffected, e);
}

#[test]
fn degree_in_the_velocities() {
    let mut p = sled_pool();
    let v = [sym(&p, "x'")];
    let cases: [(&str, Option<u32>); 9] = [
        ("1/2*m*x'^2 + m*g*x*sin(theta)", Some(2)),
        ("x'/m + sin(x)", Some(1)),
        ("m*g", Some(0)),
        ("(x' + 1)^3*x'", Some(4)),
        ("sin(x')", None),
        ("1/x'", None),
        ("x'^(1/2)", None),
        ("exp(x)*x'^2/(m0 + c*x)", Some(2)),
        ("x'^x", None),
    ];
    for (text, want) in cases {
        let e = build(&mut p, text);
        assert_eq!(p.degree(e, &v), want, "degree of {text}");
    }
}

#[test]
fn terms_contains_and_free_symbols() {
    let mut p = sled_pool();
    let e = build(&mut p, "1/2*m*x'^2 + m*g*x*sin(theta) + 3");
    assert_eq!(p.terms(e).len(), 3);
    let single = build(&mut p, "m*x'");
    assert_eq!(p.terms(single), vec![single]);
    assert!(p.contains(e, sym(&p, "theta")));
    assert!(!p.contains(e, sym(&p, "c")));
    let names: Vec<&str> = p
        .free_symbols(e)
        .into_iter()
        .map(|s| p.symbols().name(s))
        .collect();
    assert_eq!(names, ["x", "x'", "g", "theta", "m"], "in table order");
}

/// The symbol filter behind `contains`, `free_symbols` and the derivatives maps symbol i to
/// bit i % 64: past 64 symbols, symbols 64 apart share a bit, and the answers must not
/// change. Here `a64` shares `a0`'s bit and `b` is a defined symbol whose value uses `a1`.
#[test]
fn symbol_queries_are_exact_past_64_symbols() {
    let mut p = ExprPool::new();
    let a: Vec<Symbol> = (0..70)
        .map(|i| p.symbols_mut().add(&format!("a{i}"), SymbolKind::Parameter))
        .collect();
    let value = build(&mut p, "2*a1");
    let b = p.define("b", value);
    let e = build(&mut p, "a0*sin(b) + a65");
    let names: Vec<&str> = p
        .free_symbols(e)
        .into_iter()
        .map(|s| p.symbols().name(s))
        .collect();
    assert_eq!(names, ["a0", "a1", "a65", "b"]);
    assert!(p.contains(e, b));
    assert!(p.contains(e, a[1]), "through the definition of b");
    assert!(
        !p.contains(e, a[64]),
        "a64 shares a0's bit but does not occur"
    );
    assert!(!p.contains(e, a[2]));
    // ∂/∂a64 visits the subtrees that hold a0 (same bit) and still finds 0.
    let d = p.diff(e, a[64]);
    assert!(p.is_zero(d));
    let d = p.diff(e, a[1]);
    let expected = build(&mut p, "2*a0*cos(b)");
    assert_eq!(d, expected);
}

#[test]
fn deep_expressions_do_not_overflow_the_stack() {
    // sin(sin(…sin(x)…)) 3000 deep: every pass is iterative, none recurses. (The derivative
    // is a product of 3000 cosines, so building it is quadratic: keep the depth moderate.)
    let mut p = ExprPool::new();
    let x = p.symbols_mut().add("x", SymbolKind::Parameter);
    let mut e = p.sym(x);
    for _ in 0..3000 {
        e = p.call(varmass_symbolic::expr::Func::Sin, &[e]);
    }
    let d = p.diff(e, x);
    // The iterated sine shrinks slowly (~sqrt(3/n)), so every cosine is near 1 and the
    // product is tiny but positive; check it against the chain rule evaluated directly.
    let mut value = 0.5f64;
    let mut rate = 1.0f64;
    for _ in 0..3000 {
        rate *= value.cos();
        value = value.sin();
    }
    let got = p.eval(d, &[0.5]);
    // 3000 products and cosines in a different order, each within an ulp: ≲ 7e-13.
    assert!((got - rate).abs() <= 1e-11 * rate, "{got} vs {rate}");
    assert!((p.eval(e, &[0.5]) - value).abs() <= 1e-14);
    let z = p.int(0);
    let s = p.substitute(e, &HashMap::from([(x, z)]));
    assert!(p.is_zero(s), "sin(0) folds all the way up");
}
