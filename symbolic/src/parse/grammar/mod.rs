//! The nom grammar of the DSL (docs/dsl.md#grammar).
//!
//! ```text
//! system    := { separator | [ tags ] statement }       separator := newline | `;`
//! tags      := `[` name { `,` name } `]`                (see `parse::select_tags`)
//! statement := `coordinates` name { `,` name }
//!            | (`mass` | `inertia`) name ( `=` expr | `:` `state` `,` `rate` expr )
//!            | `let` name `=` expr
//!            | `body` name `:` body-option { `,` body-option }
//!                  body-option := `mass` name | `position` vector     (each exactly once)
//!            | (`kinetic` | `potential` | `lagrangian`) expr
//!            | (`force` | `thrust` | `impact`) name `:` ( expr | vector )
//!            | (`outflow` | `inflow`) name [ `:` flow-option { `,` flow-option } ]
//!                  flow-option := `rate` expr | `velocity` vector | `relative_velocity` vector
//!                  (each at most once; `velocity` and `relative_velocity` exclude each other)
//!            | `check` expr `=` expr
//!            | `units` name `:` expr { `,` name `:` expr }     (each expr a unit: kg*m/s^2)
//!            | `use` file `as` name [ `:` name `=` expr { `,` name `=` expr } ]
//!            | `parameter` name `=` [ `-` ] number                (docs/components.md)
//! vector    := `[` expr { `,` expr } `]`                  (1 to 3 components)
//! expr      := product { (`+` | `-`) product }            (left-associative)
//! product   := unary { (`*` | `/`) unary }                (left-associative)
//! unary     := `-` unary | power                          (`-x^2` is -(x^2))
//! power     := atom [ `^` unary ]                         (right-associative; `x^-2` is x^(-2))
//! atom      := number | name | name `'` | name `''` | name `(` [ expr { `,` expr } ] `)`
//!            | `(` expr `)`
//! number    := digits [ `.` digits ] [ exponent ] | `.` digits [ exponent ]
//!                  exponent := (`e` | `E`) [ `+` | `-` ] digits
//! name      := [A-Za-z_][A-Za-z0-9_]*
//! ```
//!
//! **Lines.** A statement ends at a newline or `;`. Inside an open `(` or `[` a newline is
//! only whitespace, so a long expression continues on the next lines as long as it is inside
//! parentheses or brackets; outside them, an operator at the start of a line does *not*
//! continue the previous line. `#` starts a comment up to the end of the line, anywhere.
//!
//! Keywords are reserved only as statement heads: `mass` is a fine name inside an expression.
//!
//! **Errors.** Parsing does not stop at the first mistake: after a syntax error it skips to
//! the next statement boundary and goes on, so one run reports every error (up to
//! [`MAX_DIAGNOSTICS`]). See `recovery.rs` for how the boundary is chosen.
//!
//! **Limits.** Nesting of parentheses, brackets, signs and powers is bounded by
//! [`MAX_NESTING`], and the depth of an expression tree by [`MAX_DEPTH`] (a sum of a thousand
//! terms is a tree that deep), so that neither this parser nor any later recursive walk over
//! the tree can overflow the stack: past the limits the input gets a diagnostic. At the
//! limits parsing needs about 1 MB of stack in an unoptimized build (200 nested calls, the
//! worst case) and under 0.5 MB optimized, so the default 2 MB of a spawned thread is
//! enough.
//!
//! Every parser below skips the whitespace *before* its token and never after, so the input
//! left after a node starts right after the node's text: that is how node and statement
//! spans cover exactly their text.

mod building;
mod component;
mod expression;
mod input;
mod lexical;
mod positions;
mod recovery;
mod rigid;
mod statement;
mod table;

use super::ast::{ExprNode, SystemAst};
use super::span::{Diagnostic, Span};
use nom::IResult;
use positions::LineIndex;

/// Deepest nesting of parentheses, brackets, unary minus signs and powers.
pub const MAX_NESTING: u32 = 200;

/// Deepest expression tree (a leaf has depth 1).
pub const MAX_DEPTH: u32 = 1000;

/// Most syntax errors reported for one system: beyond that the input is likely not DSL at
/// all and more messages would only bury the first, useful ones.
pub const MAX_DIAGNOSTICS: usize = 100;

/// Parses a whole system, reporting every syntax error found (recovering at statement
/// boundaries).
///
/// ```
/// use varmass_symbolic::parse::{parse_system, ast::StatementKind};
/// let system = parse_system("coordinates x\nmass m = m0 + c*x; kinetic m*x'^2/2").unwrap();
/// assert_eq!(system.statements.len(), 3);
/// assert!(matches!(system.statements[1].kind, StatementKind::Mass(_)));
///
/// let errors = parse_system("coordinates x\nforse x: 1\nkinetic 1 +").unwrap_err();
/// assert_eq!(errors.len(), 2);
/// assert_eq!(errors[1].message, "expected an expression after `+`");
/// ```
pub fn parse_system(source: &str) -> Result<SystemAst, Vec<Diagnostic>> {
    let grammar = Grammar::new(source);
    let mut statements = Vec::new();
    let mut diagnostics = Vec::new();
    let mut rest = source;
    loop {
        rest = grammar.skip_separators(rest);
        let Some(first) = rest.chars().next() else {
            break;
        };
        let start = grammar.offset(rest);
        match grammar.statement(rest) {
            Ok((after, statement)) => {
                statements.push(statement);
                rest = after;
            }
            Err(error) => {
                let (at, diagnostic) = grammar.diagnostic(error, "a statement");
                diagnostics.push(diagnostic);
                if diagnostics.len() >= MAX_DIAGNOSTICS {
                    let here = grammar.span(at, at);
                    diagnostics.push(Diagnostic::new(
                        here,
                        format!("too many syntax errors; stopped after {MAX_DIAGNOSTICS}"),
                    ));
                    break;
                }
                // Always move forward, whatever the recovery heuristics say.
                let resume = grammar.resume(start, at).max(start + first.len_utf8());
                rest = source.get(resume..).unwrap_or("");
            }
        }
    }
    if diagnostics.is_empty() {
        Ok(SystemAst { statements })
    } else {
        Err(diagnostics)
    }
}

