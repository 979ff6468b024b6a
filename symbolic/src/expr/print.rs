//! Printing in the DSL's own syntax (see `docs/dsl.md`), with minimal parentheses, so that
//! the text parses back to the same canonical expression: the [`Syntax`] of DSL text for
//! the shared walk. Also the views of sums and products (signs pulled out, negative powers
//! as denominators) shared with the LaTeX printer.

use std::fmt;

use super::func::Func;
use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use super::rational::Rational;
use super::symbol::Symbol;
use super::walk::{print, print_all, Prec, Printed, Printer, Syntax};

/// The exponent of a power as printed: either the node itself or its negation (a negative
/// power printed as a denominator).
#[derive(Clone, Copy)]
pub(crate) enum Exponent {
    Of(Id),
    Negated(Id),
}

/// A product as printed: `sign coefficient·numerator / denominator`.
pub(crate) struct ProductView {
    pub(crate) negative: bool,
    /// |coefficient|.
    pub(crate) coefficient: Number,
    pub(crate) numerator: Vec<Id>,
    /// Bases with their (positive) exponents.
    pub(crate) denominator: Vec<(Id, Exponent)>,
}

/// `e` displayed in DSL syntax; see [`ExprPool::display`].
pub struct DisplayExpr<'a> {
    pool: &'a ExprPool,
    id: Id,
}

impl fmt::Display for DisplayExpr<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&print(self.pool, &Dsl, self.id).text)
    }
}

/// An inexact constant as a literal the DSL reads back to the same `f64` (Rust prints the
/// shortest round-trip form).
pub(crate) fn float_literal(x: f64) -> String {
    format!("{x:?}")
}

impl ExprPool {
    /// `e` in DSL syntax (`x'`, `^`, `sqrt(...)`, `a/b` for negative powers, `-` for
    /// negative coefficients), with minimal parentheses. The text parses back to the same
    /// canonical expression (inexact constants to the same value).
    pub fn display(&self, e: Id) -> DisplayExpr<'_> {
        DisplayExpr { pool: self, id: e }
    }

    /// The [`display`](Self::display) text of each of `roots`, from one walk: a
    /// subexpression shared by several roots is printed once.
    pub fn display_all(&self, roots: &[Id]) -> Vec<String> {
        let printed = print_all(self, &Dsl, roots, |_, _| None);
        printed.into_iter().map(|p| p.text).collect()
    }

    /// Whether the exponent `x` is negative as printed (a negative constant, or a product
    /// with a negative coefficient).
    pub(crate) fn exponent_is_negative(&self, x: Id) -> bool {
        self.has_negative_coefficient(x)
    }

    /// The terms of a sum in print order (the constant last), each with its sign.
    pub(crate) fn sum_view(&self, terms: &[Id]) -> Vec<(Id, bool)> {
        let mut view: Vec<(Id, bool)> = terms
            .iter()
            .map(|t| (*t, self.has_negative_coefficient(*t)))
            .collect();
        // The constant is stored first; `x - 1` reads better than `-1 + x`.
        let constant_first = terms
            .first()
            .is_some_and(|t| self.node(*t).number().is_some());
        if view.len() > 1 && constant_first {
            view.rotate_left(1);
        }
        // Lead with a positive term when there is one: `g - x`, not `-x + g`.
        if let Some(i) = view.iter().position(|(_, negative)| !negative) {
            let lead = view.remove(i);
            view.insert(0, lead);
        }
        view
    }

    /// A product's factors split into sign, |coefficient|, numerator and denominator.
    /// `negate` flips the sign (to print a negative term after ` - `).
    pub(crate) fn product_view(&self, factors: &[Id], negate: bool) -> ProductView {
        let mut coefficient = Number::ONE;
        let mut numerator = Vec::new();
        let mut denominator = Vec::new();
        for &f in factors {
            match self.node(f) {
                Node::Num(_) | Node::Float(_) => {
                    if let Some(n) = self.node(f).number() {
                        coefficient = coefficient.mul(n);
                    }
                }
                Node::Pow(b, x) if self.exponent_is_negative(*x) => {
                    denominator.push((*b, Exponent::Negated(*x)));
                }
                _ => numerator.push(f),
            }
        }
        let negative = coefficient.is_negative() != negate;
        let coefficient = match coefficient {
            Number::Exact(r) => Number::Exact(r.checked_abs().unwrap_or(r)),
            Number::Inexact(x) => Number::Inexact(x.abs()),
        };
        ProductView {
            negative,
            coefficient,
            numerator,
            denominator,
        }
    }

    /// The value of a printed exponent, if it is a constant.
    pub(crate) fn exponent_value(&self, x: Exponent) -> Option<Number> {
        match x {
            Exponent::Of(x) => self.node(x).number(),
            Exponent::Negated(x) => self
                .node(x)
                .number()
                .map(|n| n.mul(Number::Exact(Rational::MINUS_ONE))),
        }
    }
}

