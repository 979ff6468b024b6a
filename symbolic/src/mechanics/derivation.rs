//! The derivation: every quantity of the paper (see `docs/mechanics.md`) as simplified
//! expressions, derived one equation at a time (`equations.rs`), the `check`s verified
//! against them, then assembled into one [`Derivation`].
//!
//! Expressions are in **velocity form** — functions of q, q̇, t, the parameters and the
//! frozen mass symbols — unless a field says otherwise. Generated code evaluates the mass
//! laws first, then q̇ from p, then these expressions; so one set of formulas serves both
//! the Hamilton and the Lagrange form.

use super::checks::{run_checks, CheckScope};
use super::equations::{
    accelerations, cheapest_rates, hamiltonian, momentum_rates, power, Accelerations, Hamiltonian,
    MomentumRates,
};
use super::forces::{generalized_forces, GeneralizedForces};
use super::jacobian::jacobian_parts;
use super::lagrangian::{energies, momenta, require_regular, Energies, Momenta};
use super::linear::Matrix;
use super::masses::{closed_laws, flow_rates, mass_rates};
use super::model::{Coordinate, Mass, MassKind, Model};
use super::outputs::Outputs;
use super::rigid_rates::body_frame_rates;
use super::rigid_solve::{quaternion_accelerations, rigid_velocities};
use crate::expr::{ExprPool, Id, Symbol};
use crate::parse::Diagnostic;
use crate::quantity::Quantity;

pub use super::equations::SYMBOLIC_INVERSE_MAX_DOF;

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
    /// ∂[ṗ; ṁ_s]/∂[m_s, u_held] at fixed q̇, (N + K) × (K + HELD).
    pub rate_wrt_state_mass: Matrix,
    /// P_q = ∂p/∂q at fixed q̇, N × N.
    pub momentum_wrt_q: Matrix,
    /// P_m = ∂p/∂[m_s, u_held] at fixed q̇, N × (K + HELD).
    pub momentum_wrt_state_mass: Matrix,
    /// F_θ = ∂[ṗ; ṁ_s]/∂θ at fixed q and q̇, the mass laws followed, (N + K) × P with a column
    /// per parameter in [`Derivation::parameters`] order; no columns unless
    /// `Outputs::sensitivities`.
    pub rate_wrt_parameter: Matrix,
    /// P_θ = ∂p/∂θ at fixed q and q̇, N × P (no columns unless `Outputs::sensitivities`).
    pub momentum_wrt_parameter: Matrix,
    /// Whether F_θ and P_θ were derived (`Outputs::sensitivities`).
    pub with_parameters: bool,
}

/// The outcome of one `check`.
#[derive(Clone, Debug)]
pub struct CheckOutcome {
    /// Both sides as the derivation reads them, in canonical DSL text.
    pub text: String,
    /// The check as written in the source (`check p_x = m*x'`).
    pub source: String,
    /// Where the check statement is.
    pub span: crate::parse::Span,
    /// How it was decided.
    pub verdict: crate::expr::Identity,
}

/// Everything derived from a system.
#[derive(Clone, Debug)]
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
    /// With [`VelocitySolve::Numeric`], q̇(q, p) in closed form when the system is a lone
    /// spatial rigid body in its own coordinates (`rigid_solve.rs`): what the generated
    /// methods on the state evaluate instead of the LDLᵀ of M.
    pub rigid_velocities: Option<super::RigidVelocities>,
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
    /// Each flow as the model declares it, for messages: ``outflow `bucket` `` or
    /// ``inflow `cart` ``, in the order of [`Self::flow_rates`].
    pub flow_names: Vec<String>,
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
    /// dH/dt = −∂*L/∂t + q̇·(Q* − R1 + R2 + Σ ṁ ∂*p/∂m) − Σ ṁᵢ ∂*L/∂mᵢ (with
    /// ∂*H/∂t = −∂*L/∂t and ∂H/∂mᵢ|_(q,p) = −∂*L/∂mᵢ|_(q,q̇)).
    pub power: Id,
    /// The Jacobian of the state rate (`None` when not asked for, see [`Outputs`]).
    pub jacobian: Option<JacobianParts>,
    /// The `check`s and how each was decided.
    pub checks: Vec<CheckOutcome>,
    /// The units of the names and quantities, when the system declares `units`.
    pub units: Option<super::UnitTable>,
    /// The model's tables (their data are in the pool).
    pub tables: Vec<super::tables::ModelTable>,
    /// The model's inputs (functions the user writes in Rust).
    pub inputs: Vec<super::inputs::ModelInput>,
    /// Each spatial rigid body's Euler middle angle (a function of q and t) and whether its
    /// sequence is proper: where the attitude's distance from gimbal lock is read
    /// (`singular_attitude_distance`, docs/mechanics.md#rigid-bodies).
    pub euler_middles: Vec<(Id, bool)>,
}

