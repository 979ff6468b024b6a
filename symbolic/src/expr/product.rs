//! Canonical products and powers: factors flattened, equal bases collected by adding
//! exponents (`x*x` → `x^2`, `x^2*x^-1` → `x`), the numeric coefficient folded exactly,
//! factors in structural order.
//!
//! Only rules that hold wherever both sides are defined:
//!
//! | rule                        | when                                   |
//! |-----------------------------|----------------------------------------|
//! | `u^0 → 1`, `u^1 → u`        | always                                 |
//! | `(u^a)^n → u^(a·n)`         | `n` an integer                         |
//! | `(a·b)^n → a^n · b^n`       | `n` an integer                         |
//! | `r^n` folded                | `r` rational, `n` integer, fits `i128` |
//! | `r^(p/q)` folded            | `r` a perfect `q`-th power             |
//! | `c·(a + b) → c·a + c·b`     | `c` a number, the sum the only factor  |
//!
//! `(x^2)^(1/2)` is *not* `x` (it is `|x|`), so it stays as written.

use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use super::rational::Rational;

/// Folds `b^e` for constants when the result is exact (or either side is inexact and the
/// result is finite); `None` leaves the power unfolded.
fn fold_power(b: Number, e: Number) -> Option<Number> {
    match (b, e) {
        (Number::Exact(b), Number::Exact(e)) => {
            if let Some(n) = e.as_integer() {
                return b.checked_pow(n).map(Number::Exact);
            }
            let q = u32::try_from(e.denom()).ok()?;
            b.exact_root(q)?.checked_pow(e.numer()).map(Number::Exact)
        }
        _ => {
            let x = b.to_f64().powf(e.to_f64());
            x.is_finite().then_some(Number::Inexact(x))
        }
    }
}

/// The base a factor is collected under: `b` for `b^e`, the factor itself otherwise.
fn collected_base(pool: &ExprPool, factor: Id) -> Id {
    match pool.node(factor) {
        Node::Pow(b, _) => *b,
        _ => factor,
    }
}

impl ExprPool {
    /// The canonical product of `factors` (1 for none).
    pub fn mul(&mut self, factors: &[Id]) -> Id {
        let (mut coefficient, mut powers) = self.gather_factors(factors);
        if coefficient.is_zero() {
            return self.number(Number::ZERO);
        }
        let (mut out, mut again) = self.collect_bases(&mut powers, &mut coefficient);
        if coefficient.is_zero() {
            return self.number(Number::ZERO);
        }
        if !again.is_empty() {
            let c = self.number(coefficient);
            again.push(c);
            again.extend(out);
            return self.mul(&again);
        }
        out.sort_by(|a, b| self.structural_cmp(*a, *b));
        // A number times a sum distributes (as in SymPy): `x - (x + y)` must cancel to `y`,
        // and it costs no growth, unlike expanding a product of sums.
        if let [single] = out.as_slice() {
            if let (Node::Add(terms), false) = (self.node(*single), coefficient.is_one()) {
                let terms = terms.clone();
                let c = self.number(coefficient);
                let scaled: Vec<Id> = terms.iter().map(|t| self.mul(&[c, *t])).collect();
                return self.add(&scaled);
            }
        }
        if !coefficient.is_one() {
            let c = self.number(coefficient);
            out.insert(0, c);
        }
        match out.as_slice() {
            [] => self.number(Number::ONE),
            [single] => *single,
            _ => self.intern(Node::Mul(out.into_boxed_slice())),
        }
    }

    /// The numeric coefficient of `factors` (nested products flattened) and the
    /// (base, exponent, factor) of every other factor, in the order met.
    fn gather_factors(&mut self, factors: &[Id]) -> (Number, Vec<(Id, Id, Id)>) {
        let mut coefficient = Number::ONE;
        let mut powers: Vec<(Id, Id, Id)> = Vec::with_capacity(factors.len());
        let one = self.int(1);
        let mut work: Vec<Id> = factors.to_vec();
        while let Some(f) = work.pop() {
            match self.node(f) {
                Node::Num(_) | Node::Float(_) => {
                    if let Some(n) = self.node(f).number() {
                        coefficient = coefficient.mul(n);
                    }
                }
                Node::Mul(inner) => work.extend_from_slice(inner),
                Node::Pow(b, e) => powers.push((*b, *e, f)),
                _ => powers.push((f, one, f)),
            }
        }
        (coefficient, powers)
    }

