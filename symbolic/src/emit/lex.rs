//! Generated Rust text turned into tokens without `TokenStream::from_str`.
//!
//! The emitters print expressions as text (a printed child is a `String`, cheap to copy
//! into its parent where a token stream is not) and turn each block into tokens once.
//! `proc_macro2`'s own lexer does that generally, and therefore slowly in an unoptimized
//! proc macro: it tries every kind of token at every position, and inside the compiler it
//! lexes the text twice (its own check, then the compiler's). The text we print is a small
//! language — ASCII identifiers, numbers, punctuation and brackets — which this lexer
//! reads in one pass, building the same tokens directly. Anything outside that language
//! (a string, a character, a comment, a non-ASCII letter, a number in exponent form) makes
//! it give up, and the caller lexes the text the general way: the tokens are the same
//! either way (`tests::same_tokens_as_proc_macro2`).

use proc_macro2::{Delimiter, Group, Ident, Literal, Punct, Spacing, Span, TokenStream, TokenTree};
use rustc_hash::FxHashMap;

/// The punctuation `proc_macro2` lexes as `Punct` (its `punct_char`); the apostrophe,
/// which starts characters and lifetimes, is left to the general lexer.
const PUNCT: &[u8] = b"~!@#$%^&*-=+|;:,<.>/?";

/// The tokens of `text`, or `None` if it holds something this lexer does not read.
pub(crate) fn lex(text: &str) -> Option<TokenStream> {
    let bytes = text.as_bytes();
    let mut lexer = Lexer {
        bytes,
        text,
        at: 0,
        literals: FxHashMap::default(),
    };
    // The open groups, innermost last, each with its delimiter and its tokens so far.
    let mut open: Vec<(Delimiter, Vec<TokenTree>)> = vec![(Delimiter::None, Vec::new())];
    while let Some(&b) = bytes.get(lexer.at) {
        let token: TokenTree = match b {
            b' ' | b'\n' | b'\t' => {
                lexer.at += 1;
                continue;
            }
            b'(' | b'[' | b'{' => {
                lexer.at += 1;
                open.push((delimiter(b)?, Vec::new()));
                continue;
            }
            b')' | b']' | b'}' => {
                lexer.at += 1;
                let (delim, trees) = open.pop()?;
                if open.is_empty() || delimiter_closed_by(b)? != delim {
                    return None;
                }
                Group::new(delim, trees.into_iter().collect()).into()
            }
            b'0'..=b'9' => lexer.number()?.into(),
            b'a'..=b'z' | b'A'..=b'Z' | b'_' => lexer.ident()?.into(),
            _ if PUNCT.contains(&b) => lexer.punct()?.into(),
            _ => return None,
        };
        open.last_mut()?.1.push(token);
    }
    let (_, trees) = open.pop()?;
    open.is_empty().then(|| trees.into_iter().collect())
}

struct Lexer<'a> {
    bytes: &'a [u8],
    text: &'a str,
    at: usize,
    /// Each literal made once per text (`2f64` recurs).
    literals: FxHashMap<&'a str, Literal>,
}

impl<'a> Lexer<'a> {
    fn peek(&self, ahead: usize) -> Option<u8> {
        self.bytes.get(self.at + ahead).copied()
    }

    /// Advances over bytes that `keep` accepts.
    fn skip_while(&mut self, keep: impl Fn(u8) -> bool) {
        while self.peek(0).is_some_and(&keep) {
            self.at += 1;
        }
    }

    fn ident(&mut self) -> Option<Ident> {
        let start = self.at;
        self.skip_while(|b| b.is_ascii_alphanumeric() || b == b'_');
        // `r#raw`, `b"bytes"`, `r"raw"`, `'lifetime`: the general lexer's business.
        if matches!(self.peek(0), Some(b'#' | b'"' | b'\'')) {
            return None;
        }
        Some(Ident::new(&self.text[start..self.at], Span::call_site()))
    }

    /// `2`, `2f64`, `0.5f64`: digits, a fraction, a suffix.
    fn number(&mut self) -> Option<Literal> {
        let start = self.at;
        self.skip_while(|b| b.is_ascii_digit());
        if self.peek(0) == Some(b'.') && self.peek(1).is_some_and(|b| b.is_ascii_digit()) {
            self.at += 1;
            self.skip_while(|b| b.is_ascii_digit());
        }
        // An exponent (`1e-5`) or anything else glued on: not ours to read.
        if matches!(self.peek(0), Some(b'e' | b'E' | b'.' | b'#' | b'"' | b'\'')) {
            return None;
        }
        self.skip_while(|b| b.is_ascii_alphanumeric() || b == b'_');
        let repr = &self.text[start..self.at];
        if let Some(known) = self.literals.get(repr) {
            return Some(known.clone());
        }
        let literal: Literal = repr.parse().ok()?;
        self.literals.insert(repr, literal.clone());
        Some(literal)
    }

