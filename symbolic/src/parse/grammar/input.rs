//! `input NAME(ARG, …) [every PERIOD]` (docs/inputs.md): a function of the time, the
//! coordinates and their velocities that the user writes in Rust. The arguments are names
//! with at most one prime (`t`, `y`, `y'`); what they name is checked when the system is
//! resolved. The period is a number literal in seconds.

use super::{Grammar, PResult};
use crate::parse::ast::{Expr, InputDecl, StatementKind};
use crate::parse::keywords;
use crate::parse::span::{Diagnostic, Spanned};

/// What may follow an input's declaration.
const AFTER_INPUT: &str = "`every`, `;` or a newline";

/// What may follow a sampled input's declaration.
const AFTER_SAMPLED: &str = "`;` or a newline";

impl<'a> Grammar<'a> {
    /// `input u(t, y, y') every 0.01`
    pub(super) fn input(&self, input: &'a str) -> PResult<'a, (StatementKind, &'static str)> {
        let (rest, name) = self.name_then(input, "an input name", keywords::INPUT, '(')?;
        let (rest, arguments) = self.comma_list(
            rest,
            ("(", ')'),
            "an argument: `t`, a coordinate or its velocity",
            |i| self.input_argument(i),
            |argument| argument.0.node.clone(),
        )?;
        let (rest, every) = match self.keyword(rest, keywords::EVERY) {
            Ok((after_every, _)) => {
                let (rest, period) = self.required(
                    after_every,
                    false,
                    "the sample period in seconds (a number)",
                    keywords::EVERY,
                    |i| self.number(self.skip_blanks(i, false)),
                )?;
                let Expr::Number(text) = period.node.as_ref() else {
                    return Err(self.unexpected(after_every, "a number"));
                };
                (rest, Some(Spanned::new(text.clone(), period.span)))
            }
            Err(_) => (rest, None),
        };
        if every.is_some() {
            // One period per input: a second `every` is named as such, not as unexpected.
            if let Ok((after, span)) = self.keyword(rest, keywords::EVERY) {
                let diagnostic = Diagnostic::new(
                    span,
                    "`every` is given twice: an input has one sample period",
                )
                .with_help("keep one `every PERIOD`");
                return Err(self.fail(after, diagnostic));
            }
        }
        let after = match every {
            Some(_) => AFTER_SAMPLED,
            None => AFTER_INPUT,
        };
        let decl = InputDecl {
            name,
            arguments,
            every,
        };
        Ok((rest, (StatementKind::Input(decl), after)))
    }

    /// One argument: a name and at most one prime.
    fn input_argument(&self, input: &'a str) -> PResult<'a, (Spanned<String>, u8)> {
        let (rest, name) = self.name(input)?;
        let primes = rest.len() - rest.trim_start_matches('\'').len();
        let after = &rest[primes..];
        if primes > 1 {
            let span = self.span(name.span.start, self.offset(after));
            let diagnostic = Diagnostic::new(
                span,
                format!(
                    "`{}{}`: an input's argument is `t`, a coordinate or its velocity, with one prime",
                    name.node,
                    "'".repeat(primes)
                ),
            );
            return Err(self.fail(after, diagnostic));
        }
        let mut name = name;
        name.span = self.span(name.span.start, self.offset(after));
        Ok((after, (name, u8::from(primes == 1))))
    }
}
