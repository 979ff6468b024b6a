//! What forward-sensitivity columns carry out of a phase that ends at an event, handed from
//! the phase's system to the next one's ([`crate::VariableMassSystem::depart`] and
//! [`crate::VariableMassSystem::arrive`], `sensitivity/phases.rs`): a type of its own so
//! that the trait and the sensitivities need not import each other.

use alloc::vec::Vec;

/// The columns w at a phase change at τ: per column dτ/dw and the derivative of the state at
/// the change along the motion, d y(τ(w); w)/dw = s + ẏ dτ/dw, in the state `[q, p, m_s]`
/// of the system that ends and in its velocity state `[q, q̇, m_s]` (each `entries` long).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Departure {
    /// The entries of one column (the mechanics' state, S).
    pub entries: usize,
    /// dτ/dw for each column.
    pub time: Vec<f64>,
    /// s + f dτ/dw for each column, one after the other.
    pub state: Vec<f64>,
    /// σ + ẋ dτ/dw for each column (σ = ∂[q, q̇, m_s]/∂w, ẋ the velocity state's rate).
    pub velocity_state: Vec<f64>,
    /// For each column, the initial entry it is the derivative with respect to, if it is
    /// one: the next phase's columns must name the same.
    pub initial: Vec<Option<usize>>,
}

impl Departure {
    /// The number of columns.
    pub fn columns(&self) -> usize {
        self.time.len()
    }
}
