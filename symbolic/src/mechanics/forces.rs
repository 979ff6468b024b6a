//! The generalized forces of the paper (§1): the active Q*, the reactive thrust R1 and the
//! impact force R2, each the projection Σᵢ Fᵢ · ∂rᵢ/∂q of body vectors, plus the components
//! given directly. Rigid bodies add forces at body points, torques and the flows at points
//! of `rigid_forces.rs`.

use super::linear::dot;
use super::masses::relative_velocity;
use super::model::{LoadKind, LoadTarget, Model};
use super::rigid_forces::{
    flow_force, jacobian, point_position, torque_force, transport, PointFlow,
};
use crate::expr::{ExprPool, Id};

/// Q*, R1 and R2, one entry per coordinate.
pub(crate) struct GeneralizedForces {
    pub active: Vec<Id>,
    pub reactive_thrust: Vec<Id>,
    pub impact: Vec<Id>,
}

/// Projects every load and flow onto the coordinates. `flow_rates` are Q1 (outflow) or Q2
/// (inflow) per flow, `body_velocities` ṙ per body (of the centre of mass of a rigid one),
/// `mass_rates` ṁ per mass.
pub(crate) fn generalized_forces(
    model: &mut Model,
    flow_rates: &[Id],
    body_velocities: &[Vec<Id>],
    mass_rates: &[Id],
) -> GeneralizedForces {
    let n = model.coordinates.len();
    let mut active: Vec<Vec<Id>> = vec![Vec::new(); n];
    let mut thrust: Vec<Vec<Id>> = vec![Vec::new(); n];
    let mut impact: Vec<Vec<Id>> = vec![Vec::new(); n];
    let coordinates: Vec<_> = model.coordinates.iter().map(|c| c.q).collect();
    let velocities: Vec<_> = model.coordinates.iter().map(|c| c.velocity).collect();
    let pool = &mut model.pool;
    // ∂rᵢ/∂q_α per body and coordinate.
    let jacobians: Vec<Vec<Vec<Id>>> = model
        .bodies
        .iter()
        .map(|b| {
            coordinates
                .iter()
                .map(|q| b.position.iter().map(|r| pool.diff(*r, *q)).collect())
                .collect()
        })
        .collect();
    for load in &model.loads {
        let sink = match load.kind {
            LoadKind::Active => &mut active,
            LoadKind::Thrust => &mut thrust,
            LoadKind::Impact => &mut impact,
        };
        match &load.target {
            LoadTarget::Coordinate(alpha, value) => sink[*alpha].push(*value),
            LoadTarget::Body(body, vector) => project(pool, vector, &jacobians[*body], sink),
            LoadTarget::Point {
                body,
                vector,
                point,
            } => {
                let Some(rigid) = &model.bodies[*body].rigid else {
                    continue;
                };
                let r_p = point_position(pool, rigid, point);
                let j_p = jacobian(pool, &r_p, &coordinates);
                project(pool, vector, &j_p, sink);
            }
            LoadTarget::Torque(body, torque) => {
                let Some(rigid) = &model.bodies[*body].rigid else {
                    continue;
                };
                let generalized = torque_force(pool, rigid, torque, &velocities);
                for (alpha, value) in generalized.into_iter().enumerate() {
                    sink[alpha].push(value);
                }
            }
        }
    }
    for (flow, rate) in model.flows.iter().zip(flow_rates) {
        if let Some(point) = &flow.point {
            let body = &model.bodies[flow.body];
            let centre = &body_velocities[flow.body];
            let generalized = flow_force(
                pool,
                body,
                centre,
                point,
                &flow.velocity,
                *rate,
                &coordinates,
            );
            let sink = if flow.inflow {
                &mut impact
            } else {
                &mut thrust
            };
            for (alpha, value) in generalized.into_iter().enumerate() {
                sink[alpha].push(value);
            }
            continue;
        }
        let Some(v_r) = relative_velocity(pool, &flow.velocity, &body_velocities[flow.body]) else {
            continue;
        };
        // R1ᵢ = Q1ᵢ v_r1ᵢ, R2ᵢ = Q2ᵢ v_r2ᵢ (eq. 2).
        let force: Vec<Id> = v_r.iter().map(|c| pool.mul(&[*rate, *c])).collect();
        let sink = if flow.inflow {
            &mut impact
        } else {
            &mut thrust
        };
        project(pool, &force, &jacobians[flow.body], sink);
    }
    // The transport term of each rigid body with flows: into R1 when it has an outflow
    // (a rocket), else into R2 with its sign turned (docs/mechanics.md#flows-at-points).
    let frozen: Vec<_> = model
        .masses
        .iter()
        .zip(mass_rates)
        .map(|(m, rate)| (m.symbol, *rate))
        .collect();
    let pairs: Vec<_> = coordinates.iter().copied().zip(velocities).collect();
    for (index, body) in model.bodies.iter().enumerate() {
        let flows: Vec<PointFlow<'_>> = model
            .flows
            .iter()
            .zip(flow_rates)
            .filter(|(f, _)| f.body == index)
            .filter_map(|(f, rate)| {
                f.point.as_deref().map(|point| PointFlow {
                    inflow: f.inflow,
                    rate: *rate,
                    point,
                })
            })
            .collect();
        if flows.is_empty() {
            continue;
        }
        let own = (model.masses[body.mass].symbol, mass_rates[body.mass]);
        let centre = &body_velocities[index];
        let term = transport(pool, body, centre, &frozen, own, &flows, &pairs);
        let outflow = flows.iter().any(|f| !f.inflow);
        for (alpha, value) in term.into_iter().enumerate() {
            if outflow {
                thrust[alpha].push(value);
            } else {
                let turned = pool.neg(value);
                impact[alpha].push(turned);
            }
        }
    }
    let mut sum = |terms: Vec<Vec<Id>>| -> Vec<Id> { terms.iter().map(|t| pool.add(t)).collect() };
    GeneralizedForces {
        active: sum(active),
        reactive_thrust: sum(thrust),
        impact: sum(impact),
    }
}

fn project(pool: &mut ExprPool, vector: &[Id], jacobian: &[Vec<Id>], sink: &mut [Vec<Id>]) {
    for (alpha, dr_dq) in jacobian.iter().enumerate() {
        sink[alpha].push(dot(pool, vector, dr_dq));
    }
}
