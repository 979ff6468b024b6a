//! Expressions as Rust: straight-line `let`s for the shared subexpressions of a set of
//! outputs, then each output as one expression — the Rust [`Syntax`] of the shared
//! printing walk, the temporaries printed by name.
//!
//! The arena makes common-subexpression elimination exact and cheap: equal subexpressions
//! are one node, so a node reached more than once from the outputs is computed once into a
//! temporary. Children have smaller ids than parents, so ascending ids are a valid order.

use rustc_hash::{FxHashMap, FxHashSet};

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use crate::expr::walk::{print_in, Prec, Printed, Printer, Syntax};
use crate::expr::{ExprPool, Func, Id, Node, Rational, Symbol, SymbolKind};

/// The Rust local that holds a symbol's value in generated code.
pub(crate) fn symbol_ident(pool: &ExprPool, s: Symbol) -> Ident {
    Ident::new(&symbol_name(pool, s), Span::call_site())
}

/// The name of [`symbol_ident`].
fn symbol_name(pool: &ExprPool, s: Symbol) -> String {
    let table = pool.symbols();
    match table.kind(s) {
        SymbolKind::Velocity { coordinate } => format!("{}_dot", table.name(coordinate)),
        SymbolKind::Acceleration { coordinate } => format!("{}_ddot", table.name(coordinate)),
        SymbolKind::Momentum { coordinate } => format!("p_{}", table.name(coordinate)),
        _ => table.name(s).to_string(),
    }
}

/// Rust source text turned into tokens. The generated code is printed as text and lexed
/// once per block instead of being assembled from many small token streams: proc macros
/// run unoptimized, where every `quote!` of a printed child clones its tokens into the
/// parent (and, inside the compiler, every token is a call through the proc-macro bridge).
/// The text is read by [`lex`](super::lex::lex), which builds the tokens directly, and by
/// `proc_macro2`'s general lexer only if it holds something `lex` does not read. The text
/// always lexes; should it not, the expansion reports it instead of panicking.
pub(crate) fn tokens(text: &str) -> TokenStream {
    #[cfg(test)]
    super::lex::tests::assert_same(text);
    if let Some(tokens) = super::lex::lex(text) {
        return tokens;
    }
    text.parse().unwrap_or_else(|_| {
        let message = format!("varmass: internal error, generated code does not lex: {text}");
        quote!(::core::compile_error!(#message);)
    })
}

/// Straight-line code for a set of outputs.
pub(crate) struct Block {
    /// `let __tN = …;` for each shared subexpression, in dependency order.
    pub lets: Vec<TokenStream>,
    /// Each output as an expression over symbols and temporaries.
    pub outputs: Vec<TokenStream>,
}

/// How generated code calls a table (docs/tables.md#errors-at-run-time): with `?` in the
/// methods that return a `Result` (a lookup outside the data is `SystemError::TableOutside`),
/// NaN on failure in the others.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lookups {
    /// `varmass_core::table::lookup(..)?`
    Fallible,
    /// `varmass_core::table::lookup_or_nan(..)`
    Nan,
}

/// Renders `roots` with their shared subexpressions hoisted into temporaries named
/// `__{prefix}{n}`.
pub(crate) fn block(
    pool: &ExprPool,
    roots: &[Id],
    prefix: &str,
    runtime: &TokenStream,
    lookups: Lookups,
) -> Block {
    let stage = Stage {
        first: &[],
        bound: &[],
        bridge: |_| Vec::new(),
    };
    staged_block(pool, stage, roots, prefix, runtime, lookups)
}

/// The first stage of a [`staged_block`]: `first` rendered, then `bridge` turns its values
/// into the `let`s that bind `bound`.
pub(crate) struct Stage<'a, F> {
    pub first: &'a [Id],
    pub bound: &'a [Symbol],
    pub bridge: F,
}

