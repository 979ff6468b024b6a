//! The evaluator (a compiled tape) against formulas written by hand, and
//! common-subexpression elimination.

mod expr_support;

use expr_support::{build, sled_pool};
use varmass_symbolic::expr::{ExprPool, Id};

fn env(p: &ExprPool, k: usize) -> Vec<f64> {
    (0..p.symbols().len())
        .map(|i| 0.3 + 1.4 * (((i + 1) * (k + 3) * 7919) % 1000) as f64 / 1000.0)
        .collect()
}

/// The value of each sample expression written out by hand in `f64` arithmetic, from the
/// value of a symbol by name: an independent reference for the evaluator.
fn by_hand(v: &dyn Fn(&str) -> f64) -> [f64; 6] {
    let (x, xd, px, t) = (v("x"), v("x'"), v("p_x"), v("t"));
    let (g, theta, c, m0, m) = (v("g"), v("theta"), v("c"), v("m0"), v("m"));
    let sign = |u: f64| if u == 0.0 { 0.0 } else { u.signum() };
    [
        0.5 * m * xd * xd + m * g * x * theta.sin(),
        px * px / (2.0 * m) - m * g * x * theta.sin(),
        x.sqrt() / (m0 + c * x).powi(2) + x.powf(1.5) - 2f64.powf(x),
        x.atan2(-g) + x.min(g) * c.max(m0) + (x - g).abs() * sign(g - x),
        (-x * t).exp() * x.cosh()
            + (m0 / m).ln() * t.tanh()
            + (x / 2.0).asin()
            + (g / 2.0).acos()
            + x.atan(),
        (x + g).powi(-3) + theta.tan(),
    ]
}

#[test]
fn evaluation_matches_the_formulas_written_by_hand() {
    let mut p = sled_pool();
    let texts = [
        "1/2*m*x'^2 + m*g*x*sin(theta)",
        "p_x^2/(2*m) - m*g*x*sin(theta)",
        "sqrt(x)/(m0 + c*x)^2 + x^(3/2) - 2^x",
        "atan2(x, -g) + min(x, g)*max(c, m0) + abs(x - g)*sign(g - x)",
        "exp(-x*t)*cosh(x) + ln(m0/m)*tanh(t) + asin(x/2) + acos(g/2) + atan(x)",
        "(x + g)^-3 + tan(theta)",
    ];
    let roots: Vec<Id> = texts.iter().map(|t| build(&mut p, t)).collect();
    // A definition is compiled through its value.
    let w = p.define("w", roots[0]);
    let ws = p.sym(w);
    let mut all = roots.clone();
    all.push(ws);
    let tape = p.compile(&all);
    assert_eq!(tape.outputs(), all.len());
    let mut out = vec![0.0; all.len()];
    for k in 0..10 {
        let e = env(&p, k);
        let value = |name: &str| {
            let s = p.symbols().lookup(name).expect("a sled symbol");
            e[s.index()]
        };
        let want = by_hand(&value);
        tape.eval(&e, &mut out);
        for ((r, got), want) in all.iter().zip(&out).zip(want.iter().chain([&want[0]])) {
            let error = (got - want).abs() / want.abs().max(1.0);
            // Measured: at most 2.0e-16 (a rounding or two in another order); bound 4 ulps
            // of the scale, 8.9e-16.
            assert!(
                error <= 4.0 * f64::EPSILON,
                "{}: {got} vs {want}",
                p.display(*r)
            );
            // One evaluator: a value at a point is the tape's value, bit for bit, whether
            // the tape holds one root or several.
            assert_eq!(got.to_bits(), p.eval(*r, &e).to_bits());
        }
    }
    // A missing value is NaN, not a panic.
    tape.eval(&[], &mut out);
    assert!(out.iter().all(|v| v.is_nan()));
    assert!(p.eval(roots[0], &[]).is_nan());
    let mut scratch = Vec::new();
    let e = env(&p, 0);
    tape.eval_with(&e, &mut scratch, &mut out);
    assert_eq!(out[6], p.eval(roots[0], &e));
}

/// Whether `part` occurs in `whole` (test-side walk, independent of the engine).
fn inside(p: &ExprPool, whole: Id, part: Id) -> bool {
    whole == part || p.node(whole).children().any(|c| inside(p, c, part))
}

#[test]
fn cse_finds_the_shared_subexpressions() {
    let mut p = sled_pool();
    // sin(theta) is a factor in both roots and x*sin(theta) is the argument of two calls;
    // p_x^2 occurs once. (Products are flat, so m*g*x*sin(theta) holds no x*sin(theta).)
    let h = build(&mut p, "p_x^2/(2*m) - m*g*x*sin(theta)");
    let q = build(&mut p, "cos(x*sin(theta)) + exp(x*sin(theta))");
    let cse = p.cse(&[h, q]);
    let shared: Vec<String> = cse
        .shared
        .iter()
        .map(|e| p.display(*e).to_string())
        .collect();
    assert!(shared.contains(&"sin(theta)".to_owned()), "{shared:?}");
    assert!(shared.contains(&"x*sin(theta)".to_owned()), "{shared:?}");
    assert!(!shared.iter().any(|s| s.contains("p_x")), "{shared:?}");
    // Dependency order: every shared node after the shared nodes inside it.
    for (i, a) in cse.shared.iter().enumerate() {
        for b in &cse.shared[i + 1..] {
            assert!(!inside(&p, *a, *b), "{} before a part of it", p.display(*a));
        }
    }
    assert!(cse.is_shared(cse.shared[0]));
    assert!(!cse.is_shared(h));
    // Nothing is shared in a tree without repetition.
    let lone = build(&mut p, "x + g*c");
    assert!(p.cse(&[lone]).shared.is_empty());
}
