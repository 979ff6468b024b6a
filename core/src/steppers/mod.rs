//! The steppers, one per file. Each is generic over the system (monomorphized: no `dyn`, no
//! allocation per step) and implements [`crate::stepper::Stepper`].

pub mod adaptive;
pub(crate) mod control;
pub mod dirk;
pub mod dop853;
pub mod dormand_prince;
pub(crate) mod dp_tableau;
pub mod esdirk43;
pub mod euler;
pub(crate) mod explicit;
pub mod fixed;
pub mod implicit_midpoint;
pub mod newton;
#[cfg(test)]
mod order_conditions;
pub mod rk4;
pub mod sdirk4;
pub(crate) mod step_size;
mod stiffness;
pub mod taylor;
pub mod variational;

pub use adaptive::{Adaptive, AdaptiveMethod};
pub use control::{AdaptiveControl, StepControl};
pub use dirk::{Dirk, DirkMethod, DirkNewton, DirkState, DirkTableau};
pub use dop853::{Dop853, Dop853State};
pub use dormand_prince::{DormandPrince, DormandPrinceState};
pub use esdirk43::{Esdirk43, Esdirk43Method};
pub use euler::{EulerMethod, ExplicitEuler};
pub use fixed::{Fixed, FixedMethod};
pub use implicit_midpoint::{ImplicitMidpoint, ImplicitMidpointConfig, ImplicitMidpointMethod};
pub use newton::NewtonConfig;
pub use rk4::{ClassicalRk4, Rk4Method};
pub use sdirk4::{Sdirk4, Sdirk4Method, Sdirk4Newton};
pub use taylor::{Taylor, TaylorControl};
pub use variational::{Principle, Variational, VariationalConfig, VariationalMethod};

use crate::error::ConfigError;

/// The configuration of a fixed-step method: just its step size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedStep {
    /// The step size h > 0. The last step of a run is shortened to land on the end time.
    pub step: f64,
}

impl FixedStep {
    /// Checks that the step is positive and finite.
    pub(crate) fn validated(step: f64) -> Result<f64, ConfigError> {
        if step.is_finite() && step > 0.0 {
            Ok(step)
        } else {
            Err(ConfigError {
                reason: "the step size must be positive and finite",
            })
        }
    }
}
