//! `check` statements: identities stated in the DSL and verified against the derived
//! equations before the derivation is assembled (see `docs/dsl.md`). Both sides are brought to velocity form with the mass laws substituted, then
//! compared by canonical form and, failing that, at random points.

use rustc_hash::FxHashMap;
use std::collections::HashMap;

use super::derivation::{CheckOutcome, Derivation};
use super::equations::SYMBOLIC_INVERSE_MAX_DOF;
use super::model::Check;
use super::resolve::{lower_with, Binding, Context, Parameters};
use crate::expr::{ExprPool, Id, Identity, Symbol};
use crate::parse::Diagnostic;
use crate::quantity::Quantity;

/// What the `check`s need of the model once its equations are assembled: the names in
/// scope, how parameters are known, and the checks themselves.
pub(crate) struct CheckScope {
    pub names: FxHashMap<String, Binding>,
    pub parameter_mode: Parameters,
    pub checks: Vec<Check>,
}

/// The names a `check` may use for derived quantities, in velocity form: every named
/// entry of the registry ([`Quantity::names`]) that `d` holds.
fn quantities(d: &Derivation) -> FxHashMap<String, Id> {
    let coordinates: Vec<&str> = d.coordinates.iter().map(|c| c.name.as_str()).collect();
    let masses: Vec<&str> = d.masses.iter().map(|m| m.name.as_str()).collect();
    let values: Vec<Vec<Id>> = Quantity::ALL.iter().map(|q| q.read(d)).collect();
    Quantity::names(&coordinates, &masses)
        .into_iter()
        .filter_map(|(name, q, i)| Some((name, *values[q.index()].get(i)?)))
        .collect()
}

/// Verifies every check of `scope` against the derivation; the failures are diagnostics.
pub(crate) fn run_checks(
    d: &mut Derivation,
    mut scope: CheckScope,
) -> Result<Vec<CheckOutcome>, Vec<Diagnostic>> {
    let quantities = quantities(d);
    let laws: HashMap<Symbol, Id> = d
        .masses
        .iter()
        .zip(&d.closed_laws)
        .filter_map(|(m, law)| law.map(|l| (m.symbol, l)))
        .collect();
    let mut errors = Vec::new();
    let mut outcomes = Vec::new();
    let mut verdicts = Verdicts::default();
    for check in &scope.checks {
        let sides = lower_sides(
            d,
            &mut scope.names,
            &scope.parameter_mode,
            check,
            &quantities,
        )
        .and_then(|(lhs, rhs)| {
            require_solved(d, check, lhs, rhs)?;
            Ok((lhs, rhs))
        });
        match sides {
            Ok((lhs, rhs)) => {
                let outcome = decide(&mut d.pool, check, lhs, rhs, &laws, &mut verdicts);
                errors.extend(verdict_error(&d.pool, check, lhs, rhs, &outcome));
                outcomes.push(outcome);
            }
            Err(e) => errors.extend(e),
        }
    }
    if errors.is_empty() {
        Ok(outcomes)
    } else {
        Err(errors)
    }
}

/// Both sides of a check lowered, with every diagnostic of either side.
fn lower_sides(
    d: &mut Derivation,
    names: &mut FxHashMap<String, Binding>,
    parameter_mode: &Parameters,
    check: &Check,
    quantities: &FxHashMap<String, Id>,
) -> Result<(Id, Id), Vec<Diagnostic>> {
    let mut lower = |node| {
        lower_with(
            &mut d.pool,
            names,
            parameter_mode,
            &mut d.parameters,
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
fn require_solved(d: &Derivation, check: &Check, lhs: Id, rhs: Id) -> Result<(), Vec<Diagnostic>> {
    let unsolved = d
        .coordinates
        .iter()
        .any(|c| d.pool.contains(lhs, c.acceleration) || d.pool.contains(rhs, c.acceleration));
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
    check: &Check,
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
    CheckOutcome {
        text,
        source: check.source.clone(),
        span: check.span,
        verdict,
    }
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