/// DSL text: `x'`, `^`, `sqrt(...)`, `a/b`, `-`.
struct Dsl;

/// A printed form of the text printers.
pub(crate) type PrintedText = Printed<String>;

impl Syntax for Dsl {
    fn group(&self, text: &str) -> String {
        format!("({text})")
    }

    fn number(&self, r: Rational) -> PrintedText {
        rational_text(r)
    }

    fn float(&self, x: f64) -> PrintedText {
        let prec = if x < 0.0 { Prec::Sum } else { Prec::Atom };
        Printed::new(float_literal(x), prec)
    }

    fn symbol(&self, pool: &ExprPool, s: Symbol) -> PrintedText {
        Printed::new(pool.symbols().name(s).to_owned(), Prec::Atom)
    }

    fn call(&self, p: &Printer<'_>, f: Func, args: &[Id]) -> PrintedText {
        let args: Vec<&str> = args.iter().map(|a| p.get(*a).text.as_str()).collect();
        let name = match f {
            Func::Table { table, order } => p.pool().table_call_name(table, order),
            Func::Input { input, partial } => p.pool().input_call_name(input, partial),
            _ => f.name().to_owned(),
        };
        Printed::new(format!("{name}({})", args.join(", ")), Prec::Atom)
    }

    fn product(&self, p: &Printer<'_>, factors: &[Id]) -> PrintedText {
        self.product_of(p, factors, false)
    }

    fn power(&self, p: &Printer<'_>, b: Id, x: Id) -> PrintedText {
        if p.pool().exponent_is_negative(x) {
            let den = self.at_least(&self.power_of(p, b, Exponent::Negated(x)), Prec::Power);
            Printed::new(format!("1/{den}"), Prec::Product)
        } else {
            self.power_of(p, b, Exponent::Of(x))
        }
    }

    /// DSL text of `-e` for a term with a negative coefficient.
    fn negated(&self, p: &Printer<'_>, e: Id) -> PrintedText {
        match p.pool().node(e) {
            Node::Num(r) => rational_text(r.checked_abs().unwrap_or(*r)),
            Node::Float(bits) => {
                Printed::new(float_literal(f64::from_bits(*bits).abs()), Prec::Atom)
            }
            Node::Mul(factors) => self.product_of(p, factors, true),
            _ => Printed::new(
                format!("-{}", self.at_least(p.get(e), Prec::Power)),
                Prec::Sum,
            ),
        }
    }
}

impl Dsl {
    /// A product in DSL text. The text is read back left to right, and a number times a
    /// lone sum distributes when it is built (`2*(x + 1)` is `2*x + 2`), so the text never
    /// lets the coefficient (or sign) meet a lone sum first: `-((a + b)*(c + d))`,
    /// `3*((a + b)/m)`, `x/((a + b)*(c + d))/2` rather than `-(a + b)*(c + d)`,
    /// `3*(a + b)/m`, `x/(2*(a + b)*(c + d))`.
    fn product_of(&self, p: &Printer<'_>, factors: &[Id], negate: bool) -> PrintedText {
        let pool = p.pool();
        let view = pool.product_view(factors, negate);
        if let ([single], [], false) = (
            view.numerator.as_slice(),
            view.denominator.as_slice(),
            view.negative,
        ) {
            if view.coefficient.is_one() {
                return p.get(*single).clone();
            }
        }
        let (numerator_number, denominator_number) = match view.coefficient {
            Number::Exact(r) => (
                (r.numer() != 1).then(|| r.numer().to_string()),
                (r.denom() != 1).then(|| r.denom().to_string()),
            ),
            Number::Inexact(x) => ((x != 1.0).then(|| float_literal(x)), None),
        };
        let is_sum = |e: &Id| matches!(pool.node(*e), Node::Add(_));
        let numerator: Vec<String> = view
            .numerator
            .iter()
            .map(|f| self.at_least(p.get(*f), Prec::Power))
            .collect();
        // Read left to right, `(2*(a + b)*m)` would distribute the 2 first: bare sums go
        // last in a denominator, and a number goes after them if nothing else is there.
        let bare_sum = |(b, x): &(Id, Exponent)| {
            is_sum(b) && pool.exponent_value(*x).is_some_and(Number::is_one)
        };
        let (sums, others): (Vec<&(Id, Exponent)>, Vec<_>) =
            view.denominator.iter().partition(|d| bare_sum(d));
        let only_sums_below = others.is_empty() && !sums.is_empty();
        let denominator: Vec<String> = others
            .into_iter()
            .chain(sums)
            .map(|d| self.at_least(&self.power_of(p, d.0, d.1), Prec::Power))
            .collect();
        let scaled = view.negative || numerator_number.is_some() || denominator_number.is_some();
        let only_sums = !view.numerator.is_empty() && view.numerator.iter().all(is_sum);
        let parts = ProductParts {
            numerator_number,
            denominator_number,
            numerator,
            denominator,
        };
        let text = parts.text(view.negative, scaled && only_sums, only_sums_below);
        let prec = if view.negative {
            Prec::Sum
        } else {
            Prec::Product
        };
        Printed::new(text, prec)
    }