/// Like [`block`], with a first stage that binds symbols the outputs use: `first` is
/// rendered, then `bridge` turns its rendered values into the `let`s that bind `bound`
/// (q̇ in closed form, or an LDLᵀ solve of M q̇ = p − b). One CSE pass covers both
/// stages, so a subexpression of the first stage that the outputs need too (`cos(a - b)`,
/// an entry of M) is computed once: temporaries free of the bound symbols come first, then
/// the bridge, then the temporaries that use them.
pub(crate) fn staged_block(
    pool: &ExprPool,
    stage: Stage<'_, impl FnOnce(Vec<TokenStream>) -> Vec<TokenStream>>,
    roots: &[Id],
    prefix: &str,
    runtime: &TokenStream,
    lookups: Lookups,
) -> Block {
    let Stage {
        first,
        bound,
        bridge,
    } = stage;
    let mut all: Vec<Id> = first.to_vec();
    all.extend(roots);
    // One walk serves the CSE, the split into early and late, and the printing.
    let order = pool.reachable(&all, false);
    let late_ids = using_any(pool, &order, bound);
    let (late, early): (Vec<Id>, Vec<Id>) = pool
        .cse_in(&all, order.clone())
        .shared
        .into_iter()
        .partition(|id| late_ids.contains(id));
    // Early temporaries are numbered first, then late ones, each in id order.
    let names: FxHashMap<Id, String> = early
        .iter()
        .chain(&late)
        .enumerate()
        .map(|(n, id)| (*id, format!("__{prefix}{n}")))
        .collect();
    // One walk over everything: a shared node is printed once, bound to its temporary,
    // and printed by name wherever it is used above.
    let mut values: FxHashMap<Id, String> = FxHashMap::default();
    let syntax = RustSyntax {
        runtime: runtime.to_string(),
        lookups,
    };
    let mut printed = print_in(pool, &syntax, &all, order, |id, value| {
        let name = names.get(&id)?;
        values.insert(id, value.text.clone());
        Some(atom(name.clone()))
    })
    .into_iter()
    .map(|p| tokens(&p.text));
    let mut lets_of = |ids: &[Id]| -> TokenStream {
        let mut text = String::new();
        for id in ids {
            if let (Some(name), Some(value)) = (names.get(id), values.remove(id)) {
                text.push_str(&format!("let {name} = {value};\n"));
            }
        }
        tokens(&text)
    };
    let mut lets = vec![lets_of(&early)];
    let first_values = printed.by_ref().take(first.len()).collect();
    lets.extend(bridge(first_values));
    lets.push(lets_of(&late));
    let outputs = printed.collect();
    Block { lets, outputs }
}

/// The ids of `order` (ascending, closed under children) whose expression uses one of
/// `bound`, looking through defined symbols as [`ExprPool::contains`] does: one pass,
/// children before parents, instead of one walk per id and symbol.
fn using_any(pool: &ExprPool, order: &[Id], bound: &[Symbol]) -> FxHashSet<Id> {
    let mut using = FxHashSet::default();
    if bound.is_empty() {
        return using;
    }
    for &id in order {
        let uses = match pool.node(id) {
            Node::Sym(s) => {
                bound.contains(s)
                    || pool
                        .definition(*s)
                        .is_some_and(|v| bound.iter().any(|b| pool.contains(v, *b)))
            }
            node => node.children().any(|c| using.contains(&c)),
        };
        if uses {
            using.insert(id);
        }
    }
    using
}

/// Rust source text: `f64` arithmetic and methods (`.powi`, `.sqrt`, `.sin()`),
/// temporaries printed by name. Binary operators are spaced so that no two punctuation
/// marks lex as one (`- -x`, never `--x`).
struct RustSyntax {
    /// The path to the runtime, as text.
    runtime: String,
    /// How tables are called.
    lookups: Lookups,
}

type Rendered = Printed<String>;

fn atom(text: String) -> Rendered {
    Printed::new(text, Prec::Atom)
}

