//! The Jacobian of the state rate: its blocks as total derivatives at fixed q̇ with the mass
//! laws followed (see [`JacobianParts`]).

use super::derivation::JacobianParts;
use super::linear::Matrix;
use super::model::{MassKind, Model};
use super::Derivation;
use crate::expr::{ExprPool, Id, Symbol};

/// Total derivative at fixed q̇ with the mass laws followed: ∂e/∂w + Σ ∂e/∂mᵢ ∂mᵢ/∂w.
fn total_diff(pool: &mut ExprPool, e: Id, wrt: Symbol, law_masses: &[(Symbol, Id)]) -> Id {
    let mut terms = vec![pool.diff(e, wrt)];
    for (mass, law) in law_masses {
        let outer = pool.diff(e, *mass);
        if pool.is_zero(outer) {
            continue;
        }
        let inner = pool.diff(*law, wrt);
        terms.push(pool.mul(&[outer, inner]));
    }
    pool.add(&terms)
}

/// The blocks of the Jacobian of [q̇, ṗ, ṁ_s] with respect to [q, p, m_s, u_held] (the
/// `state_mass` blocks have a column per state mass, then per held input).
pub(crate) fn jacobian_parts(
    model: &mut Model,
    closed: &[Option<Id>],
    momenta: &[Id],
    momentum_rate: &[Id],
    rates: &[Id],
    velocities: &[Symbol],
    sensitivities: bool,
) -> JacobianParts {
    let law_masses: Vec<(Symbol, Id)> = model
        .masses
        .iter()
        .zip(closed)
        .filter_map(|(m, law)| law.map(|l| (m.symbol, l)))
        .collect();
    let state_masses: Vec<Symbol> = model
        .masses
        .iter()
        .filter(|m| matches!(m.kind, MassKind::State { .. }))
        .map(|m| m.symbol)
        .collect();
    let mass_count = state_masses.len();
    // The held values of the sampled inputs are the state's last entries: their columns
    // follow the state masses' (rate 0, so no rows).
    let state_masses: Vec<Symbol> = (state_masses.into_iter())
        .chain(model.inputs.iter().filter_map(|i| i.held))
        .collect();
    let coordinates: Vec<Symbol> = model.coordinates.iter().map(|c| c.q).collect();
    // The parameters' columns only for sensitivities (`Outputs::sensitivities`).
    let parameters: Vec<Symbol> = match sensitivities {
        true => model.parameters.iter().map(|(_, s)| *s).collect(),
        false => Vec::new(),
    };
    let pool = &mut model.pool;
    let rows: Vec<Id> = momentum_rate
        .iter()
        .copied()
        .chain(rates.iter().take(mass_count).copied())
        .collect();
    let block = |pool: &mut ExprPool, rows: &[Id], wrt: &[Symbol], total: bool| -> Matrix {
        rows.iter()
            .map(|r| {
                wrt.iter()
                    .map(|w| {
                        if total {
                            total_diff(pool, *r, *w, &law_masses)
                        } else {
                            pool.diff(*r, *w)
                        }
                    })
                    .collect()
            })
            .collect()
    };
    JacobianParts {
        rate_wrt_q: block(pool, &rows, &coordinates, true),
        rate_wrt_velocity: block(pool, &rows, velocities, false),
        rate_wrt_state_mass: block(pool, &rows, &state_masses, true),
        momentum_wrt_q: block(pool, momenta, &coordinates, true),
        momentum_wrt_state_mass: block(pool, momenta, &state_masses, true),
        rate_wrt_parameter: block(pool, &rows, &parameters, true),
        momentum_wrt_parameter: block(pool, momenta, &parameters, true),
        with_parameters: sensitivities,
    }
}

/// The gradient of `e` — an expression of t, q, q̇, the masses and the parameters, such as
/// a [`crate::quantity::Quantity`]'s entry — with respect to [t, q, q̇, m_s, θ]
/// (1 + 2N + K + P entries, θ in [`Derivation::parameters`] order), each a total
/// derivative at fixed q̇ with the mass laws followed, as the Jacobian's blocks are: what
/// the derivative of a recorded quantity along the sensitivities reads
/// (docs/sensitivities.md).
pub fn gradient(d: &mut Derivation, e: Id) -> Vec<Id> {
    let law_masses: Vec<(Symbol, Id)> = (d.masses.iter())
        .zip(&d.closed_laws)
        .filter_map(|(m, law)| law.map(|l| (m.symbol, l)))
        .collect();
    let state_masses = (d.masses.iter()).filter(|m| matches!(m.kind, MassKind::State { .. }));
    let wrt: Vec<Symbol> = std::iter::once(d.time)
        .chain(d.coordinates.iter().map(|c| c.q))
        .chain(d.coordinates.iter().map(|c| c.velocity))
        .chain(state_masses.map(|m| m.symbol))
        .chain(d.parameters.iter().map(|(_, s)| *s))
        .collect();
    (wrt.into_iter())
        .map(|w| total_diff(&mut d.pool, e, w, &law_masses))
        .collect()
}
