//! `check` statements: identities stated in the DSL and verified against the derived
//! equations before the derivation is assembled (see `docs/dsl.md`). Both sides are brought to velocity form with the mass laws substituted, then
//! compared by canonical form and, failing that, at random points.

use rustc_hash::FxHashMap;
use std::collections::HashMap;

use super::derivation::{CheckOutcome, Equations};
use super::equations::SYMBOLIC_INVERSE_MAX_DOF;
use super::model::{Check, Model};
use super::resolve::lower_with;
use super::resolve::Context;
use crate::expr::{ExprPool, Id, Identity, Symbol};
use crate::parse::Diagnostic;

/// The names a `check` may use for derived quantities, in velocity form.
fn quantities(model: &Model, e: &Equations) -> FxHashMap<String, Id> {
    let mut q = FxHashMap::default();
    q.insert("H".to_string(), e.hamiltonian.energy);
    q.insert("L".to_string(), e.energies.lagrangian);
    q.insert("T".to_string(), e.energies.kinetic);
    q.insert("V".to_string(), e.energies.potential);
    q.insert("power".to_string(), e.power);
    for (a, c) in model.coordinates.iter().enumerate() {
        let name = &c.name;
        q.insert(format!("p_{name}"), e.momenta.momenta[a]);
        q.insert(format!("Q_{name}"), e.forces.active[a]);
        q.insert(format!("R1_{name}"), e.forces.reactive_thrust[a]);
        q.insert(format!("R2_{name}"), e.forces.impact[a]);
        q.insert(format!("dp_{name}"), e.rates.frozen[a]);
        q.insert(format!("pdot_{name}"), e.rates.total[a]);
        if let Some(acc) = &e.accelerations.solved {
            q.insert(format!("{name}''"), acc[a]);
        }
    }
    for (m, rate) in model.masses.iter().zip(&e.mass_rates) {
        q.insert(format!("mdot_{}", m.name), *rate);
    }
    q
}

/// Verifies every check of the model against its equations; the failures are diagnostics.
pub(crate) fn run_checks(
    model: &mut Model,
    equations: &Equations,
) -> Result<Vec<CheckOutcome>, Vec<Diagnostic>> {
    let quantities = quantities(model, equations);
    let laws: HashMap<Symbol, Id> = model
        .masses
        .iter()
        .zip(&equations.closed_laws)
        .filter_map(|(m, law)| law.map(|l| (m.symbol, l)))
        .collect();
    let mut errors = Vec::new();
    let mut outcomes = Vec::new();
    let mut verdicts = Verdicts::default();
    let checks = std::mem::take(&mut model.checks);
    for check in &checks {
        let sides = lower_sides(model, check, &quantities).and_then(|(lhs, rhs)| {
            require_solved(model, check, lhs, rhs)?;
            Ok((lhs, rhs))
        });
        match sides {
            Ok((lhs, rhs)) => {
                let outcome = decide(&mut model.pool, lhs, rhs, &laws, &mut verdicts);
                errors.extend(verdict_error(&model.pool, check, lhs, rhs, &outcome));
                outcomes.push(outcome);
            }
            Err(e) => errors.extend(e),
        }
    }
    model.checks = checks;
    if errors.is_empty() {
        Ok(outcomes)
    } else {
        Err(errors)
    }
}

/// Both sides of a check lowered, with every diagnostic of either side.
fn lower_sides(
    model: &mut Model,
    check: &Check,
    quantities: &FxHashMap<String, Id>,
) -> Result<(Id, Id), Vec<Diagnostic>> {
    let mut lower = |node| {
        lower_with(
            &mut model.pool,
            &mut model.names,
            &model.parameter_mode,
            &mut model.parameters,
            node,
            Context::Check,
            Some(quantities),
        )
    };
    match (lower(&check.lhs), lower(&check.rhs)) {
        (Ok(l), Ok(r)) => Ok((l, r)),
        (l, r) => Err(l.err().into_iter().chain(r.err()).flatten().collect()),
    }
}

/// Accelerations left as symbols mean q̈ was not solved symbolically.
fn require_solved(model: &Model, check: &Check, lhs: Id, rhs: Id) -> Result<(), Vec<Diagnostic>> {
    let unsolved = model.coordinates.iter().any(|c| {
        model.pool.contains(lhs, c.acceleration) || model.pool.contains(rhs, c.acceleration)
    });
    if !unsolved {
        return Ok(());
    }
    Err(vec![Diagnostic::new(
        check.span,
        format!(
            "a check on accelerations needs q̈ in closed form, which is derived for up to {} coordinates",
            SYMBOLIC_INVERSE_MAX_DOF
        ),
    )])
}

/// The verdicts already reached, by the two sides compared: tagged checks often state
/// one identity twice (`x'' = … + R2_x/m` and, under a tag, `x'' = … - c*x'^2/m` with
/// R2_x = -c*x'^2), and a numerical decision costs hundreds of evaluations.
type Verdicts = FxHashMap<(Id, Id), Identity>;

/// Compares both sides with the mass laws substituted.
fn decide(
    pool: &mut ExprPool,
    lhs: Id,
    rhs: Id,
    laws: &HashMap<Symbol, Id>,
    verdicts: &mut Verdicts,
) -> CheckOutcome {
    let lhs_physical = pool.substitute(lhs, laws);
    let rhs_physical = pool.substitute(rhs, laws);
    let verdict = verdicts
        .entry((lhs_physical, rhs_physical))
        .or_insert_with(|| pool.identical(lhs_physical, rhs_physical))
        .clone();
    let text = format!("{} = {}", pool.display(lhs), pool.display(rhs));
    CheckOutcome { text, verdict }
}

/// The diagnostic of a refuted or undecided check.
fn verdict_error(
    pool: &ExprPool,
    check: &Check,
    lhs: Id,
    rhs: Id,
    outcome: &CheckOutcome,
) -> Option<Diagnostic> {
    match &outcome.verdict {
        Identity::Refuted {
            env,
            lhs: l,
            rhs: r,
        } => {
            let at: Vec<String> = env
                .iter()
                .map(|(s, v)| format!("{} = {v:.4}", pool.symbols().name(*s)))
                .collect();
            Some(
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
            )
        }
        Identity::Undecided => Some(Diagnostic::new(
            check.span,
            "check undecided: no sample point lies where both sides are defined",
        )),
        Identity::Proven | Identity::Numerical { .. } => None,
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
