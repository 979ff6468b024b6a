//! Mass laws and mass rates: closed laws m(q, t, m_s), ṁ for every mass, and the rates of
//! the flows, checked against the mass law (ṁ = Q2 − Q1, docs/mechanics.md#systems-bodies-and-flows).

use std::collections::HashMap;

use super::model::{FlowVelocityValue, MassKind, Model};
use crate::expr::{ExprPool, Id, Symbol};
use crate::parse::{Diagnostic, Span};

/// The laws with every other law-mass substituted, so that each depends only on q, t,
/// parameters and state masses. `None` for state masses.
pub(crate) fn closed_laws(model: &mut Model) -> Result<Vec<Option<Id>>, Vec<Diagnostic>> {
    let law_map: HashMap<Symbol, Id> = model
        .masses
        .iter()
        .filter_map(|m| match m.kind {
            MassKind::Law(law) => Some((m.symbol, law)),
            MassKind::State { .. } => None,
        })
        .collect();
    let mut errors = Vec::new();
    let mut closed = Vec::with_capacity(model.masses.len());
    for mass in &model.masses {
        let MassKind::Law(law) = mass.kind else {
            closed.push(None);
            continue;
        };
        // A chain of laws is at most as long as the number of masses; a law still naming a
        // law-mass after that many rounds is circular.
        let mut value = law;
        for _ in 0..=law_map.len() {
            value = model.pool.substitute(value, &law_map);
        }
        let circular = law_map.keys().any(|s| model.pool.contains(value, *s));
        if circular {
            errors.push(Diagnostic::new(
                mass.span,
                format!(
                    "the law of `{}` is circular: it depends on itself through other mass laws",
                    mass.name
                ),
            ));
        }
        closed.push(Some(value));
    }
    if errors.is_empty() {
        Ok(closed)
    } else {
        Err(errors)
    }
}

/// ṁ for every mass (model order): the declared rate of a state mass, or the total time
/// derivative of a closed law, d/dt m(q, t, m_s) = Σ ∂m/∂q q̇ + ∂m/∂t + Σ ∂m/∂m_s ṁ_s.
pub(crate) fn mass_rates(
    model: &mut Model,
    closed: &[Option<Id>],
) -> Result<Vec<Id>, Vec<Diagnostic>> {
    let state_rates: Vec<(Symbol, Id)> = model
        .masses
        .iter()
        .filter_map(|m| match m.kind {
            MassKind::State { rate } => Some((m.symbol, rate)),
            MassKind::Law(_) => None,
        })
        .collect();
    let mut rates = Vec::with_capacity(model.masses.len());
    let mut errors = Vec::new();
    for (mass, law) in model.masses.iter().zip(closed) {
        match (mass.kind.clone(), law) {
            (MassKind::State { rate }, _) => rates.push(rate),
            (MassKind::Law(_), Some(law)) => {
                let pool = &mut model.pool;
                let explicit = match pool.time_derivative(*law) {
                    Ok(d) => d,
                    Err(e) => {
                        errors.push(Diagnostic::new(
                            mass.span,
                            format!("cannot differentiate the law of `{}`: {e}", mass.name),
                        ));
                        continue;
                    }
                };
                let mut terms = vec![explicit];
                for (symbol, rate) in &state_rates {
                    let partial = pool.diff(*law, *symbol);
                    terms.push(pool.mul(&[partial, *rate]));
                }
                rates.push(pool.add(&terms));
            }
            (MassKind::Law(_), None) => rates.push(model.pool.int(0)),
        }
    }
    if errors.is_empty() {
        Ok(rates)
    } else {
        Err(errors)
    }
}

