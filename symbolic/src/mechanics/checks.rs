//! `check` statements: identities stated in the DSL and verified against the derivation
//! (SPEC §2). Both sides are brought to velocity form with the mass laws substituted, then
//! compared by canonical form and, failing that, at random points.

use std::collections::HashMap;

use super::derivation::{CheckOutcome, Derivation};
use super::resolve::lower_with;
use super::resolve::Context;
use crate::expr::{Id, Identity, Symbol};
use crate::parse::Diagnostic;

/// The names a `check` may use for derived quantities, in velocity form.
fn quantities(d: &Derivation) -> HashMap<String, Id> {
    let mut q = HashMap::new();
    q.insert("H".to_string(), d.energy);
    q.insert("L".to_string(), d.lagrangian);
    q.insert("T".to_string(), d.kinetic);
    q.insert("V".to_string(), d.potential);
    q.insert("power".to_string(), d.power);
    for (a, c) in d.coordinates.iter().enumerate() {
        let name = &c.name;
        q.insert(format!("p_{name}"), d.momenta[a]);
        q.insert(format!("Q_{name}"), d.active_force[a]);
        q.insert(format!("R1_{name}"), d.reactive_thrust[a]);
        q.insert(format!("R2_{name}"), d.impact_force[a]);
        q.insert(format!("dp_{name}"), d.frozen_momentum_rate[a]);
        q.insert(format!("pdot_{name}"), d.momentum_rate[a]);
        if let Some(acc) = &d.accelerations {
            q.insert(format!("{name}''"), acc[a]);
        }
    }
    for (m, rate) in d.masses.iter().zip(&d.mass_rates) {
        q.insert(format!("mdot_{}", m.name), *rate);
    }
    q
}

/// Verifies every pending check against the derivation; the failures are diagnostics.
pub(crate) fn run_checks(derivation: &mut Derivation) -> Result<(), Vec<Diagnostic>> {
    let quantities = quantities(derivation);
    let laws: HashMap<Symbol, Id> = derivation
        .masses
        .iter()
        .zip(&derivation.closed_laws)
        .filter_map(|(m, law)| law.map(|l| (m.symbol, l)))
        .collect();
    let mut errors = Vec::new();
    let checks = std::mem::take(&mut derivation.scope.pending_checks);
    for check in &checks {
        let d = &mut *derivation;
        let scope = &mut d.scope;
        let mut lower = |node| {
            lower_with(
                &mut d.pool,
                &mut scope.names,
                &scope.parameter_mode,
                &mut d.parameters,
                node,
                Context::Check,
                Some(&quantities),
            )
        };
        let lhs = lower(&check.lhs);
        let rhs = lower(&check.rhs);
        let (lhs, rhs) = match (lhs, rhs) {
            (Ok(l), Ok(r)) => (l, r),
            (l, r) => {
                errors.extend(l.err().into_iter().flatten());
                errors.extend(r.err().into_iter().flatten());
                continue;
            }
        };
        // Accelerations left as symbols mean q̈ was not solved symbolically.
        let unsolved = derivation.coordinates.iter().any(|c| {
            derivation.pool.contains(lhs, c.acceleration)
                || derivation.pool.contains(rhs, c.acceleration)
        });
        if unsolved {
            errors.push(Diagnostic::new(
                check.span,
                format!(
                    "a check on accelerations needs q̈ in closed form, which is derived for up to {} coordinates",
                    super::derivation::SYMBOLIC_INVERSE_MAX_DOF
                ),
            ));
            continue;
        }
        let pool = &mut derivation.pool;
        let lhs_physical = pool.substitute(lhs, &laws);
        let rhs_physical = pool.substitute(rhs, &laws);
        let verdict = pool.identical(lhs_physical, rhs_physical);
        let text = format!("{} = {}", pool.display(lhs), pool.display(rhs));
        match &verdict {
            Identity::Refuted {
                env,
                lhs: l,
                rhs: r,
            } => {
                let at: Vec<String> = env
                    .iter()
                    .map(|(s, v)| format!("{} = {v:.4}", pool.symbols().name(*s)))
                    .collect();
                errors.push(
                    Diagnostic::new(
                        check.span,
                        format!(
                            "check failed: the derivation gives {}, but the check states {}",
                            pool.display(lhs),
                            pool.display(rhs)
                        ),
                    )
                    .with_help(format!(
                        "at {} the sides are {} and {}",
                        at.join(", "),
                        short(*l),
                        short(*r)
                    )),
                );
            }
            Identity::Undecided => errors.push(Diagnostic::new(
                check.span,
                "check undecided: no sample point lies where both sides are defined",
            )),
            Identity::Proven | Identity::Numerical { .. } => {}
        }
        derivation.checks.push(CheckOutcome { text, verdict });
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// A number for a message: fixed point where that is readable, scientific otherwise.
fn short(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        format!("{x:.6}")
    } else {
        format!("{x:.4e}")
    }
}
