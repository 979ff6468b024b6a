//! The equations of the paper, each from L, the momenta and the generalized forces: the
//! frozen and the true momentum rate (eq. 14), the right side of M q̈ (eq. 6), the energy
//! function and H (eqs. 9–10), and the power dH/dt. One function per equation, each
//! returning one small struct; see `docs/mechanics.md`.

use std::collections::HashMap;

use super::forces::GeneralizedForces;
use super::lagrangian::Momenta;
use super::linear::{dot, inverse, mat_vec, Matrix};
use super::model::Model;
use super::VelocitySolve;
use crate::expr::{ExprPool, Id, Rational, Symbol};
use crate::parse::Diagnostic;

/// Up to this many coordinates, q̇(q, p) and q̈ are solved symbolically (adjugate of M);
/// beyond, generated code solves M x = y numerically (the straight-line LDLᵀ of
/// `emit/factor.rs`).
///
/// Measured against the LDLᵀ path (`cargo bench -p varmass-benches --bench costs`, its
/// "symbolic-inverse threshold" rows, recorded in `docs/bench/costs.txt`): for the 3-link
/// chain of accreting bobs the closed form's state rate takes 45.5 ns against 50.1 ns for
/// the straight-line LDLᵀ (ratio 0.91, fastest of 101 alternating rounds), a saving of
/// under 5 ns per evaluation. Against it, the closed-form q̇ alone (the bench's
/// `threshold_expansion` row, in the dev profile users expand in:
/// `cargo bench --profile dev -p varmass-benches --bench costs -- none`) makes the 3-link
/// chain's generated code 2.35× larger (73 115 → 171 591 bytes formatted, exact) and its
/// expansion 1.17× longer (219 → 256 ms, fastest of 10, on a machine loaded ~15 on 2
/// cores, so the time ratio is rough); a closed-form q̈ would add to both. Compile time and
/// code size every user pays, for a few ns. At 2 coordinates the adjugate is small and
/// stays.
pub const SYMBOLIC_INVERSE_MAX_DOF: usize = 2;

/// The momentum balance of eq. 14 and the true momentum rate, one entry per coordinate.
pub(crate) struct MomentumRates {
    /// ∂*L/∂q (= −∂*H/∂q, eq. 13).
    pub lagrangian_gradient: Vec<Id>,
    /// Q* − R1 + R2, shared by d*p/dt and the power.
    pub applied: Vec<Id>,
    /// d*p/dt = ∂*L/∂q + Q* − R1 + R2 (eq. 14).
    pub frozen: Vec<Id>,
    /// Σᵢ ṁᵢ ∂*p/∂mᵢ.
    pub mass_flux: Vec<Id>,
    /// The true ṗ = d*p/dt + Σᵢ ṁᵢ ∂*p/∂mᵢ: as derived from [`momentum_rates`], then the
    /// form generated code evaluates ([`cheapest_rates`]).
    pub total: Vec<Id>,
}

/// Eq. 14 with the mass-flux term: d*p/dt and the true ṗ (as derived, unreduced).
pub(crate) fn momentum_rates(
    model: &mut Model,
    lagrangian: Id,
    forces: &GeneralizedForces,
    momenta: &[Id],
    mass_rates: &[Id],
) -> MomentumRates {
    let pool = &mut model.pool;
    let lagrangian_gradient: Vec<Id> = model
        .coordinates
        .iter()
        .map(|c| pool.diff(lagrangian, c.q))
        .collect();
    let applied: Vec<Id> = (0..momenta.len())
        .map(|a| {
            let thrust = pool.neg(forces.reactive_thrust[a]);
            pool.add(&[forces.active[a], thrust, forces.impact[a]])
        })
        .collect();
    let frozen = pairwise_sum(pool, &lagrangian_gradient, &applied);
    let mass_flux: Vec<Id> = momenta
        .iter()
        .map(|p_a| {
            let terms: Vec<Id> = model
                .masses
                .iter()
                .zip(mass_rates)
                .map(|(m, rate)| {
                    let partial = pool.diff(*p_a, m.symbol);
                    pool.mul(&[*rate, partial])
                })
                .collect();
            pool.add(&terms)
        })
        .collect();
    let total = pairwise_sum(pool, &frozen, &mass_flux);
    MomentumRates {
        lagrangian_gradient,
        applied,
        frozen,
        mass_flux,
        total,
    }
}