/// The rate (Q1 or Q2, ≥ 0) of every flow, defaults filled in, checked against the mass law.
///
/// Why the check: R1 and R2 are built from these rates; if Q2 − Q1 ≠ ṁ the forces describe
/// a different mass history than the one in L, and every result would be silently wrong.
pub(crate) fn flow_rates(model: &mut Model, mass_rates: &[Id]) -> Result<Vec<Id>, Vec<Diagnostic>> {
    let mut rates: Vec<Option<Id>> = model.flows.iter().map(|f| f.rate).collect();
    let mut errors = Vec::new();
    for (mass_index, mass) in model.masses.iter().enumerate() {
        let flows: Vec<usize> = (0..model.flows.len())
            .filter(|&f| model.bodies[model.flows[f].body].mass == mass_index)
            .collect();
        if flows.is_empty() {
            continue;
        }
        let missing: Vec<usize> = flows
            .iter()
            .copied()
            .filter(|&f| rates[f].is_none())
            .collect();
        let pool = &mut model.pool;
        // Σ Q2 − Σ Q1 over the flows with a given rate.
        let mut net_terms = Vec::new();
        for &f in &flows {
            if let Some(rate) = rates[f] {
                net_terms.push(if model.flows[f].inflow {
                    rate
                } else {
                    pool.neg(rate)
                });
            }
        }
        let given_net = pool.add(&net_terms);
        match missing.as_slice() {
            [] => {
                let span = model.flows[flows[0]].span;
                let law = (mass.name.as_str(), mass_rates[mass_index]);
                errors.extend(unbalanced(pool, law, given_net, span));
            }
            [only] => {
                // The one flow without a rate carries what the mass law leaves over.
                let rest = pool.sub(mass_rates[mass_index], given_net);
                rates[*only] = Some(if model.flows[*only].inflow {
                    rest
                } else {
                    pool.neg(rest)
                });
            }
            [_, second, ..] => errors.push(Diagnostic::new(
                model.flows[*second].span,
                format!(
                    "more than one flow of mass `{}` has no `rate`; give the rate of all but one",
                    mass.name
                ),
            )),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(rates
        .into_iter()
        .map(|r| r.unwrap_or_else(|| model.pool.int(0)))
        .collect())
}

/// Why the given rates of a mass's flows, inflow − outflow = `given_net`, break its mass
/// law (`name`, ṁ): they contradict it, or the two cannot be compared; `None` when they
/// agree.
fn unbalanced(
    pool: &mut ExprPool,
    (name, mass_rate): (&str, Id),
    given_net: Id,
    span: Span,
) -> Option<Diagnostic> {
    let verdict = pool.identical(mass_rate, given_net);
    let (law, given) = (pool.display(mass_rate), pool.display(given_net));
    match verdict {
        // Neither proven nor seen to hold: the balance is not known to hold, and the forces
        // built on these rates would not be trusted either.
        crate::expr::Identity::Undecided => Some(
            Diagnostic::new(
                span,
                format!(
                    "the flow rates of `{name}` cannot be checked against its mass law: ṁ = {law} and inflow − outflow = {given} are not both defined at any sample point"
                ),
            )
            .with_help("write the rates so that they are defined for the states the system reaches, or leave one flow's `rate` out to have it derived from ṁ"),
        ),
        crate::expr::Identity::Refuted { .. } => Some(
            Diagnostic::new(
                span,
                format!(
                    "the flow rates contradict the mass law of `{name}`: ṁ = {law}, but inflow − outflow = {given}"
                ),
            )
            .with_help("mass is conserved: the rates of all inflows minus all outflows of a body must equal its ṁ"),
        ),
        crate::expr::Identity::Proven | crate::expr::Identity::Numerical { .. } => None,
    }
}

/// The relative velocity v_r = u − ṙ of a flow's mass, or `None` when it moves with the body.
pub(crate) fn relative_velocity(
    pool: &mut ExprPool,
    velocity: &FlowVelocityValue,
    body_velocity: &[Id],
) -> Option<Vec<Id>> {
    match velocity {
        FlowVelocityValue::Absolute(u) => Some(
            u.iter()
                .zip(body_velocity)
                .map(|(u, v)| pool.sub(*u, *v))
                .collect(),
        ),
        FlowVelocityValue::Relative(v_r) => Some(v_r.clone()),
        FlowVelocityValue::WithBody => None,
    }
}
