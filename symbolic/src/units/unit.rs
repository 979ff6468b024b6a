//! Unit expressions of a `units` statement (`kg*m^2`, `m/s^2`, `N/m`, `1`) read into
//! [`Dimension`]s.

use crate::dimension::Dimension;
use crate::expr::Rational;
use crate::parse::ast::{BinOp, Expr, ExprNode};
use crate::parse::keywords::closest;
use crate::parse::Diagnostic;

/// The unit symbols a `units` statement knows, with their dimensions. `rad` is
/// dimensionless: it documents that a coordinate or parameter is an angle.
pub const UNITS: &[(&str, Dimension)] = &[
    ("kg", Dimension::MASS),
    ("m", Dimension::LENGTH),
    ("s", Dimension::TIME),
    ("rad", Dimension::NONE),
    ("N", Dimension::FORCE),
    ("J", Dimension::ENERGY),
    ("W", Dimension::POWER),
    ("Pa", Dimension::PRESSURE),
    ("K", Dimension::TEMPERATURE),
    ("mol", Dimension::AMOUNT),
];

/// `kg, m, s, rad, N, J, W, Pa, K, mol and 1`, for messages.
fn known_units() -> String {
    let names: Vec<&str> = UNITS.iter().map(|(name, _)| *name).collect();
    format!("{} and 1", names.join(", "))
}

/// The dimension of a unit expression: products, quotients and constant (integer or
/// rational) powers of the known units and of `1`.
///
/// ```
/// use varmass_symbolic::parse::parse_expression;
/// use varmass_symbolic::units::{unit_dimension, Dimension};
/// let newton = unit_dimension(&parse_expression("kg*m/s^2").unwrap()).unwrap();
/// assert_eq!(newton, Dimension::FORCE);
/// assert_eq!(newton.to_string(), "kg·m/s²");
/// ```
pub fn unit_dimension(node: &ExprNode) -> Result<Dimension, Diagnostic> {
    let too_large = || Diagnostic::new(node.span, "this unit's exponents are too large");
    match &*node.node {
        Expr::Name(name) => symbol(name, node),
        Expr::Number(text) if Rational::from_decimal(text) == Some(Rational::ONE) => {
            Ok(Dimension::NONE)
        }
        Expr::Number(text) => Err(Diagnostic::new(
            node.span,
            format!("`{text}` in a unit: a unit has no numeric factor other than 1"),
        )
        .with_help("give the parameter's value in SI units (kg, m, s) instead")),
        Expr::Binary { op, lhs, rhs } if matches!(op, BinOp::Mul | BinOp::Div) => {
            let (left, right) = (unit_dimension(lhs)?, unit_dimension(rhs)?);
            let combined = match op {
                BinOp::Mul => left.checked_mul(right),
                _ => left.checked_div(right),
            };
            combined.ok_or_else(too_large)
        }
        Expr::Binary {
            op: BinOp::Pow,
            lhs,
            rhs,
        } => {
            let base = unit_dimension(lhs)?;
            let Some(power) = constant(rhs) else {
                return Err(Diagnostic::new(
                    rhs.span,
                    "the exponent of a unit must be a constant number such as 2, -1 or (1/2)",
                ));
            };
            base.pow(power).ok_or_else(too_large)
        }
        _ => Err(Diagnostic::new(
            node.span,
            format!(
                "not a unit: a unit is a product, quotient or power of {}",
                known_units()
            ),
        )
        .with_help("for example `kg*m^2`, `m/s^2` or `N/m`")),
    }
}

/// One unit symbol, or "unknown unit" with a suggestion.
fn symbol(name: &str, node: &ExprNode) -> Result<Dimension, Diagnostic> {
    if let Some((_, dimension)) = UNITS.iter().find(|(unit, _)| *unit == name) {
        return Ok(*dimension);
    }
    let symbols: Vec<&str> = UNITS.iter().map(|(unit, _)| *unit).collect();
    let mut diagnostic = Diagnostic::new(
        node.span,
        format!("unknown unit `{name}`; the units are {}", known_units()),
    );
    if let Some(close) = closest(name, &symbols) {
        diagnostic = diagnostic.with_help(format!("did you mean `{close}`?"));
    }
    Err(diagnostic)
}

