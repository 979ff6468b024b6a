//! The generalized forces of the paper (§1): the active Q*, the reactive thrust R1 and the
//! impact force R2, each the projection Σᵢ Fᵢ · ∂rᵢ/∂q of body vectors, plus the components
//! given directly. Rigid bodies add forces at body points, torques and the flows at points
//! of `rigid_forces.rs`.

use super::linear::{dot, Matrix};
use super::masses::relative_velocity;
use super::model::{Body, Flow, Load, LoadKind, LoadTarget, Mass, Model};
use super::rigid_forces::{
    flow_force, jacobian, point_position, torque_force, transport, PointFlow,
};
use crate::expr::{ExprPool, Id, Symbol};

/// Q*, R1 and R2, one entry per coordinate.
pub(crate) struct GeneralizedForces {
    pub active: Vec<Id>,
    pub reactive_thrust: Vec<Id>,
    pub impact: Vec<Id>,
}

/// The terms of Q*, R1 and R2 gathered so far, one list per coordinate each.
struct Sinks {
    active: Vec<Vec<Id>>,
    thrust: Vec<Vec<Id>>,
    impact: Vec<Vec<Id>>,
}

impl Sinks {
    /// Where a load of `kind` goes.
    fn load(&mut self, kind: LoadKind) -> &mut Vec<Vec<Id>> {
        match kind {
            LoadKind::Active => &mut self.active,
            LoadKind::Thrust => &mut self.thrust,
            LoadKind::Impact => &mut self.impact,
        }
    }

    /// Where a flow's force goes: R2 for an inflow, R1 for an outflow.
    fn flow(&mut self, inflow: bool) -> &mut Vec<Vec<Id>> {
        if inflow {
            &mut self.impact
        } else {
            &mut self.thrust
        }
    }
}

/// What the projections read of a model (all but its pool): its coordinates and
/// velocities, ∂rᵢ/∂q_α per body and coordinate, and its bodies, loads, flows and masses.
struct Frame<'m> {
    coordinates: Vec<Symbol>,
    velocities: Vec<Symbol>,
    jacobians: Vec<Matrix>,
    bodies: &'m [Body],
    loads: &'m [Load],
    flows: &'m [Flow],
    masses: &'m [Mass],
}

/// The rates the flows' forces are made of: Q1 (outflow) or Q2 (inflow) per flow, ṙ per
/// body (of the centre of mass of a rigid one), ṁ per mass.
struct Rates<'r> {
    flows: &'r [Id],
    body_velocities: &'r [Vec<Id>],
    masses: &'r [Id],
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
    let mut sinks = Sinks {
        active: vec![Vec::new(); n],
        thrust: vec![Vec::new(); n],
        impact: vec![Vec::new(); n],
    };
    let coordinates: Vec<_> = model.coordinates.iter().map(|c| c.q).collect();
    let velocities: Vec<_> = model.coordinates.iter().map(|c| c.velocity).collect();
    let pool = &mut model.pool;
    let jacobians = model
        .bodies
        .iter()
        .map(|b| jacobian(pool, &b.position, &coordinates))
        .collect();
    let frame = Frame {
        coordinates,
        velocities,
        jacobians,
        bodies: &model.bodies,
        loads: &model.loads,
        flows: &model.flows,
        masses: &model.masses,
    };
    let rates = Rates {
        flows: flow_rates,
        body_velocities,
        masses: mass_rates,
    };
    project_loads(pool, &frame, &mut sinks);
    project_flows(pool, &frame, &rates, &mut sinks);
    add_transport(pool, &frame, &rates, &mut sinks);
    let mut sum = |terms: Vec<Vec<Id>>| -> Vec<Id> { terms.iter().map(|t| pool.add(t)).collect() };
    GeneralizedForces {
        active: sum(sinks.active),
        reactive_thrust: sum(sinks.thrust),
        impact: sum(sinks.impact),
    }
}

