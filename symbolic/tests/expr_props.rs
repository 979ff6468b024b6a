//! Property tests on random expression trees: canonical construction preserves value,
//! derivatives match finite differences, the tape matches the interpreter, printing reads
//! back, and operand order does not matter.

mod expr_support;

use expr_support::read;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use varmass_symbolic::expr::{lower, ExprPool, Func, Id, Rational, SymbolKind, TableResolver};

/// A random expression over three symbols, built only from operations that are finite
/// everywhere (denominators are 1 + b², roots are of 1 + a²), so no point is singular.
#[derive(Clone, Debug)]
enum Tree {
    Var(usize),
    Num(i64, i64),
    Add(Box<Tree>, Box<Tree>),
    Sub(Box<Tree>, Box<Tree>),
    Mul(Box<Tree>, Box<Tree>),
    /// a / (1 + b²)
    SafeDiv(Box<Tree>, Box<Tree>),
    /// a / symbol (symbols are drawn away from 0)
    DivVar(Box<Tree>, usize),
    Neg(Box<Tree>),
    Pow(Box<Tree>, i32),
    /// sqrt(1 + a²)
    Hypot(Box<Tree>),
    /// sin, cos, atan, tanh, exp∘sin
    Func(usize, Box<Tree>),
}

fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (0..3usize).prop_map(Tree::Var),
        (-3i64..=3, 1i64..=3).prop_map(|(n, d)| Tree::Num(n, d)),
    ];
    leaf.prop_recursive(5, 40, 2, |inner| {
        let b = |t: Tree| Box::new(t);
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Add(b(x), b(y))),
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Sub(b(x), b(y))),
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::Mul(b(x), b(y))),
            (inner.clone(), inner.clone()).prop_map(move |(x, y)| Tree::SafeDiv(b(x), b(y))),
            (inner.clone(), 0..3usize).prop_map(move |(x, i)| Tree::DivVar(b(x), i)),
            inner.clone().prop_map(move |x| Tree::Neg(b(x))),
            (inner.clone(), 2i32..=3).prop_map(move |(x, k)| Tree::Pow(b(x), k)),
            inner.clone().prop_map(move |x| Tree::Hypot(b(x))),
            (0..5usize, inner).prop_map(move |(f, x)| Tree::Func(f, b(x))),
        ]
    })
}

/// Naive evaluation, independent of the engine: the value and a magnitude M that bounds
/// how rounding errors grow (sums add magnitudes instead of cancelling; each function
/// contributes its Lipschitz bound). Evaluation error is then ≲ (operations × ε) × M.
fn naive(t: &Tree, env: &[f64]) -> (f64, f64) {
    match t {
        Tree::Var(i) => (env[*i], env[*i].abs()),
        Tree::Num(n, d) => {
            let v = *n as f64 / *d as f64;
            (v, v.abs())
        }
        Tree::Add(a, b) | Tree::Sub(a, b) => {
            let ((va, ma), (vb, mb)) = (naive(a, env), naive(b, env));
            let v = if matches!(t, Tree::Add(..)) {
                va + vb
            } else {
                va - vb
            };
            (v, ma + mb)
        }
        Tree::Mul(a, b) => {
            let ((va, ma), (vb, mb)) = (naive(a, env), naive(b, env));
            (va * vb, ma * mb)
        }
        // |∂/∂a| ≤ 1 and |∂/∂b| ≤ |a|.
        Tree::SafeDiv(a, b) => {
            let ((va, ma), (vb, mb)) = (naive(a, env), naive(b, env));
            (va / (1.0 + vb * vb), ma * (1.0 + mb))
        }
        // |∂/∂a| = 1/|s| and |∂/∂s| = |a|/s², with s ≥ 0.5.
        Tree::DivVar(a, i) => {
            let (va, ma) = naive(a, env);
            (va / env[*i], ma * (2.0 + 4.0 * env[*i].abs()))
        }
        Tree::Neg(a) => {
            let (va, ma) = naive(a, env);
            (-va, ma)
        }
        Tree::Pow(a, k) => {
            let (va, ma) = naive(a, env);
            (va.powi(*k), f64::from(*k) * ma.powi(*k))
        }
        Tree::Hypot(a) => {
            let (va, ma) = naive(a, env);
            ((1.0 + va * va).sqrt(), 1.0 + ma * ma)
        }
        Tree::Func(f, a) => {
            let (va, ma) = naive(a, env);
            let v = match f {
                0 => va.sin(),
                1 => va.cos(),
                2 => va.atan(),
                3 => va.tanh(),
                _ => va.sin().exp(),
            };
            // Lipschitz constant 1, or e for exp∘sin.
            (v, std::f64::consts::E * (1.0 + ma))
        }
    }
}

