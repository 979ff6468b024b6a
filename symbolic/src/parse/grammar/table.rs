//! `table NAME(ARG) = "FILE" [, OPTION]*` or `table NAME(ARG) = runtime [, OPTION]*`
//! (docs/tables.md#statements): options after the file in any order, `linear` (default) | `pchip` | `spline` and `outside error` (default)
//! | `outside zero` | `outside hold`; a repeated or contradictory option is a diagnostic at
//! the second one.

use super::{Grammar, PResult};
use crate::parse::ast::{StatementKind, TableDecl};
use crate::parse::keywords::{self, closest};
use crate::parse::span::{Diagnostic, Spanned};
use varmass_table::{Interpolation, Outside};

/// What may follow a table's file or option.
const AFTER_TABLE: &str = "`,`, `;` or a newline";

impl<'a> Grammar<'a> {
    /// `table F(t) = "motors/M1670.eng", outside zero`
    pub(super) fn table(&self, input: &'a str) -> PResult<'a, (StatementKind, &'static str)> {
        let (rest, name) = self.name_then(input, "a table name", keywords::TABLE, '(')?;
        let (rest, parameter) =
            self.required(rest, false, "the argument's name", "(", |i| self.name(i))?;
        let (rest, _) = self.required(rest, false, "`)`", &parameter.node, |i| {
            self.punct_after_blanks(i, ')')
        })?;
        let (rest, _) =
            self.required(rest, false, "`=`", ")", |i| self.punct_after_blanks(i, '='))?;
        let (mut rest, (file, runtime)) = self.table_source(rest)?;
        let mut decl = TableDecl {
            name,
            parameter,
            file,
            runtime,
            interpolation: Interpolation::Linear,
            outside: Outside::Error,
        };
        let mut seen: Vec<Spanned<String>> = Vec::new();
        while let Ok((next, _)) = self.punct_after_blanks(rest, ',') {
            (rest, ()) = self.table_option(next, &mut decl, &mut seen)?;
        }
        Ok((rest, (StatementKind::Table(decl), AFTER_TABLE)))
    }

    /// The quoted file name, or the word `runtime` (true beside it).
    fn table_source(&self, input: &'a str) -> PResult<'a, (Spanned<String>, bool)> {
        if let Ok((rest, span)) = self.keyword(input, keywords::RUNTIME) {
            return Ok((
                rest,
                (Spanned::new(keywords::RUNTIME.to_string(), span), true),
            ));
        }
        let written = format!(
            "a table is written `{} F(t) = \"motors/M1670.eng\"` (a path in double quotes, \
             relative to the model file) or `{} F(t) = {}` (the data given at run time)",
            keywords::TABLE,
            keywords::TABLE,
            keywords::RUNTIME
        );
        let (rest, file) = self.file_name(input, &written)?;
        Ok((rest, (file, false)))
    }

    /// The quoted file name; the span covers the quotes. `written` (how the statement is
    /// written) is the help of a diagnostic.
    pub(super) fn file_name(&self, input: &'a str, written: &str) -> PResult<'a, Spanned<String>> {
        let help = |d: Diagnostic| d.with_help(written);
        let start = self.skip_blanks(input, false);
        let Ok((inside, _)) = self.punct(start, '"') else {
            let diagnostic = self.unexpected_diagnostic(start, "a file name in double quotes");
            return Err(self.fail(start, help(diagnostic)));
        };
        let line = inside.split('\n').next().unwrap_or_default();
        let Some(end) = line.find('"') else {
            let diagnostic = Diagnostic::new(
                self.span_between(start, &inside[line.len()..]),
                "the file name has no closing `\"` on its line",
            );
            return Err(self.fail(&inside[line.len()..], help(diagnostic)));
        };
        let rest = &inside[end + 1..];
        let written = &inside[..end];
        let span = self.span_between(start, rest);
        if written.trim().is_empty() {
            return Err(self.fail(rest, help(Diagnostic::new(span, "the file name is empty"))));
        }
        Ok((rest, Spanned::new(written.to_string(), span)))
    }

    /// One option after a `,`: an interpolation, or `outside` and its rule.
    fn table_option(
        &self,
        input: &'a str,
        decl: &mut TableDecl,
        seen: &mut Vec<Spanned<String>>,
    ) -> PResult<'a, ()> {
        let expected = "`linear`, `pchip`, `spline` or `outside`";
        let (rest, option) = self.required(input, false, expected, ",", |i| self.name(i))?;
        let interpolation = match option.node.as_str() {
            "linear" => Some(Interpolation::Linear),
            "pchip" => Some(Interpolation::Pchip),
            "spline" => Some(Interpolation::Spline),
            keywords::OUTSIDE => None,
            other => {
                let mut diagnostic = Diagnostic::new(
                    option.span,
                    format!(
                        "unknown option `{other}` for table `{}`; expected {expected}",
                        decl.name.node
                    ),
                );
                if let Some(word) = closest(other, keywords::TABLE_OPTIONS) {
                    diagnostic = diagnostic.with_help(format!("did you mean `{word}`?"));
                }
                return Err(self.fail(rest, diagnostic));
            }
        };
        // Interpolations exclude each other; `outside` is given once.
        let clash = seen.iter().find(|s| match interpolation {
            Some(_) => s.node != keywords::OUTSIDE,
            None => s.node == keywords::OUTSIDE,
        });
        if let Some(first) = clash {
            let diagnostic = Diagnostic::new(
                option.span,
                format!(
                    "`{}` contradicts or repeats `{}` for table `{}`",
                    option.node, first.node, decl.name.node
                ),
            )
            .with_help(format!(
                "first given at {}:{}",
                first.span.line, first.span.column
            ));
            return Err(self.fail(rest, diagnostic));
        }
        seen.push(option);
        match interpolation {
            Some(interpolation) => {
                decl.interpolation = interpolation;
                Ok((rest, ()))
            }
            None => {
                let (rest, rule) = self.outside_rule(rest)?;
                decl.outside = rule;
                Ok((rest, ()))
            }
        }
    }

    /// `error`, `zero` or `hold` after `outside`.
    fn outside_rule(&self, input: &'a str) -> PResult<'a, Outside> {
        let expected = "`error`, `zero` or `hold`";
        let (rest, rule) =
            self.required(input, false, expected, keywords::OUTSIDE, |i| self.name(i))?;
        match rule.node.as_str() {
            "error" => Ok((rest, Outside::Error)),
            "zero" => Ok((rest, Outside::Zero)),
            "hold" => Ok((rest, Outside::Hold)),
            other => {
                let mut diagnostic = Diagnostic::new(
                    rule.span,
                    format!("unknown rule `{other}` after `outside`; expected {expected}"),
                );
                if let Some(word) = closest(other, keywords::OUTSIDE_RULES) {
                    diagnostic = diagnostic.with_help(format!("did you mean `{word}`?"));
                }
                Err(self.fail(rest, diagnostic))
            }
        }
    }
}