impl Derivation {
    /// The expressions of `quantity` in this derivation, in velocity form: the one place
    /// that answers "give me quantity Q" (the registry, [`crate::quantity`], names them;
    /// this says where each is held). Empty when the derivation does not hold it in closed
    /// form (accelerations beyond [`SYMBOLIC_INVERSE_MAX_DOF`]).
    pub fn quantity(&self, quantity: Quantity) -> Vec<Id> {
        match quantity {
            Quantity::MassRates => self.mass_rates.clone(),
            Quantity::Momenta => self.momenta.clone(),
            Quantity::MassMatrix => self.mass_matrix.iter().flatten().copied().collect(),
            Quantity::Lagrangian => vec![self.lagrangian],
            Quantity::Kinetic => vec![self.kinetic],
            Quantity::Potential => vec![self.potential],
            Quantity::LagrangianGradient => self.lagrangian_gradient.clone(),
            Quantity::ActiveForce => self.active_force.clone(),
            Quantity::ReactiveThrust => self.reactive_thrust.clone(),
            Quantity::ImpactForce => self.impact_force.clone(),
            Quantity::FrozenMomentumRate => self.frozen_momentum_rate.clone(),
            Quantity::MassFluxForce => self.mass_flux_force.clone(),
            Quantity::MomentumRate => self.momentum_rate.clone(),
            Quantity::AccelerationRhs => self.acceleration_rhs.clone(),
            Quantity::Accelerations => self.accelerations.clone().unwrap_or_default(),
            Quantity::Power => vec![self.power],
            Quantity::Energy => vec![self.energy],
        }
    }

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
        // The laws the interpreter samples for held inputs.
        roots.extend(self.inputs.iter().filter_map(|i| i.law));
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

    /// The held values of the sampled inputs, in declaration order: the state's last
    /// entries, after the state masses (docs/inputs.md#sampled-inputs).
    pub fn held(&self) -> Vec<Symbol> {
        self.inputs.iter().filter_map(|i| i.held).collect()
    }

    /// The length S of the state: `2N + K + HELD`.
    pub fn state_len(&self) -> usize {
        2 * self.coordinates.len() + self.state_mass_count() + self.held().len()
    }

    /// Every expression generated code evaluates with `outputs`: L, the energy, the power
    /// and H as asked, the state rate's equations ([`Derivation::equation_roots`]) and the
    /// Jacobian as asked. The emitter reads it, and the interpreter with every output, so
    /// that both place stop times at the knots of every table of t the code reads (one
    /// only L, V or H reads included).
    pub fn code_roots(&self, outputs: Outputs) -> Vec<Id> {
        let mut head = vec![self.lagrangian, self.energy];
        if outputs.power {
            head.push(self.power);
        }
        if outputs.hamiltonian {
            head.extend(self.hamiltonian);
        }
        let mut roots = self.equation_roots(head, false);
        let asked = outputs.jacobian || outputs.sensitivities;
        if let Some(j) = self.jacobian.as_ref().filter(|_| asked) {
            for matrix in [
                &j.rate_wrt_q,
                &j.rate_wrt_velocity,
                &j.rate_wrt_state_mass,
                &j.momentum_wrt_q,
                &j.momentum_wrt_state_mass,
                &j.rate_wrt_parameter,
                &j.momentum_wrt_parameter,
            ] {
                roots.extend(matrix.iter().flatten());
            }
        }
        roots
    }

