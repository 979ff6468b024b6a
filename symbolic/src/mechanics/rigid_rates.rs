//! The true momentum rate ṗ of a lone spatial rigid body in its own coordinates, built in
//! body axes (docs/mechanics.md#rigid-bodies, "ṗ in body axes"): the generalized forces on
//! the angles are Eᵀ times one body-frame vector, plus the explicit η-derivative of ω in T,
//! instead of eq. 14's world-frame projections expanded and reduced. The rule of
//! `rigid_solve.rs` for q̇, applied to ṗ.
//!
//! With q = [r_O, η], R(η) body → world, ω = ω(η, η̇) in body axes, E_k = ∂ω/∂η̇_k (so
//! Rᵀ ∂R/∂η_k = [E_k]×, whatever the sequence), the centre c and inertia I (frozen),
//! V = Rᵀ ṙ_O, w = V + ω × c (the centre's velocity), P = m w, h = I ω + c × P:
//!
//! ```text
//! T = ½ m |w|² + ½ ωᵀ I ω
//! ∂T/∂r_O = 0,   ∂T/∂η_k = ∂ω/∂η_k · h + E_k · (P × V)          (∂Rᵀ/∂η_k ṙ_O = −E_k × V)
//! P × V = m (ω × c) × V
//! ```
//!
//! Every projection onto an angle is E_k · (a body vector): for a body point a,
//! ∂r_P/∂η_k = R (E_k × a), so u · ∂r_P/∂η_k = E_k · (a × Rᵀu); ṙ_c · (∂R/∂η_k) I =
//! E_k · (I × w); ṙ_c · ∂r_c/∂η_k = E_k · (c × w). The true rate of F1
//! (docs/mechanics.md#flows-at-points) — eq. 14's d*p/dt + Σ φ̇ ∂*p/∂φ, with K cancelling
//! the frozen quantities' rates — is then, with u_j = Rᵀ u the absolute velocity of flow j
//! in body axes (V + ω × a_j + Rᵀ v_r,j for a relative velocity), s_j = −1 for an outflow and
//! +1 for an inflow (ṁ = Σ s_j Q_j, which the derivation requires of a body with flows, so
//! the ṁ ṙ_c · ∂r_c/∂q terms of K cancel):
//!
//! ```text
//! G   = P × V + Σ s_j Q_j a_j × u_j + I × w,   I = d(m c)/dt − Σ s_j Q_j a_j
//! B   = Σ s_j Q_j u_j
//! ṗ_r = ∂L₀/∂r_O + Q*_r + R B,   R (V + t) written ṙ_O + R t
//! ṗ_η = ∂L₀/∂η + Q*_η + [∂ω/∂η_k · h]_k + Eᵀ G
//! ```
//!
//! with L₀ = L − T the velocity-free rest of L. Without flows, R1 = R2 = 0 and the frozen
//! quantities enter through Σ φ̇ ∂*p/∂φ with p_r = R P and p_η = Eᵀ h:
//! G = P × V + Σ φ̇ ∂h/∂φ and B = Σ φ̇ ∂P/∂φ.
//!
//! A quaternion's components take the place of η unchanged (Ṙ = R [ω]× on every path, so
//! Rᵀ ∂R/∂e_k = [E_k]× with E_k = ∂ω/∂ė_k; ω depends on q, hence the explicit term), and its
//! gauge term T_g = ½ λ (q·q̇)²/n², which the formulas above do not hold, adds its own part
//! from its generic derivation: ∂T_g/∂e_k, plus Σ φ̇ ∂(∂T_g/∂ė_k)/∂φ without flows (with
//! flows K takes it back with the frozen rates of the rest of the body's momentum).
//!
//! Only where it is exact: one body, rigid and spatial, in its own coordinates
//! (`rigid_solve::own_coordinates`), every flow at a point that is fixed in the body, and
//! no `thrust` or `impact` load (those are summed into R1 and R2 as given). Q* (forces,
//! torques) is taken as derived.

use super::forces::GeneralizedForces;
use super::linear::{dot, mat_vec};
use super::model::{FlowVelocityValue, LoadKind, Model, TermKind};
use super::rigid_solve::{cross, own_coordinates};
use super::rotation::transpose;
use crate::expr::{ExprPool, Id, Symbol, SymbolKind};

