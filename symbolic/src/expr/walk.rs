//! One walk over the arena for every printer (DSL text, LaTeX, Rust tokens): the nodes
//! below a root are printed bottom-up, in ascending id order (children before parents, see
//! [`ExprPool`]), each by a small [`Syntax`] from the printed forms of its descendants. No
//! recursion, so deep expressions cannot overflow the stack.

use std::collections::HashMap;

use super::func::Func;
use super::node::{Id, Node};
use super::pool::ExprPool;
use super::rational::Rational;
use super::symbol::Symbol;

/// How tightly a printed form binds, loosest first. A child printed where a tighter form
/// is needed is grouped (parenthesised).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Prec {
    /// `a + b`, `a - b`, and a leading minus in the DSL and LaTeX.
    Sum,
    /// `a*b`, `a/b`.
    Product,
    /// Tighter than `*`: `a^b` in the DSL and LaTeX; a unary minus in Rust (which has no
    /// power operator).
    Power,
    /// A name, a number, a call, a group.
    Atom,
}

/// A printed form and how tightly it binds.
#[derive(Clone, Debug)]
pub(crate) struct Printed<T> {
    pub(crate) text: T,
    pub(crate) prec: Prec,
}

impl<T> Printed<T> {
    pub(crate) fn new(text: T, prec: Prec) -> Printed<T> {
        Printed { text, prec }
    }
}

/// One target's spelling of the expression grammar. The walk calls one method per node,
/// after every node below it is printed (read them through the [`Printer`]).
pub(crate) trait Syntax: Sized {
    /// The printed text: a `String`, or Rust tokens.
    type Text: Clone + Default;

    /// `text` in parentheses.
    fn group(&self, text: Self::Text) -> Self::Text;
    /// An exact constant.
    fn number(&self, r: Rational) -> Printed<Self::Text>;
    /// An inexact constant.
    fn float(&self, x: f64) -> Printed<Self::Text>;
    /// A symbol.
    fn symbol(&self, pool: &ExprPool, s: Symbol) -> Printed<Self::Text>;
    /// A call.
    fn call(&self, p: &Printer<'_, Self>, f: Func, args: &[Id]) -> Printed<Self::Text>;
    /// A product.
    fn product(&self, p: &Printer<'_, Self>, factors: &[Id]) -> Printed<Self::Text>;
    /// `base ^ exponent`.
    fn power(&self, p: &Printer<'_, Self>, base: Id, exponent: Id) -> Printed<Self::Text>;
    /// The terms of a sum in print order, each with whether it is printed after ` - `.
    fn terms(&self, p: &Printer<'_, Self>, terms: &[Id]) -> Vec<(Id, bool)>;
    /// The magnitude of a term that [`terms`](Self::terms) calls negative.
    fn negated(&self, p: &Printer<'_, Self>, term: Id) -> Printed<Self::Text>;
    /// The first term of a sum.
    fn lead(&self, p: &Printer<'_, Self>, term: Id, negative: bool) -> Self::Text;
    /// `sum + term`, or `sum - term` when `negative`.
    fn join(&self, sum: Self::Text, negative: bool, term: Self::Text) -> Self::Text;

    /// `printed`, grouped if it binds more loosely than `prec`.
    fn at_least(&self, printed: Printed<Self::Text>, prec: Prec) -> Self::Text {
        if printed.prec < prec {
            self.group(printed.text)
        } else {
            printed.text
        }
    }

    /// A sum: the lead term, then every other after ` + ` or ` - `, binding at least like
    /// a product.
    fn sum(&self, p: &Printer<'_, Self>, terms: &[Id]) -> Printed<Self::Text> {
        let mut text = None;
        for (t, negative) in self.terms(p, terms) {
            text = Some(match text {
                None => self.lead(p, t, negative),
                Some(sum) => {
                    let term = if negative {
                        self.negated(p, t)
                    } else {
                        p.get(t)
                    };
                    self.join(sum, negative, self.at_least(term, Prec::Product))
                }
            });
        }
        Printed::new(text.unwrap_or_default(), Prec::Sum)
    }
}

/// The printed forms of the nodes below the one being printed.
pub(crate) struct Printer<'a, S: Syntax> {
    pool: &'a ExprPool,
    bound: &'a HashMap<Id, Printed<S::Text>>,
    printed: HashMap<Id, Printed<S::Text>>,
}

impl<S: Syntax> Printer<'_, S> {
    /// The arena.
    pub(crate) fn pool(&self) -> &ExprPool {
        self.pool
    }

    /// Whether `id` was given its printed form by the caller (a temporary of generated
    /// code), so that its structure is not to be looked into.
    pub(crate) fn is_bound(&self, id: Id) -> bool {
        self.bound.contains_key(&id)
    }

    /// The printed form of a node below the current one.
    pub(crate) fn get(&self, id: Id) -> Printed<S::Text> {
        self.bound
            .get(&id)
            .or_else(|| self.printed.get(&id))
            .cloned()
            // Unreachable: the walk prints every node below a parent before it.
            .unwrap_or_else(|| Printed::new(S::Text::default(), Prec::Atom))
    }
}

/// Prints `root` in `syntax`. The nodes in `bound` are printed as given and not looked
/// into (the temporaries of generated code).
pub(crate) fn print<S: Syntax>(
    pool: &ExprPool,
    syntax: &S,
    root: Id,
    bound: &HashMap<Id, Printed<S::Text>>,
) -> Printed<S::Text> {
    let mut printer = Printer {
        pool,
        bound,
        printed: HashMap::new(),
    };
    for id in pool.reachable_until(root, |id| bound.contains_key(&id)) {
        let printed = match pool.node(id) {
            Node::Num(r) => syntax.number(*r),
            Node::Float(bits) => syntax.float(f64::from_bits(*bits)),
            Node::Sym(s) => syntax.symbol(pool, *s),
            Node::Call(f, args) => syntax.call(&printer, *f, args),
            Node::Add(terms) => syntax.sum(&printer, terms),
            Node::Mul(factors) => syntax.product(&printer, factors),
            Node::Pow(b, x) => syntax.power(&printer, *b, *x),
        };
        printer.printed.insert(id, printed);
    }
    match printer.printed.contains_key(&root) || bound.contains_key(&root) {
        true => printer.get(root),
        // An id of another pool reads as the zero constant (see `ExprPool::node`).
        false => syntax.number(Rational::ZERO),
    }
}
