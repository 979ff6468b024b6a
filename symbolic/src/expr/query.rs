//! Questions about an expression's symbols: which occur, and the polynomial degree in some
//! of them (L must be at most quadratic in the velocities, docs/dsl.md#kinetic-potential-lagrangian).

use super::node::{Id, Node};
use super::pool::{symbol_bit, ExprPool};
use super::symbol::Symbol;
use rustc_hash::FxHashMap;
use std::collections::BTreeSet;

impl ExprPool {
    /// Whether `s` occurs in `e`, directly or inside the value of a defined symbol.
    pub fn contains(&self, e: Id, s: Symbol) -> bool {
        self.reachable_depending_on(&[e], symbol_bit(s))
            .into_iter()
            .any(|id| *self.node(id) == Node::Sym(s))
    }

    /// Every symbol that occurs in `e`: defined symbols and the symbols of their values.
    pub fn free_symbols(&self, e: Id) -> BTreeSet<Symbol> {
        if self.symbols().len() <= 64 {
            // With at most 64 symbols, bit i of the node's symbol filter is exactly symbol
            // i (the filter holds every symbol reachable through definitions): no walk.
            let mask = self.symbol_mask(e);
            return (0..64u32)
                .filter(|i| mask >> i & 1 == 1)
                .map(Symbol)
                .collect();
        }
        self.reachable(&[e], true)
            .into_iter()
            .filter_map(|id| self.as_symbol(id))
            .collect()
    }

    /// The total degree of `e` as a polynomial in `vars` (whose coefficients may be any
    /// expressions free of `vars`); `None` if `e` is not polynomial in them, e.g. `sin(x')`
    /// or `1/x'`. Defined symbols are looked through.
    pub fn degree(&self, e: Id, vars: &[Symbol]) -> Option<u32> {
        // None = not polynomial; Some(0) = free of vars (canonical form has no `x - x`).
        let mut degrees: FxHashMap<Id, Option<u32>> = FxHashMap::default();
        for id in self.reachable(&[e], true) {
            let of = |c: &Id| degrees.get(c).copied().flatten();
            let degree = match self.node(id) {
                Node::Num(_) | Node::Float(_) => Some(0),
                Node::Sym(s) => match self.definition(*s) {
                    Some(v) => of(&v),
                    None => Some(u32::from(vars.contains(s))),
                },
                Node::Add(terms) => terms
                    .iter()
                    .map(of)
                    .try_fold(0u32, |acc, d| d.map(|d| acc.max(d))),
                Node::Mul(factors) => factors
                    .iter()
                    .map(of)
                    .try_fold(0u32, |acc, d| acc.checked_add(d?)),
                Node::Pow(b, x) => match (of(b), of(x)) {
                    (Some(0), Some(0)) => Some(0),
                    (Some(db), Some(0)) => self
                        .as_rational(*x)
                        .and_then(|r| r.as_integer())
                        .and_then(|n| u32::try_from(n).ok())
                        .and_then(|n| db.checked_mul(n)),
                    _ => None,
                },
                Node::Call(_, args) => args.iter().all(|a| of(a) == Some(0)).then_some(0),
            };
            degrees.insert(id, degree);
        }
        degrees.get(&e).copied().flatten()
    }

    /// The arithmetic operations that evaluating `roots` once costs with every shared
    /// subexpression computed once (what generated code does after its CSE): n − 1 for a
    /// sum or product of n, one for a power or a call. A measure for choosing between
    /// equal forms of an expression, not a count of machine instructions.
    pub fn operation_count(&self, roots: &[Id]) -> usize {
        self.reachable(roots, false)
            .into_iter()
            .map(|id| match self.node(id) {
                Node::Add(c) | Node::Mul(c) => c.len().saturating_sub(1),
                Node::Pow(..) | Node::Call(..) => 1,
                Node::Num(_) | Node::Float(_) | Node::Sym(_) => 0,
            })
            .sum()
    }
}
