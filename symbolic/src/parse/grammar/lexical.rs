//! Lexical pieces: blanks and comments, names, numbers, punctuation, and how the next bit
//! of input is described in an error message.

use super::{Grammar, PResult, ParseError};
use crate::parse::ast::{Expr, ExprNode};
use crate::parse::span::{Diagnostic, Span, Spanned};
use nom::branch::alt;
use nom::bytes::complete::{take_while, take_while1};
use nom::character::complete::{char, digit1, one_of, satisfy};
use nom::combinator::{opt, recognize};
use nom::multi::many0_count;
use nom::Parser;

/// Characters that may appear in a system outside comments. Anything else is reported as an
/// "unexpected character" rather than as a misplaced token.
fn is_dsl_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || " \t\r\n_+-*/^()[],:;=.'#".contains(c)
}

fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

impl<'a> Grammar<'a> {
    /// Skips spaces, tabs, `\r` and comments; newlines too when `newlines` (inside brackets).
    /// A comment runs to the end of its line and leaves the newline in place.
    pub(super) fn skip_blanks(&self, input: &'a str, newlines: bool) -> &'a str {
        self.skip(input, newlines, false)
    }

    /// Skips everything between statements: blanks, comments, newlines and `;`.
    pub(super) fn skip_separators(&self, input: &'a str) -> &'a str {
        self.skip(input, true, true)
    }

    fn skip(&self, input: &'a str, newlines: bool, semicolons: bool) -> &'a str {
        let blank = take_while1(move |c: char| {
            c == ' '
                || c == '\t'
                || c == '\r'
                || (newlines && c == '\n')
                || (semicolons && c == ';')
        });
        let comment = recognize((char('#'), take_while(|c: char| c != '\n')));
        let skipped: PResult<'a, usize> = many0_count(alt((blank, comment))).parse(input);
        skipped.map_or(input, |(rest, _)| rest)
    }

    /// A name `[A-Za-z_][A-Za-z0-9_]*` (no blanks skipped).
    pub(super) fn identifier(&self, input: &'a str) -> PResult<'a, Spanned<String>> {
        let (rest, name) = recognize((
            satisfy(|c| c.is_ascii_alphabetic() || c == '_'),
            take_while(is_name_char),
        ))
        .parse(input)?;
        Ok((
            rest,
            Spanned::new(name.to_string(), self.span_between(input, rest)),
        ))
    }

    /// A name after optional blanks (not newlines): names in statements.
    pub(super) fn name(&self, input: &'a str) -> PResult<'a, Spanned<String>> {
        self.identifier(self.skip_blanks(input, false))
    }

    /// The keyword `word` after optional blanks; a different name backtracks.
    pub(super) fn keyword(&self, input: &'a str, word: &str) -> PResult<'a, Span> {
        let (rest, name) = self.name(input)?;
        if name.node == word {
            Ok((rest, name.span))
        } else {
            Err(nom::Err::Error(ParseError {
                remaining: input.len(),
                diagnostic: None,
            }))
        }
    }

    /// The character `c` (no blanks skipped), with its span.
    pub(super) fn punct(&self, input: &'a str, c: char) -> PResult<'a, Span> {
        let (rest, _) = char(c).parse(input)?;
        Ok((rest, self.span_between(input, rest)))
    }

    /// The character `c` after optional blanks (not newlines).
    pub(super) fn punct_after_blanks(&self, input: &'a str, c: char) -> PResult<'a, Span> {
        self.punct(self.skip_blanks(input, false), c)
    }

    /// A number literal, kept as written. Backtracks if no number starts here; a number run
    /// into letters, dots or a bare exponent (`2x`, `1.2.3`, `1.`, `1e`) is an error over the
    /// whole run, since splitting it would only produce a more confusing error later.
    pub(super) fn number(&self, input: &'a str) -> PResult<'a, ExprNode> {
        let mantissa = alt((
            recognize((digit1, opt((char('.'), digit1)))),
            recognize((char('.'), digit1)),
        ));
        let exponent = (one_of("eE"), opt(one_of("+-")), digit1);
        let (rest, text) = recognize((mantissa, opt(exponent))).parse(input)?;
        let tail: PResult<'a, &'a str> = take_while(|c: char| is_name_char(c) || c == '.')(rest);
        let (after, tail) = tail.unwrap_or((rest, ""));
        if let Some(first) = tail.chars().next() {
            let span = self.span_between(input, after);
            let written = input.get(..input.len() - after.len()).unwrap_or(text);
            let help = if first == 'e' || first == 'E' {
                "an exponent needs digits, as in `1e-3` or `6.02E23`".to_string()
            } else if first == '.' {
                "a number has at most one decimal point, with digits after it, as in `0.5`"
                    .to_string()
            } else {
                format!("a number cannot run into a name; for a product write `{text}*{tail}`")
            };
            let diagnostic =
                Diagnostic::new(span, format!("malformed number `{written}`")).with_help(help);
            return Err(self.fail(after, diagnostic));
        }
        let span = self.span_between(input, rest);
        Ok((
            rest,
            Spanned::new(Box::new(Expr::Number(text.to_string())), span),
        ))
    }

    /// What is at `input`, for messages ("`)`", "`foo`", "the end of the line"), with its
    /// span (empty at the end of a line or of the input).
    pub(super) fn found(&self, input: &'a str) -> (String, Span) {
        let at = self.offset(input);
        let Some(c) = input.chars().next() else {
            return ("the end of the input".to_string(), self.span(at, at));
        };
        if c == '\n' {
            return ("the end of the line".to_string(), self.span(at, at));
        }
        let word: PResult<'a, &'a str> = take_while1(|c: char| is_name_char(c) || c == '.')(input);
        let end = match word {
            Ok((rest, _)) => self.offset(rest),
            Err(_) => at + c.len_utf8(),
        };
        let text = self.source.get(at..end).unwrap_or("");
        (format!("`{}`", printable(text)), self.span(at, end))
    }

    /// "unexpected X; expected `expected`" about the input at `input`, with a hint for
    /// characters the DSL never uses and for closing brackets that close nothing.
    pub(super) fn unexpected_diagnostic(&self, input: &'a str, expected: &str) -> Diagnostic {
        let (found, span) = self.found(input);
        let first = input.chars().next();
        match first {
            Some(c) if !is_dsl_char(c) => Diagnostic::new(
                span,
                format!("unexpected character {found}; expected {expected}"),
            )
            .with_help(foreign_character_help(c)),
            Some(c @ (')' | ']')) => {
                let open = if c == ')' { '(' } else { '[' };
                Diagnostic::new(span, format!("unexpected {found}; expected {expected}"))
                    .with_help(format!("there is no open `{open}` for it to close"))
            }
            _ => Diagnostic::new(span, format!("unexpected {found}; expected {expected}")),
        }
    }

    /// [`Grammar::unexpected_diagnostic`] as a failure that recovers from `input`.
    pub(super) fn unexpected(&self, input: &'a str, expected: &str) -> nom::Err<ParseError> {
        self.fail(input, self.unexpected_diagnostic(input, expected))
    }

    /// Runs `parser`, which must find something: if it backtracks, the error says
    /// "expected `what` after `after`" (or "expected `what`, found …" when `after` is
    /// empty), pointing at whatever is there instead.
    pub(super) fn required<T>(
        &self,
        input: &'a str,
        newlines: bool,
        what: &str,
        after: &str,
        mut parser: impl FnMut(&'a str) -> PResult<'a, T>,
    ) -> PResult<'a, T> {
        self.or_missing(parser(input), input, newlines, what, after)
    }

    /// A declaration's name after its `keyword`, then `punct` (`input u(`, `table F(`,
    /// `rigid b:`, `body b:`), each required; `what` names the name in a diagnostic.
    pub(super) fn name_then(
        &self,
        input: &'a str,
        what: &str,
        keyword: &str,
        punct: char,
    ) -> PResult<'a, Spanned<String>> {
        let (rest, name) = self.required(input, false, what, keyword, |i| self.name(i))?;
        let punct_text = format!("`{punct}`");
        let (rest, _) = self.required(rest, false, &punct_text, &name.node, |i| {
            self.punct_after_blanks(i, punct)
        })?;
        Ok((rest, name))
    }

    /// Items separated by `,` up to the closing bracket (`open`, already read, and `close`),
    /// each read by `item` and required (`what` names it in a diagnostic, after the text
    /// before it: `open`, `,` or the last item's `text`).
    pub(super) fn comma_list<T>(
        &self,
        mut rest: &'a str,
        (open, close): (&str, char),
        what: &str,
        mut item: impl FnMut(&'a str) -> PResult<'a, T>,
        text: impl Fn(&T) -> String,
    ) -> PResult<'a, Vec<T>> {
        let mut items = Vec::new();
        let mut after = open.to_string();
        loop {
            let (next, one) = self.required(rest, false, what, &after, &mut item)?;
            after = text(&one);
            items.push(one);
            match self.punct_after_blanks(next, ',') {
                Ok((next, _)) => (rest, after) = (next, ",".to_string()),
                Err(_) => {
                    rest = next;
                    break;
                }
            }
        }
        let expected = format!("`,` or `{close}`");
        let (rest, _) = self.required(rest, false, &expected, &after, |i| {
            self.punct_after_blanks(i, close)
        })?;
        Ok((rest, items))
    }

    /// What follows `punct` (after blanks), or a failure at the next token saying it expected
    /// `expected` there, with `help` (how the statement is written).
    pub(super) fn punct_or_help(
        &self,
        rest: &'a str,
        punct: char,
        expected: &str,
        help: impl FnOnce() -> String,
    ) -> Result<&'a str, nom::Err<ParseError>> {
        match self.punct_after_blanks(rest, punct) {
            Ok((after, _)) => Ok(after),
            Err(_) => {
                let at = self.skip_blanks(rest, false);
                let diagnostic = self.unexpected_diagnostic(at, expected).with_help(help());
                Err(self.fail(at, diagnostic))
            }
        }
    }

    /// The failure at `at` for the declaration of `name`, a `kind` (`body`, `rigid body`),
    /// that lacks `option`, with `help` (how the declaration is written).
    pub(super) fn missing_option(
        &self,
        at: &'a str,
        (kind, name): (&str, &Spanned<String>),
        option: &str,
        help: &str,
    ) -> nom::Err<ParseError> {
        let message = format!("missing `{option}` for {kind} `{}`", name.node);
        let diagnostic = Diagnostic::new(name.span, message).with_help(help.to_string());
        self.fail(at, diagnostic)
    }

    /// [`Grammar::required`] applied to a result already computed. The recursive
    /// expression parsers use this form so that neither a closure nor the error building
    /// sits on the stack between nesting levels.
    pub(super) fn or_missing<T>(
        &self,
        result: PResult<'a, T>,
        input: &'a str,
        newlines: bool,
        what: &str,
        after: &str,
    ) -> PResult<'a, T> {
        match result {
            Err(nom::Err::Error(_)) => Err(self.missing(input, newlines, what, after)),
            other => other,
        }
    }

    /// The error for [`Grammar::required`].
    #[cold]
    #[inline(never)]
    fn missing(
        &self,
        input: &'a str,
        newlines: bool,
        what: &str,
        after: &str,
    ) -> nom::Err<ParseError> {
        let at = self.skip_blanks(input, newlines);
        let (found, span) = self.found(at);
        let message = if after.is_empty() {
            format!("expected {what}, found {found}")
        } else {
            format!("expected {what} after `{after}`")
        };
        let mut diagnostic = Diagnostic::new(span, message);
        match at.chars().next() {
            Some(c) if !is_dsl_char(c) => {
                diagnostic = diagnostic.with_help(foreign_character_help(c));
            }
            Some('\n') if !newlines && what.starts_with("an expression") => {
                diagnostic = diagnostic.with_help(
                    "a statement ends at the end of its line; to go on on the next \
                     line, put the expression in parentheses",
                );
            }
            _ => {}
        }
        self.fail(at, diagnostic)
    }
}

fn foreign_character_help(c: char) -> String {
    if c.is_alphabetic() {
        format!("names use only ASCII letters, digits and `_`: spell `{c}` out in Latin letters")
    } else {
        format!("`{}` is not part of the DSL", printable(&c.to_string()))
    }
}

/// `text` with control characters escaped (`\0`, `\u{7f}`), so a message stays one
/// readable line; everything else as written.
fn printable(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_debug().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}
