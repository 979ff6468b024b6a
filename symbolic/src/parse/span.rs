//! Positions in the DSL text and the diagnostics that point at them.

use std::fmt;

/// A region of the DSL source: a byte range plus the 1-based line and column (in characters)
/// of its first byte. Every statement and expression node carries one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// Byte offset of the first byte.
    pub start: usize,
    /// Byte offset one past the last byte (`start == end` for an empty span).
    pub end: usize,
    /// 1-based line of `start`.
    pub line: u32,
    /// 1-based column of `start`, counted in characters.
    pub column: u32,
}

impl Span {
    /// The span of `source[start..end]`, with line and column computed from `source`.
    /// Offsets past the end or inside a character are clamped, never a panic.
    pub fn from_range(source: &str, start: usize, end: usize) -> Span {
        let mut start = start.min(source.len());
        while !source.is_char_boundary(start) {
            start -= 1;
        }
        let end = end.clamp(start, source.len());
        let before = &source[..start];
        let line = before.matches('\n').count() as u32 + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = source[line_start..start].chars().count() as u32 + 1;
        Span {
            start,
            end,
            line,
            column,
        }
    }

    /// The smallest span covering both `self` and `other`.
    pub fn join(self, other: Span) -> Span {
        if other.start < self.start {
            return other.join(self);
        }
        Span {
            end: self.end.max(other.end),
            ..self
        }
    }
}

/// A problem found in a DSL system, with the position it is about.
///
/// `Display` gives a one-line `line:column: message`; [`Diagnostic::render`] adds the
/// source line and a caret under the offending text, as a compiler does.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}:{}: {message}", span.line, span.column)]
pub struct Diagnostic {
    /// What is wrong, in words a physicist understands.
    pub message: String,
    /// Where it is.
    pub span: Span,
    /// Further explanation or a suggested fix, shown after the caret.
    pub help: Option<String>,
}

impl Diagnostic {
    /// A diagnostic at `span`.
    pub fn new(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            message: message.into(),
            span,
            help: None,
        }
    }

    /// Adds a help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    /// The message with the offending source line and a caret line under the span:
    ///
    /// ```text
    /// error: unknown symbol `mm`
    ///  --> 2:8
    ///   |
    /// 2 | mass m = mm + c*x
    ///   |          ^^
    /// ```
    pub fn render(&self, source: &str) -> String {
        let span = Span::from_range(source, self.span.start, self.span.end);
        let line_text = source.lines().nth(span.line as usize - 1).unwrap_or("");
        let gutter = span.line.to_string().len();
        let pad = " ".repeat(gutter);
        let col = span.column as usize - 1;
        let available = line_text.chars().count().saturating_sub(col);
        let width = source[span.start..span.end]
            .split('\n')
            .next()
            .map_or(0, |s| s.chars().count())
            .min(available)
            .max(1);
        let mut out = format!(
            "error: {}\n{pad}--> {}:{}\n{pad} |\n{} | {}\n{pad} | {}{}",
            self.message,
            span.line,
            span.column,
            span.line,
            line_text,
            " ".repeat(col),
            "^".repeat(width)
        );
        if let Some(help) = &self.help {
            out.push_str(&format!("\n{pad} = help: {help}"));
        }
        out
    }
}

/// A value with the span of the text it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Spanned<T> {
    /// The value.
    pub node: T,
    /// Where it was written.
    pub span: Span,
}

impl<T> Spanned<T> {
    /// Wraps `node` with `span`.
    pub fn new(node: T, span: Span) -> Self {
        Spanned { node, span }
    }
}

impl<T: fmt::Display> fmt::Display for Spanned<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.node.fmt(f)
    }
}
