//! The derivation: every quantity of SPEC §1 and §3 as simplified expressions.
//!
//! Expressions are in **velocity form** — functions of q, q̇, t, the parameters and the
//! frozen mass symbols — unless a field says otherwise. Generated code evaluates the mass
//! laws first, then q̇ from p, then these expressions; so one set of formulas serves both
//! the Hamilton and the Lagrange form.

use std::collections::HashMap;

use super::forces::generalized_forces;
use super::lagrangian::{energies, momenta, singular_everywhere};
use super::linear::{dot, inverse, mat_vec, Matrix};
use super::masses::{closed_laws, flow_rates, mass_rates};
use super::model::{Coordinate, Mass, MassKind, Model};
use crate::expr::{ExprPool, Id, Rational, Symbol};
use crate::parse::Diagnostic;

/// Up to this many coordinates, q̇(q, p) and q̈ are solved symbolically (adjugate of M);
/// beyond, generated code solves M x = y numerically (Cholesky).
///
/// Measured (`cargo bench -p varmass-benches --bench costs`, and the expansion of a 3-link
/// chain of accreting bobs): the closed form makes the state rate cheaper at 2 and 3
/// coordinates alike (0.56× and 0.54× of the Cholesky path), but at 3 it multiplies the
/// macro's expansion time by ~3 (80 → 227 ms, unoptimized as proc macros run) and the
/// generated code by 5 (58K → 307K characters): compile time and code size every user
/// pays, for a saving of ~60 ns per evaluation.
pub const SYMBOLIC_INVERSE_MAX_DOF: usize = 2;

/// How q̇ is recovered from p.
#[derive(Clone, Debug)]
pub enum VelocitySolve {
    /// q̇ = M⁻¹ (p − b) as expressions in q, p, t (momentum symbols `p_x`).
    Symbolic(Vec<Id>),
    /// Solve M q̇ = p − b numerically (more than [`SYMBOLIC_INVERSE_MAX_DOF`] coordinates).
    Numeric,
}

/// The pieces of the Jacobian of the state rate f = [q̇, ṗ, ṁ_s] with respect to the
/// state [q, p, m_s]. With the velocities v = M⁻¹(p − b) and masses following their laws,
/// ∂v/∂p = M⁻¹, ∂v/∂q = −M⁻¹ P_q, ∂v/∂m_s = −M⁻¹ P_m, so
///
/// ```text
/// J_q = F_q − F_v M⁻¹ P_q,   J_p = F_v M⁻¹,   J_m = F_m − F_v M⁻¹ P_m
/// ```
///
/// Every block is a total derivative at fixed q̇ with the mass laws followed (not frozen:
/// the Jacobian is ordinary calculus of the rate function). Rows are ṗ (N) then ṁ_s (K);
/// the q̇ rows are [0, I, 0] in (q, q̇, m_s) and need no expressions.
#[derive(Clone, Debug)]
pub struct JacobianParts {
    /// ∂[ṗ; ṁ_s]/∂q at fixed q̇, (N + K) × N.
    pub rate_wrt_q: Matrix,
    /// ∂[ṗ; ṁ_s]/∂q̇, (N + K) × N.
    pub rate_wrt_velocity: Matrix,
    /// ∂[ṗ; ṁ_s]/∂m_s at fixed q̇, (N + K) × K.
    pub rate_wrt_state_mass: Matrix,
    /// P_q = ∂p/∂q at fixed q̇, N × N.
    pub momentum_wrt_q: Matrix,
    /// P_m = ∂p/∂m_s at fixed q̇, N × K.
    pub momentum_wrt_state_mass: Matrix,
}

/// The outcome of one `check`.
#[derive(Clone, Debug)]
pub struct CheckOutcome {
    /// The check as written.
    pub text: String,
    /// How it was decided.
    pub verdict: crate::expr::Identity,
}

