//! Tables of t (docs/tables.md#knots-are-switches): the table calls whose argument is affine
//! in t, a·t + b with a and b made of parameters only. Their knots are where the state rate
//! is not smooth in t, at t = (knot − b)/a: the stop times the runs land on (generated
//! code's `next_stop_time`, the interpreter's too).

use super::Derivation;
use crate::expr::{Func, Id, Node, SymbolKind};

/// A table of t: the table and the slope a and offset b of its argument a·t + b.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimeTable {
    /// The table's index in the pool.
    pub table: u16,
    /// a, made of parameters.
    pub slope: Id,
    /// b, made of parameters.
    pub offset: Id,
}

/// The tables of t among the calls reachable from `roots`, each (table, argument) once.
pub fn time_tables(d: &mut Derivation, roots: &[Id]) -> Vec<TimeTable> {
    let mut calls: Vec<(u16, Id)> = Vec::new();
    for id in d.pool.reachable(roots, true) {
        if let Node::Call(Func::Table { table, .. }, args) = d.pool.node(id) {
            if let [argument] = args.as_ref() {
                if !calls.contains(&(*table, *argument)) {
                    calls.push((*table, *argument));
                }
            }
        }
    }
    let t = d.pool.sym(d.time);
    let mut found = Vec::new();
    for (table, argument) in calls {
        let slope = d.pool.diff(argument, d.time);
        let moved = d.pool.mul(&[slope, t]);
        let offset = d.pool.sub(argument, moved);
        let only_parameters = |d: &Derivation, e: Id| {
            d.pool
                .free_symbols(e)
                .into_iter()
                .all(|s| d.pool.symbols().kind(s) == SymbolKind::Parameter)
        };
        if !d.pool.is_zero(slope) && only_parameters(d, slope) && only_parameters(d, offset) {
            found.push(TimeTable {
                table,
                slope,
                offset,
            });
        }
    }
    found
}
