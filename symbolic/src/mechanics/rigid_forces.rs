//! The generalized forces of rigid bodies (docs/mechanics.md#flows-at-points): forces at
//! body points, torques, and the momentum that flows carry across the boundary at their
//! points, split into the per-flow terms and the body's transport term so that eq. 14's
//! form d*p/dt = ∂*L/∂q + Q* − R1 + R2 holds unchanged.

use super::linear::{dot, mat_vec, Matrix};
use super::model::{Body, FlowVelocityValue, Rigid};
use crate::expr::{ExprPool, Id, Rational, Symbol};

/// ½ ωᵀ I ω, ω and I in body components (and a quaternion's gauge term, `Rigid::gauge`).
pub(crate) fn rotational_kinetic(pool: &mut ExprPool, rigid: &Rigid) -> Id {
    let half = pool.rational(Rational::HALF);
    let spin = mat_vec(pool, &rigid.inertia, &rigid.angular_velocity);
    let twice = dot(pool, &rigid.angular_velocity, &spin);
    let rotational = pool.mul(&[half, twice]);
    match rigid.gauge {
        Some(gauge) => pool.add(&[rotational, gauge]),
        None => rotational,
    }
}

/// r_P = r_O + R a for the body-frame point a.
pub(crate) fn point_position(pool: &mut ExprPool, rigid: &Rigid, point: &[Id]) -> Vec<Id> {
    let offset = mat_vec(pool, &rigid.rotation, point);
    rigid
        .origin
        .iter()
        .zip(&offset)
        .map(|(r, a)| pool.add(&[*r, *a]))
        .collect()
}

/// ∂r/∂q_α for every coordinate: one vector per α.
pub(crate) fn jacobian(pool: &mut ExprPool, r: &[Id], coordinates: &[Symbol]) -> Matrix {
    coordinates
        .iter()
        .map(|q| r.iter().map(|c| pool.diff(*c, *q)).collect())
        .collect()
}

/// Q_α = τ · ∂ω/∂q̇_α (τ and ω in body components): the virtual power of a couple.
pub(crate) fn torque_force(
    pool: &mut ExprPool,
    rigid: &Rigid,
    torque: &[Id],
    velocities: &[Symbol],
) -> Vec<Id> {
    velocities
        .iter()
        .map(|v| {
            let d_omega: Vec<Id> = rigid
                .angular_velocity
                .iter()
                .map(|w| pool.diff(*w, *v))
                .collect();
            dot(pool, torque, &d_omega)
        })
        .collect()
}

/// What one flow at point P of a rigid body adds to R1 (outflow) or R2 (inflow):
/// Q (u · ∂r_P/∂q_α − ṙ_c · ∂r_c/∂q_α), with u = ṙ_P + v_r the absolute velocity of the
/// flowing mass (v_r relative to the material point at P). For a particle (P = c) this is
/// the paper's Q v_r · ∂r/∂q.
pub(crate) fn flow_force(
    pool: &mut ExprPool,
    body: &Body,
    centre_velocity: &[Id],
    point: &[Id],
    velocity: &FlowVelocityValue,
    rate: Id,
    coordinates: &[Symbol],
) -> Vec<Id> {
    let Some(rigid) = &body.rigid else {
        return vec![pool.int(0); coordinates.len()];
    };
    let r_p = point_position(pool, rigid, point);
    let point_velocity: Vec<Id> = r_p
        .iter()
        .map(|r| pool.time_derivative(*r).unwrap_or(*r))
        .collect();
    let u: Vec<Id> = match velocity {
        FlowVelocityValue::Absolute(u) => u.clone(),
        FlowVelocityValue::Relative(v_r) => point_velocity
            .iter()
            .zip(v_r)
            .map(|(v, w)| pool.add(&[*v, *w]))
            .collect(),
        FlowVelocityValue::WithBody => point_velocity,
    };
    let j_p = jacobian(pool, &r_p, coordinates);
    let j_c = jacobian(pool, &body.position, coordinates);
    j_p.iter()
        .zip(&j_c)
        .map(|(dp, dc)| {
            let carried = dot(pool, &u, dp);
            let centre = dot(pool, centre_velocity, dc);
            let net = pool.sub(carried, centre);
            pool.mul(&[rate, net])
        })
        .collect()
}

