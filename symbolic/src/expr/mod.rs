//! Stage 2: expressions.
//!
//! An [`ExprPool`] is a flat, hash-consed arena of expressions (after egg's `RecExpr`):
//! children always have smaller ids than their parents, identical nodes are stored once,
//! and the constructors keep every node in a canonical form, so simplification happens at
//! construction and `x - x` *is* `0`. There is no rewriting to saturation: sums and
//! products are sorted and collected instead, which keeps associativity and commutativity
//! from exploding.
//!
//! Constants are exact [`Rational`]s (falling back to inexact `f64` constants on overflow).
//! The calculus is the frozen-mass calculus of Zhang Jiuzhu (2015): under ∂* and d*/dt
//! every `Frozen` symbol (mass, inertia) is held constant (docs/mechanics.md#the-frozen-mass-rule).
//!
//! ```
//! use varmass_symbolic::expr::{ExprPool, SymbolKind};
//!
//! let mut pool = ExprPool::new();
//! let x = pool.symbols_mut().add_coordinate("x");
//! let m = pool.symbols_mut().add("m", SymbolKind::Frozen);
//! let (xs, ms) = (pool.sym(x), pool.sym(m));
//! let v = pool.sym(pool.symbols().velocity_of(x).unwrap());
//! // L = ½ m x'² + m x; ∂*L/∂x' = m x' with m frozen.
//! let half = pool.rational(varmass_symbolic::expr::Rational::HALF);
//! let two = pool.int(2);
//! let v2 = pool.pow(v, two);
//! let t = pool.mul(&[half, ms, v2]);
//! let w = pool.mul(&[ms, xs]);
//! let lagrangian = pool.add(&[t, w]);
//! let p = pool.diff(lagrangian, pool.symbols().velocity_of(x).unwrap());
//! let expected = pool.mul(&[ms, v]);
//! assert_eq!(p, expected);
//! ```

mod call;
mod cse;
mod diff;
mod eval;
mod expand;
mod func;
mod horner;
mod identity;
mod input_call;
mod latex;
mod lower;
mod node;
mod order;
mod pool;
mod print;
mod product;
mod query;
mod rational;
mod subst;
mod sum;
mod symbol;
mod table_call;
mod tape;
mod taylor;
mod trig;
pub(crate) mod walk;

pub use cse::Cse;
pub use diff::UnsupportedDerivative;
pub use func::Func;
pub use identity::{Identity, SamplePoints};
pub use lower::{lower, Resolver, TableResolver, Written};
pub use node::{Id, Node};
pub use pool::ExprPool;
pub use print::DisplayExpr;
pub use rational::Rational;
pub use symbol::{Symbol, SymbolKind, SymbolTable};
pub use tape::Tape;
pub(crate) use taylor::{Instr, Op};
pub use taylor::{TaylorJet, TaylorTape};
