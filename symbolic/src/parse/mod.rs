//! Stage 1: DSL text → [`ast::SystemAst`], with positions (docs/dsl.md).
//!
//! One `nom` grammar serves the attribute macro (a string literal) and `.vms` files.
//! Statements are separated by newlines or `;` (a newline inside an open `(` or `[`
//! continues the statement); `#` starts a comment. The grammar and its error recovery are
//! described in `grammar/mod.rs`.

pub mod ast;
mod grammar;
pub mod keywords;
mod span;
mod tags;

pub use grammar::{parse_expression, parse_system, MAX_DEPTH, MAX_DIAGNOSTICS, MAX_NESTING};
pub use span::{Diagnostic, Origin, Span, Spanned};
pub use tags::{known_tags, select_tags, UnknownTag};
