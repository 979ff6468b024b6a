//! LaTeX rendering for the derivation the system exposes (SPEC §3): `\frac`, `\dot{x}`,
//! greek names, subscripts from `m0` and `u_e`, `\sin`, `\sqrt`, `\left( \right)`.

use super::func::Func;
use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use super::print::{float_literal, Exponent, ATOM, POWER, PRODUCT, SUM};
use super::rational::Rational;
use super::symbol::{Symbol, SymbolKind};

const GREEK: &[&str] = &[
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "varepsilon",
    "zeta",
    "eta",
    "theta",
    "vartheta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "pi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "varphi",
    "chi",
    "psi",
    "omega",
    "Gamma",
    "Delta",
    "Theta",
    "Lambda",
    "Xi",
    "Pi",
    "Sigma",
    "Upsilon",
    "Phi",
    "Psi",
    "Omega",
];

/// One part of a name: a greek letter, a single letter, or an upright word.
fn name_part(part: &str) -> String {
    if GREEK.contains(&part) {
        format!("\\{part}")
    } else if part.chars().count() <= 1 || part.bytes().all(|b| b.is_ascii_digit()) {
        part.to_owned()
    } else {
        format!("\\mathrm{{{part}}}")
    }
}

/// `theta` → `\theta`, `m0` → `m_{0}`, `u_e` → `u_{e}`, `p_theta` → `p_{\theta}`.
fn name_tex(name: &str) -> String {
    let (head, tail) = name.split_once('_').unwrap_or((name, ""));
    // Trailing digits of the head are a subscript too: m0, theta12.
    let stem = head.trim_end_matches(|c: char| c.is_ascii_digit());
    let (stem, digits) = if stem.is_empty() {
        (head, "")
    } else {
        (stem, &head[stem.len()..])
    };
    let mut subscript: Vec<String> = Vec::new();
    if !digits.is_empty() {
        subscript.push(digits.to_owned());
    }
    subscript.extend(tail.split('_').filter(|p| !p.is_empty()).map(name_part));
    let base = name_part(stem);
    if subscript.is_empty() {
        base
    } else {
        format!("{base}_{{{}}}", subscript.join(","))
    }
}

fn wrap((text, precedence): (String, u8), at_least: u8) -> String {
    if precedence < at_least {
        format!("\\left({text}\\right)")
    } else {
        text
    }
}

fn rational_tex(r: Rational) -> (String, u8) {
    let magnitude = r.checked_abs().unwrap_or(r);
    let text = if magnitude.denom() == 1 {
        magnitude.numer().to_string()
    } else {
        format!("\\frac{{{}}}{{{}}}", magnitude.numer(), magnitude.denom())
    };
    if r.is_negative() {
        (format!("-{text}"), SUM)
    } else if r.denom() != 1 {
        (text, PRODUCT)
    } else {
        (text, ATOM)
    }
}

fn float_tex(x: f64) -> (String, u8) {
    let text = float_literal(x);
    let (text, precedence) = match text.split_once('e') {
        Some(("1", exponent)) => (format!("10^{{{exponent}}}"), POWER),
        Some((mantissa, exponent)) => (format!("{mantissa} \\times 10^{{{exponent}}}"), POWER),
        None => (text, ATOM),
    };
    (text, if x < 0.0 { SUM } else { precedence })
}

/// Joins the factors of a product: a space, or `\cdot` before a digit.
fn join_factors(parts: &[String]) -> String {
    let mut out = String::new();
    for (i, p) in parts.iter().enumerate() {
        if i > 0 {
            let digit = p.starts_with(|c: char| c.is_ascii_digit());
            out.push_str(if digit { " \\cdot " } else { " " });
        }
        out.push_str(p);
    }
    out
}

impl ExprPool {
    /// `e` in LaTeX (math mode, without delimiters).
    pub fn latex(&self, e: Id) -> String {
        self.tex(e).0
    }

    /// The LaTeX of a symbol: `\dot{x}` for x', `\ddot{x}` for x'', else from its name.
    pub fn latex_symbol(&self, s: Symbol) -> String {
        match self.symbols().kind(s) {
            SymbolKind::Velocity { coordinate } => {
                format!("\\dot{{{}}}", self.latex_symbol(coordinate))
            }
            SymbolKind::Acceleration { coordinate } => {
                format!("\\ddot{{{}}}", self.latex_symbol(coordinate))
            }
            _ => name_tex(self.symbols().name(s)),
        }
    }

