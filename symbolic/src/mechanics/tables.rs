//! `table` statements (docs/tables.md#statements): each file read relative to the model's
//! directory with `varmass-table` (`.eng` RASP, `.csv` CSV), the interpolant built, and the
//! table registered in the pool under its name, so that calls lower to
//! `Call(Func::Table { .. })`. A missing or malformed file is a diagnostic at the file's
//! name, with the file's line and column.

use std::path::{Path, PathBuf};

use super::build::Builder;
use super::derivation::Derivation;
use super::resolve::Binding;
use crate::expr::{Func, Node};
use crate::parse::ast::TableDecl;
use crate::parse::{Diagnostic, Span};
use varmass_table::{CsvTable, Interpolation, Motor, Outside, Piecewise, Points, Table};

/// A table of the model.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelTable {
    /// Its name, called as a function.
    pub name: String,
    /// The file as written in the statement.
    pub file: String,
    /// The file as read (the model's directory joined with `file`).
    pub path: PathBuf,
    /// The interpolation.
    pub interpolation: Interpolation,
    /// What it is worth outside its data.
    pub outside: Outside,
    /// Its index in the pool ([`crate::expr::ExprPool::table`]).
    pub index: u16,
    /// Where the statement names the file (or says `runtime`).
    pub span: Span,
    /// `= runtime`: the data come from the struct's field or the tool's `--table`; the pool
    /// holds a placeholder ([`runtime_placeholder`]) and `path` is empty.
    pub runtime: bool,
}

/// The data a `= runtime` table's placeholder interpolates, where the derivation evaluates
/// the table (its checks at random points, which extrapolate the pieces): any points do,
/// since the checks test algebra; these have pieces of every slope sign.
pub fn runtime_placeholder(interpolation: Interpolation, outside: Outside) -> Table {
    match Points::new(vec![0.0, 1.0, 2.0, 3.0], vec![1.0, 2.0, 1.5, 3.0]) {
        Ok(points) => Table::new(&points, interpolation, outside),
        // Not reached (the points are valid); a line rather than a panic.
        Err(_) => {
            Table::from_piecewise(Piecewise::from_static(&[0.0, 1.0], &[1.0, 1.0], 1), outside)
        }
    }
}

/// The points of `decl`'s file, read relative to `base`, and the path read.
pub fn read_points(decl: &TableDecl, base: &Path) -> Result<(Points, PathBuf), Diagnostic> {
    let written = &decl.file.node;
    let path = base.join(written);
    let at = |message: String| Diagnostic::new(decl.file.span, message);
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default();
    if !matches!(extension, "eng" | "csv") {
        return Err(at(format!(
            "`{written}`: a table file is a RASP motor (`.eng`) or a CSV table (`.csv`)"
        )));
    }
    let text = std::fs::read_to_string(&path).map_err(|error| {
        at(format!("cannot read the table file `{written}`: {error}")).with_help(
            "table files are read relative to the model file (inline DSL: the crate's directory)",
        )
    })?;
    let points = match extension {
        // Read for the table's interpolation: data whose pchip or spline overflows are
        // refused at their line (varmass-table's `InterpolantNotFinite`).
        "eng" => Motor::parse_for(&text, decl.interpolation).map(|m| m.thrust),
        _ => CsvTable::parse_for(&text, decl.interpolation).map(|c| c.points),
    };
    let points =
        points.map_err(|e| at(format!("{written}:{}:{}: {}", e.line, e.column, e.kind)))?;
    Ok((points, path))
}

impl Builder {
    /// Reads the table of `decl` and binds its name.
    pub(super) fn declare_table(&mut self, decl: &TableDecl) {
        if !self.check_new_name(&decl.name.node, decl.name.span, "table") {
            return;
        }
        if decl.runtime {
            self.declare_runtime_table(decl);
            return;
        }
        let (points, path) = match read_points(decl, &self.base) {
            Ok(read) => read,
            Err(diagnostic) => {
                self.errors.push(diagnostic);
                // Still a table, so that its calls are not "unknown function" as well
                // (the index names no table: a call lowers to NaN, and the model fails).
                self.model
                    .names
                    .insert(decl.name.node.clone(), Binding::Table(u16::MAX));
                return;
            }
        };
        let table = Table::new(&points, decl.interpolation, decl.outside);
        let index = self.model.pool.add_table(&decl.name.node, table);
        self.bind_table(decl, index, path, false);
    }

