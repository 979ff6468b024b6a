//! An independent reference for Taylor coefficients: truncated power series with plain
//! polynomial arithmetic, each elementary function composed from its known power series in
//! the increment d = u − u₀ (exp, ln, the binomial series, sin/cos and sinh/cosh by the
//! addition theorems) or integrated from its derivative (tan, tanh as quotients; atan,
//! asin, acos, atan2 through their derivatives), and an expression evaluator walking the
//! pool's nodes. It shares no code with the recurrences of `varmass_symbolic::expr::taylor`.

use std::collections::HashMap;

use varmass::symbolic::expr::{ExprPool, Func, Id, Node, Symbol};

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

fn exp(a: &[f64]) -> Series {
    scale(&compose(&increment(a), |n| 1.0 / factorial(n)), a[0].exp())
}

fn ln(a: &[f64]) -> Series {
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

/// The series of `roots`, with the symbols of `inputs` given as series and every other
/// symbol a constant `env[index]` (defined symbols through their values).
pub fn evaluate(
    pool: &ExprPool,
    roots: &[Id],
    inputs: &HashMap<Symbol, Series>,
    env: &[f64],
) -> Vec<Series> {
    let mut memo: HashMap<Id, Series> = HashMap::new();
    // Children before parents: ids ascend topologically, so evaluate the reachable ids in
    // ascending order.
    let mut reachable = Vec::new();
    let mut stack: Vec<Id> = roots.to_vec();
    let mut seen = std::collections::HashSet::new();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        reachable.push(id);
        stack.extend(pool.node(id).children());
        if let Node::Sym(s) = pool.node(id) {
            stack.extend(pool.definition(*s));
        }
    }
    reachable.sort_by_key(|id| id.index());
    for id in reachable {
        let value = node(pool, id, &memo, inputs, env);
        memo.insert(id, value);
    }
    roots.iter().map(|r| memo[r].clone()).collect()
}

fn node(
    pool: &ExprPool,
    id: Id,
    memo: &HashMap<Id, Series>,
    inputs: &HashMap<Symbol, Series>,
    env: &[f64],
) -> Series {
    let of = |c: &Id| memo[c].clone();
    match pool.node(id) {
        Node::Num(r) => constant(r.to_f64()),
        Node::Float(bits) => constant(f64::from_bits(*bits)),
        Node::Sym(s) => match (pool.definition(*s), inputs.get(s)) {
            (Some(value), _) => memo
                .get(&value)
                .cloned()
                .unwrap_or_else(|| constant(f64::NAN)),
            (None, Some(series)) => series.clone(),
            (None, None) => constant(env[s.index()]),
        },
        Node::Add(terms) => terms
            .iter()
            .fold(constant(0.0), |total, t| add(&total, &of(t))),
        Node::Mul(factors) => factors
            .iter()
            .fold(constant(1.0), |total, f| mul(&total, &of(f))),
        Node::Pow(b, e) => {
            let (b, e) = (of(b), of(e));
            if e[1..].iter().any(|x| *x != 0.0) {
                exp_of_product(&e, &b)
            } else if e[0].fract() == 0.0 && e[0] > 0.0 {
                (0..e[0] as usize).fold(constant(1.0), |total, _| mul(&total, &b))
            } else {
                power(&b, e[0])
            }
        }
        Node::Call(f, args) => {
            let args: Vec<Series> = args.iter().map(of).collect();
            call(*f, &args)
        }
    }
}

fn exp_of_product(e: &[f64], b: &[f64]) -> Series {
    exp(&mul(e, &ln(b)))
}

/// Solves M v = r for series by Gaussian elimination without pivoting (M symmetric positive
/// definite at order 0), with series quotients.
#[allow(clippy::needless_range_loop)] // row i is written while row j is read
pub fn solve(mut m: Vec<Vec<Series>>, mut r: Vec<Series>) -> Vec<Series> {
    let n = r.len();
    for j in 0..n {
        for i in j + 1..n {
            let factor = divide(&m[i][j], &m[j][j]);
            for k in j..n {
                let product = mul(&factor, &m[j][k]);
                m[i][k] = add(&m[i][k], &scale(&product, -1.0));
            }
            let product = mul(&factor, &r[j]);
            r[i] = add(&r[i], &scale(&product, -1.0));
        }
    }
    let mut v = vec![constant(0.0); n];
    for i in (0..n).rev() {
        let mut rest = r[i].clone();
        for k in i + 1..n {
            rest = add(&rest, &scale(&mul(&m[i][k], &v[k]), -1.0));
        }
        v[i] = divide(&rest, &m[i][i]);
    }
    v
}
