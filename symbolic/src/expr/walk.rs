//! One walk over the arena for every printer (DSL text, LaTeX, Rust tokens): the nodes
//! below a root are printed bottom-up, in ascending id order (children before parents, see
//! [`ExprPool`]), each by a small [`Syntax`] from the printed forms of its descendants. No
//! recursion, so deep expressions cannot overflow the stack.

use rustc_hash::FxHashSet;

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
    /// `text` in parentheses.
    fn group(&self, text: &str) -> String;
    /// An exact constant.
    fn number(&self, r: Rational) -> Printed<String>;
    /// An inexact constant.
    fn float(&self, x: f64) -> Printed<String>;
    /// A symbol.
    fn symbol(&self, pool: &ExprPool, s: Symbol) -> Printed<String>;
    /// A call.
    fn call(&self, p: &Printer<'_>, f: Func, args: &[Id]) -> Printed<String>;
    /// A product.
    fn product(&self, p: &Printer<'_>, factors: &[Id]) -> Printed<String>;
    /// `base ^ exponent`.
    fn power(&self, p: &Printer<'_>, base: Id, exponent: Id) -> Printed<String>;
    /// The terms of a sum in print order, each with whether it is printed after ` - `: by
    /// default the reading order of `ExprPool::sum_view` (the DSL text and LaTeX).
    fn terms(&self, p: &Printer<'_>, terms: &[Id]) -> Vec<(Id, bool)> {
        p.pool().sum_view(terms)
    }
    /// The magnitude of a term that [`terms`](Self::terms) calls negative.
    fn negated(&self, p: &Printer<'_>, term: Id) -> Printed<String>;
    /// The first term of a sum: by default as printed, whole, whatever its sign (the DSL
    /// text must keep `-((a + b)*(c + d))` grouped: see `Dsl::product_of`).
    fn lead(&self, p: &Printer<'_>, term: Id, _negative: bool) -> String {
        p.get(term).text.clone()
    }

    /// Appends ` + term`, or ` - term` when `negative`, to `sum`.
    fn join(&self, sum: &mut String, negative: bool, term: String) {
        sum.push_str(if negative { " - " } else { " + " });
        sum.push_str(&term);
    }

    /// `printed`, grouped if it binds more loosely than `prec`.
    fn at_least(&self, printed: &Printed<String>, prec: Prec) -> String {
        if printed.prec < prec {
            self.group(&printed.text)
        } else {
            printed.text.clone()
        }
    }

    /// A sum: the lead term, then every other after ` + ` or ` - `, binding at least like
    /// a product.
    fn sum(&self, p: &Printer<'_>, terms: &[Id]) -> Printed<String> {
        let mut text: Option<String> = None;
        for (t, negative) in self.terms(p, terms) {
            match &mut text {
                None => text = Some(self.lead(p, t, negative)),
                Some(sum) => {
                    let term = if negative {
                        self.at_least(&self.negated(p, t), Prec::Product)
                    } else {
                        self.at_least(p.get(t), Prec::Product)
                    };
                    self.join(sum, negative, term);
                }
            }
        }
        Printed::new(text.unwrap_or_default(), Prec::Sum)
    }
}

/// The printed forms of the nodes below the one being printed.
pub(crate) struct Printer<'a> {
    pool: &'a ExprPool,
    /// The nodes printed so far, in ascending id order (the order of the walk).
    printed: Vec<(Id, Printed<String>)>,
    /// The nodes whose printed form the caller replaced (temporaries of generated code).
    bound: FxHashSet<Id>,
    /// What [`get`](Self::get) answers for a node not printed (unreachable).
    missing: Printed<String>,
}

impl Printer<'_> {
    /// The arena.
    pub(crate) fn pool(&self) -> &ExprPool {
        self.pool
    }

    /// Whether `id` is printed as the caller replaced it (a temporary of generated code,
    /// by name), so that its structure is not to be looked into.
    pub(crate) fn is_bound(&self, id: Id) -> bool {
        self.bound.contains(&id)
    }

    /// The printed form of a node below the current one.
    pub(crate) fn get(&self, id: Id) -> &Printed<String> {
        match self.printed.binary_search_by_key(&id, |(i, _)| *i) {
            Ok(at) => &self.printed[at].1,
            // Unreachable: the walk prints every node below a parent before it.
            Err(_) => &self.missing,
        }
    }

    fn print_node<S: Syntax>(&self, syntax: &S, id: Id) -> Printed<String> {
        match self.pool.node(id) {
            Node::Num(r) => syntax.number(*r),
            Node::Float(bits) => syntax.float(f64::from_bits(*bits)),
            Node::Sym(s) => syntax.symbol(self.pool, *s),
            Node::Call(f, args) => syntax.call(self, *f, args),
            Node::Add(terms) => syntax.sum(self, terms),
            Node::Mul(factors) => syntax.product(self, factors),
            Node::Pow(b, x) => syntax.power(self, *b, *x),
        }
    }
}

/// Prints `root` in `syntax`.
pub(crate) fn print<S: Syntax>(pool: &ExprPool, syntax: &S, root: Id) -> Printed<String> {
    let mut printed = print_all(pool, syntax, &[root], |_, _| None);
    printed
        .pop()
        .unwrap_or_else(|| syntax.number(Rational::ZERO))
}

/// Prints every root in `syntax`, in one walk over the nodes below them. After each node
/// is printed, `bind` may replace its printed form (a temporary of generated code, then
/// printed by name in every node above it, which [`Printer::is_bound`] then tells).
pub(crate) fn print_all<S: Syntax>(
    pool: &ExprPool,
    syntax: &S,
    roots: &[Id],
    bind: impl FnMut(Id, &Printed<String>) -> Option<Printed<String>>,
) -> Vec<Printed<String>> {
    print_in(pool, syntax, roots, pool.reachable(roots, false), bind)
}

/// [`print_all`] over `order`, the ids reachable from `roots` in ascending order, for a
/// caller that has it already.
pub(crate) fn print_in<S: Syntax>(
    pool: &ExprPool,
    syntax: &S,
    roots: &[Id],
    order: Vec<Id>,
    mut bind: impl FnMut(Id, &Printed<String>) -> Option<Printed<String>>,
) -> Vec<Printed<String>> {
    let mut printer = Printer {
        pool,
        printed: Vec::with_capacity(order.len()),
        bound: FxHashSet::default(),
        missing: Printed::new(String::default(), Prec::Atom),
    };
    for id in order {
        let mut printed = printer.print_node(syntax, id);
        if let Some(replaced) = bind(id, &printed) {
            printed = replaced;
            printer.bound.insert(id);
        }
        printer.printed.push((id, printed));
    }
    roots
        .iter()
        .map(
            |r| match printer.printed.binary_search_by_key(r, |(i, _)| *i) {
                Ok(at) => printer.printed[at].1.clone(),
                // An id of another pool reads as the zero constant (see `ExprPool::node`).
                Err(_) => syntax.number(Rational::ZERO),
            },
        )
        .collect()
}
