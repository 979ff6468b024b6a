//! Canonical function calls: exact values at the few points where they are rational
//! (`sin(0)`, `cos(0)`, `ln(1)`, `abs`, `sign`, `min`, `max` of rationals), inexact
//! arguments folded, and symmetry pulling a negative coefficient out of the argument of an
//! odd (`sin(-x)` → `-sin(x)`, `sin(y - x)` → `-sin(x - y)`) or even (`cos(-x)` →
//! `cos(x)`) function.

use super::func::Func;
use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use super::rational::Rational;

/// The exact value of `f` at rational arguments, where it is rational.
fn fold_exact(f: Func, args: &[Rational]) -> Option<Rational> {
    match (f, args) {
        (Func::Abs, [u]) => u.checked_abs(),
        (Func::Sign, [u]) => Some(Rational::integer(u.numer().signum())),
        (Func::Min, [a, b]) => Some(*a.min(b)),
        (Func::Max, [a, b]) => Some(*a.max(b)),
        (Func::Sin | Func::Tan | Func::Sinh | Func::Tanh | Func::Asin | Func::Atan, [u])
            if u.is_zero() =>
        {
            Some(Rational::ZERO)
        }
        (Func::Cos | Func::Cosh | Func::Exp, [u]) if u.is_zero() => Some(Rational::ONE),
        (Func::Ln | Func::Acos, [u]) if u.is_one() => Some(Rational::ZERO),
        _ => None,
    }
}

impl ExprPool {
    /// The canonical call `f(args)`. The caller guarantees `args.len() == f.arity()`
    /// (lowering checks it); a wrong count is stored as given and evaluates to NaN.
    pub fn call(&mut self, f: Func, args: &[Id]) -> Id {
        if let Func::Input { .. } = f {
            // The user's function: nothing is known of it here.
            return self.intern(Node::Call(f, args.into()));
        }
        let numbers: Option<Vec<Number>> = args.iter().map(|a| self.node(*a).number()).collect();
        if let Some(numbers) = numbers.filter(|n| n.len() == f.arity()) {
            let exact: Option<Vec<Rational>> = numbers
                .iter()
                .map(|n| match n {
                    Number::Exact(r) => Some(*r),
                    Number::Inexact(_) => None,
                })
                .collect();
            match exact {
                Some(exact) => {
                    if let Some(r) = fold_exact(f, &exact) {
                        return self.rational(r);
                    }
                }
                None => {
                    let values: Vec<f64> = numbers.iter().map(|n| n.to_f64()).collect();
                    let x = f.apply(&values);
                    if x.is_finite() {
                        return self.float(x);
                    }
                }
            }
        }
        if let [u] = args {
            if (f.is_odd() || f.is_even()) && self.argument_is_negative(*u) {
                let positive = self.neg(*u);
                let value = self.call(f, &[positive]);
                return if f.is_odd() { self.neg(value) } else { value };
            }
            if f == Func::Abs {
                if let Node::Call(Func::Abs, _) = self.node(*u) {
                    return *u;
                }
            }
        }
        self.intern(Node::Call(f, args.into()))
    }

    /// Whether `f(u)` should be written `±f(−u)`: `u` is a negative constant, a product
    /// with a negative coefficient, or a sum whose leading (first non-constant) term is
    /// such a product. Exactly one of `u` and `−u` qualifies, so `cos(x − y)` and
    /// `cos(y − x)` become one node.
    fn argument_is_negative(&self, u: Id) -> bool {
        match self.node(u) {
            Node::Add(terms) => terms
                .iter()
                .find(|t| self.node(**t).number().is_none())
                .is_some_and(|t| self.has_negative_coefficient(*t)),
            _ => self.has_negative_coefficient(u),
        }
    }

    /// Whether `u` is a negative constant or a product with a negative coefficient.
    pub(crate) fn has_negative_coefficient(&self, u: Id) -> bool {
        match self.node(u) {
            Node::Num(_) | Node::Float(_) => self.node(u).number().is_some_and(Number::is_negative),
            Node::Mul(factors) => factors
                .first()
                .and_then(|c| self.node(*c).number())
                .is_some_and(Number::is_negative),
            _ => false,
        }
    }
}