    /// `b^x` with `x` as printed: `b` alone for 1, `sqrt(b)` for 1/2.
    fn power_of(&self, p: &Printer<'_>, b: Id, x: Exponent) -> PrintedText {
        match p.pool().exponent_value(x) {
            Some(n) if n.is_one() => return p.get(b).clone(),
            Some(Number::Exact(r)) if r == Rational::HALF => {
                return Printed::new(format!("sqrt({})", p.get(b).text), Prec::Atom)
            }
            _ => {}
        }
        let exponent = match x {
            Exponent::Of(x) => p.get(x).clone(),
            Exponent::Negated(x) => self.negated(p, x),
        };
        let text = format!(
            "{}^{}",
            self.at_least(p.get(b), Prec::Atom),
            self.at_least(&exponent, Prec::Power)
        );
        Printed::new(text, Prec::Power)
    }
}

/// The printed pieces of a product in DSL text.
struct ProductParts {
    numerator_number: Option<String>,
    denominator_number: Option<String>,
    numerator: Vec<String>,
    denominator: Vec<String>,
}

impl ProductParts {
    /// `-n*(a*b/c)/d` when `grouped` (a scaled product of sums only), else
    /// `-n*a*b/(d*c)`, with a lone-sum denominator keeping its number last.
    fn text(self, negative: bool, grouped: bool, only_sums_below: bool) -> String {
        let mut text = String::new();
        if negative {
            text.push('-');
        }
        let mut trailing_number = self.denominator_number.clone();
        if grouped {
            // Group everything that is not a number, then apply the number to the group.
            if let Some(n) = &self.numerator_number {
                text.push_str(n);
                text.push('*');
            }
            text.push('(');
            text.push_str(&self.numerator.join("*"));
            push_denominator(&mut text, &self.denominator);
            text.push(')');
        } else {
            let mut parts: Vec<String> = self.numerator_number.into_iter().collect();
            parts.extend(self.numerator);
            if parts.is_empty() {
                text.push('1');
            } else {
                text.push_str(&parts.join("*"));
            }
            match (&self.denominator_number, only_sums_below) {
                (Some(d), false) => {
                    let mut all = vec![d.clone()];
                    all.extend(self.denominator);
                    push_denominator(&mut text, &all);
                    trailing_number = None;
                }
                _ => push_denominator(&mut text, &self.denominator),
            }
        }
        if let Some(d) = trailing_number {
            text.push('/');
            text.push_str(&d);
        }
        text
    }
}

/// Appends `/d` or `/(d1*d2*…)`.
fn push_denominator(text: &mut String, parts: &[String]) {
    match parts {
        [] => {}
        [single] => {
            text.push('/');
            text.push_str(single);
        }
        many => {
            text.push_str("/(");
            text.push_str(&many.join("*"));
            text.push(')');
        }
    }
}

fn rational_text(r: Rational) -> Printed<String> {
    let prec = if r.is_negative() {
        Prec::Sum
    } else if r.denom() != 1 {
        Prec::Product
    } else {
        Prec::Atom
    };
    Printed::new(r.to_string(), prec)
}
