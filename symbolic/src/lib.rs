//! The symbolic engine of varmass.
//!
//! The pipeline reads top to bottom, one module a stage:
//!
//! 1. [`parse`] — the DSL text (see `docs/dsl.md`) into a statement AST that keeps positions;
//! 2. [`expr`] — hash-consed expressions with exact rational constants, the frozen-mass
//!    calculus (∂*, d*/dt), canonical simplification, evaluation, printing and CSE;
//! 3. [`mechanics`] — from a checked system to H, the canonical equations and the forces
//!    (Zhang Jiuzhu, *Hamilton's canonical equations and Hamilton's principle for variable
//!    mass systems*, Mechanics in Engineering 37(1):125–128, 2015; see
//!    `docs/mechanics.md`);
//! 4. [`emit`] — the derivation as Rust: the `VariableMassSystem` impl that the
//!    `#[variable_mass_system]` macro adds, straight-line code with shared subexpressions.
//!
//! Beside the stages, [`units`] checks the dimensions of a system that declares `units` on
//! its resolved model, between name resolution and the derivation (see `docs/dsl.md#units`);
//! [`pipeline`] is the driver that runs the three in turn (its functions are named here,
//! [`derive_source`] and the others), [`dimension`] the algebra of dimensions that `units`,
//! `mechanics` and the registry share, and [`quantity`] the registry's vocabulary (names,
//! labels, dimension rules).
//!
//! Before the derivation, [`compose`] expands the `use` of other model files as components
//! (`docs/components.md`) into one composed model.
//!
//! Each module reads only those before it in: parse → expr → dimension → quantity →
//! compose → mechanics (the derivation, which answers "give me quantity Q") → units → emit (which
//! owns the quantity → generated-method map) → pipeline.
//!
//! `ARCHITECTURE.md` at the repository root describes the stages and their invariants.
//!
//! Nothing in this crate panics on user input: every problem is a [`Diagnostic`] with the
//! position of the offending text.
#![warn(missing_docs)]

pub mod compose;
pub mod dimension;
pub mod emit;
pub mod expr;
pub mod mechanics;
pub mod parse;
pub mod pipeline;
pub mod quantity;
pub mod units;

pub use parse::{Diagnostic, Span};
pub use pipeline::{derive, derive_for, derive_in, derive_source, derive_with_laws};
