//! Non-smooth points: a mass law that can jump is refused (a jump in a mass is a phase
//! change, docs/mechanics.md#jumps-and-phases), and the switching functions of what a
//! derivation emits are collected so that a run can land on each crossing.
//!
//! A switching function g(t, q, q̇, m_s) is an expression whose sign change is a jump or a
//! kink of the state rate: the argument of `sign` (a jump) and of `abs` (a kink), and the
//! gap a − b between the two sides of `min(a, b)` and `max(a, b)` (a kink).

use super::derivation::Derivation;
use super::stops::{affine_in_time, table_calls};
use crate::expr::{ExprPool, Func, Id, Node, SymbolKind};
use crate::parse::ast::{Expr, ExprNode};
use crate::parse::{Diagnostic, Span};

/// The functions whose value jumps where their argument changes sign: a law containing one
/// makes its mass jump. `abs`, `min` and `max` only kink, which a law may do.
const JUMPING: [Func; 1] = [Func::Sign];

/// A diagnostic if the lowered law `law` of mass `name` can jump: at the `sign` written in
/// `written` when there is one, else (a jump reached through a `let`) at `span`, the law.
pub(crate) fn jump_in_law(
    pool: &ExprPool,
    law: Id,
    written: &ExprNode,
    span: Span,
    name: &str,
) -> Option<Diagnostic> {
    let jumps = pool
        .reachable(&[law], true)
        .into_iter()
        .find_map(|id| match pool.node(id) {
            Node::Call(f, _) if JUMPING.contains(f) => Some(*f),
            _ => None,
        })?;
    let at = written_call(written, jumps).unwrap_or(span);
    let message = format!(
        "the law of `{name}` can jump (it contains `{}`): a mass that changes at an instant is a change of phase, not a term of its law",
        jumps.name()
    );
    let help = "run the scene in phases (docs/scenes.md): at the event, set the new mass; the velocity carries over (the separated mass leaves with the body), the momentum does not; a kink (`abs`, `min`, `max`) is allowed";
    Some(Diagnostic::new(at, message).with_help(help))
}

/// The span of the first call of `func` written in `node` (the name only), searched
/// without recursion.
fn written_call(node: &ExprNode, func: Func) -> Option<Span> {
    let mut stack: Vec<&ExprNode> = vec![node];
    while let Some(node) = stack.pop() {
        match &*node.node {
            Expr::Call { func: name, args } => {
                if name.node == func.name() {
                    return Some(name.span);
                }
                stack.extend(args.iter().rev());
            }
            Expr::Neg(inner) => stack.push(inner),
            Expr::Binary { lhs, rhs, .. } => {
                stack.push(rhs);
                stack.push(lhs);
            }
            Expr::Number(_) | Expr::Name(_) | Expr::Derivative { .. } => {}
        }
    }
    None
}

/// The switching functions of what a derivation emits, each once (g and −g are one
/// switch): every non-smooth call reachable from the state rate — ṗ, M and the momentum
/// offset b (which give q̇), the mass rates and the closed mass laws — in velocity form with
/// frozen mass symbols, as the emitted methods are. A switch on parameters alone never
/// crosses and is left out.
pub fn switching_functions(d: &mut Derivation) -> Vec<Id> {
    let roots = state_rate_roots(d);
    let calls: Vec<(Func, Vec<Id>)> = d
        .pool
        .reachable(&roots, true)
        .into_iter()
        .filter_map(|id| match d.pool.node(id) {
            Node::Call(f @ (Func::Sign | Func::Abs | Func::Min | Func::Max), args) => {
                Some((*f, args.to_vec()))
            }
            _ => None,
        })
        .collect();
    let mut switches: Vec<Id> = Vec::new();
    for (f, args) in calls {
        let g = match (f, args.as_slice()) {
            (Func::Min | Func::Max, [a, b]) => d.pool.sub(*a, *b),
            (_, [u]) => *u,
            _ => continue,
        };
        let negated = d.pool.neg(g);
        let moves = d
            .pool
            .free_symbols(g)
            .into_iter()
            .any(|s| d.pool.symbols().kind(s) != SymbolKind::Parameter);
        if moves && !switches.contains(&g) && !switches.contains(&negated) {
            switches.push(g);
        }
    }
    switches
}

/// What the state rate's switching functions are computed from: ṗ, M and the momentum
/// offset b (which give q̇), the mass rates and the closed mass laws.
fn state_rate_roots(d: &Derivation) -> Vec<Id> {
    let mut roots: Vec<Id> = d.momentum_rate.clone();
    roots.extend(d.mass_matrix.iter().flatten());
    roots.extend(&d.momentum_offset);
    roots.extend(&d.mass_rates);
    roots.extend(d.closed_laws.iter().flatten());
    roots
}

/// A switch at the knots of a table of the state (docs/tables.md#knots-are-switches):
/// g = the distance from `argument` to the nearer end of the knot bracket the run was
/// anchored in (`varmass_core::table::knot_gap_read`), one switch per call however many knots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableSwitch {
    /// The table's index in the pool.
    pub table: u16,
    /// The highest derivative order the equations read of it at this argument: the edges
    /// at its ends are those of the first order read that jumps there.
    pub order: u8,
    /// The call's argument, in velocity form.
    pub argument: Id,
}

/// The table calls reachable from the state rate (as [`switching_functions`]) whose
/// argument moves and is not a·t + b with parameters a and b (those are tables of t, whose
/// knots are stop times): each (table, argument) once, whatever the derivative order.
pub fn table_switches(d: &mut Derivation) -> Vec<TableSwitch> {
    let roots = state_rate_roots(d);
    let mut found = Vec::new();
    for (table, argument, order) in table_calls(d, &roots) {
        let moves = d
            .pool
            .free_symbols(argument)
            .into_iter()
            .any(|s| d.pool.symbols().kind(s) != SymbolKind::Parameter);
        if moves && affine_in_time(d, argument).is_none() {
            found.push(TableSwitch {
                table,
                order,
                argument,
            });
        }
    }
    found
}
