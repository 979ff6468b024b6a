//! Expansion: products of sums distributed and integer powers of sums multiplied out,
//! everywhere in an expression (function arguments and exponents included). Canonical
//! construction does not expand, because expansion can explode; identity checks use this.

use super::node::{Id, Node};
use super::pool::ExprPool;
use rustc_hash::FxHashMap;

/// What every [`ExprPool::expand`] of a pool shares (see its field `expansions`).
#[derive(Clone, Debug, Default)]
pub(crate) struct Expansions {
    /// The expanded form of each node visited.
    images: FxHashMap<Id, Id>,
    /// `a * t` for terms `a` and `t` that a distribution multiplied.
    products: FxHashMap<(Id, Id), Id>,
}

/// A product whose expansion would exceed this many terms is left as a product: the
/// identity check then falls back to numerical evaluation instead of running out of memory.
const MAX_TERMS: usize = 5_000;

/// Integer powers of sums above this are left as powers, for the same reason.
const MAX_EXPONENT: i128 = 32;

impl ExprPool {
    /// The expanded form of `e`: a sum of products with no sum inside a product or under an
    /// integer power (within the size limits above). Defined symbols are kept as symbols.
    ///
    /// Only the nodes no earlier call expanded are visited (the pool remembers every
    /// image, and every product of two terms): expanding a node again would only re-intern
    /// nodes that exist, so skipping it changes neither the result nor the order in which
    /// nodes are created.
    pub fn expand(&mut self, e: Id) -> Id {
        let todo =
            self.reachable_where(&[e], false, |id| !self.expansions.images.contains_key(&id));
        for id in todo {
            let new = &self.expansions.images;
            let image = |c: &Id| new.get(c).copied().unwrap_or(*c);
            let value = match self.node(id).clone() {
                Node::Num(_) | Node::Float(_) | Node::Sym(_) => id,
                Node::Add(terms) => {
                    let terms: Vec<Id> = terms.iter().map(image).collect();
                    self.add(&terms)
                }
                Node::Mul(factors) => {
                    let factors: Vec<Id> = factors.iter().map(image).collect();
                    self.distribute(&factors)
                }
                Node::Pow(b, x) => {
                    let (b, x) = (image(&b), image(&x));
                    self.expand_power(b, x)
                }
                Node::Call(f, args) => {
                    let args: Vec<Id> = args.iter().map(image).collect();
                    self.call(f, &args)
                }
            };
            self.expansions.images.insert(id, value);
        }
        self.expansions.images.get(&e).copied().unwrap_or(e)
    }

    /// Π factors with every sum among them distributed, term by term, collecting as it goes
    /// (so `(a+b)(a-b)` never holds more than its collected terms).
    fn distribute(&mut self, factors: &[Id]) -> Id {
        let mut acc: Vec<Id> = vec![self.int(1)];
        for (i, &f) in factors.iter().enumerate() {
            let f_terms = self.terms(f);
            if acc.len().saturating_mul(f_terms.len()) > MAX_TERMS {
                // Too big to expand further: keep the expanded part times every factor not
                // yet distributed (all of them — dropping any would change the value).
                let mut rest = vec![self.add(&acc)];
                rest.extend(&factors[i..]);
                return self.mul(&rest);
            }
            let mut products = Vec::with_capacity(acc.len() * f_terms.len());
            for &a in &acc {
                for &t in &f_terms {
                    products.push(self.product(a, t));
                }
            }
            let sum = self.add(&products);
            acc = self.terms(sum);
        }
        self.add(&acc)
    }

    /// `a * t`, formed once per pool.
    fn product(&mut self, a: Id, t: Id) -> Id {
        if let Some(known) = self.expansions.products.get(&(a, t)) {
            return *known;
        }
        let product = self.mul(&[a, t]);
        self.expansions.products.insert((a, t), product);
        product
    }

    /// `b^x` with a sum `b` multiplied out for a small integer `x`
    /// (a negative one gives the reciprocal of the expanded positive power).
    fn expand_power(&mut self, b: Id, x: Id) -> Id {
        let n = self.as_rational(x).and_then(|r| r.as_integer());
        match (self.node(b), n) {
            (Node::Add(_), Some(n)) if n != 0 && n.abs() <= MAX_EXPONENT => {
                let copies = vec![b; n.unsigned_abs() as usize];
                let positive = self.distribute(&copies);
                if n > 0 {
                    positive
                } else {
                    let minus_one = self.int(-1);
                    self.pow(positive, minus_one)
                }
            }
            _ => self.pow(b, x),
        }
    }
}