/// One flow of the body as the rates need it.
struct BodyFlow {
    /// s_j Q_j: −Q for an outflow, +Q for an inflow.
    signed_rate: Id,
    /// The body-frame point a.
    point: Vec<Id>,
    /// u_j in body axes.
    velocity: Vec<Id>,
    /// How R u_j is written in ṗ_r.
    world: Carried,
}

/// R u_j without the round trip R Rᵀ.
enum Carried {
    /// u_j = V + t: R u_j = ṙ_O + R t, with t (body axes) held here.
    Material(Vec<Id>),
    /// An absolute velocity, world components.
    Absolute(Vec<Id>),
}

/// B of the module's comment as ṗ_r reads it: R B = along ṙ_O + R body + world.
struct Push {
    along: Id,
    body: Vec<Id>,
    world: Vec<Id>,
}

/// The body's motion in body axes, as functions of q and q̇.
pub(super) struct Motion {
    /// V = Rᵀ ṙ_O.
    origin: Vec<Id>,
    /// ω.
    omega: Vec<Id>,
    /// ω × c.
    turn: Vec<Id>,
    /// w = V + ω × c.
    pub(super) centre: Vec<Id>,
    /// h = I ω + c × P.
    pub(super) angular: Vec<Id>,
}

/// ṗ in coordinate order by the formulas of the module's comment, `None` where they do not
/// apply. `forces` supplies Q*; `mass_rates` and `flow_rates` follow the model's masses and
/// flows.
pub(crate) fn body_frame_rates(
    model: &mut Model,
    forces: &GeneralizedForces,
    mass_rates: &[Id],
    flow_rates: &[Id],
) -> Option<Vec<Id>> {
    let slots = own_coordinates(model)?;
    if model.loads.iter().any(|l| l.kind != LoadKind::Active) {
        return None;
    }
    let motion = motion(model, &slots)?;
    let flows = body_flows(model, &motion, flow_rates)?;
    let frozen: Vec<(Symbol, Id)> = (model.masses.iter().map(|m| m.symbol))
        .zip(mass_rates.iter().copied())
        .collect();
    let (turning, pushing) = body_vectors(model, &motion, &flows, &frozen)?;
    let rest = rest_gradient(model);
    let gauge = gauge_rates(model, &frozen, flows.is_empty());
    let rotation = model.bodies[0].rigid.as_ref()?.rotation.clone();
    let pool = &mut model.pool;
    let turned = mat_vec(pool, &rotation, &pushing.body);
    let mut out = vec![pool.int(0); slots.len()];
    for (k, &slot) in slots.iter().enumerate() {
        let (q, v) = (model.coordinates[slot].q, model.coordinates[slot].velocity);
        let mut terms = vec![rest[slot], forces.active[slot]];
        if k < 3 {
            // (R B)_k = along ṙ_O,k + (R body)_k + world_k.
            let rate = pool.sym(v);
            terms.push(pool.mul(&[pushing.along, rate]));
            terms.extend([turned[k], pushing.world[k]]);
        } else {
            // [∂ω/∂η_k · h] + E_k · G.
            let axis: Vec<Id> = motion.omega.iter().map(|w| pool.diff(*w, v)).collect();
            let explicit: Vec<Id> = motion.omega.iter().map(|w| pool.diff(*w, q)).collect();
            terms.push(dot(pool, &explicit, &motion.angular));
            terms.push(dot(pool, &axis, &turning));
        }
        if let Some(gauge) = &gauge {
            terms.push(gauge[slot]);
        }
        out[slot] = pool.add(&terms);
    }
    Some(out)
}

/// G and B of the module's comment.
fn body_vectors(
    model: &mut Model,
    motion: &Motion,
    flows: &[BodyFlow],
    frozen: &[(Symbol, Id)],
) -> Option<(Vec<Id>, Push)> {
    let body_mass = model.bodies[0].mass;
    let centre = model.bodies[0].rigid.as_ref()?.centre.clone();
    let mass = model.pool.sym(model.masses[body_mass].symbol);
    let pool = &mut model.pool;
    // P × V = m (ω × c) × V exactly (w − V = ω × c): no cancellation when the body flies
    // fast and turns slowly, as P × V written out would have.
    let moment: Vec<Id> = (motion.turn.iter())
        .map(|x| pool.mul(&[mass, *x]))
        .collect();
    let twist = Vectors(pool).cross(&moment, &motion.origin);
    let (turning, pushing) = if flows.is_empty() {
        let h = frozen_rate(pool, &motion.angular, frozen);
        // P = m V + m ω × c, V free of the frozen symbols.
        let along = frozen_rate(pool, &[mass], frozen)[0];
        let body = frozen_rate(pool, &moment, frozen);
        let world = vec![pool.int(0); 3];
        (h, Push { along, body, world })
    } else {
        flow_terms(pool, motion, &centre, mass, frozen, flows)
    };
    Some((Vectors(pool).sum(&twist, &turning), pushing))
}

