//! The nodes of the expression arena, and numeric constants with their exact/inexact
//! arithmetic.

use super::func::Func;
use super::rational::Rational;
use super::symbol::Symbol;

/// An expression: an index into its [`ExprPool`](super::ExprPool). Two ids of one pool
/// are equal exactly when the expressions are structurally equal (hash-consing).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Id(pub(crate) u32);

impl Id {
    /// The position in the arena.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One node of the arena. Children are [`Id`]s of earlier nodes.
///
/// Canonical form (kept by the pool's constructors, never built by hand):
/// - `Add`: ≥ 2 terms, no `Add` among them, the constant (if nonzero) first, then the
///   other terms in structural order, each `coefficient × rest` with distinct rests;
/// - `Mul`: ≥ 2 factors, no `Mul` among them, the numeric coefficient (if ≠ 1) first, then
///   the factors `base^exponent` in structural order with distinct bases; never a number
///   times a lone sum (that distributes);
/// - `Pow(b, e)`: `e ≠ 0, 1`, no integer power of a power or of a product;
/// - `Call`: no negative argument to an odd or even function (it is pulled out).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// An exact rational constant.
    Num(Rational),
    /// An inexact constant: the bits of an `f64` (from a literal that does not fit a
    /// rational, or from folding that overflowed).
    Float(u64),
    /// A symbol.
    Sym(Symbol),
    /// A sum.
    Add(Box<[Id]>),
    /// A product.
    Mul(Box<[Id]>),
    /// `base ^ exponent`.
    Pow(Id, Id),
    /// A function applied to its arguments.
    Call(Func, Box<[Id]>),
}

impl Node {
    /// The children, in order (for `Pow`: base, then exponent).
    pub fn children(&self) -> impl Iterator<Item = Id> + '_ {
        let (list, pair): (&[Id], [Option<Id>; 2]) = match self {
            Node::Num(_) | Node::Float(_) | Node::Sym(_) => (&[], [None, None]),
            Node::Add(c) | Node::Mul(c) | Node::Call(_, c) => (c, [None, None]),
            Node::Pow(b, e) => (&[], [Some(*b), Some(*e)]),
        };
        list.iter().copied().chain(pair.into_iter().flatten())
    }

    /// Calls `f` on each child, in order: what [`children`](Self::children) yields, without
    /// its chained iterators (which cost a call per step in the unoptimized builds where
    /// proc macros run).
    pub(crate) fn for_each_child(&self, mut f: impl FnMut(Id)) {
        match self {
            Node::Num(_) | Node::Float(_) | Node::Sym(_) => {}
            Node::Add(c) | Node::Mul(c) | Node::Call(_, c) => {
                for &child in c.iter() {
                    f(child);
                }
            }
            Node::Pow(b, e) => {
                f(*b);
                f(*e);
            }
        }
    }

    /// The constant's value, if the node is a constant.
    pub(crate) fn number(&self) -> Option<Number> {
        match self {
            Node::Num(r) => Some(Number::Exact(*r)),
            Node::Float(bits) => Some(Number::Inexact(f64::from_bits(*bits))),
            _ => None,
        }
    }
}

/// A numeric constant during folding: exact when it can be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Number {
    Exact(Rational),
    Inexact(f64),
}

impl Number {
    pub(crate) const ZERO: Number = Number::Exact(Rational::ZERO);
    pub(crate) const ONE: Number = Number::Exact(Rational::ONE);

    pub(crate) fn to_f64(self) -> f64 {
        match self {
            Number::Exact(r) => r.to_f64(),
            Number::Inexact(x) => x,
        }
    }

    /// A zero coefficient annihilates its term whether exact or not.
    pub(crate) fn is_zero(self) -> bool {
        match self {
            Number::Exact(r) => r.is_zero(),
            Number::Inexact(x) => x == 0.0,
        }
    }

    pub(crate) fn is_one(self) -> bool {
        match self {
            Number::Exact(r) => r.is_one(),
            Number::Inexact(x) => x == 1.0,
        }
    }

    pub(crate) fn is_negative(self) -> bool {
        match self {
            Number::Exact(r) => r.is_negative(),
            Number::Inexact(x) => x < 0.0,
        }
    }

    fn combine(
        self,
        other: Number,
        exact: impl Fn(Rational, Rational) -> Option<Rational>,
        inexact: impl Fn(f64, f64) -> f64,
    ) -> Number {
        if let (Number::Exact(a), Number::Exact(b)) = (self, other) {
            if let Some(r) = exact(a, b) {
                return Number::Exact(r);
            }
        }
        Number::Inexact(inexact(self.to_f64(), other.to_f64())).normalized()
    }

    pub(crate) fn add(self, other: Number) -> Number {
        self.combine(other, Rational::checked_add, |a, b| a + b)
    }

    pub(crate) fn mul(self, other: Number) -> Number {
        self.combine(other, Rational::checked_mul, |a, b| a * b)
    }

    /// An inexact zero is exactly zero: keep one representation so that `0.1*x - 0.1*x`
    /// vanishes like `x - x`.
    pub(crate) fn normalized(self) -> Number {
        match self {
            n if n.is_zero() => Number::ZERO,
            n => n,
        }
    }
}
