//! `--table NAME=FILE`: the data of a table of the model read from a file at run time
//! (docs/tables.md#runtime-tables). A `table F(t) = runtime` statement needs one (a run
//! without it is refused, naming the table); for a file table it replaces the statement's
//! file. Either way the statement's options (interpolation, `outside`) hold, and the
//! extension chooses the reader (`.eng` RASP, `.csv` CSV). The path is the command line's:
//! relative to the current directory, not to the model file. Every mistake is a
//! [`CliError::Input`] (exit 2): a malformed option, a name that is no table, a table given
//! twice, a file that cannot be read or does not parse (with its line and column).

use std::path::{Path, PathBuf};

use varmass::symbolic::mechanics::read_points;
use varmass::symbolic::parse::ast::TableDecl;
use varmass::symbolic::parse::{Span, Spanned};

use super::names::resolve;
use crate::error::CliError;
use crate::model::LoadedModel;

/// `model` with the tables `options` (the `--table` values) read from their files and the
/// model derived again; without `--table` the model as it is.
pub fn apply(model: LoadedModel, options: &[String]) -> Result<LoadedModel, CliError> {
    if options.is_empty() {
        return Ok(model);
    }
    let files = files(options, &model)?;
    model.with_tables(&files)
}

/// Each option's (table, absolute path), every file read and parsed once here so that a
/// bad one is the tool's input error with its line.
fn files(options: &[String], model: &LoadedModel) -> Result<Vec<(String, PathBuf)>, CliError> {
    let known: Vec<(String, usize)> = model
        .derivation
        .tables
        .iter()
        .enumerate()
        .map(|(k, t)| (t.name.clone(), k))
        .collect();
    let here = std::env::current_dir().unwrap_or_default();
    let mut files: Vec<(String, PathBuf)> = Vec::new();
    for option in options {
        let Some((name, file)) = option.split_once('=') else {
            return Err(CliError::Input(format!(
                "--table `{option}`: expected NAME=FILE (a .eng or .csv file)"
            )));
        };
        let (name, file) = (name.trim().to_string(), file.trim());
        if known.is_empty() {
            return Err(CliError::Input(format!(
                "--table {name}: the model declares no table"
            )));
        }
        let k = resolve(&name, &known, "a table")?;
        if files.iter().any(|(given, _)| *given == name) {
            return Err(CliError::Input(format!("--table {name} is given twice")));
        }
        let path = here.join(file);
        check_file(&model.derivation.tables[k], file, &here)?;
        files.push((name, path));
    }
    Ok(files)
}

/// Reads and parses `file` as the table `table`'s statement would (the same reader).
fn check_file(
    table: &varmass::symbolic::mechanics::ModelTable,
    file: &str,
    here: &Path,
) -> Result<(), CliError> {
    let span = Span::default();
    let decl = TableDecl {
        name: Spanned::new(table.name.clone(), span),
        parameter: Spanned::new(String::new(), span),
        file: Spanned::new(file.to_string(), span),
        runtime: false,
        interpolation: table.interpolation,
        outside: table.outside,
    };
    read_points(&decl, here)
        .map(|_| ())
        .map_err(|d| CliError::Input(format!("--table {}: {}", table.name, d.message)))
}
