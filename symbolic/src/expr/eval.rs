//! Numeric evaluation of an expression at one point (for checks and tests; generated code
//! and [`Tape`](super::Tape) are the fast paths).

use super::func::Func;
use super::node::{Id, Node};
use super::pool::ExprPool;
use super::rational::Rational;
use std::collections::HashMap;

/// `b^e`, by `powi` for integer exponents (it keeps `(-2)^3 = -8` and is more accurate).
/// Evaluation and [`Tape`](super::Tape) make the same choices (`sqrt` for `^(1/2)`,
/// `powi` for integers), so they agree bit for bit.
pub(crate) fn power(b: f64, e: f64) -> f64 {
    if e.fract() == 0.0 && e.abs() <= f64::from(i32::MAX) {
        b.powi(e as i32)
    } else {
        b.powf(e)
    }
}

impl ExprPool {
    /// The value of `e` with symbol `s` worth `env[s.index()]`; NaN where a value is
    /// missing (an index past the end of `env`). Defined symbols evaluate their value.
    pub fn eval(&self, e: Id, env: &[f64]) -> f64 {
        let mut values: HashMap<Id, f64> = HashMap::new();
        for id in self.reachable(&[e], true) {
            let v = |c: &Id| values.get(c).copied().unwrap_or(f64::NAN);
            let value = match self.node(id) {
                Node::Num(r) => r.to_f64(),
                Node::Float(bits) => f64::from_bits(*bits),
                Node::Sym(s) => match self.definition(*s) {
                    Some(value) => v(&value),
                    None => env.get(s.index()).copied().unwrap_or(f64::NAN),
                },
                Node::Add(terms) => terms.iter().map(v).sum(),
                Node::Mul(factors) => factors.iter().map(v).product(),
                Node::Pow(b, x) if self.as_rational(*x) == Some(Rational::HALF) => v(b).sqrt(),
                Node::Pow(b, x) => power(v(b), v(x)),
                Node::Call(f, args) => apply(*f, args.iter().map(v)),
            };
            values.insert(id, value);
        }
        values.get(&e).copied().unwrap_or(f64::NAN)
    }
}

/// Applies `f` to up to two argument values without allocating.
pub(crate) fn apply(f: Func, mut args: impl Iterator<Item = f64>) -> f64 {
    match (args.next(), args.next(), args.next()) {
        (Some(a), None, _) => f.apply(&[a]),
        (Some(a), Some(b), None) => f.apply(&[a, b]),
        _ => f64::NAN,
    }
}
