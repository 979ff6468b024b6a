//! The generalized forces of the paper (§1): the active Q*, the reactive thrust R1 and the
//! impact force R2, each the projection Σᵢ Fᵢ · ∂rᵢ/∂q of body vectors, plus the components
//! given directly.

use super::linear::dot;
use super::masses::relative_velocity;
use super::model::{LoadKind, LoadTarget, Model};
use crate::expr::{ExprPool, Id};

/// Q*, R1 and R2, one entry per coordinate.
pub(crate) struct GeneralizedForces {
    pub active: Vec<Id>,
    pub reactive_thrust: Vec<Id>,
    pub impact: Vec<Id>,
}

/// Projects every load and flow onto the coordinates. `flow_rates` are Q1 (outflow) or Q2
/// (inflow) per flow, `body_velocities` ṙ per body.
pub(crate) fn generalized_forces(
    model: &mut Model,
    flow_rates: &[Id],
    body_velocities: &[Vec<Id>],
) -> GeneralizedForces {
    let n = model.coordinates.len();
    let mut active: Vec<Vec<Id>> = vec![Vec::new(); n];
    let mut thrust: Vec<Vec<Id>> = vec![Vec::new(); n];
    let mut impact: Vec<Vec<Id>> = vec![Vec::new(); n];
    let coordinates: Vec<_> = model.coordinates.iter().map(|c| c.q).collect();
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
        }
    }
    for (flow, rate) in model.flows.iter().zip(flow_rates) {
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
