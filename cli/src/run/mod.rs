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

pub use output::Table;
pub use plan::DEFAULT_TOLERANCE;

/// What a run computed, for a library caller (the Python package): what [`run`] prints and
/// writes, as values.
pub struct Completed {
    /// The recorded quantities at every output time (the start included).
    pub table: Table,
    /// The time and state `[q, p, m_s]` where the run ended.
    pub end: (f64, Vec<f64>),
    /// The index of the `stop_when` condition that ended the run, if one did.
    pub stopped_by: Option<usize>,
    /// The stepper's work.
    pub statistics: varmass::core::Statistics,
    /// The summary the tool prints.
    pub summary: String,
}

/// [`run`] on a model already derived, with the parameter values given as numbers
/// (`args.set` is not read) and nothing written to files: the same plan, stepper and
/// recording, so a library caller gets exactly the tool's run and messages.
pub fn run_derived(
    derivation: varmass::symbolic::mechanics::Derivation,
    parameters: &[(&str, f64)],
    args: &RunArgs,
) -> Result<Completed, CliError> {
    let program =
        Program::new(derivation, parameters).map_err(|e| CliError::Input(e.to_string()))?;
    let plan = plan::plan(args, &program)?;
    let outcome = dispatch::dispatch(program, &plan)?;
    let program = &outcome.program;
    let table = output::table(program, &plan.record, &outcome.points)?;
    let end = outcome
        .points
        .last()
        .cloned()
        .ok_or_else(|| CliError::Run("the run returned no point".to_string()))?;
    let stopped_by = outcome
        .stopped_by
        .and_then(|index| args.stop_when.get(index))
        .map(|c| format!("'{c}'"));
    let summary = output::summary(
        program,
        end.0,
        &end.1,
        stopped_by.as_deref(),
        &outcome.statistics,
    );
    Ok(Completed {
        table,
        end,
        stopped_by: outcome.stopped_by,
        statistics: outcome.statistics,
        summary,
    })
}
