//! The state rate in the order every evaluator runs it (ARCHITECTURE.md, "the state rate"):
//! the closed mass laws first (a law mass is a value, not a state), then q̇ (in closed form
//! up to `SYMBOLIC_INVERSE_MAX_DOF`, else the mass matrix and the momentum offset for a
//! numerical solve), then ṗ and the state masses' ṁ. The interpreter's tapes, its Taylor
//! tapes and the emitted Taylor method all take their roots from here, so the order is
//! written once.

use super::{Derivation, MassKind, VelocitySolve};
use crate::expr::{Id, Symbol, TaylorTape};

/// The roots of the three stages of the state rate.
#[derive(Clone, Debug, PartialEq)]
pub struct RateStages {
    /// The index (into `Derivation::masses`) of each law mass, in order.
    pub law_masses: Vec<usize>,
    /// The closed law of each law mass.
    pub laws: Vec<Id>,
    /// q̇ in closed form, or (when `numeric`) M's entries row by row then the offset c of
    /// p = M q̇ + c.
    pub velocities: Vec<Id>,
    /// Whether q̇ is solved numerically from `velocities`.
    pub numeric: bool,
    /// ṗ for every coordinate, then ṁ for every state mass: the state's rate after q̇.
    pub rates: Vec<Id>,
}

/// The three stages compiled as Taylor tapes over one list of inputs
/// ([`Derivation::taylor_inputs`]): what the emitted `taylor_coefficients` and the
/// interpreter's Taylor program both run, so their choices are made once.
#[derive(Clone, Debug)]
pub struct TaylorStages {
    /// How many inputs the tapes share.
    pub inputs: usize,
    /// The law masses' stage.
    pub laws: TaylorTape,
    /// Mass index of each law output.
    pub law_masses: Vec<usize>,
    /// q̇'s stage (closed form, or M and c when `numeric`).
    pub velocities: TaylorTape,
    /// Whether q̇ is solved numerically, order by order.
    pub numeric: bool,
    /// ṗ and the state masses' ṁ.
    pub rates: TaylorTape,
}

impl Derivation {
    /// The state rate's stages compiled as Taylor tapes ([`ExprPool::compile_taylor_rate`](crate::expr::ExprPool::compile_taylor_rate)).
    pub fn taylor_stages(&self) -> TaylorStages {
        let (inputs, stages) = (self.taylor_inputs(), self.rate_stages());
        let symbols: Vec<Symbol> = (stages.law_masses.iter())
            .map(|m| self.masses[*m].symbol)
            .collect();
        let later = [&stages.velocities[..], &stages.rates[..]];
        let [laws, velocities, rates] =
            (self.pool).compile_taylor_rate(&inputs, (&stages.laws, &symbols), later);
        TaylorStages {
            inputs: inputs.len(),
            laws,
            law_masses: stages.law_masses,
            velocities,
            numeric: stages.numeric,
            rates,
        }
    }

    /// The roots of the state rate's stages (see the module's documentation).
    pub fn rate_stages(&self) -> RateStages {
        let mut law_masses = Vec::new();
        let mut laws = Vec::new();
        for (index, (mass, law)) in self.masses.iter().zip(&self.closed_laws).enumerate() {
            if let (MassKind::Law(_), Some(law)) = (&mass.kind, law) {
                law_masses.push(index);
                laws.push(*law);
            }
        }
        let (velocities, numeric) = match &self.velocities {
            VelocitySolve::Symbolic(v) => (v.clone(), false),
            VelocitySolve::Numeric => {
                let mut roots: Vec<Id> = self.mass_matrix.iter().flatten().copied().collect();
                roots.extend(&self.momentum_offset);
                (roots, true)
            }
        };
        let mut rates = self.momentum_rate.clone();
        rates.extend(self.mass_rates.iter().take(self.state_mass_count()));
        RateStages {
            law_masses,
            laws,
            velocities,
            numeric,
            rates,
        }
    }

    /// The inputs of the Taylor tapes, in order: t, every q, every p, every q̇, every mass.
    pub fn taylor_inputs(&self) -> Vec<Symbol> {
        let mut inputs: Vec<Symbol> = vec![self.time];
        inputs.extend(self.coordinates.iter().map(|c| c.q));
        inputs.extend(self.coordinates.iter().map(|c| c.momentum));
        inputs.extend(self.coordinates.iter().map(|c| c.velocity));
        inputs.extend(self.masses.iter().map(|m| m.symbol));
        // The held values of the sampled inputs: constant series (docs/inputs.md).
        inputs.extend(self.held());
        inputs
    }
}
