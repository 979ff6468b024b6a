//! Common-subexpression elimination. Hash-consing has already merged equal
//! subexpressions into one node; CSE only has to find the nodes used more than once.

use super::node::{Id, Node};
use super::pool::ExprPool;
use rustc_hash::{FxHashMap, FxHashSet};

/// The subexpressions shared by some roots, for emitting straight-line code: compute
/// each of [`shared`](Self::shared) once, in order, into a local, then the roots.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cse {
    /// Non-leaf subexpressions used at least twice across the roots (by several parents,
    /// or as a root and inside another), children before parents.
    pub shared: Vec<Id>,
    /// The roots, as given.
    pub roots: Vec<Id>,
    set: FxHashSet<Id>,
}

impl Cse {
    /// Whether `id` is one of the shared subexpressions.
    pub fn is_shared(&self, id: Id) -> bool {
        self.set.contains(&id)
    }
}

impl ExprPool {
    /// Finds the shared subexpressions of `roots`. Defined symbols are not looked
    /// through: inline them first if their values should be shared too.
    pub fn cse(&self, roots: &[Id]) -> Cse {
        self.cse_in(roots, self.reachable(roots, false))
    }

    /// [`cse`](Self::cse) with `order`, the ids reachable from `roots` in ascending order,
    /// for a caller that has it already.
    pub(crate) fn cse_in(&self, roots: &[Id], order: Vec<Id>) -> Cse {
        let mut uses: FxHashMap<Id, usize> = FxHashMap::default();
        for r in roots {
            *uses.entry(*r).or_default() += 1;
        }
        for id in &order {
            for c in self.node(*id).children() {
                *uses.entry(c).or_default() += 1;
            }
        }
        let shared: Vec<Id> = order
            .into_iter()
            .filter(|id| {
                !matches!(self.node(*id), Node::Num(_) | Node::Float(_) | Node::Sym(_))
                    && uses.get(id).copied().unwrap_or(0) >= 2
            })
            .collect();
        Cse {
            set: shared.iter().copied().collect(),
            shared,
            roots: roots.to_vec(),
        }
    }
}