    fn tex(&self, e: Id) -> (String, u8) {
        match self.node(e) {
            Node::Num(r) => rational_tex(*r),
            Node::Float(bits) => float_tex(f64::from_bits(*bits)),
            Node::Sym(s) => (self.latex_symbol(*s), ATOM),
            Node::Call(f, args) => self.tex_call(*f, args, None),
            Node::Add(terms) => {
                let mut text = String::new();
                for (i, (t, negative)) in self.sum_view(terms).into_iter().enumerate() {
                    match (i, negative) {
                        (0, _) => text.push_str(&self.tex(t).0),
                        // A term binds at least like a product, or it is parenthesised.
                        (_, true) => {
                            text.push_str(" - ");
                            text.push_str(&wrap(self.tex_negated(t), PRODUCT));
                        }
                        (_, false) => {
                            text.push_str(" + ");
                            text.push_str(&wrap(self.tex(t), PRODUCT));
                        }
                    }
                }
                (text, SUM)
            }
            Node::Mul(factors) => self.tex_product(factors, false),
            Node::Pow(b, x) => {
                if self.exponent_is_negative(*x) {
                    let den = self.tex_power(*b, Exponent::Negated(*x)).0;
                    (format!("\\frac{{1}}{{{den}}}"), PRODUCT)
                } else {
                    self.tex_power(*b, Exponent::Of(*x))
                }
            }
        }
    }

    fn tex_negated(&self, e: Id) -> (String, u8) {
        match self.node(e) {
            Node::Num(r) => rational_tex(r.checked_abs().unwrap_or(*r)),
            Node::Float(bits) => float_tex(f64::from_bits(*bits).abs()),
            Node::Mul(factors) => self.tex_product(factors, true),
            _ => (format!("-{}", wrap(self.tex(e), POWER)), SUM),
        }
    }

    /// `\sin\left(u\right)`, or `\sin^{n}\left(u\right)` for a power of it.
    fn tex_call(&self, f: Func, args: &[Id], power: Option<&str>) -> (String, u8) {
        let args: Vec<String> = args.iter().map(|a| self.tex(*a).0).collect();
        let inner = args.join(", ");
        let named = |command: &str| match power {
            Some(p) => format!("{command}^{{{p}}}\\left({inner}\\right)"),
            None => format!("{command}\\left({inner}\\right)"),
        };
        let text = match f {
            Func::Abs => format!("\\left|{inner}\\right|"),
            Func::Exp => return (format!("e^{{{inner}}}"), POWER),
            Func::Sign | Func::Atan2 => named(&format!("\\operatorname{{{}}}", f.name())),
            Func::Asin => named("\\arcsin"),
            Func::Acos => named("\\arccos"),
            Func::Atan => named("\\arctan"),
            _ => named(&format!("\\{}", f.name())),
        };
        (text, ATOM)
    }

    fn tex_product(&self, factors: &[Id], negate: bool) -> (String, u8) {
        let view = self.product_view(factors, negate);
        let mut numerator: Vec<(String, u8)> = Vec::new();
        let mut denominator: Vec<(String, u8)> = Vec::new();
        match view.coefficient {
            Number::Exact(r) => {
                if r.numer() != 1 {
                    numerator.push((r.numer().to_string(), ATOM));
                }
                if r.denom() != 1 {
                    denominator.push((r.denom().to_string(), ATOM));
                }
            }
            Number::Inexact(x) => {
                if x != 1.0 {
                    numerator.push(float_tex(x));
                }
            }
        }
        numerator.extend(view.numerator.iter().map(|f| self.tex(*f)));
        denominator.extend(view.denominator.iter().map(|(b, x)| self.tex_power(*b, *x)));
        // A lone factor needs no parentheses: the fraction bar groups it.
        let side = |parts: Vec<(String, u8)>| -> String {
            match parts.len() {
                0 => "1".to_owned(),
                1 => parts.into_iter().map(|p| p.0).collect(),
                _ => join_factors(
                    &parts
                        .into_iter()
                        .map(|p| wrap(p, POWER))
                        .collect::<Vec<_>>(),
                ),
            }
        };
        let (body, precedence) = if denominator.is_empty() {
            if let [single] = numerator.as_slice() {
                let single = single.clone();
                return if view.negative {
                    (format!("-{}", wrap(single, POWER)), SUM)
                } else {
                    single
                };
            }
            (side(numerator), PRODUCT)
        } else {
            (
                format!("\\frac{{{}}}{{{}}}", side(numerator), side(denominator)),
                PRODUCT,
            )
        };
        if view.negative {
            (format!("-{body}"), SUM)
        } else {
            (body, precedence)
        }
    }

    fn tex_power(&self, b: Id, x: Exponent) -> (String, u8) {
        let value = self.exponent_value(x);
        match value {
            Some(n) if n.is_one() => return self.tex(b),
            Some(Number::Exact(r)) if r == Rational::HALF => {
                return (format!("\\sqrt{{{}}}", self.tex(b).0), ATOM)
            }
            _ => {}
        }
        let exponent = match x {
            Exponent::Of(x) => self.tex(x).0,
            Exponent::Negated(x) => self.tex_negated(x).0,
        };
        // sin²(u) rather than (sin(u))² for positive integer powers of named functions.
        if let (Node::Call(f, args), Some(Number::Exact(r))) = (self.node(b), value) {
            let named = !matches!(f, Func::Abs | Func::Exp | Func::Sign | Func::Atan2);
            if named && r.as_integer().is_some_and(|n| n > 1) {
                return self.tex_call(*f, args, Some(&exponent));
            }
        }
        (format!("{}^{{{exponent}}}", wrap(self.tex(b), ATOM)), POWER)
    }
}