    /// One punctuation mark, joint with the next when that is punctuation too (as
    /// `proc_macro2` decides: `::` is a joint `:` and an alone one).
    fn punct(&mut self) -> Option<Punct> {
        let ch = self.peek(0)?;
        // A comment: the general lexer's business.
        if ch == b'/' && matches!(self.peek(1), Some(b'/' | b'*')) {
            return None;
        }
        self.at += 1;
        let next_is_punct = self
            .peek(0)
            .is_some_and(|b| PUNCT.contains(&b) || b == b'\'');
        let comment_next = self.peek(0) == Some(b'/') && matches!(self.peek(1), Some(b'/' | b'*'));
        let spacing = if next_is_punct && !comment_next {
            Spacing::Joint
        } else {
            Spacing::Alone
        };
        Some(Punct::new(char::from(ch), spacing))
    }
}

fn delimiter(open: u8) -> Option<Delimiter> {
    match open {
        b'(' => Some(Delimiter::Parenthesis),
        b'[' => Some(Delimiter::Bracket),
        b'{' => Some(Delimiter::Brace),
        _ => None,
    }
}

fn delimiter_closed_by(close: u8) -> Option<Delimiter> {
    match close {
        b')' => Some(Delimiter::Parenthesis),
        b']' => Some(Delimiter::Bracket),
        b'}' => Some(Delimiter::Brace),
        _ => None,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Token trees as a comparable description: kind, text, spacing, delimiters.
    fn describe(stream: TokenStream, out: &mut Vec<String>) {
        for tree in stream {
            match tree {
                TokenTree::Group(g) => {
                    out.push(format!("open {:?}", g.delimiter()));
                    describe(g.stream(), out);
                    out.push("close".to_string());
                }
                TokenTree::Ident(i) => out.push(format!("ident {i}")),
                TokenTree::Punct(p) => out.push(format!("punct {} {:?}", p.as_char(), p.spacing())),
                TokenTree::Literal(l) => out.push(format!("literal {l}")),
            }
        }
    }

    fn described(stream: TokenStream) -> Vec<String> {
        let mut out = Vec::new();
        describe(stream, &mut out);
        out
    }

    /// `text` lexes here to exactly the tokens `proc_macro2` makes of it.
    pub(crate) fn assert_same(text: &str) {
        let general: TokenStream = text.parse().expect("generated text lexes");
        if let Some(ours) = lex(text) {
            assert_eq!(described(ours), described(general), "lexing {text:?}");
        }
    }

    #[test]
    fn same_tokens_as_proc_macro2() {
        for text in [
            "let __t0 = x.sin();\nlet __t1 = -2f64 * m_p.powi(2) / (a - -b);",
            "[1.0f64 / (x * y).sqrt(), -0.5f64 * __t3, x_dot.powf(1.5f64)]",
            "::varmass::core::table::lookup_or_nan(&__TABLE_F_0, t)",
            "a.max(b) - (c)?.abs() + d[2] * e.atan2(f) {}",
            "x <= y && z != w || !v; a::<f64>()",
        ] {
            assert_same(text);
            assert!(lex(text).is_some(), "{text:?} is in the language read here");
        }
    }

    /// Every block of every model file's emission (each optional output, the Taylor
    /// recurrences and the lanes too) lexes to the same tokens here as in `proc_macro2`:
    /// under `cfg(test)` [`tokens`](super::super::expression::tokens) asserts it.
    #[test]
    fn every_model_emits_the_same_tokens() {
        use crate::emit::{emit_system_for, Target};
        use crate::mechanics::{Outputs, Parameters};
        let models = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../models");
        let mut files: Vec<_> = std::fs::read_dir(&models)
            .expect("models/ is there")
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|path| path.extension().is_some_and(|e| e == "vms"))
            .collect();
        files.sort();
        let outputs = Outputs {
            taylor: true,
            lanes: true,
            ..Outputs::FULL
        };
        let target = Target {
            name: Ident::new("System", Span::call_site()),
            runtime: "::varmass::core".parse().expect("a path"),
        };
        let mut emitted = 0;
        for file in &files {
            let source = std::fs::read_to_string(file).expect("a model file reads");
            let Ok(ast) = crate::parse::parse_system(&source) else {
                continue;
            };
            let Ok(mut d) = crate::pipeline::derive_for(&ast, Parameters::Inferred, outputs) else {
                continue;
            };
            let code = emit_system_for(&mut d, &source, &target, outputs);
            assert!(!code.is_empty(), "{} emits code", file.display());
            emitted += 1;
        }
        // Measured: 13 of the 15 model files derive without tags (2026-11-26).
        assert!(emitted >= 13, "{emitted} model files emitted");
    }

    #[test]
    fn gives_up_outside_its_language() {
        for text in [
            "lookup(&T, \"F\", t)",
            "1e-5f64",
            "x // note",
            "r#type",
            "'a",
            "é",
            "(a",
            "a)",
            "(a]",
        ] {
            assert!(lex(text).is_none(), "{text:?} is left to proc_macro2");
        }
    }
}
