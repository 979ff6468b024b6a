//! Stage 3: from a parsed system to its derivation (docs/mechanics.md; ARCHITECTURE.md#stage-3-mechanics).
//!
//! [`derive()`](fn@derive) runs the whole stage: it resolves names and lowers every expression into a
//! checked [`Model`], derives every quantity into a [`Derivation`], then verifies the
//! system's `check`s against it. Every problem is a [`Diagnostic`] with the position of the
//! statement it is about.
//!
//! ```
//! use varmass_symbolic::mechanics::{derive_source, Parameters};
//!
//! let sled = "coordinates x
//!             mass m = m0 + c*x
//!             body sled: mass m, position [x]
//!             potential -m*g*x*sin(theta)
//!             force sled: [-f_d*m*g*cos(theta)]
//!             inflow sled: velocity [0]
//!             check p_x = m*x'
//!             check R2_x = -c*x'^2";
//! let derivation = derive_source(sled, Parameters::Inferred).expect("the sled derives");
//! assert_eq!(derivation.checks.len(), 2);
//! ```

mod build;
mod checks;
mod derivation;
mod equations;
mod forces;
mod inputs;
mod jacobian;
mod lagrangian;
mod linear;
mod masses;
mod model;
mod outputs;
mod render;
mod resolve;
mod rigid;
mod rigid_forces;
mod rotation;
mod stops;
mod switches;
mod tables;

pub use derivation::{
    CheckOutcome, Derivation, JacobianParts, VelocitySolve, SYMBOLIC_INVERSE_MAX_DOF,
};
pub use inputs::ModelInput;
pub use linear::Matrix;
pub use model::{
    Body, Check, Coordinate, Flow, FlowVelocityValue, Load, LoadKind, LoadTarget, Mass, MassKind,
    Model, Rigid, Term, TermKind,
};
pub use outputs::{Outputs, UnknownOutput};
pub(crate) use render::Of;
pub use resolve::{is_reserved, Parameters};
pub use stops::{time_tables, TimeTable};
pub use switches::switching_functions;
pub use tables::{read_points, ModelTable};

use crate::parse::{
    ast::{ExprNode, SystemAst},
    parse_system, Diagnostic,
};
use std::path::Path;

/// Resolves and lowers a parsed system into a checked [`Model`] (table files relative to
/// the current directory).
pub fn build_model(ast: &SystemAst, parameters: Parameters) -> Result<Model, Vec<Diagnostic>> {
    build::build_model(ast, parameters, Path::new("."), &[])
}

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
    let model = build::build_model(ast, parameters, base, laws)?;
    let units = crate::units::check_units(ast)?;
    let mut derivation = derivation::derive_model(model, outputs)?;
    let differentiated = inputs::check_not_differentiated(&derivation);
    if !differentiated.is_empty() {
        return Err(differentiated);
    }
    derivation.units = units;
    Ok(derivation)
}

/// Parses and derives DSL source text.
pub fn derive_source(source: &str, parameters: Parameters) -> Result<Derivation, Vec<Diagnostic>> {
    let ast = parse_system(source)?;
    derive(&ast, parameters)
}
