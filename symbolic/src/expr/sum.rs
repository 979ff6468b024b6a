//! Canonical sums: flattened, like terms collected (`2*x + 3*x` → `5*x`), constants
//! folded exactly, terms in structural order.

use super::node::{Id, Node, Number};
use super::pool::ExprPool;

impl ExprPool {
    /// The canonical sum of `terms` (0 for none).
    pub fn add(&mut self, terms: &[Id]) -> Id {
        if let Some(single) = self.single_term_sum(terms) {
            return single;
        }
        let mut constant = Number::ZERO;
        // Canonical sums never nest, so one level of flattening suffices.
        let mut flat = Vec::with_capacity(terms.len());
        for &t in terms {
            match self.node(t) {
                Node::Add(inner) => flat.extend_from_slice(inner),
                _ => flat.push(t),
            }
        }
        // (rest, coefficient, term) of every non-constant term, in the order met.
        let mut split: Vec<(Id, Number, Id)> = Vec::with_capacity(flat.len());
        for t in flat {
            if let Some(n) = self.node(t).number() {
                constant = constant.add(n);
                continue;
            }
            let (c, rest) = self.split_coefficient(t);
            split.push((rest, c, t));
        }
        // Terms in structural order; the sort is stable, so like terms are summed in the
        // order met. (A sorted list instead of a map from rest to coefficient: no hashing.)
        split.sort_by(|(r1, ..), (r2, ..)| self.structural_cmp(*r1, *r2));
        // Each rest with its summed coefficient, and the term it came from when no like
        // term joined it.
        let mut collected: Vec<(Id, Number, Option<Id>)> = Vec::with_capacity(split.len());
        for (rest, c, t) in split {
            match collected.last_mut() {
                Some((last, sum, alone)) if *last == rest => {
                    *sum = sum.add(c);
                    *alone = None;
                }
                _ => {
                    let sum = Number::ZERO.add(c);
                    collected.push((rest, sum, (sum == c).then_some(t)));
                }
            }
        }
        collected.retain(|(_, c, _)| !c.is_zero());
        let mut out = Vec::with_capacity(collected.len() + 1);
        let constant = constant.normalized();
        if !constant.is_zero() {
            out.push(self.number(constant));
        }
        for (rest, c, alone) in collected {
            // A term that no like term joined is its own `scale(c, rest)` (a canonical term
            // is its coefficient's node before its other factors): scaling it again would
            // only look up nodes that exist, so taking it changes no node and no order.
            let term = match alone {
                Some(t) => t,
                None => self.scale(c, rest),
            };
            out.push(term);
        }
        match out.as_slice() {
            [] => self.number(Number::ZERO),
            [single] => *single,
            _ => self.intern(Node::Add(out.into_boxed_slice())),
        }
    }

    /// The sum of one canonical term that is not a sum: the term itself (distributing and
    /// differentiating ask for many of these). The general path would split off its
    /// coefficient, which may create the node of the rest (`x*y` for `2*x*y`), then scale
    /// it back to the same term; the split is kept so that the nodes created, and their
    /// order, stay exactly those of the general path.
    fn single_term_sum(&mut self, terms: &[Id]) -> Option<Id> {
        let [single] = *terms else {
            return None;
        };
        match self.node(single) {
            Node::Add(_) => None,
            Node::Num(_) | Node::Float(_) => Some(single),
            _ => {
                self.split_coefficient(single);
                Some(single)
            }
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
        // Split once per pool: splitting again would only look up the rest's node.
        if let Some(&known) = self.splits.get(&t) {
            return known;
        }
        let rest: Vec<Id> = factors.iter().skip(1).copied().collect();
        let rest = match rest.as_slice() {
            [single] => *single,
            // Already sorted and collected: still canonical without the coefficient.
            _ => self.intern(Node::Mul(rest.into_boxed_slice())),
        };
        self.splits.insert(t, (c, rest));
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
