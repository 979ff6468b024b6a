//! What the bench binaries share: the systems (generated and by hand), their reference
//! solutions, the n-link chain family, the run-time interpreter and the timing rule.
// Each bench binary uses part of this module.
#![allow(dead_code)]

pub mod adjugate;
pub mod chain;
/// The closed forms the core tests measure against, shared rather than copied.
#[path = "../../core/tests/support/closed_forms.rs"]
pub mod closed_forms;
pub mod diffsol_peer;
pub mod emission;
pub mod generated;
pub mod hand;
pub mod interpreted;
pub mod problems;
pub mod rocket_6dof;
pub mod stiff;
pub mod timing;
pub mod workloads;

/// The chains emitted by `build.rs` with the macro's own pipeline (`emit_system`).
#[allow(missing_docs, clippy::all)]
pub mod chains {
    include!(concat!(env!("OUT_DIR"), "/chains.rs"));
}
