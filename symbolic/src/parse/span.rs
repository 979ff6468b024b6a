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

/// `start..end` clamped into `source` and widened to character boundaries: the start
/// rounded down, the end up, so that `source[start..end]` is always valid text (0 and the
/// source's length are boundaries, so both loops stop).
pub(crate) fn char_bounds(source: &str, start: usize, end: usize) -> (usize, usize) {
    let mut start = start.min(source.len());
    while !source.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = end.clamp(start, source.len());
    while !source.is_char_boundary(end) {
        end += 1;
    }
    (start, end)
}

impl Span {
    /// The span of `source[start..end]`, with line and column computed from `source`.
    /// Offsets past the end or inside a character are clamped, never a panic.
    pub fn from_range(source: &str, start: usize, end: usize) -> Span {
        let (start, end) = char_bounds(source, start, end);
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
    ///  --> 2:10
    ///   |
    /// 2 | mass m = mm + c*x
    ///   |          ^^
    /// ```
    ///
    /// The carets line up under the text as a terminal shows it: a tab counts as
    /// four columns (and is shown as four spaces), East Asian wide characters
    /// as two, combining marks as none, and control characters are shown as `�`. A span
    /// over several lines shows its first and last line (with `...` between them when
    /// lines are skipped), each underlined where the span covers it. An empty span (at the
    /// end of a line or of the input) gets one caret just after the text.
    pub fn render(&self, source: &str) -> String {
        self.render_at(source, Origin::default())
    }

    /// [`Diagnostic::render`] for DSL text that sits inside a larger file (a string literal
    /// in Rust source): line and column numbers are shown in the file's terms.
    pub fn render_at(&self, source: &str, origin: Origin) -> String {
        self.render_located(source, origin, "")
    }

    /// [`Diagnostic::render`] for DSL text read from a file: the position line names the
    /// file, `--> models/sled.vms:3:10`.
    pub fn render_in_file(&self, source: &str, file: &str) -> String {
        self.render_located(source, Origin::default(), &format!("{file}:"))
    }

    /// The rendering, with `prefix` before the position.
    fn render_located(&self, source: &str, origin: Origin, prefix: &str) -> String {
        let span = Span::from_range(source, self.span.start, self.span.end);
        let file_line = |line: u32| line + origin.line.saturating_sub(1);
        let file_column = |line: u32, column: u32| {
            if line == 1 {
                column + origin.column.saturating_sub(1)
            } else {
                column
            }
        };
        let starts = line_starts(source);
        // The last line is the one holding the span's last byte, so a span that ends just
        // after a newline does not drag in the next, uncovered line.
        let last_line = if span.end > span.start {
            Span::from_range(source, span.end - 1, span.end).line
        } else {
            span.line
        };
        let gutter = file_line(last_line).to_string().len();
        let pad = " ".repeat(gutter);
        let mut out = format!(
            "error: {}\n{pad}--> {prefix}{}:{}\n{pad} |",
            self.message,
            file_line(span.line),
            file_column(span.line, span.column)
        );
        let mut shown = vec![span.line];
        if last_line > span.line {
            shown.push(last_line);
        }
        for (k, &line) in shown.iter().enumerate() {
            if k > 0 && line > span.line + 1 {
                out.push_str("\n...");
            }
            let line_start = starts.get(line as usize - 1).copied().unwrap_or(0);
            let line_end = starts
                .get(line as usize)
                .map_or(source.len(), |&next| next - 1);
            let text = source.get(line_start..line_end).unwrap_or("");
            let text = text.strip_suffix('\r').unwrap_or(text);
            let from = span.start.clamp(line_start, line_start + text.len()) - line_start;
            let to = span.end.clamp(line_start, line_start + text.len()) - line_start;
            let indent = display_width(text.get(..from).unwrap_or(""));
            let width = display_width(text.get(from..to).unwrap_or("")).max(1);
            out.push_str(&format!(
                "\n{:>gutter$} | {}\n{pad} | {}{}",
                file_line(line),
                display_text(text),
                " ".repeat(indent),
                "^".repeat(width)
            ));
        }
        if let Some(help) = &self.help {
            out.push_str(&format!("\n{pad} = help: {help}"));
        }
        out
    }
}

/// Where DSL text starts inside a larger file (1-based), for [`Diagnostic::render_at`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Origin {
    /// The file line of the DSL's first line.
    pub line: u32,
    /// The file column of the DSL's first character.
    pub column: u32,
}

impl Default for Origin {
    fn default() -> Self {
        Origin { line: 1, column: 1 }
    }
}

/// How many columns a tab takes in [`Diagnostic::render`].
const TAB_WIDTH: usize = 4;

/// Byte offsets where the lines of `source` start.
fn line_starts(source: &str) -> Vec<usize> {
    std::iter::once(0)
        .chain(source.match_indices('\n').map(|(i, _)| i + 1))
        .collect()
}

/// `text` as it is shown in a rendered diagnostic: tabs expanded, control characters
/// replaced, so that [`display_width`] matches what a terminal prints.
fn display_text(text: &str) -> String {
    let mut shown = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\t' => shown.push_str(&" ".repeat(TAB_WIDTH)),
            c if c.is_control() => shown.push('\u{fffd}'),
            c => shown.push(c),
        }
    }
    shown
}

/// The number of terminal columns `text` takes once passed through [`display_text`].
fn display_width(text: &str) -> usize {
    text.chars().map(char_width).sum()
}

/// Columns of one character. A small table instead of a Unicode-width crate: the DSL is
/// ASCII, non-ASCII text only appears in mistakes and comments, and this covers the wide
/// scripts and the combining marks that would visibly shift the caret.
fn char_width(c: char) -> usize {
    match c {
        '\t' => TAB_WIDTH,
        '\u{0300}'..='\u{036f}' | '\u{200b}'..='\u{200f}' | '\u{fe00}'..='\u{fe0f}' => 0,
        '\u{1100}'..='\u{115f}'
        | '\u{2e80}'..='\u{a4cf}'
        | '\u{ac00}'..='\u{d7a3}'
        | '\u{f900}'..='\u{faff}'
        | '\u{fe30}'..='\u{fe4f}'
        | '\u{ff00}'..='\u{ff60}'
        | '\u{ffe0}'..='\u{ffe6}'
        | '\u{1f300}'..='\u{1f64f}'
        | '\u{1f900}'..='\u{1f9ff}'
        | '\u{20000}'..='\u{3fffd}' => 2,
        _ => 1,
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