/// Everything derived from a system.
#[derive(Debug)]
pub struct Derivation {
    /// The arena holding every expression below.
    pub pool: ExprPool,
    /// The time symbol.
    pub time: Symbol,
    /// The coordinates with their symbols.
    pub coordinates: Vec<Coordinate>,
    /// Parameters, in order: declared fields, or inferred names in order of first use.
    pub parameters: Vec<(String, Symbol)>,
    /// Masses and inertias: state masses first, then laws (the runtime's `MASSES` order).
    pub masses: Vec<Mass>,
    /// Each law with the other laws substituted (`None` for state masses).
    pub closed_laws: Vec<Option<Id>>,
    /// ṁ of every mass.
    pub mass_rates: Vec<Id>,
    /// T.
    pub kinetic: Id,
    /// V.
    pub potential: Id,
    /// L = T − V (eq. 20 for the sled).
    pub lagrangian: Id,
    /// p = ∂*L/∂q̇ (eq. 8).
    pub momenta: Vec<Id>,
    /// M = ∂²L/∂q̇².
    pub mass_matrix: Matrix,
    /// b = p|_{q̇=0}, so p = M q̇ + b.
    pub momentum_offset: Vec<Id>,
    /// q̇(q, p, t).
    pub velocities: VelocitySolve,
    /// The energy function p·q̇ − L in velocity form (equals H on p = ∂*L/∂q̇).
    pub energy: Id,
    /// H(q, p, t) (eqs. 9–10), when q̇ is solved symbolically.
    pub hamiltonian: Option<Id>,
    /// ∂*L/∂q (= −∂*H/∂q, eq. 13).
    pub lagrangian_gradient: Vec<Id>,
    /// Q*.
    pub active_force: Vec<Id>,
    /// R1.
    pub reactive_thrust: Vec<Id>,
    /// R2.
    pub impact_force: Vec<Id>,
    /// The rate of each flow (Q1 outflow, Q2 inflow), defaults filled in.
    pub flow_rates: Vec<Id>,
    /// d*p/dt = ∂*L/∂q + Q* − R1 + R2 (eq. 14).
    pub frozen_momentum_rate: Vec<Id>,
    /// Σᵢ ṁᵢ ∂*p/∂mᵢ.
    pub mass_flux_force: Vec<Id>,
    /// The true ṗ = d*p/dt + Σᵢ ṁᵢ ∂*p/∂mᵢ.
    pub momentum_rate: Vec<Id>,
    /// The right side of M q̈ = d*p/dt − ∂*p/∂q q̇ − ∂*p/∂t (eq. 6).
    pub acceleration_rhs: Vec<Id>,
    /// q̈(q, q̇, t), when solved symbolically.
    pub accelerations: Option<Vec<Id>>,
    /// dH/dt = −∂*L/∂t + q̇·(Q* − R1 + R2 + Σ ṁ ∂*p/∂m) − Σ ṁᵢ ∂*L/∂mᵢ (SPEC §1, with
    /// ∂*H/∂t = −∂*L/∂t and ∂H/∂mᵢ|_(q,p) = −∂*L/∂mᵢ|_(q,q̇)).
    pub power: Id,
    /// The Jacobian of the state rate.
    pub jacobian: JacobianParts,
    /// The `check`s and how each was decided.
    pub checks: Vec<CheckOutcome>,
    pub(crate) scope: Scope,
}

/// What a `check` needs to resolve names after the model is consumed.
#[derive(Debug)]
pub(crate) struct Scope {
    pub names: HashMap<String, super::resolve::Binding>,
    pub parameter_mode: super::resolve::Parameters,
    pub pending_checks: Vec<super::model::Check>,
}

impl Derivation {
    /// The names of the parameters the equations read (a declared field may go unused).
    pub fn used_parameters(&self) -> Vec<String> {
        let mut roots = vec![self.lagrangian, self.power];
        roots.extend(self.closed_laws.iter().flatten());
        roots.extend(&self.mass_rates);
        roots.extend(&self.flow_rates);
        roots.extend(&self.active_force);
        roots.extend(&self.reactive_thrust);
        roots.extend(&self.impact_force);
        roots.extend(&self.momentum_rate);
        let mut used = std::collections::BTreeSet::new();
        for r in roots {
            used.extend(self.pool.free_symbols(r));
        }
        self.parameters
            .iter()
            .filter(|(_, s)| used.contains(s))
            .map(|(name, _)| name.clone())
            .collect()
    }