/// An `f64` literal as `proc_macro2::Literal::f64_suffixed` spells it (`2f64`, `0.5f64`).
fn float_literal(value: f64) -> Rendered {
    if value.is_nan() {
        return atom("f64::NAN".to_string());
    }
    if value.is_infinite() {
        return atom(if value > 0.0 {
            "f64::INFINITY".to_string()
        } else {
            "f64::NEG_INFINITY".to_string()
        });
    }
    let literal = format!("{}f64", value.abs());
    if value.is_sign_negative() && value != 0.0 {
        // A unary minus binds tighter than `*` (the `Power` level).
        Printed::new(format!("-{literal}"), Prec::Power)
    } else {
        atom(literal)
    }
}

impl Syntax for RustSyntax {
    fn group(&self, text: &str) -> String {
        format!("({text})")
    }

    fn number(&self, r: Rational) -> Rendered {
        float_literal(r.to_f64())
    }

    fn float(&self, x: f64) -> Rendered {
        float_literal(x)
    }

    fn symbol(&self, pool: &ExprPool, s: Symbol) -> Rendered {
        atom(symbol_name(pool, s))
    }

    fn call(&self, p: &Printer<'_>, func: Func, args: &[Id]) -> Rendered {
        let Some(first) = args.first() else {
            return atom("f64::NAN".to_string());
        };
        if let Func::Table { table, order } = func {
            let a = &p.get(*first).text;
            let table_static = super::tables::reference(p.pool(), table, order);
            let runtime = &self.runtime;
            return atom(match self.lookups {
                Lookups::Fallible => {
                    let name = p.pool().table_call_name(table, order);
                    format!("{runtime}::table::lookup(&{table_static}, {name:?}, {a})?")
                }
                Lookups::Nan => format!("{runtime}::table::lookup_or_nan(&{table_static}, {a})"),
            });
        }
        if let Func::Input { input, partial } = func {
            let args: Vec<&str> = args.iter().map(|a| p.get(*a).text.as_str()).collect();
            let args = args.join(", ");
            let name = p.pool().input_name(input);
            let alias = super::inputs::ALIAS;
            return atom(match partial.checked_sub(1) {
                None => format!("{alias}::{name}(self, {args})"),
                Some(j) => format!("{alias}::{name}_partials(self, {args})[{j}]"),
            });
        }
        // `f64::signum(0.0)` is 1, but the derivative of |x| needs sign(0) = 0.
        if func == Func::Sign {
            let a = &p.get(*first).text;
            return atom(format!("{}::math::sign({a})", self.runtime));
        }
        let receiver = self.at_least(p.get(*first), Prec::Atom);
        let method = func.name();
        match args.get(1).filter(|_| func.arity() == 2) {
            Some(second) => {
                let second = &p.get(*second).text;
                atom(format!("{receiver}.{method}({second})"))
            }
            None => atom(format!("{receiver}.{method}()")),
        }
    }

    fn product(&self, p: &Printer<'_>, factors: &[Id]) -> Rendered {
        match p.pool().as_rational(factors[0]) {
            Some(c) if c.numer() == -1 && c.denom() == 1 => {
                let rest = self.product_of(p, None, &factors[1..]);
                let rest = self.at_least(&rest, Prec::Power);
                Printed::new(format!("-{rest}"), Prec::Power)
            }
            Some(c) => self.product_of(p, Some(c.to_f64()), &factors[1..]),
            None => self.product_of(p, None, factors),
        }
    }

    fn power(&self, p: &Printer<'_>, base: Id, exponent: Id) -> Rendered {
        match p.pool().as_rational(exponent) {
            Some(e) if e.is_negative() => {
                let below = self.power_rational(p, base, Rational::new(-e.numer(), e.denom()));
                let below = self.at_least(&below, Prec::Atom);
                Printed::new(format!("1.0f64 / {below}"), Prec::Product)
            }
            Some(e) => self.power_rational(p, base, Some(e)),
            None => {
                let b = self.at_least(p.get(base), Prec::Atom);
                let e = &p.get(exponent).text;
                atom(format!("{b}.powf({e})"))
            }
        }
    }

