//! Tables of t (docs/tables.md#knots-are-switches): the table calls whose argument is affine
//! in t, a·t + b with a and b made of parameters only. Their knots are where the state rate
//! is not smooth in t, at t = (knot − b)/a: the stop times the runs land on (generated
//! code's `next_stop_time`, the interpreter's too).

use super::Derivation;
use crate::expr::{Func, Id, Node, SymbolKind};

/// A table of t: the table, the highest derivative order the code reads of it at this
/// argument, and the slope a and offset b of its argument a·t + b.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimeTable {
    /// The table's index in the pool.
    pub table: u16,
    /// The highest derivative order read (0: the table itself; 1 in a mass law's rate):
    /// orders 0 to this one are where a knot may make the equations jump
    /// (docs/tables.md#knots-are-switches).
    pub order: u8,
    /// a, made of parameters.
    pub slope: Id,
    /// b, made of parameters.
    pub offset: Id,
}

/// The tables of t among the calls reachable from `roots`, each (table, argument) once.
pub fn time_tables(d: &mut Derivation, roots: &[Id]) -> Vec<TimeTable> {
    table_calls(d, roots)
        .into_iter()
        .filter_map(|(table, argument, order)| {
            let (slope, offset) = affine_in_time(d, argument)?;
            Some(TimeTable {
                table,
                order,
                slope,
                offset,
            })
        })
        .collect()
}

/// The table calls reachable from `roots`, each (table, argument) once whatever the
/// derivative order (the derivatives have the table's knots), with the highest order read.
pub(crate) fn table_calls(d: &Derivation, roots: &[Id]) -> Vec<(u16, Id, u8)> {
    let mut calls: Vec<(u16, Id, u8)> = Vec::new();
    for id in d.pool.reachable(roots, true) {
        if let Node::Call(Func::Table { table, order }, args) = d.pool.node(id) {
            if let [argument] = args.as_ref() {
                match calls.iter_mut().find(|c| (c.0, c.1) == (*table, *argument)) {
                    Some(call) => call.2 = call.2.max(*order),
                    None => calls.push((*table, *argument, *order)),
                }
            }
        }
    }
    calls
}

/// The slope a and offset b of `argument` = a·t + b when both are made of parameters and
/// a ≠ 0 (a table of t), else `None`.
pub(crate) fn affine_in_time(d: &mut Derivation, argument: Id) -> Option<(Id, Id)> {
    let t = d.pool.sym(d.time);
    let slope = d.pool.diff(argument, d.time);
    let moved = d.pool.mul(&[slope, t]);
    let offset = d.pool.sub(argument, moved);
    // A held input is a constant symbol too, but read from the state: not a parameter.
    let held = d.held();
    let only_parameters = |d: &Derivation, e: Id| {
        d.pool
            .free_symbols(e)
            .into_iter()
            .all(|s| d.pool.symbols().kind(s) == SymbolKind::Parameter && !held.contains(&s))
    };
    (!d.pool.is_zero(slope) && only_parameters(d, slope) && only_parameters(d, offset))
        .then_some((slope, offset))
}

/// What of the model forward sensitivities cannot follow yet, if anything
/// (docs/sensitivities.md): an input (a parameter its Rust function reads is invisible to
/// ∂f/∂θ) or a table of t whose knots move with a parameter (`F(t - t_ign)`: f jumps there
/// at a time that moves with θ). Generated code's `sensitivity_obstacle` and the
/// interpreter's both ask this. Switches and sampled inputs the runtime refuses by itself
/// (`switch_count`, the held values).
pub fn sensitivity_obstacle(d: &Derivation, time_tables: &[TimeTable]) -> Option<&'static str> {
    if !d.inputs.is_empty() {
        return Some("inputs (their Rust functions' parameters)");
    }
    let parameters: Vec<crate::expr::Symbol> = d.parameters.iter().map(|(_, s)| *s).collect();
    let moves = |e: Id| {
        let free = d.pool.free_symbols(e);
        parameters.iter().any(|p| free.contains(p))
    };
    let moving = time_tables
        .iter()
        .any(|t| moves(t.slope) || moves(t.offset));
    moving.then_some("a table of t whose knots move with a parameter")
}
