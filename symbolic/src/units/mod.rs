//! Units and dimensions, checked before the derivation when a system has a `units`
//! statement (see `docs/dsl.md#units`).
//!
//! [`Dimension`] is the algebra (exact rational exponents of kg, m, s; rad dimensionless),
//! [`unit_dimension`] reads a unit expression, and [`check_units`] applies every rule to
//! the spanned AST: each term of T, V and L is an energy, a generalized force on q is an
//! energy per unit of q, the operands of `+` agree, and so on, each failure a diagnostic
//! at the offending term.

mod calls;
mod check;
mod infer;
mod text;
mod unit;

pub use crate::dimension::Dimension;
pub use crate::mechanics::UnitTable;
pub use check::check_units;
pub use text::text as expression_text;
pub use unit::{unit_dimension, UNITS};
