//! `--input NAME=FILE.csv` (or `.eng`): an input given by a table of its first declared
//! argument (docs/tables.md#runtime-tables), through the same path as `--table`: the model
//! gains a statement `table NAME_table(ARG) = "FILE"` (linear, `outside error`; the unit of
//! `NAME`, if the model gives one) and the option becomes the law `NAME=NAME_table(ARG)`,
//! which `--input` then puts in place of the input's calls. The path is relative to the
//! current directory; a file that cannot be read or does not parse is exit 2 with its line.

use std::path::PathBuf;

use varmass::core::table::{Interpolation, Outside};
use varmass::symbolic::mechanics::read_points;
use varmass::symbolic::parse::ast::{Statement, StatementKind, SystemAst, TableDecl};
use varmass::symbolic::parse::{Span, Spanned};

use crate::error::CliError;
use crate::model::LoadedModel;

/// `model` with a table statement for each `--input` given by a file, and the options with
/// those replaced by their laws (the others as given). Nothing changes without one.
pub fn apply(
    mut model: LoadedModel,
    options: &[String],
) -> Result<(LoadedModel, Vec<String>), CliError> {
    let mut laws = Vec::with_capacity(options.len());
    for option in options {
        let Some((name, file)) = option.split_once('=').map(|(n, f)| (n.trim(), f.trim())) else {
            laws.push(option.clone());
            continue;
        };
        if !is_table_file(file) {
            laws.push(option.clone());
            continue;
        }
        let Some(input) = model.derivation.inputs.iter().find(|i| i.name == name) else {
            // Not an input: `--input`'s own checks say so.
            laws.push(option.clone());
            continue;
        };
        let Some(argument) = input.arguments.first().cloned() else {
            laws.push(option.clone());
            continue;
        };
        let table = free_name(&model, &format!("{name}_table"));
        let decl = table_decl(name, &table, &argument, file)?;
        for ast in [&mut model.ast, &mut model.selected] {
            add_table(ast, decl.clone(), name);
        }
        laws.push(format!("{name}={table}({argument})"));
    }
    Ok((model, laws))
}

/// Whether an `--input` value names a table file rather than an expression.
pub(crate) fn is_table_file(value: &str) -> bool {
    let lower = value.to_ascii_lowercase();
    lower.ends_with(".csv") || lower.ends_with(".eng")
}

/// `wanted`, or with `_` appended until no name of the model is spelt so.
fn free_name(model: &LoadedModel, wanted: &str) -> String {
    let d = &model.derivation;
    let taken = |name: &str| {
        d.tables.iter().any(|t| t.name == name)
            || d.inputs.iter().any(|i| i.name == name)
            || d.parameters.iter().any(|(p, _)| p == name)
            || d.coordinates.iter().any(|c| c.name == name)
            || d.masses.iter().any(|m| m.name == name)
            || model
                .ast
                .statements
                .iter()
                .any(|s| is_let_of(&s.kind, name))
    };
    let mut name = wanted.to_string();
    while taken(&name) {
        name.push('_');
    }
    name
}

/// Whether `kind` is `let NAME = …` (a name the derivation inlines and no longer lists).
fn is_let_of(kind: &StatementKind, name: &str) -> bool {
    matches!(kind, StatementKind::Let { name: n, .. } if n.node == name)
}

/// The statement `table TABLE(ARGUMENT) = "FILE"` for input `input` with the file's absolute path, the file
/// read once here so that a bad one is the tool's input error with its line.
fn table_decl(input: &str, table: &str, argument: &str, file: &str) -> Result<TableDecl, CliError> {
    let span = Span::default();
    let here = std::env::current_dir().unwrap_or_default();
    let path: PathBuf = here.join(file);
    let mut decl = TableDecl {
        name: Spanned::new(table.to_string(), span),
        parameter: Spanned::new(argument.trim_end_matches('\'').to_string(), span),
        file: Spanned::new(file.to_string(), span),
        runtime: false,
        interpolation: Interpolation::Linear,
        outside: Outside::Error,
    };
    read_points(&decl, &here)
        .map_err(|d| CliError::Input(format!("--input {input}: {}", d.message)))?;
    decl.file.node = path.to_string_lossy().into_owned();
    Ok(decl)
}

/// Puts `decl` first in `ast` (a table is declared before its calls), with the unit of the
/// input `input` if a `units` statement gives one.
fn add_table(ast: &mut SystemAst, decl: TableDecl, input: &str) {
    for statement in &mut ast.statements {
        if let StatementKind::Units(units) = &mut statement.kind {
            if let Some(unit) = units.iter().find(|u| u.name.node == input).cloned() {
                let mut unit = unit;
                unit.name.node = decl.name.node.clone();
                units.push(unit);
            }
        }
    }
    let statement = Statement {
        kind: StatementKind::Table(decl),
        span: Span::default(),
        tags: Vec::new(),
    };
    ast.statements.insert(0, statement);
}