/// The value of a constant expression made of numbers, signs and `+ - * / ^` (with an
/// integer power), such as `2`, `-1`, `(1/2)` or `3/2`; `None` for anything else.
pub(crate) fn constant(node: &ExprNode) -> Option<Rational> {
    match &*node.node {
        Expr::Number(text) => Rational::from_decimal(text),
        Expr::Neg(operand) => constant(operand)?.checked_neg(),
        Expr::Binary { op, lhs, rhs } => {
            let (left, right) = (constant(lhs)?, constant(rhs)?);
            match op {
                BinOp::Add => left.checked_add(right),
                BinOp::Sub => left.checked_sub(right),
                BinOp::Mul => left.checked_mul(right),
                BinOp::Div => left.checked_div(right),
                BinOp::Pow => left.checked_pow(right.as_integer()?),
            }
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::parse_expression;

    fn dimension(unit: &str) -> Result<Dimension, Diagnostic> {
        unit_dimension(&parse_expression(unit).unwrap())
    }

    #[test]
    fn derived_units_reduce_to_base_dimensions() {
        assert_eq!(dimension("J").unwrap(), dimension("N*m").unwrap());
        assert_eq!(dimension("W").unwrap(), dimension("J/s").unwrap());
        assert_eq!(dimension("Pa").unwrap(), dimension("N/m^2").unwrap());
        assert_eq!(dimension("kg*m^2/s^2").unwrap(), Dimension::ENERGY);
        assert_eq!(dimension("1/s").unwrap().to_string(), "1/s");
        assert_eq!(
            dimension("m^(1/2)").unwrap(),
            Dimension::LENGTH.sqrt().unwrap()
        );
        assert_eq!(dimension("s^-2*m").unwrap().to_string(), "m/s²");
    }

    #[test]
    fn kelvin_and_mole_read_as_their_dimensions() {
        assert_eq!(dimension("K").unwrap(), Dimension::TEMPERATURE);
        assert_eq!(dimension("K/m").unwrap().to_string(), "K/m");
        let gas_constant = dimension("J/(mol*K)").unwrap();
        assert_eq!(gas_constant.to_string(), "kg·m²/(s²·K·mol)");
        let specific = gas_constant.checked_div(dimension("kg/mol").unwrap());
        assert_eq!(specific, Some(dimension("m^2/(s^2*K)").unwrap()));
        assert_ne!(dimension("K").unwrap(), dimension("kg").unwrap());
        assert_eq!(dimension("mol").unwrap(), Dimension::AMOUNT);
    }

    #[test]
    fn rad_is_dimensionless() {
        assert_eq!(dimension("rad").unwrap(), Dimension::NONE);
        assert_eq!(dimension("N*m/rad").unwrap(), Dimension::ENERGY);
        assert_eq!(dimension("1").unwrap(), Dimension::NONE);
    }

    #[test]
    fn an_unknown_unit_suggests_the_closest() {
        let error = dimension("kg/sec").unwrap_err();
        assert_eq!(
            error.message,
            "unknown unit `sec`; the units are kg, m, s, rad, N, J, W, Pa, K, mol and 1"
        );
        assert_eq!(error.help.as_deref(), Some("did you mean `s`?"));
        assert_eq!((error.span.start, error.span.end), (3, 6));
        assert_eq!(
            dimension("Kg").unwrap_err().help.as_deref(),
            Some("did you mean `kg`?")
        );
    }

    #[test]
    fn other_forms_are_diagnostics() {
        for bad in ["m + s", "sin(m)", "2*m", "m^x", "-m", "x'"] {
            assert!(dimension(bad).is_err(), "{bad}");
        }
        assert_eq!(
            dimension("m^x").unwrap_err().message,
            "the exponent of a unit must be a constant number such as 2, -1 or (1/2)"
        );
    }
}