fn build(p: &mut ExprPool, t: &Tree, mirrored: bool) -> Id {
    let pair = |p: &mut ExprPool, a: &Tree, b: &Tree| {
        let (x, y) = (build(p, a, mirrored), build(p, b, mirrored));
        if mirrored {
            (y, x)
        } else {
            (x, y)
        }
    };
    match t {
        Tree::Var(i) => {
            let s = p.symbols().iter().nth(*i).unwrap();
            p.sym(s)
        }
        Tree::Num(n, d) => p.rational(Rational::new(i128::from(*n), i128::from(*d)).unwrap()),
        Tree::Add(a, b) => {
            let (x, y) = pair(p, a, b);
            p.add(&[x, y])
        }
        Tree::Sub(a, b) => {
            let (x, y) = (build(p, a, mirrored), build(p, b, mirrored));
            p.sub(x, y)
        }
        Tree::Mul(a, b) => {
            let (x, y) = pair(p, a, b);
            p.mul(&[x, y])
        }
        Tree::SafeDiv(a, b) => {
            let (x, y) = (build(p, a, mirrored), build(p, b, mirrored));
            let (one, two) = (p.int(1), p.int(2));
            let y2 = p.pow(y, two);
            let den = if mirrored {
                p.add(&[y2, one])
            } else {
                p.add(&[one, y2])
            };
            p.div(x, den)
        }
        Tree::DivVar(a, i) => {
            let x = build(p, a, mirrored);
            let s = p.symbols().iter().nth(*i).unwrap();
            let s = p.sym(s);
            p.div(x, s)
        }
        Tree::Neg(a) => {
            let x = build(p, a, mirrored);
            p.neg(x)
        }
        Tree::Pow(a, k) => {
            let x = build(p, a, mirrored);
            let k = p.int(i64::from(*k));
            p.pow(x, k)
        }
        Tree::Hypot(a) => {
            let x = build(p, a, mirrored);
            let (one, two) = (p.int(1), p.int(2));
            let x2 = p.pow(x, two);
            let s = p.add(&[one, x2]);
            p.sqrt(s)
        }
        Tree::Func(f, a) => {
            let x = build(p, a, mirrored);
            match f {
                0 => p.call(Func::Sin, &[x]),
                1 => p.call(Func::Cos, &[x]),
                2 => p.call(Func::Atan, &[x]),
                3 => p.call(Func::Tanh, &[x]),
                _ => {
                    let s = p.call(Func::Sin, &[x]);
                    p.call(Func::Exp, &[s])
                }
            }
        }
    }
}

fn pool() -> ExprPool {
    let mut p = ExprPool::new();
    for n in ["x", "y", "z"] {
        p.symbols_mut().add(n, SymbolKind::Parameter);
    }
    p
}

fn config() -> Config {
    Config {
        cases: 256,
        rng_seed: RngSeed::Fixed(0x0076_6172_6d61_7373),
        failure_persistence: None,
        ..Config::default()
    }
}

