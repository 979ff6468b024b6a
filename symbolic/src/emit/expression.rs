//! Expressions as Rust: straight-line `let`s for the shared subexpressions of a set of
//! outputs, then each output as one expression.
//!
//! The arena makes common-subexpression elimination exact and cheap: equal subexpressions
//! are one node, so a node reached more than once from the outputs is computed once into a
//! temporary. Children have smaller ids than parents, so ascending ids are a valid order.

use std::collections::HashMap;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

use crate::expr::{ExprPool, Func, Id, Node, Rational, Symbol, SymbolKind};

/// The Rust local that holds a symbol's value in generated code.
pub(crate) fn symbol_ident(pool: &ExprPool, s: Symbol) -> Ident {
    let table = pool.symbols();
    let name = match table.kind(s) {
        SymbolKind::Velocity { coordinate } => format!("{}_dot", table.name(coordinate)),
        SymbolKind::Acceleration { coordinate } => format!("{}_ddot", table.name(coordinate)),
        SymbolKind::Momentum { coordinate } => format!("p_{}", table.name(coordinate)),
        _ => table.name(s).to_string(),
    };
    Ident::new(&name, Span::call_site())
}

/// Straight-line code for a set of outputs.
pub(crate) struct Block {
    /// `let __tN = …;` for each shared subexpression, in dependency order.
    pub lets: Vec<TokenStream>,
    /// Each output as an expression over symbols and temporaries.
    pub outputs: Vec<TokenStream>,
}

/// Precedence of rendered code, to parenthesise only where Rust needs it.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    Sum,
    Product,
    Unary,
    Atom,
}

struct Rendered {
    tokens: TokenStream,
    prec: Prec,
}