/// The form of the true ṗ that generated code evaluates: eq. 14's rows `derived`, each
/// reduced where that pays ([`cheaper_reduced`]), or `structured` (ṗ built in body axes by
/// `rigid_rates.rs`, where it applies) when it takes fewer operations.
///
/// The reduction is the derivation's largest cost for a spatial rigid body (a fifth of the
/// 6-dof rocket's expansion), and the body-frame form is built to avoid what it undoes:
/// when `structured` already takes fewer operations than the rows as derived, it is taken
/// without reducing them. The reduction could in principle bring the rows below it; in
/// the spatial models of the repository and of its tests it does not (the rocket: 1312
/// operations derived, 364 reduced, 227 in body axes; `mechanics_rigid.rs` holds its two
/// models to this), and the rows are reduced and compared whenever the body form is not
/// the cheaper one at once (a torque-free sphere: 5 derived, 43 in body axes).
pub(crate) fn cheapest_rates(
    pool: &mut ExprPool,
    derived: &[Id],
    structured: Option<Vec<Id>>,
) -> Vec<Id> {
    let reduce = |pool: &mut ExprPool| -> Vec<Id> {
        (derived.iter())
            .map(|row| cheaper_reduced(pool, *row))
            .collect()
    };
    let Some(structured) = structured else {
        return reduce(pool);
    };
    let bound = pool.operation_count(&structured);
    if bound < pool.operation_count(derived) {
        return structured;
    }
    let reduced = reduce(pool);
    if bound < pool.operation_count(&reduced) {
        structured
    } else {
        reduced
    }
}

/// `e` or its trigonometric reduction ([`ExprPool::reduce_trig`]: expanded, like terms
/// collected, sin² + cos² and the angle-sum identities applied), whichever takes fewer
/// operations. The true rate is a sum of parts that cancel in part once expanded: for a
/// flow at a body point, R1's transport term K takes back what Σ φ̇ ∂*p/∂φ adds
/// (docs/mechanics.md#flows-at-points), and the rigid body's world-frame products
/// collapse by sin² + cos² = 1. Sums of a few terms, as most particle systems have, stay as
/// derived; a reduction that does not pay is discarded.
fn cheaper_reduced(pool: &mut ExprPool, e: Id) -> Id {
    let reduced = pool.reduce_trig(e);
    if pool.operation_count(&[reduced]) < pool.operation_count(&[e]) {
        pool.factor_out(reduced)
    } else {
        e
    }
}

/// aᵢ + bᵢ for every i.
fn pairwise_sum(pool: &mut ExprPool, a: &[Id], b: &[Id]) -> Vec<Id> {
    a.iter().zip(b).map(|(x, y)| pool.add(&[*x, *y])).collect()
}

/// The equation of motion M q̈ = rhs (eq. 6), solved for q̈ when M is inverted symbolically.
pub(crate) struct Accelerations {
    /// d*p/dt − ∂*p/∂q q̇ − ∂*p/∂t.
    pub rhs: Vec<Id>,
    /// M⁻¹, up to [`SYMBOLIC_INVERSE_MAX_DOF`] coordinates.
    pub inverse_mass: Option<Matrix>,
    /// q̈(q, q̇, t), when M⁻¹ exists.
    pub solved: Option<Vec<Id>>,
}

/// Eq. 6: M q̈ = d*p/dt − (d*p/dt with q̈ = 0), since the frozen total derivative of p
/// without its acceleration part is ∂*p/∂q q̇ + ∂*p/∂t.
pub(crate) fn accelerations(
    model: &mut Model,
    momenta: &Momenta,
    frozen_rate: &[Id],
) -> Result<Accelerations, Vec<Diagnostic>> {
    let pool = &mut model.pool;
    let zero = pool.int(0);
    let no_acceleration: HashMap<Symbol, Id> = model
        .coordinates
        .iter()
        .map(|c| (c.acceleration, zero))
        .collect();
    let mut rhs = Vec::with_capacity(frozen_rate.len());
    for ((momentum, rate), coordinate) in momenta
        .momenta
        .iter()
        .zip(frozen_rate)
        .zip(&model.coordinates)
    {
        let dp = pool
            .time_derivative(*momentum)
            .map_err(|e| vec![Diagnostic::new(coordinate.span, e.to_string())])?;
        let convective = pool.substitute(dp, &no_acceleration);
        rhs.push(pool.sub(*rate, convective));
    }
    let inverse_mass = if model.coordinates.len() <= SYMBOLIC_INVERSE_MAX_DOF {
        inverse(pool, &momenta.mass_matrix)
    } else {
        None
    };
    let solved = inverse_mass.as_ref().map(|inv| mat_vec(pool, inv, &rhs));
    Ok(Accelerations {
        rhs,
        inverse_mass,
        solved,
    })
}

