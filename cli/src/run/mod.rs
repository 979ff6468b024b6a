//! `varmass run`: integrate a model file from an initial state with one of the core's
//! steppers, print the final state and the run's work, and record, write and plot the
//! quantities asked for.

mod dispatch;
mod integrate;
mod names;
mod output;
mod plan;
mod plot;
mod watch;

use varmass::interpret::Program;

use crate::args::RunArgs;
use crate::error::CliError;
use crate::model::load;

/// Runs the model as `args` say; returns the summary to print.
pub fn run(args: &RunArgs) -> Result<String, CliError> {
    let model = load(&args.model)?;
    let values = plan::parameters(args)?;
    let borrowed: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let program =
        Program::new(model.derivation, &borrowed).map_err(|e| CliError::Input(e.to_string()))?;
    let plan = plan::plan(args, &program)?;
    let outcome = dispatch::dispatch(program, &plan)?;
    let program = &outcome.program;
    let table = output::table(program, &plan.record, &outcome.points)?;
    if let Some(path) = &args.csv {
        output::write_csv(&table, path)?;
    }
    if let Some(failure) = outcome.failure {
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