impl Rendered {
    fn at_least(self, prec: Prec) -> TokenStream {
        let tokens = self.tokens;
        if self.prec >= prec {
            tokens
        } else {
            quote!((#tokens))
        }
    }
}

/// Renders `roots` with their shared subexpressions hoisted into temporaries named
/// `__{prefix}{n}`.
pub(crate) fn block(pool: &ExprPool, roots: &[Id], prefix: &str, runtime: &TokenStream) -> Block {
    staged_block(pool, &[], &[], |_| Vec::new(), roots, prefix, runtime)
}

/// Like [`block`], with a first stage that binds symbols the outputs use: `first` is
/// rendered, then `bridge` turns its rendered values into the `let`s that bind `bound`
/// (q̇ in closed form, or a Cholesky solve of M q̇ = p − b). One CSE pass covers both
/// stages, so a subexpression of the first stage that the outputs need too (`cos(a - b)`,
/// an entry of M) is computed once: temporaries free of the bound symbols come first, then
/// the bridge, then the temporaries that use them.
pub(crate) fn staged_block(
    pool: &ExprPool,
    first: &[Id],
    bound: &[Symbol],
    bridge: impl FnOnce(Vec<TokenStream>) -> Vec<TokenStream>,
    roots: &[Id],
    prefix: &str,
    runtime: &TokenStream,
) -> Block {
    let mut all: Vec<Id> = first.to_vec();
    all.extend(roots);
    let (late, early): (Vec<Id>, Vec<Id>) = pool
        .cse(&all)
        .shared
        .into_iter()
        .partition(|id| bound.iter().any(|s| pool.contains(*id, *s)));
    let mut renderer = Renderer {
        pool,
        temps: HashMap::new(),
        runtime,
    };
    let mut lets = Vec::new();
    let mut counter = 0usize;
    let mut hoist = |renderer: &mut Renderer, ids: &[Id], lets: &mut Vec<TokenStream>| {
        for id in ids {
            let value = renderer.render(*id).tokens;
            let name = format_ident!("__{}{}", prefix, counter);
            counter += 1;
            lets.push(quote!(let #name = #value;));
            renderer.temps.insert(*id, name);
        }
    };
    hoist(&mut renderer, &early, &mut lets);
    let first_values = first.iter().map(|e| renderer.render(*e).tokens).collect();
    lets.extend(bridge(first_values));
    hoist(&mut renderer, &late, &mut lets);
    let outputs = roots.iter().map(|r| renderer.render(*r).tokens).collect();
    Block { lets, outputs }
}

struct Renderer<'a> {
    pool: &'a ExprPool,
    temps: HashMap<Id, Ident>,
    runtime: &'a TokenStream,
}

fn float_literal(value: f64) -> Rendered {
    if value.is_nan() {
        return Rendered {
            tokens: quote!(f64::NAN),
            prec: Prec::Atom,
        };
    }
    if value.is_infinite() {
        let tokens = if value > 0.0 {
            quote!(f64::INFINITY)
        } else {
            quote!(f64::NEG_INFINITY)
        };
        return Rendered {
            tokens,
            prec: Prec::Atom,
        };
    }
    let literal = Literal::f64_suffixed(value.abs());
    if value.is_sign_negative() && value != 0.0 {
        Rendered {
            tokens: quote!(-#literal),
            prec: Prec::Unary,
        }
    } else {
        Rendered {
            tokens: quote!(#literal),
            prec: Prec::Atom,
        }
    }
}

impl Renderer<'_> {
    fn render(&self, id: Id) -> Rendered {
        if let Some(name) = self.temps.get(&id) {
            return Rendered {
                tokens: quote!(#name),
                prec: Prec::Atom,
            };
        }
        match self.pool.node(id) {
            Node::Num(r) => float_literal(r.to_f64()),
            Node::Float(bits) => float_literal(f64::from_bits(*bits)),
            Node::Sym(s) => {
                let name = symbol_ident(self.pool, *s);
                Rendered {
                    tokens: quote!(#name),
                    prec: Prec::Atom,
                }
            }
            Node::Add(terms) => self.sum(terms),
            Node::Mul(factors) => self.product(factors),
            Node::Pow(base, exponent) => self.power(*base, *exponent),
            Node::Call(func, args) => self.call(*func, args),
        }
    }

    fn rational(&self, id: Id) -> Option<Rational> {
        match self.pool.node(id) {
            Node::Num(r) => Some(*r),
            _ => None,
        }
    }

    /// A term's sign and magnitude: `-3*x` renders as `- 3*x` inside a sum.
    fn split_sign(&self, id: Id) -> (bool, Option<Rendered>) {
        match self.pool.node(id) {
            Node::Num(r) if r.is_negative() => (true, Some(float_literal(-r.to_f64()))),
            Node::Mul(factors) if !self.temps.contains_key(&id) => {
                match self.rational(factors[0]) {
                    Some(c) if c.is_negative() => {
                        let magnitude = -c.to_f64();
                        let rest = self.product_of(Some(magnitude), &factors[1..]);
                        (true, Some(rest))
                    }
                    _ => (false, None),
                }
            }
            _ => (false, None),
        }
    }

    fn sum(&self, terms: &[Id]) -> Rendered {
        let mut tokens = TokenStream::new();
        for (i, term) in terms.iter().enumerate() {
            let (negative, magnitude) = self.split_sign(*term);
            match (i, negative, magnitude) {
                (0, true, Some(m)) => {
                    let m = m.at_least(Prec::Product);
                    tokens.extend(quote!(-#m));
                }
                (_, true, Some(m)) => {
                    let m = m.at_least(Prec::Product);
                    tokens.extend(quote!(- #m));
                }
                (0, _, _) => tokens.extend(self.render(*term).at_least(Prec::Sum)),
                _ => {
                    let t = self.render(*term).at_least(Prec::Product);
                    tokens.extend(quote!(+ #t));
                }
            }
        }
        Rendered {
            tokens,
            prec: Prec::Sum,
        }
    }

    fn product(&self, factors: &[Id]) -> Rendered {
        match self.rational(factors[0]) {
            Some(c) if c.numer() == -1 && c.denom() == 1 => {
                let rest = self.product_of(None, &factors[1..]).at_least(Prec::Unary);
                Rendered {
                    tokens: quote!(-#rest),
                    prec: Prec::Unary,
                }
            }
            Some(c) => self.product_of(Some(c.to_f64()), &factors[1..]),
            None => self.product_of(None, factors),
        }
    }

    /// `coefficient * numerator / (denominator)`, with factors of negative constant
    /// exponent moved below the line.
    fn product_of(&self, coefficient: Option<f64>, factors: &[Id]) -> Rendered {
        let mut numerator = Vec::new();
        let mut denominator = Vec::new();
        if let Some(c) = coefficient.filter(|c| *c != 1.0) {
            numerator.push(float_literal(c).at_least(Prec::Unary));
        }
        for f in factors {
            match self.pool.node(*f) {
                Node::Pow(base, exponent) if !self.temps.contains_key(f) => match self
                    .rational(*exponent)
                {
                    Some(e) if e.is_negative() => {
                        denominator
                            .push(self.power_rational(*base, Rational::new(-e.numer(), e.denom())));
                    }
                    _ => numerator.push(self.render(*f).at_least(Prec::Unary)),
                },
                _ => numerator.push(self.render(*f).at_least(Prec::Unary)),
            }
        }
        let numerator_tokens = if numerator.is_empty() {
            quote!(1.0f64)
        } else {
            let mut t = TokenStream::new();
            for (i, n) in numerator.into_iter().enumerate() {
                if i > 0 {
                    t.extend(quote!(*));
                }
                t.extend(n);
            }
            t
        };
        if denominator.is_empty() {
            return Rendered {
                tokens: numerator_tokens,
                prec: Prec::Product,
            };
        }
        let below = if denominator.len() == 1 {
            denominator
                .pop()
                .map(|d| d.at_least(Prec::Atom))
                .unwrap_or_default()
        } else {
            let mut t = TokenStream::new();
            for (i, d) in denominator.into_iter().enumerate() {
                if i > 0 {
                    t.extend(quote!(*));
                }
                t.extend(d.at_least(Prec::Unary));
            }
            quote!((#t))
        };
        Rendered {
            tokens: quote!(#numerator_tokens / #below),
            prec: Prec::Product,
        }
    }

    /// `base ^ e` for a constant exponent, with `e = 1` meaning the base itself.
    fn power_rational(&self, base: Id, e: Option<Rational>) -> Rendered {
        let Some(e) = e else {
            return Rendered {
                tokens: quote!(f64::NAN),
                prec: Prec::Atom,
            };
        };
        let b = self.render(base);
        if e.is_one() {
            return b;
        }
        let receiver = b.at_least(Prec::Atom);
        let tokens = match (e.numer(), e.denom()) {
            (1, 2) => quote!(#receiver.sqrt()),
            (1, 3) => quote!(#receiver.cbrt()),
            (n, 1) if i32::try_from(n).is_ok() => {
                let n = Literal::i32_unsuffixed(n as i32);
                quote!(#receiver.powi(#n))
            }
            _ => {
                let e = float_literal(e.to_f64()).at_least(Prec::Atom);
                quote!(#receiver.powf(#e))
            }
        };
        Rendered {
            tokens,
            prec: Prec::Atom,
        }
    }

    fn power(&self, base: Id, exponent: Id) -> Rendered {
        match self.rational(exponent) {
            Some(e) if e.is_negative() => {
                let below = self
                    .power_rational(base, Rational::new(-e.numer(), e.denom()))
                    .at_least(Prec::Atom);
                Rendered {
                    tokens: quote!(1.0f64 / #below),
                    prec: Prec::Product,
                }
            }
            Some(e) => self.power_rational(base, Some(e)),
            None => {
                let b = self.render(base).at_least(Prec::Atom);
                let e = self.render(exponent).tokens;
                Rendered {
                    tokens: quote!(#b.powf(#e)),
                    prec: Prec::Atom,
                }
            }
        }
    }

    fn call(&self, func: Func, args: &[Id]) -> Rendered {
        let runtime = self.runtime;
        let arg = |i: usize| self.render(args[i]).at_least(Prec::Atom);
        let tokens = match func {
            Func::Sin => {
                let a = arg(0);
                quote!(#a.sin())
            }
            Func::Cos => {
                let a = arg(0);
                quote!(#a.cos())
            }
            Func::Tan => {
                let a = arg(0);
                quote!(#a.tan())
            }
            Func::Exp => {
                let a = arg(0);
                quote!(#a.exp())
            }
            Func::Ln => {
                let a = arg(0);
                quote!(#a.ln())
            }
            Func::Abs => {
                let a = arg(0);
                quote!(#a.abs())
            }
            Func::Tanh => {
                let a = arg(0);
                quote!(#a.tanh())
            }
            Func::Sinh => {
                let a = arg(0);
                quote!(#a.sinh())
            }
            Func::Cosh => {
                let a = arg(0);
                quote!(#a.cosh())
            }
            Func::Asin => {
                let a = arg(0);
                quote!(#a.asin())
            }
            Func::Acos => {
                let a = arg(0);
                quote!(#a.acos())
            }
            Func::Atan => {
                let a = arg(0);
                quote!(#a.atan())
            }
            // `f64::signum(0.0)` is 1, but the derivative of |x| needs sign(0) = 0.
            Func::Sign => {
                let a = self.render(args[0]).tokens;
                quote!(#runtime::math::sign(#a))
            }
            Func::Atan2 => {
                let (y, x) = (arg(0), self.render(args[1]).tokens);
                quote!(#y.atan2(#x))
            }
            Func::Min => {
                let (a, b) = (arg(0), self.render(args[1]).tokens);
                quote!(#a.min(#b))
            }
            Func::Max => {
                let (a, b) = (arg(0), self.render(args[1]).tokens);
                quote!(#a.max(#b))
            }
        };
        Rendered {
            tokens,
            prec: Prec::Atom,
        }
    }
}