    /// Equal bases collected by adding their exponents: the resulting factors, and those
    /// to collect once more (see below); constants go into `coefficient`.
    fn collect_bases(
        &mut self,
        powers: &mut [(Id, Id, Id)],
        coefficient: &mut Number,
    ) -> (Vec<Id>, Vec<Id>) {
        // Bases in structural order so that the result does not depend on the order of the
        // factors; the sort is stable, so each base's exponents stay in the order met. (A
        // sorted list instead of a map from base to exponents: no hashing, one allocation.)
        powers.sort_by(|(a, ..), (b, ..)| self.structural_cmp(*a, *b));
        let mut out: Vec<Id> = Vec::with_capacity(powers.len() + 1);
        let mut again: Vec<Id> = Vec::new();
        for group in powers.chunk_by(|(a, ..), (b, ..)| a == b) {
            let [(base, _, factor), rest @ ..] = group else {
                continue;
            };
            let base = *base;
            if rest.is_empty() {
                // A base met once keeps its factor: that factor is `base` (exponent 1) or a
                // `Pow` node, which only `pow(base, exponent)` creates, so calling it again
                // would return the factor, after an interning lookup.
                out.push(*factor);
                continue;
            }
            let exponents: Vec<Id> = group.iter().map(|(_, e, _)| *e).collect();
            let e = self.add(&exponents);
            let p = self.pow(base, e);
            match self.node(p) {
                Node::Num(_) | Node::Float(_) => {
                    if let Some(n) = self.node(p).number() {
                        *coefficient = coefficient.mul(n);
                    }
                }
                // Collected exponents made an integer power of a product, which distributes
                // over factors that may meet others here: collect once more.
                Node::Mul(_) => again.push(p),
                // The power simplified to another base (`sqrt(x^2)^2` is `x^2`) that is also
                // a base here: collect once more, or the product would hold `x` twice. Each
                // such round merges two factors, so this ends.
                _ if collected_base(self, p) != base
                    && powers.iter().any(|(b, ..)| *b == collected_base(self, p)) =>
                {
                    again.push(p)
                }
                _ => out.push(p),
            }
        }
        (out, again)
    }

    /// `a / b`, that is `a * b^-1`.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let minus_one = self.int(-1);
        let inverse = self.pow(b, minus_one);
        self.mul(&[a, inverse])
    }

    /// `sqrt(a)`, that is `a^(1/2)`.
    pub fn sqrt(&mut self, a: Id) -> Id {
        let half = self.rational(Rational::HALF);
        self.pow(a, half)
    }

    /// The canonical power `base ^ exp`.
    pub fn pow(&mut self, base: Id, exp: Id) -> Id {
        let e = self.node(exp).number();
        if let Some(e) = e {
            if e.is_zero() {
                return self.number(Number::ONE);
            }
            if e.is_one() {
                return base;
            }
        }
        if let Some(b) = self.node(base).number() {
            if b.is_one() {
                return self.number(Number::ONE);
            }
            if let Some(folded) = e.and_then(|e| fold_power(b, e)) {
                return self.number(folded);
            }
        }
        let integer_exponent = self.as_rational(exp).and_then(|r| r.as_integer()).is_some();
        if integer_exponent {
            // Copy out only what these two cases need: cloning the node would copy the
            // terms of every sum raised to a power.
            match self.node(base) {
                &Node::Pow(b, inner) => {
                    let product = self.mul(&[inner, exp]);
                    return self.pow(b, product);
                }
                Node::Mul(factors) => {
                    let factors = factors.clone();
                    let powers: Vec<Id> = factors.iter().map(|f| self.pow(*f, exp)).collect();
                    return self.mul(&powers);
                }
                _ => {}
            }
        }
        self.intern(Node::Pow(base, exp))
    }
}