/// V, ω, w, P and h of the module's comment (also what a quaternion body's momenta are
/// built from, `rigid_solve::quaternion_momenta`).
pub(super) fn motion(model: &mut Model, slots: &[usize]) -> Option<Motion> {
    let body = &model.bodies[0];
    let rigid = body.rigid.as_ref()?;
    let mass = model.pool.sym(model.masses[body.mass].symbol);
    let (rotation, omega, inertia, centre) = (
        rigid.rotation.clone(),
        rigid.angular_velocity.clone(),
        rigid.inertia.clone(),
        rigid.centre.clone(),
    );
    let pool = &mut model.pool;
    let rates: Vec<Id> = slots[..3]
        .iter()
        .map(|&i| pool.sym(model.coordinates[i].velocity))
        .collect();
    let origin = mat_vec(pool, &transpose(&rotation), &rates);
    let turn = cross(pool, &omega, &centre);
    let centre_velocity = Vectors(pool).sum(&origin, &turn);
    let momentum: Vec<Id> = centre_velocity
        .iter()
        .map(|w| pool.mul(&[mass, *w]))
        .collect();
    let spin = mat_vec(pool, &inertia, &omega);
    let lever = cross(pool, &centre, &momentum);
    let angular = Vectors(pool).sum(&spin, &lever);
    Some(Motion {
        origin,
        omega,
        turn,
        centre: centre_velocity,
        angular,
    })
}

/// Every flow of the body, `None` if one has no point or a point that moves in the body.
fn body_flows(model: &mut Model, motion: &Motion, flow_rates: &[Id]) -> Option<Vec<BodyFlow>> {
    let rotation = model.bodies[0].rigid.as_ref()?.rotation.clone();
    let back = transpose(&rotation);
    let mut flows = Vec::with_capacity(model.flows.len());
    for (flow, rate) in model.flows.iter().zip(flow_rates) {
        let point = flow.point.clone()?;
        let pool = &mut model.pool;
        let moving = point.iter().flat_map(|a| pool.free_symbols(*a)).any(|s| {
            matches!(
                pool.symbols().kind(s),
                SymbolKind::Coordinate | SymbolKind::Velocity { .. } | SymbolKind::Time
            )
        });
        if moving {
            return None;
        }
        let turn = cross(pool, &motion.omega, &point);
        let in_body = |pool: &mut ExprPool, world: &[Id]| -> Vec<Id> {
            let turned = mat_vec(pool, &back, world);
            turned.into_iter().map(|x| pool.reduce_trig(x)).collect()
        };
        let (velocity, world) = match &flow.velocity {
            FlowVelocityValue::WithBody => {
                let velocity = Vectors(pool).sum(&motion.origin, &turn);
                (velocity, Carried::Material(turn))
            }
            FlowVelocityValue::Relative(v_r) => {
                let relative = in_body(pool, v_r);
                let extra = Vectors(pool).sum(&turn, &relative);
                let velocity = Vectors(pool).sum(&motion.origin, &extra);
                (velocity, Carried::Material(extra))
            }
            FlowVelocityValue::Absolute(u) => (in_body(pool, u), Carried::Absolute(u.clone())),
        };
        let signed_rate = if flow.inflow { *rate } else { pool.neg(*rate) };
        flows.push(BodyFlow {
            signed_rate,
            point,
            velocity,
            world,
        });
    }
    Some(flows)
}

