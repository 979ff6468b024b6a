//! The `#[variable_mass_system("…")]` attribute macro of varmass.
//!
//! A thin entry point; the stages are files named after them (as in thiserror's `impl/`):
//! `ast.rs` reads the attribute and the struct, `valid.rs` checks the struct and the names
//! the generated code will bind, `expand.rs` runs the symbolic pipeline (parse → derive →
//! emit, in `varmass-symbolic`) and `fallback.rs` emits a stub impl when anything fails, so
//! one mistake does not cascade (its method signatures come from the emitter's own list,
//! `varmass_symbolic::emit::REQUIRED`). Errors are collected in a `ctxt::Ctxt` and
//! reported together.

mod ast;
mod ctxt;
mod expand;
mod fallback;
mod model;
mod valid;

#[cfg(test)]
mod tests;

use proc_macro::TokenStream;

/// Derives the equations of a variable-mass system from its Lagrangian, written in the
/// varmass DSL, and implements `varmass::core::VariableMassSystem` for the struct, whose
/// `f64` fields are the parameters.
///
/// The system is given inline, `#[variable_mass_system("coordinates x …")]`, or in a model
/// file relative to the crate's directory, `#[variable_mass_system(file = "models/sled.vms")]`;
/// options follow: `with = ["drag"]` selects tagged statements (optional effects) and
/// `emit = [...]` the optional outputs (`"hamiltonian"`, `"power"`, `"jacobian"`,
/// `"derivation"`; all without it). See the `varmass` crate for the DSL and an example.
#[proc_macro_attribute]
pub fn variable_mass_system(attr: TokenStream, item: TokenStream) -> TokenStream {
    expand::expand(attr.into(), item.into()).into()
}
