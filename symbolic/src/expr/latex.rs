//! LaTeX rendering for the derivation the system exposes: `\frac`, `\dot{x}`, greek
//! names, subscripts from `m0` and `u_e`, `\sin`, `\sqrt`, `\left( \right)` — the LaTeX
//! [`Syntax`] of the shared printing walk.

use super::func::Func;
use super::node::{Id, Node, Number};
use super::pool::ExprPool;
use super::print::{float_literal, Exponent, PrintedText};
use super::rational::Rational;
use super::symbol::{Symbol, SymbolKind};
use super::walk::{print, print_all, Prec, Printed, Printer, Syntax};

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

fn rational_tex(r: Rational) -> PrintedText {
    let magnitude = r.checked_abs().unwrap_or(r);
    let text = if magnitude.denom() == 1 {
        magnitude.numer().to_string()
    } else {
        format!("\\frac{{{}}}{{{}}}", magnitude.numer(), magnitude.denom())
    };
    if r.is_negative() {
        Printed::new(format!("-{text}"), Prec::Sum)
    } else if r.denom() != 1 {
        Printed::new(text, Prec::Product)
    } else {
        Printed::new(text, Prec::Atom)
    }
}

fn float_tex(x: f64) -> PrintedText {
    let text = float_literal(x);
    let (text, prec) = match text.split_once('e') {
        Some(("1", exponent)) => (format!("10^{{{exponent}}}"), Prec::Power),
        Some((mantissa, exponent)) => {
            (format!("{mantissa} \\times 10^{{{exponent}}}"), Prec::Power)
        }
        None => (text, Prec::Atom),
    };
    Printed::new(text, if x < 0.0 { Prec::Sum } else { prec })
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
        print(self, &Latex, e).text
    }

    /// The [`latex`](Self::latex) of each of `roots`, from one walk: a subexpression shared
    /// by several roots is printed once.
    pub fn latex_all(&self, roots: &[Id]) -> Vec<String> {
        let printed = print_all(self, &Latex, roots, |_, _| None);
        printed.into_iter().map(|p| p.text).collect()
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
}

/// LaTeX: `\frac`, `\dot{x}`, `\sqrt`, `\sin^{2}`, `\left( \right)`.
struct Latex;

impl Syntax for Latex {
    fn group(&self, text: &str) -> String {
        format!("\\left({text}\\right)")
    }

    fn number(&self, r: Rational) -> PrintedText {
        rational_tex(r)
    }

    fn float(&self, x: f64) -> PrintedText {
        float_tex(x)
    }

    fn symbol(&self, pool: &ExprPool, s: Symbol) -> PrintedText {
        Printed::new(pool.latex_symbol(s), Prec::Atom)
    }

    fn call(&self, p: &Printer<'_>, f: Func, args: &[Id]) -> PrintedText {
        self.call_to(p, f, args, None)
    }

    fn product(&self, p: &Printer<'_>, factors: &[Id]) -> PrintedText {
        self.product_of(p, factors, false)
    }

    fn power(&self, p: &Printer<'_>, b: Id, x: Id) -> PrintedText {
        if p.pool().exponent_is_negative(x) {
            let den = self.power_of(p, b, Exponent::Negated(x)).text;
            Printed::new(format!("\\frac{{1}}{{{den}}}"), Prec::Product)
        } else {
            self.power_of(p, b, Exponent::Of(x))
        }
    }

    fn negated(&self, p: &Printer<'_>, e: Id) -> PrintedText {
        match p.pool().node(e) {
            Node::Num(r) => rational_tex(r.checked_abs().unwrap_or(*r)),
            Node::Float(bits) => float_tex(f64::from_bits(*bits).abs()),
            Node::Mul(factors) => self.product_of(p, factors, true),
            _ => Printed::new(
                format!("-{}", self.at_least(p.get(e), Prec::Power)),
                Prec::Sum,
            ),
        }
    }
}

