//! `check` statements: identities stated in the DSL and verified against the derived
//! equations before the derivation is assembled (see `docs/dsl.md`). Both sides are brought
//! to velocity form with the mass laws substituted, then compared exactly — by canonical
//! form, then as rational functions (over a common denominator, the numerator expanded) —
//! and only failing that at random points.

use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::HashMap;

use super::derivation::{CheckOutcome, Derivation};
use super::equations::SYMBOLIC_INVERSE_MAX_DOF;
use super::model::Check;
use super::resolve::{lower_with, Binding, Context, Parameters};
use crate::expr::{ExprPool, Id, Identity, Node, Symbol};
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
    let values: Vec<Vec<Id>> = Quantity::ALL.iter().map(|q| d.quantity(*q)).collect();
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
        .or_insert_with(
            || match rational_identity(pool, lhs_physical, rhs_physical) {
                true => Identity::Proven,
                false => pool.identical(lhs_physical, rhs_physical),
            },
        )
        .clone();
    let text = format!("{} = {}", pool.display(lhs), pool.display(rhs));
    CheckOutcome {
        text,
        source: check.source.clone(),
        span: check.span,
        verdict,
    }
}

/// Whether `lhs − rhs` is 0 as a rational function of its symbols (function calls and
/// non-integer powers taken as opaque): the difference is brought over one denominator
/// and its numerator expanded. `(g*m - k*x)/m = g - k*x/m` is decided here, exactly,
/// where canonical forms alone (which do not combine fractions) leave it to random points.
/// The identity then holds wherever both sides are defined; a numerator the expansion
/// limits leave unexpanded just fails here and goes on to [`ExprPool::identical`].
fn rational_identity(pool: &mut ExprPool, lhs: Id, rhs: Id) -> bool {
    let difference = pool.sub(lhs, rhs);
    if pool.is_zero(difference) {
        return true;
    }
    let difference = pool.inline_definitions(difference);
    let (numerator, _) = fraction(pool, difference);
    let expanded = pool.expand(numerator);
    pool.is_zero(expanded)
}

/// `e` as (numerator, denominator), both free of negative integer powers at the top: sums
/// over a common denominator (the product of the distinct ones), products factor by
/// factor, `b^-k` as `den(b)^k / num(b)^k`. A loop over the nodes it descends into,
/// children (lower ids) before parents, as every pass over an expression is
/// (ARCHITECTURE.md, invariants of `expr`): no recursion, whatever the depth.
fn fraction(pool: &mut ExprPool, root: Id) -> (Id, Id) {
    let mut nodes = Vec::new();
    let mut pending = vec![root];
    let mut seen = FxHashSet::default();
    while let Some(e) = pending.pop() {
        if seen.insert(e) {
            nodes.push(e);
            pending.extend(fraction_children(pool, e));
        }
    }
    nodes.sort_unstable();
    let mut parts: FxHashMap<Id, (Id, Id)> = FxHashMap::default();
    for e in nodes {
        let part = fraction_of(pool, e, &parts);
        parts.insert(e, part);
    }
    parts[&root]
}

/// The operands `fraction` descends into: the terms of a sum, the factors of a product,
/// the base of an integer power.
fn fraction_children(pool: &ExprPool, e: Id) -> Vec<Id> {
    match pool.node(e) {
        Node::Add(terms) => terms.to_vec(),
        Node::Mul(factors) => factors.to_vec(),
        Node::Pow(base, exponent) => match pool.node(*exponent) {
            Node::Num(k) if k.denom() == 1 && k.numer() != 0 => vec![*base],
            _ => Vec::new(),
        },
        _ => Vec::new(),
    }
}

