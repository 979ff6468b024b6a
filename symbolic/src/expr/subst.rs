//! Substitution and inlining: rebuild an expression bottom-up through the canonical
//! constructors, so the result is canonical (`m` := `m0 + c*x` in `m - m0` gives `c*x`).

use super::node::{Id, Node};
use super::pool::{symbol_bit, ExprPool};
use super::symbol::Symbol;
use rustc_hash::FxHashMap;
use std::collections::HashMap;

/// What happens to a defined symbol during a rebuild.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Definitions {
    /// Replace it by its (rebuilt) value.
    Inline,
    /// Keep it, unless the rebuild changes its value: then inline, so the result means the
    /// same as substituting into the inlined expression.
    InlineIfChanged,
}

impl ExprPool {
    /// Replaces every symbol of `map` by its image, simultaneously (images are not
    /// substituted into again). The result is canonical.
    ///
    /// A defined symbol whose value mentions a replaced symbol is inlined, so substitution
    /// means the same with or without [`inline_definitions`](Self::inline_definitions).
    pub fn substitute(&mut self, e: Id, map: &HashMap<Symbol, Id>) -> Id {
        self.rebuild(e, map, Definitions::InlineIfChanged)
    }

    /// Replaces every defined symbol by its value, recursively.
    pub fn inline_definitions(&mut self, e: Id) -> Id {
        self.rebuild(e, &HashMap::new(), Definitions::Inline)
    }

    fn rebuild(&mut self, e: Id, map: &HashMap<Symbol, Id>, policy: Definitions) -> Id {
        let mut new: FxHashMap<Id, Id> = FxHashMap::default();
        // Only the nodes that may contain a replaced symbol, or (to inline) a defined one:
        // the others are their own image, and rebuilding them would build no node.
        let mut symbols = map.keys().fold(0, |mask, s| mask | symbol_bit(*s));
        if policy == Definitions::Inline {
            symbols = self
                .defined_symbols()
                .fold(symbols, |mask, s| mask | symbol_bit(s));
        }
        for id in self.reachable_depending_on(&[e], symbols) {
            let image = |c: &Id| new.get(c).copied().unwrap_or(*c);
            let node = self.node(id).clone();
            let children: Vec<Id> = node.children().collect();
            let rebuilt: Vec<Id> = children.iter().map(image).collect();
            let changed = children != rebuilt;
            let value = match node {
                Node::Sym(s) => match (map.get(&s), self.definition(s)) {
                    (Some(v), _) => *v,
                    (None, Some(v)) => {
                        let inlined = image(&v);
                        if policy == Definitions::Inline || inlined != v {
                            inlined
                        } else {
                            id
                        }
                    }
                    (None, None) => id,
                },
                _ if !changed => id,
                Node::Add(_) => self.add(&rebuilt),
                Node::Mul(_) => self.mul(&rebuilt),
                Node::Pow(..) => match rebuilt.as_slice() {
                    [b, x] => self.pow(*b, *x),
                    _ => id,
                },
                Node::Call(f, _) => self.call(f, &rebuilt),
                Node::Num(_) | Node::Float(_) => id,
            };
            new.insert(id, value);
        }
        new.get(&e).copied().unwrap_or(e)
    }
}