/// The loads (`force`, `thrust`, `impact`, on coordinates, bodies, points and as torques)
/// into their sinks.
fn project_loads(pool: &mut ExprPool, frame: &Frame<'_>, sinks: &mut Sinks) {
    for load in frame.loads {
        let sink = sinks.load(load.kind);
        match &load.target {
            LoadTarget::Coordinate(alpha, value) => sink[*alpha].push(*value),
            LoadTarget::Body(body, vector) => project(pool, vector, &frame.jacobians[*body], sink),
            LoadTarget::Point {
                body,
                vector,
                point,
            } => {
                let Some(rigid) = &frame.bodies[*body].rigid else {
                    continue;
                };
                let r_p = point_position(pool, rigid, point);
                let j_p = jacobian(pool, &r_p, &frame.coordinates);
                project(pool, vector, &j_p, sink);
            }
            LoadTarget::Torque(body, torque) => {
                let Some(rigid) = &frame.bodies[*body].rigid else {
                    continue;
                };
                let generalized = torque_force(pool, rigid, torque, &frame.velocities);
                push_all(sink, generalized);
            }
        }
    }
}

/// The flows' forces R1ᵢ = Q1ᵢ v_r1ᵢ, R2ᵢ = Q2ᵢ v_r2ᵢ (eq. 2) projected into R1 and R2:
/// a flow at a point of a rigid body through `flow_force`, any other at its body's
/// position.
fn project_flows(pool: &mut ExprPool, frame: &Frame<'_>, rates: &Rates<'_>, sinks: &mut Sinks) {
    for (flow, rate) in frame.flows.iter().zip(rates.flows) {
        let centre = &rates.body_velocities[flow.body];
        if let Some(point) = &flow.point {
            let body = &frame.bodies[flow.body];
            let (velocity, coordinates) = (&flow.velocity, &frame.coordinates);
            let generalized = flow_force(pool, body, centre, point, velocity, *rate, coordinates);
            push_all(sinks.flow(flow.inflow), generalized);
            continue;
        }
        let Some(v_r) = relative_velocity(pool, &flow.velocity, centre) else {
            continue;
        };
        let force: Vec<Id> = v_r.iter().map(|c| pool.mul(&[*rate, *c])).collect();
        let jacobian = &frame.jacobians[flow.body];
        project(pool, &force, jacobian, sinks.flow(flow.inflow));
    }
}

/// The transport term of each rigid body with flows at points: into R1 when it has an
/// outflow (a rocket), else into R2 with its sign turned (docs/mechanics.md#flows-at-points).
fn add_transport(pool: &mut ExprPool, frame: &Frame<'_>, rates: &Rates<'_>, sinks: &mut Sinks) {
    let (flow_rates, body_velocities, mass_rates) =
        (rates.flows, rates.body_velocities, rates.masses);
    let frozen: Vec<_> = frame
        .masses
        .iter()
        .zip(mass_rates)
        .map(|(m, rate)| (m.symbol, *rate))
        .collect();
    let velocities = frame.velocities.iter().copied();
    let pairs: Vec<_> = frame.coordinates.iter().copied().zip(velocities).collect();
    for (index, body) in frame.bodies.iter().enumerate() {
        let flows: Vec<PointFlow<'_>> = frame
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
        let own = (frame.masses[body.mass].symbol, mass_rates[body.mass]);
        let centre = &body_velocities[index];
        let term = transport(pool, body, centre, &frozen, own, &flows, &pairs);
        if flows.iter().any(|f| !f.inflow) {
            push_all(&mut sinks.thrust, term);
        } else {
            let turned = term.into_iter().map(|value| pool.neg(value)).collect();
            push_all(&mut sinks.impact, turned);
        }
    }
}

/// Each of `values` to the terms of its coordinate.
fn push_all(sink: &mut [Vec<Id>], values: Vec<Id>) {
    for (alpha, value) in values.into_iter().enumerate() {
        sink[alpha].push(value);
    }
}

fn project(pool: &mut ExprPool, vector: &[Id], jacobian: &[Vec<Id>], sink: &mut [Vec<Id>]) {
    for (alpha, dr_dq) in jacobian.iter().enumerate() {
        sink[alpha].push(dot(pool, vector, dr_dq));
    }
}
