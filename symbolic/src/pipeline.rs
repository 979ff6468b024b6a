//! The driver of the derivation: resolution (`mechanics`), the units check on the resolved
//! model (`units`), then the derivation (`mechanics`). It sits above both stages so that
//! neither calls the other: `units` reads the resolved [`Model`](crate::mechanics::Model),
//! `mechanics` never names `units`.
//!
//! ```
//! use varmass_symbolic::{derive_source, mechanics::Parameters};
//! let source = "coordinates x; units x: m, k: N/m, m0: kg; kinetic m0*x'^2/2; potential k*x^2/2";
//! let derivation = derive_source(source, Parameters::Inferred).unwrap();
//! assert_eq!(derivation.units.unwrap().written("k"), Some("N/m"));
//! ```

use crate::mechanics::{build_model_in, derive_model, Derivation, Outputs, Parameters};
use crate::parse::{
    ast::{ExprNode, SystemAst},
    parse_system, Diagnostic,
};
use std::path::Path;

/// Derives a parsed system and verifies its `check`s. A system with a `units` statement
/// is first checked for dimensions ([`crate::units::check_units`]).
pub fn derive(ast: &SystemAst, parameters: Parameters) -> Result<Derivation, Vec<Diagnostic>> {
    derive_for(ast, parameters, Outputs::FULL)
}

/// [`derive()`](fn@derive), deriving only the optional quantities `outputs` asks for (the Jacobian is
/// `None` without [`Outputs::jacobian`]).
pub fn derive_for(
    ast: &SystemAst,
    parameters: Parameters,
    outputs: Outputs,
) -> Result<Derivation, Vec<Diagnostic>> {
    derive_in(ast, parameters, outputs, Path::new("."))
}

/// [`derive_for`] with `table` files read relative to `base` (the model file's directory;
/// for an inline system the crate's, `CARGO_MANIFEST_DIR`).
pub fn derive_in(
    ast: &SystemAst,
    parameters: Parameters,
    outputs: Outputs,
    base: &Path,
) -> Result<Derivation, Vec<Diagnostic>> {
    derive_with_laws(ast, parameters, outputs, base, &[])
}

/// [`derive_in`] with a law for some of the model's inputs: `laws` pairs an input's name
/// with an expression of its declared arguments and the parameters (parsed with
/// [`crate::parse::parse_expression`]), which replaces each call of that input before
/// anything is differentiated (docs/inputs.md#the-command-line-tool). Such an input is no
/// longer one of [`Derivation::inputs`]. A law that calls an input is a diagnostic at the
/// input's declaration; a law for a name that is no input is ignored (the caller names
/// it).
pub fn derive_with_laws(
    ast: &SystemAst,
    parameters: Parameters,
    outputs: Outputs,
    base: &Path,
    laws: &[(String, ExprNode)],
) -> Result<Derivation, Vec<Diagnostic>> {
    let model = build_model_in(ast, parameters, base, laws)?;
    let units = crate::units::check_units(ast, &model)?;
    let mut derivation = derive_model(model, outputs)?;
    let mut refused = crate::mechanics::check_not_differentiated(&derivation);
    refused.extend(crate::mechanics::check_smooth_enough(&derivation));
    if !refused.is_empty() {
        return Err(refused);
    }
    derivation.units = units;
    Ok(derivation)
}

/// Parses and derives DSL source text.
pub fn derive_source(source: &str, parameters: Parameters) -> Result<Derivation, Vec<Diagnostic>> {
    let ast = parse_system(source)?;
    derive(&ast, parameters)
}
