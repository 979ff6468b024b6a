//! `varmass run`: integrate a model file from an initial state with one of the core's
//! steppers, print the final state and the run's work, and record, write and plot the
//! quantities asked for.

pub(crate) mod compiled;
pub(crate) mod dispatch;
#[cfg(test)]
mod fuzz;
pub(crate) mod input_tables;
pub(crate) mod inputs;
pub(crate) mod integrate;
pub mod names;
pub mod output;
pub mod plan;
pub(crate) mod plot;
pub(crate) mod record;
pub(crate) mod sensitivity;
pub(crate) mod tables;
pub(crate) mod watch;

use std::path::Path;

use varmass::interpret::ProgramError;
use varmass::symbolic::parse::ast::SystemAst;

use crate::args::{RunArgs, Words};
use crate::error::CliError;
use crate::model::{load, tag_with_parameter};

pub use compiled::{Compiled, Completed, Failed};
pub use record::column_name;

/// Runs the model as `args` say ([`Compiled::execute`]); writes the CSV (up to the failure,
/// if the run failed) and the plot; returns the summary to print.
pub fn run(args: &RunArgs) -> Result<String, CliError> {
    if args.summary_json.is_some() {
        return Err(CliError::Input(
            "--summary-json writes a flight summary: it goes with a scene file `SCENE.toml` \
             that has a `[flight]` table (docs/scenes.md#flight)"
                .to_string(),
        ));
    }
    let model = load(&args.model)?;
    for warning in &model.warnings {
        eprintln!("warning: {warning}");
    }
    let values = plan::parameters(args)?;
    let warn = |warning: &str| eprintln!("warning: {warning}");
    let done = Compiled::new(model).execute(args, true, values, warn);
    let table = match &done {
        Ok(completed) => Some(&completed.table),
        Err(failed) => failed.table.as_ref(),
    };
    if let (Some(path), Some(table)) = (&args.csv, table) {
        output::write_csv(table, path)?;
    }
    // The CSV holds the points up to a failure; the error is what the run reports.
    let completed = done.map_err(|failed| failed.error)?;
    if let Some(path) = &args.plot {
        let title = args.model.file.display().to_string();
        plot::plot(&completed.table, &title, path)?;
    }
    Ok(completed.summary.to_string())
}

/// A value list that does not fit `model`, as the tool says it: an unknown name that a tag
/// left out would make a parameter names the tag; missing values name the flags (or the
/// scene file's keys, as `words` says) to give.
fn program_error(
    ast: &SystemAst,
    with: &[String],
    base: &Path,
    words: Words,
    e: ProgramError,
) -> CliError {
    match &e {
        ProgramError::UnknownParameter { name, .. } => {
            match tag_with_parameter(ast, with, name, base) {
                Some(tag) => CliError::Input(format!(
                    "`{name}` is a parameter of the statements tagged `[{tag}]`, which this \
                     run leaves out; add {} to include them",
                    words.add_tag(&tag)
                )),
                None => CliError::Input(e.to_string()),
            }
        }
        ProgramError::MissingParameters { missing, .. } => {
            CliError::Input(format!("{e}; give {}", words.give_parameters(missing)))
        }
        _ => CliError::Input(e.to_string()),
    }
}

pub use output::{Summary, Table};
pub use plan::DEFAULT_TOLERANCE;
