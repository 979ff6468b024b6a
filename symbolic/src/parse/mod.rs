//! Stage 1: DSL text → [`ast::SystemAst`], with positions (SPEC §2).
//!
//! One `nom` grammar serves the attribute macro (a string literal) and `.vms` files.
//! Statements are separated by newlines or `;`; `#` starts a comment.

pub mod ast;
mod grammar;
pub mod keywords;
mod span;

pub use grammar::{parse_expression, parse_system, MAX_DEPTH, MAX_DIAGNOSTICS, MAX_NESTING};
pub use span::{Diagnostic, Span, Spanned};