    /// The number of state masses (the first masses).
    pub fn state_mass_count(&self) -> usize {
        self.masses
            .iter()
            .filter(|m| matches!(m.kind, MassKind::State { .. }))
            .count()
    }
}

/// Derives everything from a checked model.
pub fn derive_model(mut model: Model) -> Result<Derivation, Vec<Diagnostic>> {
    let velocities: Vec<Symbol> = model.coordinates.iter().map(|c| c.velocity).collect();
    let closed = closed_laws(&mut model)?;
    let rates = mass_rates(&mut model, &closed)?;
    let flows = flow_rates(&mut model, &rates)?;
    let energies = energies(&mut model, &velocities)?;
    let forces = generalized_forces(&mut model, &flows, &energies.body_velocities);
    let pool = &mut model.pool;
    let p = momenta(pool, energies.lagrangian, &velocities);
    let symbol_count = pool.symbols().len();
    if singular_everywhere(pool, &p.mass_matrix, symbol_count) {
        return Err(vec![singular_diagnostic(&model, &p.mass_matrix)]);
    }
    let n = model.coordinates.len();
    let lagrangian = energies.lagrangian;
    let lagrangian_gradient: Vec<Id> = model
        .coordinates
        .iter()
        .map(|c| pool.diff(lagrangian, c.q))
        .collect();
    // Q* − R1 + R2, shared by d*p/dt and the power.
    let applied: Vec<Id> = (0..n)
        .map(|a| {
            let thrust = pool.neg(forces.reactive_thrust[a]);
            pool.add(&[forces.active[a], thrust, forces.impact[a]])
        })
        .collect();
    let frozen_momentum_rate: Vec<Id> = (0..n)
        .map(|a| pool.add(&[lagrangian_gradient[a], applied[a]]))
        .collect();
    let mass_flux_force: Vec<Id> = p
        .momenta
        .iter()
        .map(|p_a| {
            let terms: Vec<Id> = model
                .masses
                .iter()
                .zip(&rates)
                .map(|(m, rate)| {
                    let partial = pool.diff(*p_a, m.symbol);
                    pool.mul(&[*rate, partial])
                })
                .collect();
            pool.add(&terms)
        })
        .collect();
    let momentum_rate: Vec<Id> = (0..n)
        .map(|a| pool.add(&[frozen_momentum_rate[a], mass_flux_force[a]]))
        .collect();

    // M q̈ = d*p/dt − (d*p/dt with q̈ = 0): the frozen total derivative of p without its
    // acceleration part is ∂*p/∂q q̇ + ∂*p/∂t.
    let no_acceleration: HashMap<Symbol, Id> = {
        let zero = pool.int(0);
        model
            .coordinates
            .iter()
            .map(|c| (c.acceleration, zero))
            .collect()
    };
    let mut acceleration_rhs = Vec::with_capacity(n);
    for ((momentum, rate), coordinate) in p
        .momenta
        .iter()
        .zip(&frozen_momentum_rate)
        .zip(&model.coordinates)
    {
        let dp = pool
            .time_derivative(*momentum)
            .map_err(|e| vec![Diagnostic::new(coordinate.span, e.to_string())])?;
        let convective = pool.substitute(dp, &no_acceleration);
        acceleration_rhs.push(pool.sub(*rate, convective));
    }
    let symbolic = n <= SYMBOLIC_INVERSE_MAX_DOF;
    let inverse_mass = if symbolic {
        inverse(pool, &p.mass_matrix)
    } else {
        None
    };
    let accelerations = inverse_mass
        .as_ref()
        .map(|inv| mat_vec(pool, inv, &acceleration_rhs));

    // Energy function and H.
    let pv: Vec<Id> = (0..n)
        .map(|a| {
            let v = pool.sym(velocities[a]);
            pool.mul(&[p.momenta[a], v])
        })
        .collect();
    let pv = pool.add(&pv);
    let energy = pool.sub(pv, lagrangian);
    let energy = pool.reduce_trig(energy);
    let (velocity_solve, hamiltonian) = match &inverse_mass {
        Some(inv) => {
            let excess: Vec<Id> = (0..n)
                .map(|a| {
                    let momentum = pool.sym(model.coordinates[a].momentum);
                    pool.sub(momentum, p.offset[a])
                })
                .collect();
            let v = mat_vec(pool, inv, &excess);
            // H = ½ (p − b)·q̇ − L₀ with q̇ = M⁻¹ (p − b): the same function as p·q̇ − L with
            // q̇ eliminated (L = ½ q̇ᵀ M q̇ + b·q̇ + L₀), without squaring M⁻¹.
            let zero = pool.int(0);
            let at_rest: HashMap<Symbol, Id> = velocities.iter().map(|v| (*v, zero)).collect();
            let rest_lagrangian = pool.substitute(lagrangian, &at_rest);
            let half = pool.rational(Rational::HALF);
            let kinetic_part = dot(pool, &excess, &v);
            let kinetic_part = pool.mul(&[half, kinetic_part]);
            let h = pool.sub(kinetic_part, rest_lagrangian);
            (VelocitySolve::Symbolic(v), Some(h))
        }
        None => (VelocitySolve::Numeric, None),
    };

    let power = {
        let dl_dt = pool.diff(lagrangian, model.time);
        let mut terms = vec![pool.neg(dl_dt)];
        for a in 0..n {
            let force = pool.add(&[applied[a], mass_flux_force[a]]);
            let v = pool.sym(velocities[a]);
            terms.push(pool.mul(&[v, force]));
        }
        for (m, rate) in model.masses.iter().zip(&rates) {
            let dl_dm = pool.diff(lagrangian, m.symbol);
            let product = pool.mul(&[*rate, dl_dm]);
            terms.push(pool.neg(product));
        }
        pool.add(&terms)
    };

    let jacobian = jacobian_parts(
        &mut model,
        &closed,
        &p.momenta,
        &momentum_rate,
        &rates,
        &velocities,
    );
    Ok(Derivation {
        time: model.time,
        coordinates: model.coordinates,
        parameters: model.parameters,
        masses: model.masses,
        closed_laws: closed,
        mass_rates: rates,
        kinetic: energies.kinetic,
        potential: energies.potential,
        lagrangian,
        momenta: p.momenta,
        mass_matrix: p.mass_matrix,
        momentum_offset: p.offset,
        velocities: velocity_solve,
        energy,
        hamiltonian,
        lagrangian_gradient,
        active_force: forces.active,
        reactive_thrust: forces.reactive_thrust,
        impact_force: forces.impact,
        flow_rates: flows,
        frozen_momentum_rate,
        mass_flux_force,
        momentum_rate,
        acceleration_rhs,
        accelerations,
        power,
        jacobian,
        checks: Vec::new(),
        pool: model.pool,
        scope: Scope {
            names: model.names,
            parameter_mode: model.parameter_mode,
            pending_checks: model.checks,
        },
    })
}