/// G − P × V and B of the module's comment for a body with flows.
fn flow_terms(
    pool: &mut ExprPool,
    motion: &Motion,
    centre: &[Id],
    mass: Id,
    frozen: &[(Symbol, Id)],
    flows: &[BodyFlow],
) -> (Vec<Id>, Push) {
    let zero = vec![pool.int(0); 3];
    let mut turning = zero.clone();
    let mut along = Vec::new();
    let (mut body, mut world) = (zero.clone(), zero);
    let moment: Vec<Id> = centre.iter().map(|c| pool.mul(&[mass, *c])).collect();
    let mut internal = frozen_rate(pool, &moment, frozen);
    for flow in flows {
        let carried = cross(pool, &flow.point, &flow.velocity);
        turning = Vectors(pool).sum_scaled(&turning, flow.signed_rate, &carried);
        match &flow.world {
            Carried::Material(extra) => {
                along.push(flow.signed_rate);
                body = Vectors(pool).sum_scaled(&body, flow.signed_rate, extra);
            }
            Carried::Absolute(u) => world = Vectors(pool).sum_scaled(&world, flow.signed_rate, u),
        }
        let minus = pool.neg(flow.signed_rate);
        internal = Vectors(pool).sum_scaled(&internal, minus, &flow.point);
    }
    let coupling = cross(pool, &internal, &motion.centre);
    turning = Vectors(pool).sum(&turning, &coupling);
    let along = pool.add(&along);
    (turning, Push { along, body, world })
}

/// ∂L₀/∂q_α for every coordinate, L₀ = L − T the terms of L without a velocity (every
/// term, under `own_coordinates`), trigonometrically reduced.
fn rest_gradient(model: &mut Model) -> Vec<Id> {
    let pool = &mut model.pool;
    let parts: Vec<Id> = model
        .terms
        .iter()
        .map(|t| match t.kind {
            TermKind::Potential => pool.neg(t.value),
            TermKind::Kinetic | TermKind::Lagrangian => t.value,
        })
        .collect();
    let rest = pool.add(&parts);
    let rest = pool.reduce_trig(rest);
    model
        .coordinates
        .iter()
        .map(|c| {
            let d = pool.diff(rest, c.q);
            pool.reduce_trig(d)
        })
        .collect()
}

/// The part of ṗ of a quaternion's gauge term T_g (docs/mechanics.md#quaternions), which
/// the body-frame formulas do not contain, from its generic derivation: ∂T_g/∂q_α, plus
/// Σ φ̇ ∂(∂T_g/∂q̇_α)/∂φ without flows (with flows, the transport term K takes back the
/// frozen rates of the body's whole momentum, the gauge's with it). `None` without a gauge.
fn gauge_rates(model: &mut Model, frozen: &[(Symbol, Id)], without_flows: bool) -> Option<Vec<Id>> {
    let gauge = model.bodies[0].rigid.as_ref()?.gauge?;
    let pool = &mut model.pool;
    let rates = (model.coordinates.iter())
        .map(|c| {
            let mut terms = vec![pool.diff(gauge, c.q)];
            if without_flows {
                let momentum = pool.diff(gauge, c.velocity);
                terms.extend(frozen_rate(pool, &[momentum], frozen));
            }
            pool.add(&terms)
        })
        .collect();
    Some(rates)
}

/// Σ_φ φ̇ ∂x/∂φ for each component x (its true rate through the frozen symbols).
fn frozen_rate(pool: &mut ExprPool, x: &[Id], frozen: &[(Symbol, Id)]) -> Vec<Id> {
    x.iter()
        .map(|e| {
            let terms: Vec<Id> = frozen
                .iter()
                .map(|(phi, rate)| {
                    let partial = pool.diff(*e, *phi);
                    pool.mul(&[*rate, partial])
                })
                .collect();
            pool.add(&terms)
        })
        .collect()
}

/// Vector sums on the pool.
struct Vectors<'a>(&'a mut ExprPool);

impl Vectors<'_> {
    /// a + b.
    fn sum(&mut self, a: &[Id], b: &[Id]) -> Vec<Id> {
        a.iter()
            .zip(b)
            .map(|(x, y)| self.0.add(&[*x, *y]))
            .collect()
    }

    /// a + s b.
    fn sum_scaled(&mut self, a: &[Id], s: Id, b: &[Id]) -> Vec<Id> {
        a.iter()
            .zip(b)
            .map(|(x, y)| {
                let scaled = self.0.mul(&[s, *y]);
                self.0.add(&[*x, scaled])
            })
            .collect()
    }

    /// a × b.
    fn cross(&mut self, a: &[Id], b: &[Id]) -> Vec<Id> {
        cross(self.0, a, b)
    }
}