/// One node of [`fraction`], its operands' parts already in `parts`.
fn fraction_of(pool: &mut ExprPool, e: Id, parts: &FxHashMap<Id, (Id, Id)>) -> (Id, Id) {
    let one = pool.int(1);
    match pool.node(e).clone() {
        Node::Add(terms) => {
            let (mut numerator, mut denominator) = (pool.int(0), one);
            for term in terms.iter() {
                let (n, d) = parts[term];
                if d == denominator {
                    numerator = pool.add(&[numerator, n]);
                } else {
                    let left = pool.mul(&[numerator, d]);
                    let right = pool.mul(&[n, denominator]);
                    numerator = pool.add(&[left, right]);
                    denominator = pool.mul(&[denominator, d]);
                }
            }
            (numerator, denominator)
        }
        Node::Mul(factors) => {
            let numerators: Vec<Id> = factors.iter().map(|f| parts[f].0).collect();
            let denominators: Vec<Id> = factors.iter().map(|f| parts[f].1).collect();
            (pool.mul(&numerators), pool.mul(&denominators))
        }
        Node::Pow(base, exponent) => match pool.node(exponent).clone() {
            Node::Num(k) if k.denom() == 1 && k.numer() != 0 => {
                let (n, d) = parts[&base];
                let power = pool.int(i64::try_from(k.numer().abs()).unwrap_or(i64::MAX));
                let (n, d) = (pool.pow(n, power), pool.pow(d, power));
                if k.numer() < 0 {
                    (d, n)
                } else {
                    (n, d)
                }
            }
            _ => (e, one),
        },
        _ => (e, one),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::SymbolKind;

    fn symbols<const K: usize>(pool: &mut ExprPool, names: [&str; K]) -> [Id; K] {
        names.map(|name| {
            let s = pool.symbols_mut().add(name, SymbolKind::Parameter);
            pool.sym(s)
        })
    }

    /// The issue's `(g*m − k*x)/m = g − k*x/m`: over the common denominator m the numerator
    /// g*m − k*x − (g*m − k*x) expands to 0. One more term (`+ 1/m`) is not an identity: the
    /// numerator is then −1.
    #[test]
    fn the_issues_rational_identity_is_proven_and_a_near_miss_is_not() {
        let mut pool = ExprPool::new();
        let [g, m, k, x] = symbols(&mut pool, ["g", "m", "k", "x"]);
        let gm = pool.mul(&[g, m]);
        let kx = pool.mul(&[k, x]);
        let numerator = pool.sub(gm, kx);
        let lhs = pool.div(numerator, m);
        let kx_m = pool.div(kx, m);
        let rhs = pool.sub(g, kx_m);
        assert!(rational_identity(&mut pool, lhs, rhs));
        let one = pool.int(1);
        let one_m = pool.div(one, m);
        let wrong = pool.add(&[rhs, one_m]);
        assert!(!rational_identity(&mut pool, lhs, wrong));
    }

    /// Fractions whose sum needs a common denominator: 1/(x+1) − 1/(x−1) = −2/(x²−1) and
    /// x/(x*g + x*k) = 1/(g+k). Canonical form and expansion alone (`identical`) leave both
    /// to random points, as this test shows first; the rational decision proves them.
    #[test]
    fn sums_of_fractions_are_decided_exactly() {
        let mut pool = ExprPool::new();
        let [g, k, x] = symbols(&mut pool, ["g", "k", "x"]);
        let (one, two, minus_two) = (pool.int(1), pool.int(2), pool.int(-2));
        let (x1, x_1) = (pool.add(&[x, one]), pool.sub(x, one));
        let a = pool.div(one, x1);
        let b = pool.div(one, x_1);
        let left = pool.sub(a, b);
        let x2 = pool.pow(x, two);
        let x2_1 = pool.sub(x2, one);
        let right = pool.div(minus_two, x2_1);
        let xg = pool.mul(&[x, g]);
        let xk = pool.mul(&[x, k]);
        let sum = pool.add(&[xg, xk]);
        let left_2 = pool.div(x, sum);
        let gk = pool.add(&[g, k]);
        let right_2 = pool.div(one, gk);
        for (l, r) in [(left, right), (left_2, right_2)] {
            assert!(matches!(pool.identical(l, r), Identity::Numerical { .. }));
            assert!(rational_identity(&mut pool, l, r));
        }
    }
}