fn singular_diagnostic(model: &Model, mass_matrix: &Matrix) -> Diagnostic {
    // A coordinate whose row of M is identically zero has no kinetic energy at all.
    let idle = mass_matrix
        .iter()
        .position(|row| row.iter().all(|e| model.pool.is_zero(*e)));
    match idle {
        Some(a) => {
            let c = &model.coordinates[a];
            Diagnostic::new(
                c.span,
                format!(
                    "the mass matrix is singular: no term of T depends on the velocity `{}'`",
                    c.name
                ),
            )
            .with_help("every coordinate needs kinetic energy, or q̇ cannot be recovered from p")
        }
        None => Diagnostic::new(
            model
                .coordinates
                .first()
                .map_or_else(Default::default, |c| c.span),
            "the mass matrix ∂²L/∂q̇² is singular at every state: q̇ cannot be recovered from p",
        )
        .with_help("the coordinates may not be independent (e.g. two coordinates for one motion)"),
    }
}

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

fn jacobian_parts(
    model: &mut Model,
    closed: &[Option<Id>],
    momenta: &[Id],
    momentum_rate: &[Id],
    rates: &[Id],
    velocities: &[Symbol],
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
    let coordinates: Vec<Symbol> = model.coordinates.iter().map(|c| c.q).collect();
    let pool = &mut model.pool;
    let rows: Vec<Id> = momentum_rate
        .iter()
        .copied()
        .chain(rates.iter().take(state_masses.len()).copied())
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
    }
}