/// Parses a single expression (the whole input must be one expression). Newlines and
/// comments count as whitespace here, as inside parentheses.
///
/// ```
/// use varmass_symbolic::parse::{parse_expression, ast::{Expr, BinOp}};
/// let e = parse_expression("-x^2 + 1").unwrap();
/// assert!(matches!(&*e.node, Expr::Binary { op: BinOp::Add, .. }));
/// assert_eq!(parse_expression("2 +").unwrap_err().message, "expected an expression after `+`");
/// ```
pub fn parse_expression(source: &str) -> Result<ExprNode, Diagnostic> {
    let grammar = Grammar::new(source);
    grammar
        .whole_expression(source)
        .map_err(|error| grammar.diagnostic(error, "an expression").1)
}

/// The grammar over one source text. Parsers are methods taking the rest of the input; the
/// position of a rest is `source.len() - rest.len()`, since every rest is a suffix of the
/// source.
struct Grammar<'a> {
    source: &'a str,
    lines: LineIndex,
}

/// Why a parser stopped: a plain nom backtrack (`diagnostic` is `None`: "nothing of mine
/// here, try something else") or a syntax error with its message, raised as
/// `nom::Err::Failure` so that no `alt` swallows it.
struct ParseError {
    /// Bytes of input left where parsing stopped; recovery starts from there, which may
    /// differ from where the diagnostic points (an unclosed `(` is reported at the `(`).
    remaining: usize,
    diagnostic: Option<Box<Diagnostic>>,
}

impl<'a> nom::error::ParseError<&'a str> for ParseError {
    fn from_error_kind(input: &'a str, _kind: nom::error::ErrorKind) -> Self {
        ParseError {
            remaining: input.len(),
            diagnostic: None,
        }
    }

    fn append(_input: &'a str, _kind: nom::error::ErrorKind, other: Self) -> Self {
        other
    }
}

type PResult<'a, T> = IResult<&'a str, T, ParseError>;

/// Where an expression is being parsed.
#[derive(Clone, Copy, Debug)]
struct Context {
    /// Parentheses, brackets, signs and powers open around this point.
    nesting: u32,
    /// Inside `(` or `[`, where newlines are whitespace.
    nested: bool,
}

/// The context of an expression directly in a statement.
const STATEMENT_LEVEL: Context = Context {
    nesting: 0,
    nested: false,
};

impl<'a> Grammar<'a> {
    fn new(source: &'a str) -> Self {
        Grammar {
            source,
            lines: LineIndex::new(source),
        }
    }

    /// Byte offset of `rest` in the source.
    fn offset(&self, rest: &str) -> usize {
        self.source.len().saturating_sub(rest.len())
    }

    /// The span of the source bytes `start..end`.
    fn span(&self, start: usize, end: usize) -> Span {
        self.lines.span(self.source, start, end)
    }

    /// The span of the text consumed going from `before` to `after` (both rests).
    fn span_between(&self, before: &str, after: &str) -> Span {
        self.span(self.offset(before), self.offset(after))
    }

    /// A syntax error: `diagnostic` explains it, and recovery restarts from `at`.
    fn fail(&self, at: &str, diagnostic: Diagnostic) -> nom::Err<ParseError> {
        nom::Err::Failure(ParseError {
            remaining: at.len(),
            diagnostic: Some(Box::new(diagnostic)),
        })
    }

    /// The offset where `error` stopped and its diagnostic. A bare backtrack that escaped to
    /// the top becomes "unexpected …; expected `expected`".
    fn diagnostic(&self, error: nom::Err<ParseError>, expected: &str) -> (usize, Diagnostic) {
        match error {
            nom::Err::Error(error) | nom::Err::Failure(error) => {
                let at = self.source.len().saturating_sub(error.remaining);
                let diagnostic = match error.diagnostic {
                    Some(diagnostic) => *diagnostic,
                    None => {
                        let rest = self.source.get(at..).unwrap_or("");
                        self.unexpected_diagnostic(rest, expected)
                    }
                };
                (at, diagnostic)
            }
            // Only streaming parsers ask for more input; this grammar uses complete ones.
            nom::Err::Incomplete(_) => {
                let end = self.source.len();
                let span = self.span(end, end);
                (end, Diagnostic::new(span, "unexpected end of the input"))
            }
        }
    }

    /// The whole input as one expression (for [`parse_expression`]).
    fn whole_expression(&self, source: &'a str) -> Result<ExprNode, nom::Err<ParseError>> {
        let context = Context {
            nesting: 0,
            nested: true,
        };
        let (rest, (node, _depth)) = self.required(source, true, "an expression", "", |i| {
            self.expression(i, context)
        })?;
        let rest = self.skip_blanks(rest, true);
        if rest.is_empty() {
            Ok(node)
        } else {
            Err(self.unexpected(rest, "an operator or the end of the expression"))
        }
    }
}
