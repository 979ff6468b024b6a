//! The `varmass` command line tool as a library: reading and deriving a model file
//! ([`model`]), the subcommands ([`commands`]) and `varmass run`'s planning and integration
//! ([`run`]), scene files run through phases ([`scene`]), with the command line's own arguments ([`args`]) and errors ([`error`]).
//!
//! The binary (`src/main.rs`) is a thin shell over it; the Python package (`python/`) calls
//! the same functions so that a run from Python has exactly the tool's semantics (`--set`,
//! `--init`, `--until`, `--stop-when`, `--method`, `--tol`, `--record`, `--every`) and its
//! messages.
#![warn(missing_docs)]

pub mod args;
pub mod commands;
pub mod error;
pub mod fit;
pub mod lint;
pub mod model;
pub mod run;
pub mod scene;
