//! `varmass run`: integrate a model file from an initial state with one of the core's
//! steppers, print the final state and the run's work, and record, write and plot the
//! quantities asked for.

pub(crate) mod dispatch;
#[cfg(test)]
mod fuzz;
pub(crate) mod inputs;
pub(crate) mod integrate;
pub(crate) mod names;
pub(crate) mod output;
pub(crate) mod plan;
pub(crate) mod plot;
pub(crate) mod record;
pub(crate) mod watch;

use varmass::interpret::{Program, ProgramError};
use varmass::symbolic::parse::ast::SystemAst;

use crate::args::RunArgs;
use crate::error::CliError;
use crate::model::{load, tag_with_parameter, LoadedModel};

/// Runs the model as `args` say; returns the summary to print.
pub fn run(args: &RunArgs) -> Result<String, CliError> {
    let model = load(&args.model)?;
    for warning in &model.warnings {
        eprintln!("warning: {warning}");
    }
    let (program, plan) = prepare(args, model, |warning| eprintln!("warning: {warning}"))?;
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
    // Each input's law from `--input`, put in place of its calls (docs/inputs.md).
    let model = if model.derivation.inputs.is_empty() && args.input.is_empty() {
        model
    } else {
        let laws = inputs::laws(&args.input, &model.derivation.inputs)?;
        model.with_laws(&laws)?
    };
    let values = plan::parameters(args)?;
    for warning in plan::unused_parameters(&model.derivation, &values) {
        warn(&warning);
    }
    let (ast, with) = (&model.ast, &model.with);
    let tag_hint = |e: ProgramError| match &e {
        ProgramError::UnknownParameter { name, .. } => {
            match tag_with_parameter(ast, with, name, &model.base) {
                Some(tag) => CliError::Input(format!(
                    "`{name}` is a parameter of the statements tagged `[{tag}]`, which this run \
                 leaves out; add `--with {tag}` to include them"
                )),
                None => CliError::Input(e.to_string()),
            }
        }
        ProgramError::MissingParameters { missing, .. } => {
            let give: Vec<String> = missing.iter().map(|m| format!("--set {m}=VALUE")).collect();
            CliError::Input(format!("{e}; give {}", give.join(" ")))
        }
        _ => CliError::Input(e.to_string()),
    };
    let borrowed: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let program = Program::new(model.derivation, &borrowed).map_err(tag_hint)?;
    Ok(Prepared {
        program,
        flows: model.flows,
        selected: model.selected,
    })
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

/// [`run`] on a model already loaded, with the parameter values given as numbers (they
/// replace `args.set`, written back exactly with `{:?}`) and nothing written to files: the
/// same checks, plan, stepper and recording, so a library caller gets exactly the tool's run
/// and messages. A run that fails returns its error; the points up to it are in
/// [`Failed::table`].
pub fn run_derived(
    model: LoadedModel,
    parameters: &[(&str, f64)],
    args: &RunArgs,
) -> Result<Completed, Failed> {
    let mut args = args.clone();
    args.set = parameters
        .iter()
        .map(|(name, value)| format!("{name}={value:?}"))
        .collect();
    let (program, plan) = prepare(&args, model, |_| {}).map_err(Failed::before)?;
    let outcome = dispatch::dispatch(program, &plan).map_err(Failed::before)?;
    let program = &outcome.program;
    let table = output::table(program, &plan.record, &outcome.points).map_err(Failed::before)?;
    if let Some(error) = outcome.failure {
        let table = Some(table);
        return Err(Failed { error, table });
    }
    let end =
        outcome.points.last().cloned().ok_or_else(|| {
            Failed::before(CliError::Run("the run returned no point".to_string()))
        })?;
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

/// A run of [`run_derived`] that failed: the error, and the points recorded up to the
/// failure when the run got as far as stepping.
pub struct Failed {
    /// What went wrong, with the tool's message.
    pub error: CliError,
    /// The recorded quantities up to the failure (`None` when it failed before the first
    /// step).
    pub table: Option<Table>,
}

impl Failed {
    /// A failure before any point was computed.
    fn before(error: CliError) -> Self {
        Self { error, table: None }
    }
}
