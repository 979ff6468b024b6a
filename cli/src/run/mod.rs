//! `varmass run`: integrate a model file from an initial state with one of the core's
//! steppers, print the final state and the run's work, and record, write and plot the
//! quantities asked for.

mod dispatch;
mod flows;
mod integrate;
mod names;
mod output;
mod plan;
mod plot;
mod record;
mod watch;

use varmass::interpret::{Program, ProgramError};

use crate::args::RunArgs;
use crate::error::CliError;
use crate::model::{load, tag_with_parameter};

/// Runs the model as `args` say; returns the summary to print.
pub fn run(args: &RunArgs) -> Result<String, CliError> {
    let model = load(&args.model)?;
    for warning in &model.warnings {
        eprintln!("warning: {warning}");
    }
    let values = plan::parameters(args)?;
    for warning in plan::unused_parameters(&model.derivation, &values) {
        eprintln!("warning: {warning}");
    }
    let (ast, with) = (&model.ast, &model.with);
    let borrowed: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let tag_hint = |e: ProgramError| match &e {
        ProgramError::UnknownParameter { name, .. } => match tag_with_parameter(&ast, with, name) {
            Some(tag) => CliError::Input(format!(
                "`{name}` is a parameter of the statements tagged `[{tag}]`, which this run \
                 leaves out; add `--with {tag}` to include them"
            )),
            None => CliError::Input(e.to_string()),
        },
        _ => CliError::Input(e.to_string()),
    };
    let program = Program::new(model.derivation, &borrowed).map_err(tag_hint)?;
    let mut plan = plan::plan(args, &program, &model.selected)?;
    plan.flows = model.flows;
    let outcome = dispatch::dispatch(program, &plan)?;
    let program = &outcome.program;
    let table = output::table(program, &plan.record, &outcome.points)?;
    if let Some(path) = &args.csv {
        output::write_csv(&table, path)?;
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
        .and_then(|index| args.stop_when.get(index))
        .map(|c| format!("'{c}'"));
    Ok(output::summary(
        program,
        *time,
        state,
        stopped_by.as_deref(),
        &outcome.statistics,
    ))
}
