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

/// Where each series sits among the Taylor tapes' inputs ([`Derivation::taylor_inputs`]):
/// t, every q, every p, every q̇, every mass (in mass order, the state masses first), then
/// the held values of the sampled inputs (constant series, docs/inputs.md). The emitted
/// Taylor method, the interpreter's Taylor program and `taylor_inputs` itself read the
/// positions from here, so they are written once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TaylorLayout {
    /// Coordinates.
    pub n: usize,
    /// Masses, law and state.
    pub masses: usize,
    /// State masses (the first `state_masses` masses).
    pub state_masses: usize,
    /// Held values of sampled inputs.
    pub held: usize,
}

impl TaylorLayout {
    /// The input holding t.
    pub const TIME: usize = 0;

    /// How many inputs the tapes share.
    pub fn len(&self) -> usize {
        1 + 3 * self.n + self.masses + self.held
    }

    /// Never: t is always an input.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The input of coordinate `a`'s q.
    pub fn q(&self, a: usize) -> usize {
        1 + a
    }

    /// The input of coordinate `a`'s momentum p.
    pub fn momentum(&self, a: usize) -> usize {
        1 + self.n + a
    }

    /// The input of coordinate `a`'s velocity q̇.
    pub fn velocity(&self, a: usize) -> usize {
        1 + 2 * self.n + a
    }

    /// The input of mass `m` (its index in `Derivation::masses`).
    pub fn mass(&self, m: usize) -> usize {
        1 + 3 * self.n + m
    }

    /// The input of held input `i` (its index in `Derivation::held`).
    pub fn held(&self, i: usize) -> usize {
        1 + 3 * self.n + self.masses + i
    }

    /// The state's length: q, p, the state masses and the held inputs.
    pub fn state_len(&self) -> usize {
        2 * self.n + self.state_masses + self.held
    }

    /// The input of state component `j` (q, p, the state masses, then the held inputs).
    pub fn state(&self, j: usize) -> usize {
        let (n, masses) = (self.n, self.state_masses);
        if j < n {
            self.q(j)
        } else if j < 2 * n {
            self.momentum(j - n)
        } else if j < 2 * n + masses {
            self.mass(j - 2 * n)
        } else {
            self.held(j - 2 * n - masses)
        }
    }
}

/// The three stages compiled as Taylor tapes over one list of inputs
/// ([`Derivation::taylor_inputs`]): what the emitted `taylor_coefficients` and the
/// interpreter's Taylor program both run, so their choices are made once.
#[derive(Clone, Debug)]
pub struct TaylorStages {
    /// Where each input sits.
    pub layout: TaylorLayout,
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
            layout: self.taylor_layout(),
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

    /// Where each series sits among the Taylor tapes' inputs.
    pub fn taylor_layout(&self) -> TaylorLayout {
        TaylorLayout {
            n: self.coordinates.len(),
            masses: self.masses.len(),
            state_masses: self.state_mass_count(),
            held: self.held().len(),
        }
    }

    /// The inputs of the Taylor tapes, each where [`TaylorLayout`] puts it.
    pub fn taylor_inputs(&self) -> Vec<Symbol> {
        let layout = self.taylor_layout();
        let mut inputs = vec![self.time; layout.len()];
        for (a, c) in self.coordinates.iter().enumerate() {
            inputs[layout.q(a)] = c.q;
            inputs[layout.momentum(a)] = c.momentum;
            inputs[layout.velocity(a)] = c.velocity;
        }
        for (m, mass) in self.masses.iter().enumerate() {
            inputs[layout.mass(m)] = mass.symbol;
        }
        for (i, held) in self.held().into_iter().enumerate() {
            inputs[layout.held(i)] = held;
        }
        inputs
    }
}

#[cfg(test)]
mod tests {
    use super::TaylorLayout;
    use crate::mechanics::Parameters;

    /// Two coordinates, a state mass before a law mass, and one sampled (held) input.
    const SOURCE: &str = "coordinates x, y
input u(t, x) every 0.1
mass m: state, rate -mu
mass w = w0 + c*x
body a: mass m, position [x]
body b: mass w, position [x + y]
potential m*g*x + k*y^2/2
force a: [u(t, x)]
";

    /// The positions counted by hand: t at 0; q = (x, y) at 1, 2; p at 3, 4; q̇ at 5, 6;
    /// the masses (m, w) at 7, 8; the held u at 9; ten inputs. The state (x, y, p_x, p_y,
    /// m, u) reads 1, 2, 3, 4, 7, 9. Every position holds one quantity (the list of all of
    /// them is 0..10, each once), and `taylor_inputs` puts each symbol there.
    #[test]
    fn every_taylor_input_has_the_position_counted_by_hand() {
        let d = crate::derive_source(SOURCE, Parameters::Inferred).expect("derives");
        let layout = d.taylor_layout();
        let expected = TaylorLayout {
            n: 2,
            masses: 2,
            state_masses: 1,
            held: 1,
        };
        assert_eq!(layout, expected);
        assert_eq!(layout.len(), 10);
        let state: Vec<usize> = (0..layout.state_len()).map(|j| layout.state(j)).collect();
        assert_eq!(state, [1, 2, 3, 4, 7, 9]);
        let mut all = vec![TaylorLayout::TIME];
        all.extend((0..2).flat_map(|a| [layout.q(a), layout.momentum(a), layout.velocity(a)]));
        all.extend([layout.mass(0), layout.mass(1), layout.held(0)]);
        all.sort_unstable();
        assert_eq!(all, (0..10).collect::<Vec<_>>());
        let inputs = d.taylor_inputs();
        assert_eq!(inputs.len(), 10);
        assert_eq!(inputs[TaylorLayout::TIME], d.time);
        for (a, c) in d.coordinates.iter().enumerate() {
            let at = [layout.q(a), layout.momentum(a), layout.velocity(a)];
            assert_eq!(at.map(|i| inputs[i]), [c.q, c.momentum, c.velocity]);
        }
        assert_eq!(inputs[layout.mass(1)], d.masses[1].symbol);
        assert_eq!(inputs[layout.held(0)], d.held()[0]);
    }
}
