//! Stage 3: from a parsed system to its derivation (docs/mechanics.md; ARCHITECTURE.md#stage-3-mechanics).
//!
//! `derive` (the driver, `crate::pipeline`, which stands above this stage and the units
//! check and is named at the crate root) runs the whole stage: it resolves names and lowers
//! every expression into a checked [`Model`], has the units check read that model, derives
//! every quantity into a [`Derivation`], then verifies the system's `check`s against it.
//! Every problem is a [`Diagnostic`] with the position of the statement it is about.
//!
//! ```
//! use varmass_symbolic::{derive_source, mechanics::Parameters};
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
mod rigid_rates;
mod rigid_solve;
mod rotation;
mod stages;
mod stops;
mod switches;
mod tables;
mod unit_table;

pub use derivation::{
    CheckOutcome, Derivation, JacobianParts, VelocitySolve, SYMBOLIC_INVERSE_MAX_DOF,
};
pub(crate) use inputs::check_not_differentiated;
pub use inputs::ModelInput;
pub use jacobian::gradient;
pub use linear::Matrix;
pub use model::{
    Body, Check, Coordinate, Flow, FlowVelocityValue, Load, LoadKind, LoadTarget, Mass, MassKind,
    Model, Rigid, Term, TermKind,
};
pub use outputs::{Outputs, UnknownOutput};
pub(crate) use render::Of;
pub use resolve::{is_reserved, Parameters};
pub use rigid_solve::RigidVelocities;
pub use stages::{RateStages, TaylorLayout, TaylorStages};
pub use stops::{sensitivity_obstacle, time_tables, TimeTable};
pub use switches::{switching_functions, table_switches, TableSwitch};
pub(crate) use tables::check_smooth_enough;
pub use tables::{read_points, runtime_placeholder, ModelTable};
pub use unit_table::UnitTable;

pub(crate) use build::build_model as build_model_in;
pub(crate) use derivation::derive_model;
pub(crate) use resolve::Binding;

use crate::parse::{ast::SystemAst, Diagnostic};
use std::path::Path;

/// Resolves and lowers a parsed system into a checked [`Model`] (table files relative to
/// the current directory).
pub fn build_model(ast: &SystemAst, parameters: Parameters) -> Result<Model, Vec<Diagnostic>> {
    build::build_model(ast, parameters, Path::new("."), &[])
}
