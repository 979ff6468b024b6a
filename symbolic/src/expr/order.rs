//! The structural total order that sorts the terms of a sum and the factors of a product.
//!
//! It depends only on the shape of the expressions (symbols by their table index), never on
//! [`Id`] values, so a canonical expression does not depend on the order in which it was
//! built.
//!
//! The key, compared in turn: kind (constants, symbols, calls, powers, products, sums),
//! (for symbols: their role, then their index),
//! height of the tree, then the contents (constant value, symbol index, function, children
//! in order). Height comes before contents so that deep expressions that share a long
//! spine (`sin(sin(…x…))` against `sin(sin(…y…))` is rare; `cos(u)` against
//! `cos(sin(u))` is everywhere in derivatives) are usually told apart in O(1).

use super::node::{Id, Node};
use super::pool::ExprPool;
use std::cmp::Ordering;

/// Kinds in the order they sort: constants, symbols, calls, powers, products, sums.
fn rank(node: &Node) -> u8 {
    match node {
        Node::Num(_) | Node::Float(_) => 0,
        Node::Sym(_) => 1,
        Node::Call(..) => 2,
        Node::Pow(..) => 3,
        Node::Mul(_) => 4,
        Node::Add(_) => 5,
    }
}

/// Symbols sort by role first, as a physicist writes them: parameters, masses, time,
/// coordinates, velocities, momenta (`m*g*x*sin(theta)`, `c*x'^2`); then by table index.
fn symbol_rank(pool: &ExprPool, s: super::symbol::Symbol) -> u8 {
    use super::symbol::SymbolKind;
    match pool.symbols().kind(s) {
        SymbolKind::Parameter => 0,
        SymbolKind::Frozen => 1,
        SymbolKind::Time => 2,
        SymbolKind::Coordinate => 3,
        SymbolKind::Velocity { .. } => 4,
        SymbolKind::Momentum { .. } => 5,
        SymbolKind::Acceleration { .. } => 6,
        SymbolKind::Definition => 7,
    }
}

impl ExprPool {
    /// Compares two expressions structurally.
    ///
    /// Runs in a loop, not by recursion: hash-consing makes equal ids exactly the equal
    /// structures, so two child lists compare as their first pair of *different* ids, and
    /// that pair is compared next. The cost is O(depth × width), with no stack growth.
    pub fn structural_cmp(&self, mut a: Id, mut b: Id) -> Ordering {
        loop {
            if a == b {
                return Ordering::Equal;
            }
            let (na, nb) = (self.node(a), self.node(b));
            let by_shape = rank(na)
                .cmp(&rank(nb))
                .then_with(|| self.height(a).cmp(&self.height(b)));
            if by_shape != Ordering::Equal {
                return by_shape;
            }
            let (ca, cb): (&[Id], &[Id]) = match (na, nb) {
                (Node::Num(x), Node::Num(y)) => return x.cmp(y),
                (Node::Float(x), Node::Float(y)) => {
                    return f64::from_bits(*x).total_cmp(&f64::from_bits(*y))
                }
                // An exact constant sorts before an inexact one of the same value.
                (Node::Num(x), Node::Float(y)) => {
                    return x
                        .to_f64()
                        .total_cmp(&f64::from_bits(*y))
                        .then(Ordering::Less)
                }
                (Node::Float(x), Node::Num(y)) => {
                    return f64::from_bits(*x)
                        .total_cmp(&y.to_f64())
                        .then(Ordering::Greater)
                }
                (Node::Sym(x), Node::Sym(y)) => {
                    return symbol_rank(self, *x)
                        .cmp(&symbol_rank(self, *y))
                        .then(x.cmp(y))
                }
                (Node::Call(f, x), Node::Call(g, y)) => {
                    let by_func = f.cmp(g);
                    if by_func != Ordering::Equal {
                        return by_func;
                    }
                    (x, y)
                }
                (Node::Pow(b1, e1), Node::Pow(b2, e2)) => {
                    if b1 != b2 {
                        (a, b) = (*b1, *b2);
                    } else {
                        (a, b) = (*e1, *e2);
                    }
                    continue;
                }
                (Node::Mul(x), Node::Mul(y)) | (Node::Add(x), Node::Add(y)) => (x, y),
                // Equal ranks with different variants cannot happen; order by rank alone.
                _ => return Ordering::Equal,
            };
            // The first pair of different children (a plain loop: the zip/find chain costs
            // several calls per child unoptimized, and sorting compares a lot).
            let shared = ca.len().min(cb.len());
            let mut i = 0;
            while i < shared && ca[i] == cb[i] {
                i += 1;
            }
            if i == shared {
                return ca.len().cmp(&cb.len());
            }
            (a, b) = (ca[i], cb[i]);
        }
    }
}
