//! Canonical sums: flattened, like terms collected (`2*x + 3*x` → `5*x`), constants
//! folded exactly, terms in structural order.

use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use rustc_hash::FxHashMap;
use std::cmp::Ordering;

impl ExprPool {
    /// The canonical sum of `terms` (0 for none).
    pub fn add(&mut self, terms: &[Id]) -> Id {
        let mut constant = Number::ZERO;
        let mut coefficients: FxHashMap<Id, Number> = FxHashMap::default();
        // Canonical sums never nest, so one level of flattening suffices.
        let mut flat = Vec::with_capacity(terms.len());
        for &t in terms {
            match self.node(t) {
                Node::Add(inner) => flat.extend_from_slice(inner),
                _ => flat.push(t),
            }
        }
        for t in flat {
            if let Some(n) = self.node(t).number() {
                constant = constant.add(n);
                continue;
            }
            let (c, rest) = self.split_coefficient(t);
            let entry = coefficients.entry(rest).or_insert(Number::ZERO);
            *entry = entry.add(c);
        }
        let mut collected: Vec<(Id, Number)> = coefficients
            .into_iter()
            .filter(|(_, c)| !c.is_zero())
            .collect();
        // Distinct rests never compare equal, so the coefficient never decides the order;
        // it is only a tie-break for completeness.
        collected.sort_by(|(r1, c1), (r2, c2)| {
            self.structural_cmp(*r1, *r2).then_with(|| {
                c1.to_f64()
                    .partial_cmp(&c2.to_f64())
                    .unwrap_or(Ordering::Equal)
            })
        });
        let mut out = Vec::with_capacity(collected.len() + 1);
        let constant = constant.normalized();
        if !constant.is_zero() {
            out.push(self.number(constant));
        }
        for (rest, c) in collected {
            let term = self.scale(c, rest);
            out.push(term);
        }
        match out.as_slice() {
            [] => self.number(Number::ZERO),
            [single] => *single,
            _ => self.intern(Node::Add(out.into_boxed_slice())),
        }
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.add(&[a, nb])
    }

    /// `-a`, that is `-1 * a`.
    pub fn neg(&mut self, a: Id) -> Id {
        let minus_one = self.int(-1);
        self.mul(&[minus_one, a])
    }

    /// Splits a non-constant canonical term into its numeric coefficient and the rest:
    /// `3*x*y` → `(3, x*y)`, `x` → `(1, x)`.
    pub(crate) fn split_coefficient(&mut self, t: Id) -> (Number, Id) {
        let Node::Mul(factors) = self.node(t) else {
            return (Number::ONE, t);
        };
        let Some(c) = factors.first().and_then(|f| self.node(*f).number()) else {
            return (Number::ONE, t);
        };
        let rest: Vec<Id> = factors.iter().skip(1).copied().collect();
        let rest = match rest.as_slice() {
            [single] => *single,
            // Already sorted and collected: still canonical without the coefficient.
            _ => self.intern(Node::Mul(rest.into_boxed_slice())),
        };
        (c, rest)
    }

    /// `c * rest` for a canonical non-constant `rest` without a coefficient, built directly.
    pub(crate) fn scale(&mut self, c: Number, rest: Id) -> Id {
        if c.is_zero() {
            return self.number(Number::ZERO);
        }
        if c.is_one() {
            return rest;
        }
        let c = self.number(c);
        let factors: Vec<Id> = match self.node(rest) {
            Node::Mul(inner) => std::iter::once(c).chain(inner.iter().copied()).collect(),
            _ => vec![c, rest],
        };
        self.intern(Node::Mul(factors.into_boxed_slice()))
    }
}
