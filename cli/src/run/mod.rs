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
pub(crate) mod names;
pub(crate) mod output;
pub(crate) mod plan;
pub(crate) mod plot;
pub(crate) mod record;
pub(crate) mod tables;
pub(crate) mod watch;

use std::path::Path;

use varmass::interpret::{Program, ProgramError};
use varmass::symbolic::parse::ast::SystemAst;

use crate::args::{RunArgs, Words};
use crate::error::CliError;
use crate::model::{load, tag_with_parameter, LoadedModel};

pub use compiled::{Compiled, Completed, Failed};

/// Runs the model as `args` say; returns the summary to print.
pub fn run(args: &RunArgs) -> Result<String, CliError> {
    let model = load(&args.model)?;
    for warning in &model.warnings {
        eprintln!("warning: {warning}");
    }
    let values = plan::parameters(args)?;
    let warn = |warning: &str| eprintln!("warning: {warning}");
    Compiled::new(model).execute(args, true, values, warn, |outcome, plan| {
        finish(args, outcome, plan)
    })?
}

/// What `run` does with a run's outcome: the CSV, the plot and the summary.
fn finish(
    args: &RunArgs,
    outcome: &mut integrate::Outcome,
    plan: &plan::Plan,
) -> Result<String, CliError> {
    let program = &outcome.program;
    let (table, failure) = match output::table(program, &plan.record, outcome.points.iter()) {
        Ok(table) => (table, outcome.failure.take()),
        Err(partial) => {
            let (table, error) = partial.with_run_failure(outcome.failure.take());
            (table, Some(error))
        }
    };
    if let Some(path) = &args.csv {
        output::write_csv(&table, path)?;
    }
    if let Some(failure) = failure {
        // The CSV holds the points up to the failure; the error is what the run reports.
        return Err(failure);
    }
    if let Some(path) = &args.plot {
        let title = args.model.file.display().to_string();
        plot::plot(&table, &title, path)?;
    }
    let (time, state) = outcome
        .points
        .last()
        .ok_or_else(|| CliError::Run("the run returned no point".to_string()))?;
    let stopped_by = outcome
        .stopped_by
        .and_then(|index| args.stop_when.get(index));
    Ok(output::summary(
        program,
        time,
        state,
        stopped_by.map(String::as_str),
        &outcome.statistics,
    ))
}

/// Everything before the first step: the program (see [`program`]) and the checked plan.
/// Every mistake in the arguments is found here, before any work, as a
/// [`CliError::Input`].
pub fn prepare(
    args: &RunArgs,
    model: LoadedModel,
    warn: impl FnMut(&str),
) -> Result<(Program, plan::Plan), CliError> {
    let prepared = program(args, model, warn)?;
    let mut plan = plan::plan(args, &prepared.program, &prepared.selected)?;
    plan.flows = prepared.flows;
    Ok((prepared.program, plan))
}

/// A model's program with the run's parameter values, and what the plan needs of its
/// statements.
pub struct Prepared {
    /// The program.
    pub program: Program,
    /// The flows' names, in the derivation's order.
    pub flows: Vec<String>,
    /// The statements selected by the tags.
    pub selected: SystemAst,
}

/// The program of `model` with the `--set` values of `args` (`warn` is told of those that
/// enter nothing); a parameter of a tag not asked for names the tag.
pub fn program(
    args: &RunArgs,
    model: LoadedModel,
    mut warn: impl FnMut(&str),
) -> Result<Prepared, CliError> {
    // Each table's data from `--table` (docs/tables.md#runtime-tables), then each input's
    // law from `--input`, put in place of its calls (docs/inputs.md).
    let model = tables::apply(model, &args.table)?;
    let model = inputs::apply(model, &args.input)?;
    let values = plan::parameters(args)?;
    for warning in plan::unused_parameters(&model.derivation, &values) {
        warn(&warning);
    }
    let borrowed: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let program = Program::new(model.derivation, &borrowed)
        .map_err(|e| program_error(&model.ast, &model.with, &model.base, args.words, e))?;
    Ok(Prepared {
        program,
        flows: model.flows,
        selected: model.selected,
    })
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
                Some(tag) => {
                    let add = match words {
                        Words::Flags => format!("`--with {tag}`"),
                        Words::Scene => format!("\"{tag}\" to `with`"),
                    };
                    CliError::Input(format!(
                        "`{name}` is a parameter of the statements tagged `[{tag}]`, which \
                         this run leaves out; add {add} to include them"
                    ))
                }
                None => CliError::Input(e.to_string()),
            }
        }
        ProgramError::MissingParameters { missing, .. } => {
            let give: Vec<String> = missing.iter().map(|m| words.give_parameter(m)).collect();
            let join = match words {
                Words::Flags => " ",
                Words::Scene => ", ",
            };
            CliError::Input(format!("{e}; give {}", give.join(join)))
        }
        _ => CliError::Input(e.to_string()),
    }
}

pub use output::{Summary, Table};
pub use plan::DEFAULT_TOLERANCE;
