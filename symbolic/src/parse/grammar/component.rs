//! `use "FILE" as NAME [: NAME = EXPR {, NAME = EXPR}]` and `parameter NAME = NUMBER`
//! (docs/components.md): a model file used as a named component, and a parameter with a
//! default value. What the names mean is checked by the expansion (`crate::compose`).

use super::{Grammar, PResult, STATEMENT_LEVEL};
use crate::parse::ast::{Expr, ParameterDecl, StatementKind, UseBinding, UseDecl};
use crate::parse::keywords;
use crate::parse::span::Diagnostic;

/// What may follow a `use` statement's instance name or a binding.
const AFTER_USE: &str = "`:`, `,`, an operator, `;` or a newline";

/// What may follow a parameter's default.
const AFTER_PARAMETER: &str = "`;` or a newline";

impl<'a> Grammar<'a> {
    /// `use "lib/thruster.vms" as left: F = 2*F0, on = rocket`
    pub(super) fn use_component(
        &self,
        input: &'a str,
    ) -> PResult<'a, (StatementKind, &'static str)> {
        let written = format!(
            "a component is used as `{} \"lib/thruster.vms\" {} left: F = 2*F0` (a path in \
             double quotes, relative to this file, and an instance name)",
            keywords::USE,
            keywords::AS
        );
        let (rest, file) = self.file_name(input, &written)?;
        let quoted = format!("\"{}\"", file.node);
        let (rest, _) = self.required(rest, false, "`as`", &quoted, |i| {
            self.keyword(i, keywords::AS)
        })?;
        let (mut rest, instance) =
            self.required(rest, false, "an instance name", keywords::AS, |i| {
                self.name(i)
            })?;
        let mut bindings = Vec::new();
        if let Ok((after, _)) = self.punct_after_blanks(rest, ':') {
            let mut after_what = ":".to_string();
            let mut at = after;
            loop {
                let (next, binding) = self.binding(at, &after_what)?;
                after_what = binding.name.node.clone();
                bindings.push(binding);
                rest = next;
                match self.punct_after_blanks(next, ',') {
                    Ok((next, _)) => at = next,
                    Err(_) => break,
                }
            }
        }
        let decl = UseDecl {
            file,
            instance,
            bindings,
        };
        Ok((rest, (StatementKind::Use(decl), AFTER_USE)))
    }

    /// `name = expr` of a `use` statement, after `after`.
    fn binding(&self, input: &'a str, after: &str) -> PResult<'a, UseBinding> {
        let (rest, name) =
            self.required(input, false, "a name to bind", after, |i| self.name(i))?;
        let (rest, _) = self.required(rest, false, "`=`", &name.node, |i| {
            self.punct_after_blanks(i, '=')
        })?;
        let (rest, (value, _)) = self.required_expression(rest, STATEMENT_LEVEL, "=")?;
        Ok((rest, UseBinding { name, value }))
    }

    /// `parameter g0 = 9.80665`: the default is a number, signed or not, in SI units.
    pub(super) fn parameter(&self, input: &'a str) -> PResult<'a, (StatementKind, &'static str)> {
        let (rest, name) = self.name_then(input, "a parameter name", keywords::PARAMETER, '=')?;
        let (rest, (value, _)) = self.required_expression(rest, STATEMENT_LEVEL, "=")?;
        let number = match value.node.as_ref() {
            Expr::Number(text) => text.parse::<f64>().ok(),
            Expr::Neg(inner) => match inner.node.as_ref() {
                Expr::Number(text) => text.parse::<f64>().ok().map(|v| -v),
                _ => None,
            },
            _ => None,
        };
        let Some(number) = number.filter(|v| v.is_finite()) else {
            let diagnostic = Diagnostic::new(
                value.span,
                "a parameter's default must be a finite number (in SI units)",
            )
            .with_help(format!(
                "write `{} {} = 9.80665`; an expression of other names is a `{}`",
                keywords::PARAMETER,
                name.node,
                keywords::LET
            ));
            return Err(self.fail(rest, diagnostic));
        };
        let decl = ParameterDecl {
            name,
            default: value,
            value: number,
        };
        Ok((rest, (StatementKind::Parameter(decl), AFTER_PARAMETER)))
    }
}
