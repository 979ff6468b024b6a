//! The runtime of varmass: the [`VariableMassSystem`] trait and monomorphized steppers.
#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]

pub mod system;

pub use system::{SystemError, VariableMassSystem};