    /// `head`, then the roots of every equation of the state rate: the closed laws, the
    /// per-coordinate equations (the flow rates among them if `flows`), q̈, q̇ when solved
    /// symbolically, and M. The emitter (its code roots) and the input check (every equation
    /// but the Jacobian) read this one list, in this order (the emitter's output depends on
    /// it).
    pub fn equation_roots(&self, head: Vec<Id>, flows: bool) -> Vec<Id> {
        let mut roots = head;
        roots.extend(self.closed_laws.iter().flatten());
        let flow_rates: &[Id] = if flows { &self.flow_rates } else { &[] };
        for list in [
            &self.mass_rates[..],
            flow_rates,
            &self.momenta,
            &self.momentum_offset,
            &self.lagrangian_gradient,
            &self.active_force,
            &self.reactive_thrust,
            &self.impact_force,
            &self.frozen_momentum_rate,
            &self.mass_flux_force,
            &self.momentum_rate,
            &self.acceleration_rhs,
        ] {
            roots.extend(list);
        }
        roots.extend(self.accelerations.iter().flatten());
        if let VelocitySolve::Symbolic(v) = &self.velocities {
            roots.extend(v);
        }
        roots.extend(self.mass_matrix.iter().flatten());
        roots
    }

    /// The number of state masses (the first masses).
    pub fn state_mass_count(&self) -> usize {
        self.masses
            .iter()
            .filter(|m| matches!(m.kind, MassKind::State { .. }))
            .count()
    }
}

/// Every equation derived from a model, one small struct each, before assembly.
pub(crate) struct Equations {
    /// Each law with the other laws substituted (`None` for state masses).
    pub closed_laws: Vec<Option<Id>>,
    /// ṁ of every mass.
    pub mass_rates: Vec<Id>,
    /// The rate of each flow.
    pub flow_rates: Vec<Id>,
    /// T, V, L and the body velocities.
    pub energies: Energies,
    /// Q*, R1, R2.
    pub forces: GeneralizedForces,
    /// p, M and b.
    pub momenta: Momenta,
    /// Eq. 14 and the true ṗ.
    pub rates: MomentumRates,
    /// Eq. 6.
    pub accelerations: Accelerations,
    /// Eqs. 9–10.
    pub hamiltonian: Hamiltonian,
    /// q̇ of a lone spatial rigid body in closed form (`rigid_solve.rs`).
    pub rigid_velocities: Option<super::RigidVelocities>,
    /// dH/dt.
    pub power: Id,
    /// The Jacobian of the state rate (`None` when not asked for, see [`Outputs`]).
    pub jacobian: Option<JacobianParts>,
}

/// Derives every equation from a checked model, verifies its `check`s, then assembles the
/// [`Derivation`].
pub(crate) fn derive_model(
    mut model: Model,
    outputs: Outputs,
) -> Result<Derivation, Vec<Diagnostic>> {
    let equations = derive_equations(&mut model, outputs)?;
    let (mut derivation, scope) = assemble(model, equations);
    derivation.checks = run_checks(&mut derivation, scope)?;
    Ok(derivation)
}