    /// The terms in stored order; a term with a negative constant coefficient is printed
    /// after `-`.
    fn terms(&self, p: &Printer<'_>, terms: &[Id]) -> Vec<(Id, bool)> {
        terms
            .iter()
            .map(|t| (*t, self.split_sign(p, *t).is_some()))
            .collect()
    }

    fn negated(&self, p: &Printer<'_>, term: Id) -> Rendered {
        self.split_sign(p, term)
            .unwrap_or_else(|| p.get(term).clone())
    }

    fn lead(&self, p: &Printer<'_>, term: Id, negative: bool) -> String {
        if negative {
            let m = self.at_least(&self.negated(p, term), Prec::Product);
            format!("-{m}")
        } else {
            p.get(term).text.clone()
        }
    }
}

impl RustSyntax {
    /// The magnitude of a term with a negative constant coefficient (`-3*x` is `3*x`
    /// printed after `-`); `None` for any other term.
    fn split_sign(&self, p: &Printer<'_>, id: Id) -> Option<Rendered> {
        match p.pool().node(id) {
            Node::Num(r) if r.is_negative() => Some(float_literal(-r.to_f64())),
            Node::Mul(factors) if !p.is_bound(id) => match p.pool().as_rational(factors[0]) {
                Some(c) if c.is_negative() => {
                    Some(self.product_of(p, Some(-c.to_f64()), &factors[1..]))
                }
                _ => None,
            },
            _ => None,
        }
    }

    /// `coefficient * numerator / (denominator)`, with factors of negative constant
    /// exponent moved below the line.
    fn product_of(&self, p: &Printer<'_>, coefficient: Option<f64>, factors: &[Id]) -> Rendered {
        let mut numerator = Vec::new();
        let mut denominator = Vec::new();
        if let Some(c) = coefficient.filter(|c| *c != 1.0) {
            numerator.push(self.at_least(&float_literal(c), Prec::Power));
        }
        for f in factors {
            let below = match p.pool().node(*f) {
                Node::Pow(base, exponent) if !p.is_bound(*f) => p
                    .pool()
                    .as_rational(*exponent)
                    .filter(|e| e.is_negative())
                    .map(|e| (*base, e)),
                _ => None,
            };
            match below {
                Some((base, e)) => denominator.push(self.power_rational(
                    p,
                    base,
                    Rational::new(-e.numer(), e.denom()),
                )),
                None => numerator.push(self.at_least(p.get(*f), Prec::Power)),
            }
        }
        let numerator_text = if numerator.is_empty() {
            "1.0f64".to_string()
        } else {
            numerator.join(" * ")
        };
        if denominator.is_empty() {
            return Printed::new(numerator_text, Prec::Product);
        }
        let below = if denominator.len() == 1 {
            denominator
                .pop()
                .map(|d| self.at_least(&d, Prec::Atom))
                .unwrap_or_default()
        } else {
            let parts: Vec<String> = denominator
                .iter()
                .map(|d| self.at_least(d, Prec::Power))
                .collect();
            format!("({})", parts.join(" * "))
        };
        Printed::new(format!("{numerator_text} / {below}"), Prec::Product)
    }

    /// `base ^ e` for a constant exponent, with `e = 1` meaning the base itself.
    fn power_rational(&self, p: &Printer<'_>, base: Id, e: Option<Rational>) -> Rendered {
        let Some(e) = e else {
            return atom("f64::NAN".to_string());
        };
        let b = p.get(base);
        if e.is_one() {
            return b.clone();
        }
        let receiver = self.at_least(b, Prec::Atom);
        let text = match (e.numer(), e.denom()) {
            (1, 2) => format!("{receiver}.sqrt()"),
            (1, 3) => format!("{receiver}.cbrt()"),
            (n, 1) if i32::try_from(n).is_ok() => format!("{receiver}.powi({n})"),
            _ => {
                let e = self.at_least(&float_literal(e.to_f64()), Prec::Atom);
                format!("{receiver}.powf({e})")
            }
        };
        atom(text)
    }
}
