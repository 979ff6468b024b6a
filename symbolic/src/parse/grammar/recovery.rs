//! Error recovery: after a syntax error, where to start reading the next statement.
//!
//! Statements end at newlines and `;`, but a newline inside an open `(` or `[` does not end
//! one, and an error often leaves brackets unbalanced. The rules, in order:
//!
//! 1. If the error stopped at the first token of a later line and that line reads like a
//!    statement (a statement keyword, a blank, then a name, number, `-`, `(` or `.`),
//!    resume right there: typically a `)` was forgotten and the parser ran on into the next
//!    statement, which deserves to be checked too.
//! 2. Otherwise skip forward from the error to the first `;`, or the first newline where
//!    the brackets opened since the statement's start are balanced (so a multi-line
//!    expression is skipped whole), or a newline followed by a line that reads like a
//!    statement (so an unbalanced bracket does not swallow the rest of the input).
//!
//! Comments are skipped while scanning: a `;` or bracket in a comment means nothing.

use super::Grammar;
use crate::parse::keywords::STATEMENTS;

/// Whether `text` starts (after blanks) like a statement: a statement keyword, a blank, and
/// something that can follow a keyword. Keywords are not reserved inside expressions, so
/// this is a heuristic; `mass * g` at the start of a continuation line does not match.
pub(super) fn looks_like_statement(text: &str) -> bool {
    let mut text = text.trim_start_matches([' ', '\t', '\r']);
    // Tags before the keyword: `[drag] force …`.
    if let Some(tagged) = text.strip_prefix('[') {
        let Some(close) = tagged.find(']') else {
            return false;
        };
        text = tagged[close + 1..].trim_start_matches([' ', '\t']);
    }
    let length = text
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(text.len());
    let (word, rest) = text.split_at(length);
    if !STATEMENTS.contains(&word) || !rest.starts_with([' ', '\t']) {
        return false;
    }
    rest.trim_start_matches([' ', '\t'])
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphanumeric() || "_-(.".contains(c))
}

impl Grammar<'_> {
    /// Where to resume after an error in the statement starting at `start` that stopped at
    /// `at` (byte offsets). The result may be at a separator, which the caller skips.
    pub(super) fn resume(&self, start: usize, at: usize) -> usize {
        let source = self.source;
        let at = at.clamp(start, source.len());
        let before = source.get(..at).unwrap_or("");
        // Rule 1.
        if let Some(newline) = before.rfind('\n') {
            let indent = source.get(newline + 1..at).unwrap_or("");
            let first_on_line = indent.chars().all(|c| c == ' ' || c == '\t' || c == '\r');
            if newline >= start && first_on_line {
                if let Some(rest) = source.get(at..) {
                    if looks_like_statement(rest) {
                        return at;
                    }
                }
            }
        }
        // Rule 2.
        let mut depth = bracket_depth(source.get(start..at).unwrap_or(""));
        let bytes = source.as_bytes();
        let mut position = at;
        while let Some(&byte) = bytes.get(position) {
            match byte {
                b'#' => {
                    position = source
                        .get(position..)
                        .and_then(|rest| rest.find('\n'))
                        .map_or(source.len(), |n| position + n);
                    continue;
                }
                b';' => return position,
                b'\n' => {
                    let next_line = source.get(position + 1..).unwrap_or("");
                    if depth <= 0 || looks_like_statement(next_line) {
                        return position;
                    }
                }
                b'(' | b'[' => depth += 1,
                b')' | b']' => depth -= 1,
                _ => {}
            }
            position += 1;
        }
        source.len()
    }
}

/// Open minus closed brackets in `text`, ignoring comments.
fn bracket_depth(text: &str) -> i64 {
    let mut depth = 0;
    for line in text.split('\n') {
        let code = line.split('#').next().unwrap_or("");
        for c in code.chars() {
            match c {
                '(' | '[' => depth += 1,
                ')' | ']' => depth -= 1,
                _ => {}
            }
        }
    }
    depth
}