/// Five-point central difference of the naive tree along symbol 0.
fn five_point(t: &Tree, env: &[f64], h: f64) -> f64 {
    let at = |dx: f64| {
        let mut e = env.to_vec();
        e[0] += dx;
        naive(t, &e).0
    };
    (at(-2.0 * h) - 8.0 * at(-h) + 8.0 * at(h) - at(2.0 * h)) / (12.0 * h)
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn canonical_construction_preserves_value(
        t in tree(),
        env in proptest::collection::vec(0.5f64..1.2, 3),
    ) {
        let mut p = pool();
        let e = build(&mut p, &t, false);
        let (want, magnitude) = naive(&t, &env);
        let got = p.eval(e, &env);
        // ≤ ~100 roundings of ε ≈ 1.1e-16 each, scaled by M (≈ 1e-14 · M): 1e-12 leaves 100×.
        prop_assert!(
            (got - want).abs() <= 1e-12 * (1.0 + magnitude),
            "{t:?}: engine {got} vs naive {want} (M = {magnitude})"
        );
    }

    #[test]
    fn derivatives_match_finite_differences(
        t in tree(),
        env in proptest::collection::vec(0.5f64..1.2, 3),
    ) {
        let mut p = pool();
        let e = build(&mut p, &t, false);
        let x = p.symbols().lookup("x").unwrap();
        let d = p.diff(e, x);
        let exact = p.eval(d, &env);
        let (_, magnitude) = naive(&t, &env);
        // The five-point stencil errs by ~h⁴ f⁽⁵⁾/30 (truncation) plus ~ε M/h (rounding).
        // Its truncation error is estimated from two step sizes (it shrinks 16× when h
        // halves), so the bound adapts to how wild f is: 2 × the estimate, plus rounding
        // at h/2 = 5e-4, ε M/h ≈ 2e-13 M, taken as 1e-8 (1 + M).
        let (coarse, fine) = (five_point(&t, &env, 1e-3), five_point(&t, &env, 5e-4));
        let tolerance = 2.0 * (coarse - fine).abs() + 1e-8 * (1.0 + magnitude);
        prop_assert!(
            (exact - fine).abs() <= tolerance,
            "{t:?}: ∂/∂x = {exact}, finite differences {fine} (± {tolerance})"
        );
    }

    #[test]
    fn the_tape_agrees_with_the_interpreter_bit_for_bit(
        t in tree(),
        env in proptest::collection::vec(0.5f64..1.2, 3),
    ) {
        let mut p = pool();
        let e = build(&mut p, &t, false);
        let x = p.symbols().lookup("x").unwrap();
        let d = p.diff(e, x);
        let tape = p.compile(&[e, d]);
        let mut out = [0.0; 2];
        tape.eval(&env, &mut out);
        // Same operations in the same order (sum/product by iterator, powi, sqrt).
        prop_assert_eq!(out[0].to_bits(), p.eval(e, &env).to_bits());
        prop_assert_eq!(out[1].to_bits(), p.eval(d, &env).to_bits());
    }

    #[test]
    fn display_reads_back_to_the_same_expression(t in tree()) {
        let mut p = pool();
        let e = build(&mut p, &t, false);
        let x = p.symbols().lookup("x").unwrap();
        let d = p.diff(e, x);
        for root in [e, d] {
            let text = p.display(root).to_string();
            let ast = read(&text).map_err(TestCaseError::fail)?;
            let back = lower(&mut p, &ast, &mut TableResolver)
                .map_err(|errs| TestCaseError::fail(format!("{errs:?}")))?;
            prop_assert_eq!(back, root, "printed as `{}`", text);
            // And through the real nom grammar, as the DSL reads it.
            let ast = varmass_symbolic::parse::parse_expression(&text)
                .map_err(|e| TestCaseError::fail(e.render(&text)))?;
            let back = lower(&mut p, &ast, &mut TableResolver)
                .map_err(|errs| TestCaseError::fail(format!("{errs:?}")))?;
            prop_assert_eq!(back, root, "printed as `{}`, read by the DSL parser", text);
        }
    }

    #[test]
    fn operand_order_does_not_matter(t in tree()) {
        let mut p = pool();
        let e = build(&mut p, &t, false);
        let mirrored = build(&mut p, &t, true);
        prop_assert_eq!(e, mirrored);
    }
}
