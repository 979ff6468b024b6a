//! Printing in the DSL's own syntax (SPEC §2), with minimal parentheses, so that the text
//! parses back to the same canonical expression. Also the views of sums and products
//! (signs pulled out, negative powers as denominators) shared with the LaTeX printer.

use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use super::rational::Rational;
use std::fmt;

/// How tightly a printed form binds; a child printed where a tighter form is needed is
/// parenthesised.
pub(crate) const SUM: u8 = 1;
pub(crate) const PRODUCT: u8 = 2;
pub(crate) const POWER: u8 = 3;
pub(crate) const ATOM: u8 = 4;

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
        f.write_str(&self.pool.dsl(self.id).0)
    }
}

fn wrap((text, precedence): (String, u8), at_least: u8) -> String {
    if precedence < at_least {
        format!("({text})")
    } else {
        text
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

    /// DSL text of `e` with its precedence.
    fn dsl(&self, e: Id) -> (String, u8) {
        match self.node(e) {
            Node::Num(r) => rational_text(*r),
            Node::Float(bits) => {
                let x = f64::from_bits(*bits);
                (float_literal(x), if x < 0.0 { SUM } else { ATOM })
            }
            Node::Sym(s) => (self.symbols().name(*s).to_owned(), ATOM),
            Node::Call(f, args) => {
                let args: Vec<String> = args.iter().map(|a| self.dsl(*a).0).collect();
                (format!("{}({})", f.name(), args.join(", ")), ATOM)
            }
            Node::Add(terms) => {
                let mut text = String::new();
                for (i, (t, negative)) in self.sum_view(terms).into_iter().enumerate() {
                    match (i, negative) {
                        (0, _) => text.push_str(&self.dsl(t).0),
                        // A term binds at least like a product, or it is parenthesised.
                        (_, true) => {
                            text.push_str(" - ");
                            text.push_str(&wrap(self.dsl_negated(t), PRODUCT));
                        }
                        (_, false) => {
                            text.push_str(" + ");
                            text.push_str(&wrap(self.dsl(t), PRODUCT));
                        }
                    }
                }
                (text, SUM)
            }
            Node::Mul(factors) => self.dsl_product(factors, false),
            Node::Pow(b, x) => {
                if self.exponent_is_negative(*x) {
                    let den = wrap(self.dsl_power(*b, Exponent::Negated(*x)), POWER);
                    (format!("1/{den}"), PRODUCT)
                } else {
                    self.dsl_power(*b, Exponent::Of(*x))
                }
            }
        }
    }

    /// DSL text of `-e` for a term with a negative coefficient.
    fn dsl_negated(&self, e: Id) -> (String, u8) {
        match self.node(e) {
            Node::Num(r) => rational_text(r.checked_abs().unwrap_or(*r)),
            Node::Float(bits) => (float_literal(f64::from_bits(*bits).abs()), ATOM),
            Node::Mul(factors) => self.dsl_product(factors, true),
            _ => (format!("-{}", wrap(self.dsl(e), POWER)), SUM),
        }
    }

    /// A product in DSL text. The text is read back left to right, and a number times a
    /// lone sum distributes when it is built (`2*(x + 1)` is `2*x + 2`), so the text never
    /// lets the coefficient (or sign) meet a lone sum first: `-((a + b)*(c + d))`,
    /// `3*((a + b)/m)`, `x/((a + b)*(c + d))/2` rather than `-(a + b)*(c + d)`,
    /// `3*(a + b)/m`, `x/(2*(a + b)*(c + d))`.
    fn dsl_product(&self, factors: &[Id], negate: bool) -> (String, u8) {
        let view = self.product_view(factors, negate);
        if let ([single], [], false) = (
            view.numerator.as_slice(),
            view.denominator.as_slice(),
            view.negative,
        ) {
            if view.coefficient.is_one() {
                return self.dsl(*single);
            }
        }
        let (numerator_number, denominator_number) = match view.coefficient {
            Number::Exact(r) => (
                (r.numer() != 1).then(|| r.numer().to_string()),
                (r.denom() != 1).then(|| r.denom().to_string()),
            ),
            Number::Inexact(x) => ((x != 1.0).then(|| float_literal(x)), None),
        };
        let is_sum = |e: &Id| matches!(self.node(*e), Node::Add(_));
        let numerator: Vec<String> = view
            .numerator
            .iter()
            .map(|f| wrap(self.dsl(*f), POWER))
            .collect();
        // Read left to right, `(2*(a + b)*m)` would distribute the 2 first: bare sums go
        // last in a denominator, and a number goes after them if nothing else is there.
        let bare_sum = |(b, x): &(Id, Exponent)| {
            is_sum(b) && self.exponent_value(*x).is_some_and(Number::is_one)
        };
        let (sums, others): (Vec<&(Id, Exponent)>, Vec<_>) =
            view.denominator.iter().partition(|d| bare_sum(d));
        let only_sums_below = others.is_empty() && !sums.is_empty();
        let denominator: Vec<String> = others
            .into_iter()
            .chain(sums)
            .map(|d| wrap(self.dsl_power(d.0, d.1), POWER))
            .collect();
        let scaled = view.negative || numerator_number.is_some() || denominator_number.is_some();
        let only_sums = !view.numerator.is_empty() && view.numerator.iter().all(is_sum);

        let mut text = String::new();
        if view.negative {
            text.push('-');
        }
        let mut trailing_number = denominator_number.clone();
        if scaled && only_sums {
            // Group everything that is not a number, then apply the number to the group.
            if let Some(n) = &numerator_number {
                text.push_str(n);
                text.push('*');
            }
            text.push('(');
            text.push_str(&numerator.join("*"));
            push_denominator(&mut text, &denominator);
            text.push(')');
        } else {
            let mut parts: Vec<String> = numerator_number.into_iter().collect();
            parts.extend(numerator);
            if parts.is_empty() {
                text.push('1');
            } else {
                text.push_str(&parts.join("*"));
            }
            match (&denominator_number, only_sums_below) {
                (Some(d), false) => {
                    let mut all = vec![d.clone()];
                    all.extend(denominator);
                    push_denominator(&mut text, &all);
                    trailing_number = None;
                }
                _ => push_denominator(&mut text, &denominator),
            }
        }
        if let Some(d) = trailing_number {
            text.push('/');
            text.push_str(&d);
        }
        (text, if view.negative { SUM } else { PRODUCT })
    }

    /// `b^x` with `x` as printed: `b` alone for 1, `sqrt(b)` for 1/2.
    fn dsl_power(&self, b: Id, x: Exponent) -> (String, u8) {
        match self.exponent_value(x) {
            Some(n) if n.is_one() => return self.dsl(b),
            Some(Number::Exact(r)) if r == Rational::HALF => {
                return (format!("sqrt({})", self.dsl(b).0), ATOM)
            }
            _ => {}
        }
        let exponent = match x {
            Exponent::Of(x) => self.dsl(x),
            Exponent::Negated(x) => self.dsl_negated(x),
        };
        let text = format!("{}^{}", wrap(self.dsl(b), ATOM), wrap(exponent, POWER));
        (text, POWER)
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

fn rational_text(r: Rational) -> (String, u8) {
    let precedence = if r.is_negative() {
        SUM
    } else if r.denom() != 1 {
        PRODUCT
    } else {
        ATOM
    };
    (r.to_string(), precedence)
}