    /// Binds the name of a `= runtime` table over a placeholder.
    fn declare_runtime_table(&mut self, decl: &TableDecl) {
        let placeholder = runtime_placeholder(decl.interpolation, decl.outside);
        let index = self
            .model
            .pool
            .add_runtime_table(&decl.name.node, placeholder);
        self.bind_table(decl, index, PathBuf::new(), true);
    }

    /// Binds the name of the table the pool registered at `index` (`None`: too many) and
    /// records it in the model.
    fn bind_table(&mut self, decl: &TableDecl, index: Option<u16>, path: PathBuf, runtime: bool) {
        let Some(index) = index else {
            self.errors
                .push(Diagnostic::new(decl.name.span, "too many tables"));
            return;
        };
        self.model
            .names
            .insert(decl.name.node.clone(), Binding::Table(index));
        self.model.tables.push(ModelTable {
            name: decl.name.node.clone(),
            file: decl.file.node.clone(),
            path,
            interpolation: decl.interpolation,
            outside: decl.outside,
            index,
            span: decl.file.span,
            runtime,
        });
    }
}

/// The highest derivative order of a table that the equations may use: its interpolant's
/// smoothness class plus one. A `linear` table (C⁰) has a slope that jumps at each knot,
/// which the knots' stop times and switches handle; its second derivative is an impulse at
/// each knot, which the piecewise derivative (≡ 0 between knots) silently drops — a bead on
/// a piecewise-linear track would keep p across a kink and lose half its kinetic energy at a
/// 0 → 1 change of slope. `pchip` is C¹ and the natural spline C².
fn highest_order(interpolation: Interpolation) -> u8 {
    match interpolation {
        Interpolation::Linear => 1,
        Interpolation::Pchip => 2,
        Interpolation::Spline => 3,
    }
}

/// A diagnostic at each table that the equations (not the Jacobian) differentiate beyond its
/// smoothness ([`highest_order`]): a table inside a position (its second derivative enters
/// ṗ) or in a law differentiated twice.
pub(crate) fn check_smooth_enough(d: &Derivation) -> Vec<Diagnostic> {
    if d.tables.is_empty() {
        return Vec::new();
    }
    let roots = super::inputs::equation_roots(d);
    let mut orders: Vec<(u16, u8)> = Vec::new();
    for id in d.pool.reachable(&roots, false) {
        if let Node::Call(Func::Table { table, order }, _) = d.pool.node(id) {
            match orders.iter_mut().find(|(t, _)| t == table) {
                Some((_, highest)) => *highest = (*highest).max(*order),
                None => orders.push((*table, *order)),
            }
        }
    }
    d.tables
        .iter()
        .filter_map(|table| {
            let (_, order) = orders.iter().find(|(t, _)| *t == table.index)?;
            (*order > highest_order(table.interpolation)).then(|| too_rough(table, *order))
        })
        .collect()
}

fn too_rough(table: &ModelTable, order: u8) -> Diagnostic {
    Diagnostic::new(
        table.span,
        format!(
            "the equations differentiate table `{}` {order} times (it is inside a position, or a \
             law differentiated twice), more than its interpolation is smooth: `{}` tables \
             have an impulse in derivative {} at each knot, which the equations would drop",
            table.name,
            match table.interpolation {
                Interpolation::Linear => "linear",
                Interpolation::Pchip => "pchip",
                Interpolation::Spline => "spline",
            },
            highest_order(table.interpolation) + 1
        ),
    )
    .with_help(
        "give the table `pchip` (C¹) or `spline` (C²) interpolation where a position uses it",
    )
}