impl Latex {
    /// `\sin\left(u\right)`, or `\sin^{n}\left(u\right)` for a power of it.
    fn call_to(&self, p: &Printer<'_>, f: Func, args: &[Id], power: Option<&str>) -> PrintedText {
        let args: Vec<&str> = args.iter().map(|a| p.get(*a).text.as_str()).collect();
        let inner = args.join(", ");
        let named = |command: &str| match power {
            Some(p) => format!("{command}^{{{p}}}\\left({inner}\\right)"),
            None => format!("{command}\\left({inner}\\right)"),
        };
        let text = match f {
            Func::Abs => format!("\\left|{inner}\\right|"),
            Func::Exp => return Printed::new(format!("e^{{{inner}}}"), Prec::Power),
            Func::Sign | Func::Atan2 => named(&format!("\\operatorname{{{}}}", f.name())),
            Func::Asin => named("\\arcsin"),
            Func::Acos => named("\\arccos"),
            Func::Atan => named("\\arctan"),
            Func::Table { table, order } => {
                let name = p.pool().table_call_name(table, order);
                named(&format!("\\operatorname{{{name}}}"))
            }
            Func::Input { input, partial } => {
                let name = p.pool().input_name(input);
                let arguments = p.pool().input_arguments(input);
                match partial
                    .checked_sub(1)
                    .and_then(|j| arguments.get(usize::from(j)))
                {
                    Some(a) => named(&format!(
                        "\\partial_{{{}}}\\operatorname{{{name}}}",
                        a.replace('\'', "^{\\prime}")
                    )),
                    None => named(&format!("\\operatorname{{{name}}}")),
                }
            }
            _ => named(&format!("\\{}", f.name())),
        };
        Printed::new(text, Prec::Atom)
    }

    fn product_of(&self, p: &Printer<'_>, factors: &[Id], negate: bool) -> PrintedText {
        let view = p.pool().product_view(factors, negate);
        let mut numerator: Vec<PrintedText> = Vec::new();
        let mut denominator: Vec<PrintedText> = Vec::new();
        match view.coefficient {
            Number::Exact(r) => {
                if r.numer() != 1 {
                    numerator.push(Printed::new(r.numer().to_string(), Prec::Atom));
                }
                if r.denom() != 1 {
                    denominator.push(Printed::new(r.denom().to_string(), Prec::Atom));
                }
            }
            Number::Inexact(x) => {
                if x != 1.0 {
                    numerator.push(float_tex(x));
                }
            }
        }
        numerator.extend(view.numerator.iter().map(|f| p.get(*f).clone()));
        denominator.extend(
            view.denominator
                .iter()
                .map(|(b, x)| self.power_of(p, *b, *x)),
        );
        // A lone factor needs no parentheses: the fraction bar groups it.
        let side = |parts: Vec<PrintedText>| -> String {
            match parts.len() {
                0 => "1".to_owned(),
                1 => parts.into_iter().map(|p| p.text).collect(),
                _ => join_factors(
                    &parts
                        .into_iter()
                        .map(|p| self.at_least(&p, Prec::Power))
                        .collect::<Vec<_>>(),
                ),
            }
        };
        let (body, prec) = if denominator.is_empty() {
            if let [single] = numerator.as_slice() {
                let single = single.clone();
                return if view.negative {
                    Printed::new(
                        format!("-{}", self.at_least(&single, Prec::Power)),
                        Prec::Sum,
                    )
                } else {
                    single
                };
            }
            (side(numerator), Prec::Product)
        } else {
            (
                format!("\\frac{{{}}}{{{}}}", side(numerator), side(denominator)),
                Prec::Product,
            )
        };
        if view.negative {
            Printed::new(format!("-{body}"), Prec::Sum)
        } else {
            Printed::new(body, prec)
        }
    }

    fn power_of(&self, p: &Printer<'_>, b: Id, x: Exponent) -> PrintedText {
        let pool = p.pool();
        let value = pool.exponent_value(x);
        match value {
            Some(n) if n.is_one() => return p.get(b).clone(),
            Some(Number::Exact(r)) if r == Rational::HALF => {
                return Printed::new(format!("\\sqrt{{{}}}", p.get(b).text), Prec::Atom)
            }
            _ => {}
        }
        let exponent = match x {
            Exponent::Of(x) => p.get(x).text.clone(),
            Exponent::Negated(x) => self.negated(p, x).text,
        };
        // sin²(u) rather than (sin(u))² for positive integer powers of named functions.
        if let (Node::Call(f, args), Some(Number::Exact(r))) = (pool.node(b), value) {
            let named = !matches!(f, Func::Abs | Func::Exp | Func::Sign | Func::Atan2);
            if named && r.as_integer().is_some_and(|n| n > 1) {
                return self.call_to(p, *f, args, Some(&exponent));
            }
        }
        let text = format!("{}^{{{exponent}}}", self.at_least(p.get(b), Prec::Atom));
        Printed::new(text, Prec::Power)
    }
}
