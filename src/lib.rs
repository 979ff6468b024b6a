//! # varmass
//!
//! Variable-mass mechanics, from a Lagrangian to verified equations and fast steppers.
//!
//! varmass follows Zhang Jiuzhu, *Hamilton's canonical equations and Hamilton's principle
//! for variable mass systems*, Mechanics in Engineering 37(1):125–128, 2015. Its central
//! idea is the **frozen-mass rule**: the partial derivatives ∂*, variations δ* and time
//! derivative d*/dt that build the equations hold every mass constant, even where the mass
//! law depends on the coordinates; the mass change enters only through the generalized
//! reactive thrust R1 and impact force R2.
//!
//! Write the system in the DSL on a struct whose `f64` fields are its parameters; the
//! macro derives H, the canonical equations and the forces at compile time, verifies the
//! `check`s (a wrong one fails the build) and implements [`core::VariableMassSystem`]:
//!
//! ```
//! use varmass::prelude::*;
//!
//! /// The paper's sled (§4): it scoops up snow at rest, m = m0 + c x.
//! #[variable_mass_system("
//!     coordinates x
//!     mass m = m0 + c*x
//!     body sled: mass m, position [x]
//!     potential -m*g*x*sin(theta)
//!     force sled: [-f_d*m*g*cos(theta)]
//!     inflow sled: velocity [0]
//!     check R2_x = -c*x'^2                                  # eq. 23
//!     check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m  # eq. 24
//! ")]
//! struct Sled { m0: f64, c: f64, g: f64, theta: f64, f_d: f64 }
//!
//! let sled = Sled { m0: 10.0, c: 2.0, g: 9.81, theta: 30f64.to_radians(), f_d: 0.1 };
//! let start = SVector::<f64, 2>::new(0.0, 0.0); // [x, p] from rest
//! let control = StepControl::Adaptive(AdaptiveControl { relative_tolerance: 1e-12, absolute_tolerance: 1e-12, ..Default::default() });
//! let mut stepper = DormandPrince::new(&sled, 0.0, start, control)?;
//! let stop_at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
//! let solution = run(&mut stepper, &RunConfig::until(100.0), &[stop_at_50_m])?;
//! let (_, state) = solution.last().unwrap();
//! let (x, p) = (state[0], state[1]);
//! let v = p / sled.mass(0, 0.0, state);
//!
//! // The closed form (docs/mechanics.md#sled-stable-form), stable for small c: ε = c x / m0.
//! let a = sled.g * (sled.theta.sin() - sled.f_d * sled.theta.cos());
//! let eps = sled.c * x / sled.m0;
//! let v_exact = (2.0 / 3.0 * a * x * (3.0 + 3.0 * eps + eps * eps) / (1.0 + eps).powi(2)).sqrt();
//! assert!((v - v_exact).abs() < 1e-9 * v_exact);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The crates:
//! * [`symbolic`] — the DSL parser and the symbolic engine (parse → expr → mechanics → emit);
//! * [`core`] — the system trait and the steppers;
//! * [`interpret`] — a derivation evaluated at run time (compiled tapes), for models read
//!   while the program runs.
#![warn(missing_docs)]

pub mod interpret;

pub use varmass_core as core;
pub use varmass_macros::variable_mass_system;
pub use varmass_symbolic as symbolic;

/// What a user of generated systems needs in scope.
pub mod prelude {
    pub use crate::variable_mass_system;
    pub use varmass_core::nalgebra::{SMatrix, SVector};
    pub use varmass_core::steppers::{
        AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, Esdirk43, ExplicitEuler, FixedStep,
        ImplicitMidpoint, Sdirk4, StepControl, Taylor, TaylorControl, Variational,
    };
    pub use varmass_core::tolerance::{Floor, Tolerance};
    pub use varmass_core::{
        run, Direction, Event, RunConfig, RunError, Solution, StepError, StepErrorKind, Stepper,
        StopReason, Switching, SystemError, VariableMassSystem,
    };
}

/// The README's Rust examples, compiled and run by `cargo test --doc -p varmass`, so that
/// the manual's code cannot drift from the library.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