/// The equations in dependency order: mass laws and rates, energies, forces, momenta, then
/// eq. 14, eq. 6, eqs. 9–10, the power and the Jacobian.
fn derive_equations(model: &mut Model, outputs: Outputs) -> Result<Equations, Vec<Diagnostic>> {
    let velocities: Vec<Symbol> = model.coordinates.iter().map(|c| c.velocity).collect();
    let closed_laws = closed_laws(model)?;
    let mass_rates = mass_rates(model, &closed_laws)?;
    let flow_rates = flow_rates(model, &mass_rates)?;
    let energies = energies(model, &velocities)?;
    let forces = generalized_forces(model, &flow_rates, &energies.body_velocities, &mass_rates);
    let lagrangian = energies.lagrangian;
    let momenta = momenta(&mut model.pool, lagrangian, &velocities);
    require_regular(model, &momenta.mass_matrix)?;
    let mut rates = momentum_rates(model, lagrangian, &forces, &momenta.momenta, &mass_rates);
    // ṗ of a lone spatial rigid body in body axes where it takes fewer operations.
    let structured = body_frame_rates(model, &forces, &mass_rates, &flow_rates);
    rates.total = cheapest_rates(&mut model.pool, &rates.total, structured);
    let accelerations = accelerations(model, &momenta, &rates.frozen)?;
    let inverse_mass = accelerations.inverse_mass.as_ref();
    let hamiltonian = hamiltonian(model, lagrangian, &momenta, inverse_mass);
    let rigid_velocities = match hamiltonian.velocities {
        VelocitySolve::Numeric => rigid_velocities(model, &momenta).map(|mut rigid| {
            rigid.accelerations =
                quaternion_accelerations(model, &rigid, &rates.total, &mass_rates);
            rigid
        }),
        VelocitySolve::Symbolic(_) => None,
    };
    let power = power(model, lagrangian, &rates, &mass_rates);
    let jacobian = (outputs.jacobian || outputs.sensitivities).then(|| {
        jacobian_parts(
            model,
            &closed_laws,
            &momenta.momenta,
            &rates.total,
            &mass_rates,
            &velocities,
            outputs.sensitivities,
        )
    });
    Ok(Equations {
        closed_laws,
        mass_rates,
        flow_rates,
        energies,
        forces,
        momenta,
        rates,
        accelerations,
        hamiltonian,
        rigid_velocities,
        power,
        jacobian,
    })
}

/// Moves the model and its equations into one [`Derivation`], and what the `check`s need
/// of the model to be lowered against it.
fn assemble(model: Model, e: Equations) -> (Derivation, CheckScope) {
    let scope = CheckScope {
        names: model.names,
        parameter_mode: model.parameter_mode,
        checks: model.checks,
    };
    let flow_names = model
        .flows
        .iter()
        .map(|flow| {
            let kind = if flow.inflow { "inflow" } else { "outflow" };
            let body = model.bodies.get(flow.body).map_or("?", |b| b.name.as_str());
            format!("{kind} `{body}`")
        })
        .collect();
    let euler_middles = model
        .bodies
        .iter()
        .filter_map(|b| b.rigid.as_ref().and_then(|r| r.euler_middle))
        .collect();
    let derivation = Derivation {
        pool: model.pool,
        time: model.time,
        coordinates: model.coordinates,
        parameters: model.parameters,
        masses: model.masses,
        closed_laws: e.closed_laws,
        mass_rates: e.mass_rates,
        kinetic: e.energies.kinetic,
        potential: e.energies.potential,
        lagrangian: e.energies.lagrangian,
        momenta: e.momenta.momenta,
        mass_matrix: e.momenta.mass_matrix,
        momentum_offset: e.momenta.offset,
        velocities: e.hamiltonian.velocities,
        rigid_velocities: e.rigid_velocities,
        energy: e.hamiltonian.energy,
        hamiltonian: e.hamiltonian.hamiltonian,
        lagrangian_gradient: e.rates.lagrangian_gradient,
        active_force: e.forces.active,
        reactive_thrust: e.forces.reactive_thrust,
        impact_force: e.forces.impact,
        flow_rates: e.flow_rates,
        flow_names,
        frozen_momentum_rate: e.rates.frozen,
        mass_flux_force: e.rates.mass_flux,
        momentum_rate: e.rates.total,
        acceleration_rhs: e.accelerations.rhs,
        accelerations: e.accelerations.solved,
        power: e.power,
        jacobian: e.jacobian,
        checks: Vec::new(),
        units: None,
        tables: model.tables,
        inputs: model.inputs,
        euler_middles,
    };
    (derivation, scope)
}