/// The energy function and, when M⁻¹ exists, H(q, p, t) (eqs. 9–10).
pub(crate) struct Hamiltonian {
    /// p·q̇ − L in velocity form (equals H on p = ∂*L/∂q̇).
    pub energy: Id,
    /// How q̇ is recovered from p.
    pub velocities: VelocitySolve,
    /// H(q, p, t), when q̇ is solved symbolically.
    pub hamiltonian: Option<Id>,
}

/// Eqs. 9–10: the energy function p·q̇ − L, and H with q̇ = M⁻¹ (p − b) eliminated.
pub(crate) fn hamiltonian(
    model: &mut Model,
    lagrangian: Id,
    momenta: &Momenta,
    inverse_mass: Option<&Matrix>,
) -> Hamiltonian {
    let velocities: Vec<Symbol> = model.coordinates.iter().map(|c| c.velocity).collect();
    let pool = &mut model.pool;
    let pv: Vec<Id> = momenta
        .momenta
        .iter()
        .zip(&velocities)
        .map(|(p, v)| {
            let v = pool.sym(*v);
            pool.mul(&[*p, v])
        })
        .collect();
    let pv = pool.add(&pv);
    let energy = pool.sub(pv, lagrangian);
    let energy = pool.reduce_trig(energy);
    let Some(inv) = inverse_mass else {
        return Hamiltonian {
            energy,
            velocities: VelocitySolve::Numeric,
            hamiltonian: None,
        };
    };
    let momentum_symbols: Vec<Symbol> = model.coordinates.iter().map(|c| c.momentum).collect();
    let (v, h) = legendre(
        pool,
        lagrangian,
        momenta,
        inv,
        &momentum_symbols,
        &velocities,
    );
    Hamiltonian {
        energy,
        velocities: VelocitySolve::Symbolic(v),
        hamiltonian: Some(h),
    }
}

/// q̇ = M⁻¹ (p − b) in the momentum symbols, and H = ½ (p − b)·q̇ − L₀: the same function as
/// p·q̇ − L with q̇ eliminated (L = ½ q̇ᵀ M q̇ + b·q̇ + L₀), without squaring M⁻¹.
fn legendre(
    pool: &mut ExprPool,
    lagrangian: Id,
    momenta: &Momenta,
    inverse_mass: &Matrix,
    momentum_symbols: &[Symbol],
    velocities: &[Symbol],
) -> (Vec<Id>, Id) {
    let excess: Vec<Id> = momentum_symbols
        .iter()
        .zip(&momenta.offset)
        .map(|(p, b)| {
            let p = pool.sym(*p);
            pool.sub(p, *b)
        })
        .collect();
    let v = mat_vec(pool, inverse_mass, &excess);
    let zero = pool.int(0);
    let at_rest: HashMap<Symbol, Id> = velocities.iter().map(|v| (*v, zero)).collect();
    let rest_lagrangian = pool.substitute(lagrangian, &at_rest);
    let half = pool.rational(Rational::HALF);
    let kinetic_part = dot(pool, &excess, &v);
    let kinetic_part = pool.mul(&[half, kinetic_part]);
    let h = pool.sub(kinetic_part, rest_lagrangian);
    (v, h)
}

/// The power dH/dt = −∂*L/∂t + q̇·(Q* − R1 + R2 + Σ ṁ ∂*p/∂m) − Σ ṁᵢ ∂*L/∂mᵢ, with
/// ∂*H/∂t = −∂*L/∂t and ∂H/∂mᵢ|_(q,p) = −∂*L/∂mᵢ|_(q,q̇).
pub(crate) fn power(
    model: &mut Model,
    lagrangian: Id,
    rates: &MomentumRates,
    mass_rates: &[Id],
) -> Id {
    let pool = &mut model.pool;
    let dl_dt = pool.diff(lagrangian, model.time);
    let mut terms = vec![pool.neg(dl_dt)];
    for ((applied, flux), c) in rates
        .applied
        .iter()
        .zip(&rates.mass_flux)
        .zip(&model.coordinates)
    {
        let force = pool.add(&[*applied, *flux]);
        let v = pool.sym(c.velocity);
        terms.push(pool.mul(&[v, force]));
    }
    for (m, rate) in model.masses.iter().zip(mass_rates) {
        let dl_dm = pool.diff(lagrangian, m.symbol);
        let product = pool.mul(&[*rate, dl_dm]);
        terms.push(pool.neg(product));
    }
    pool.add(&terms)
}
