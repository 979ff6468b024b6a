//! The dimension of an expression, rule by rule: `+ - min max` need agreeing operands,
//! `sin cos tan exp ln sinh cosh tanh asin acos atan` a dimensionless argument, `atan2`
//! two agreeing ones; `sqrt` halves the exponents and `^` with a constant exponent scales
//! them; a dimensioned base with a non-constant exponent is an error.

use super::check::{has, Checker};
use super::text::text;
use super::unit::constant;
use crate::dimension::Dimension;
use crate::expr::Rational;
use crate::parse::ast::{BinOp, Expr, ExprNode};
use crate::parse::{Diagnostic, Span};

/// The dimension of a value: known, or "any" for the literal 0, which is a length, a
/// velocity or a force as the context needs (`velocity [0]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Dim {
    /// A definite dimension.
    Of(Dimension),
    /// The literal zero: fits every dimension.
    Zero,
}

/// Functions whose argument must be dimensionless.
const TRANSCENDENTAL: &[&str] = &[
    "sin", "cos", "tan", "exp", "ln", "sinh", "cosh", "tanh", "asin", "acos", "atan",
];

impl Checker<'_> {
    /// The dimension of `node`, or `None` when it cannot be known: a symbol without a unit
    /// (collected for one diagnostic) or an error already reported inside.
    pub(crate) fn infer(&mut self, node: &ExprNode) -> Option<Dim> {
        match &*node.node {
            Expr::Number(text) => match Rational::from_decimal(text) {
                Some(value) if value.is_zero() => Some(Dim::Zero),
                _ => Some(Dim::Of(Dimension::NONE)),
            },
            Expr::Name(name) => self.name(name, node.span),
            Expr::Derivative { name, order } => {
                let q = self.dimension_of(name, node.span)?;
                let rate = Dimension::TIME.pow(Rational::integer(i128::from(*order)))?;
                self.overflow(node.span, q.checked_div(rate)).map(Dim::Of)
            }
            Expr::Neg(operand) => self.infer(operand),
            Expr::Binary { op, lhs, rhs } => self.binary(*op, lhs, rhs, node),
            Expr::Call { func, args } => self.call(&func.node, args, node.span),
        }
    }

    /// The dimension of a name that must be a definite one.
    fn dimension_of(&mut self, name: &str, span: Span) -> Option<Dimension> {
        match self.name(name, span)? {
            Dim::Of(dimension) => Some(dimension),
            Dim::Zero => Some(Dimension::NONE),
        }
    }

    fn binary(
        &mut self,
        op: BinOp,
        lhs: &ExprNode,
        rhs: &ExprNode,
        node: &ExprNode,
    ) -> Option<Dim> {
        let left = self.infer(lhs);
        let right = self.infer(rhs);
        match op {
            BinOp::Add | BinOp::Sub => {
                let what = format!("the operands of `{op}` disagree");
                self.agree(&what, lhs, left?, rhs, right?, node.span)
            }
            BinOp::Mul | BinOp::Div => match (left?, right?) {
                (Dim::Zero, _) => Some(Dim::Zero),
                (Dim::Of(_), Dim::Zero) if op == BinOp::Mul => Some(Dim::Zero),
                (Dim::Of(a), Dim::Zero) => Some(Dim::Of(a)),
                (Dim::Of(a), Dim::Of(b)) => {
                    let product = if op == BinOp::Mul {
                        a.checked_mul(b)
                    } else {
                        a.checked_div(b)
                    };
                    self.overflow(node.span, product).map(Dim::Of)
                }
            },
            BinOp::Pow => self.power(lhs, left?, rhs, right?, node.span),
        }
    }

    /// `base^exponent`: the exponent is dimensionless; a dimensioned base needs a constant
    /// exponent, which scales its dimension.
    fn power(
        &mut self,
        base: &ExprNode,
        base_dim: Dim,
        exponent: &ExprNode,
        exponent_dim: Dim,
        span: Span,
    ) -> Option<Dim> {
        if let Dim::Of(d) = exponent_dim {
            if !d.is_dimensionless() {
                let message = format!(
                    "exponent {} has {d}, expected dimensionless",
                    text(exponent)
                );
                self.report(Diagnostic::new(exponent.span, message));
                return None;
            }
        }
        let Dim::Of(d) = base_dim else {
            return Some(Dim::Zero);
        };
        if d.is_dimensionless() {
            return Some(base_dim);
        }
        let Some(power) = constant(exponent) else {
            let message = format!(
                "{} has {d}, so its exponent must be a constant number, and {} is not",
                text(base),
                text(exponent)
            );
            let help = "a dimensioned quantity can be raised only to a fixed power such as 2 \
                        or (1/2); make the base dimensionless first (divide it by a scale)";
            self.report(Diagnostic::new(exponent.span, message).with_help(help));
            return None;
        };
        self.overflow(span, d.pow(power)).map(Dim::Of)
    }

    fn call(&mut self, func: &str, args: &[ExprNode], span: Span) -> Option<Dim> {
        let dims: Vec<Option<Dim>> = args.iter().map(|a| self.infer(a)).collect();
        let first = dims.first().copied().flatten();
        match func {
            _ if TRANSCENDENTAL.contains(&func) => {
                if let (Some(Dim::Of(d)), Some(arg)) = (first, args.first()) {
                    if !d.is_dimensionless() {
                        self.report(
                            Diagnostic::new(
                                arg.span,
                                format!(
                                    "the argument of `{func}`, {}, has {d}, expected dimensionless",
                                    text(arg)
                                ),
                            )
                            .with_help("divide it by a quantity of the same dimension"),
                        );
                    }
                }
                Some(Dim::Of(Dimension::NONE))
            }
            "sqrt" => match first? {
                Dim::Zero => Some(Dim::Zero),
                Dim::Of(d) => self.overflow(span, d.sqrt()).map(Dim::Of),
            },
            "abs" => first,
            "sign" => Some(Dim::Of(Dimension::NONE)),
            "atan2" | "min" | "max" => {
                let [a, b] = args else { return None };
                let what = format!("the arguments of `{func}` disagree");
                let agreed = self.agree(&what, a, dims[0]?, b, dims[1]?, span)?;
                match func {
                    "atan2" => Some(Dim::Of(Dimension::NONE)),
                    _ => Some(agreed),
                }
            }
            _ if self.tables.contains_key(func) => self.table_call(func, args, first, span),
            // Unknown functions were reported when the system was resolved.
            _ => None,
        }
    }

    /// The common dimension of two values that must agree, or a diagnostic at `span`.
    pub(crate) fn agree(
        &mut self,
        what: &str,
        lhs: &ExprNode,
        left: Dim,
        rhs: &ExprNode,
        right: Dim,
        span: Span,
    ) -> Option<Dim> {
        match (left, right) {
            (Dim::Zero, other) | (other, Dim::Zero) => Some(other),
            (Dim::Of(a), Dim::Of(b)) if a == b => Some(left),
            (Dim::Of(a), Dim::Of(b)) => {
                let (left, right) = (text(lhs), text(rhs));
                let message = format!("{what}: {left} {}, {right} {}", has(a), has(b));
                self.report(Diagnostic::new(span, message));
                None
            }
        }
    }

    /// `value`, or a diagnostic that an exponent overflowed.
    pub(crate) fn overflow(&mut self, span: Span, value: Option<Dimension>) -> Option<Dimension> {
        if value.is_none() {
            self.report(Diagnostic::new(
                span,
                "the exponents of this quantity's dimension are too large",
            ));
        }
        value
    }
}