/// One flow of a rigid body as the transport term needs it.
pub(crate) struct PointFlow<'a> {
    /// Inflow (Q2) or outflow (Q1).
    pub inflow: bool,
    /// Q ≥ 0.
    pub rate: Id,
    /// The body-frame point a where it crosses.
    pub point: &'a [Id],
}

/// The transport term of a rigid body with flows (docs/mechanics.md#flows-at-points):
///
/// ```text
/// K_α = Σ_φ φ̇ ∂*p_b,α/∂φ − ṁ_b ṙ_c · ∂r_c/∂q_α − ṙ_c · (∂R/∂q_α) I,
/// I = d(m c)/dt + Σ_out Q a − Σ_in Q a
/// ```
///
/// with p_b = ∂T_b/∂q̇ the body's own momentum. The first two terms are how the rates of
/// its frozen inertia and centre offset change its momentum beyond what the mass carries at
/// the centre; I is the momentum (body axes) of the internal flow that moves the centre of
/// mass in the body other than the flows do, and the last term its coupling to the motion
/// of the centre, which makes the equations the same in every inertial frame. Zero for a
/// particle; I = 0 when the laws of m and c are those of mass leaving at the flows' points.
pub(crate) fn transport(
    pool: &mut ExprPool,
    body: &Body,
    centre_velocity: &[Id],
    frozen: &[(Symbol, Id)],
    body_mass: (Symbol, Id),
    flows: &[PointFlow<'_>],
    coordinates: &[(Symbol, Symbol)],
) -> Vec<Id> {
    let Some(rigid) = &body.rigid else {
        return vec![pool.int(0); coordinates.len()];
    };
    let half = pool.rational(Rational::HALF);
    let squared = dot(pool, centre_velocity, centre_velocity);
    let translational = pool.mul(&[half, squared]);
    let mass = pool.sym(body_mass.0);
    let moving = pool.mul(&[mass, translational]);
    let rotating = rotational_kinetic(pool, rigid);
    let kinetic = pool.add(&[moving, rotating]);
    let internal = internal_flow(pool, rigid, mass, frozen, flows);
    coordinates
        .iter()
        .map(|(q, v)| {
            let momentum = pool.diff(kinetic, *v);
            let mut terms = frozen_rate_terms(pool, momentum, frozen);
            let centre = pool.diff(translational, *v);
            let minus_rate = pool.neg(body_mass.1);
            terms.push(pool.mul(&[minus_rate, centre]));
            let turning: Matrix = rigid
                .rotation
                .iter()
                .map(|row| row.iter().map(|r| pool.diff(*r, *q)).collect())
                .collect();
            let moved = mat_vec(pool, &turning, &internal);
            let coupling = dot(pool, centre_velocity, &moved);
            terms.push(pool.neg(coupling));
            pool.add(&terms)
        })
        .collect()
}

/// The terms φ̇ ∂e/∂φ of the rate of `e` through the frozen symbols φ (each with its rate
/// φ̇), in their order.
fn frozen_rate_terms(pool: &mut ExprPool, e: Id, frozen: &[(Symbol, Id)]) -> Vec<Id> {
    frozen
        .iter()
        .map(|(phi, rate)| {
            let partial = pool.diff(e, *phi);
            pool.mul(&[*rate, partial])
        })
        .collect()
}

/// I = d(m c)/dt + Σ_out Q a − Σ_in Q a in body axes: what the laws of m and c ask of the
/// matter inside beyond what the flows take away at their points. m c depends only on
/// frozen symbols and parameters, so its true rate is Σ_φ φ̇ ∂(m c)/∂φ.
fn internal_flow(
    pool: &mut ExprPool,
    rigid: &Rigid,
    mass: Id,
    frozen: &[(Symbol, Id)],
    flows: &[PointFlow<'_>],
) -> Vec<Id> {
    rigid
        .centre
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let moment = pool.mul(&[mass, *c]);
            let mut terms = frozen_rate_terms(pool, moment, frozen);
            for flow in flows {
                let carried = pool.mul(&[flow.rate, flow.point[i]]);
                terms.push(if flow.inflow {
                    pool.neg(carried)
                } else {
                    carried
                });
            }
            pool.add(&terms)
        })
        .collect()
}
