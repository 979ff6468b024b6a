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

/// How the event that ends a phase moves with the columns: what
/// [`crate::VariableMassSystem::depart`] needs of it to give the change's time its
/// derivative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PhaseEnd<'a> {
    /// g = Σ cᵢ yᵢ − value, linear in the state `[q, p, m_s]` with the coefficients
    /// `(i, cᵢ)`: an event on a state entry or a state mass (one coefficient 1), a rail's
    /// exit (the travel dᵀ(r − r₀)). dτ/dw = −Σ cᵢ sᵢ / Σ cᵢ fᵢ. Empty, dτ/dw = 0: an
    /// end at a fixed time, or a smooth one (what a support turns [`PhaseEnd::Smooth`]
    /// into).
    Linear(&'a [(usize, f64)]),
    /// g = q̇_k − value, coordinate k's velocity reaching a value (an apogee):
    /// dτ/dw = −(∂q̇_k/∂w)/q̈_k, the velocity's derivative along the column (its direct
    /// dependence on the parameters included) over its rate along the motion.
    Velocity {
        /// The coordinate, an index into the coordinates.
        coordinate: usize,
    },
    /// The travel up the rail of the system that ends ([`crate::rail`]), which a system on
    /// a rail turns into its [`PhaseEnd::Linear`] gradient.
    RailTravel,
    /// A lift-off from a support or a rail's bottom: the net force along the support is 0
    /// there and the body at rest along it, so the state rate is the same on both sides
    /// (docs/sensitivities.md#on-a-pad-and-a-rail) and the columns go on unchanged,
    /// whatever dτ/dw; [`Departure::time`] then holds 0, not dτ/dw. Only a held system
    /// takes it ([`crate::support::Supported`]); any other refuses it.
    Smooth,
}
