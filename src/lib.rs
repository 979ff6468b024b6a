//! # varmass
//!
//! Variable-mass mechanics, from a Lagrangian to verified equations and fast steppers.
//!
//! varmass follows Zhang Jiuzhu, *Hamilton's canonical equations and Hamilton's principle
//! for variable mass systems*, Mechanics in Engineering 37(1):125–128, 2015. Its central
//! idea is the **frozen-mass rule**: the partial derivatives ∂*, variations δ* and time
//! derivative d*/dt that build the equations hold every mass constant, even where the
//! mass law depends on the coordinates; the mass change enters only through the generalized
//! reactive thrust R1 and impact force R2.
//!
//! The crates:
//! * [`symbolic`] — the DSL parser and the symbolic engine;
//! * [`core`] — the system trait and the steppers.
#![warn(missing_docs)]

pub use varmass_core as core;
pub use varmass_symbolic as symbolic;
