//! A model compiled once and run many times: the entry point of a library caller (the
//! Python package's `Model` and ensembles) and of the tool's own `run`, so both have one
//! semantics and the same messages.
//!
//! Deriving a model costs more than integrating a short run (the sled: about 160 µs of a
//! 260 µs run), and compiling its tapes costs as much again; neither depends on the
//! parameter values. A [`Compiled`] keeps the derived model, compiles its program at the
//! first run and, for every later run, only gives it the new values
//! ([`Program::set_parameters`]), which evaluates exactly as a program made anew.
//! It keeps the last run's plan too: a run with the same arguments and other values of the
//! same parameters only makes again what depends on the values ([`plan::refresh`]), not
//! the parsing and resolving of every argument.

use std::time::SystemTime;

use varmass::interpret::Program;
use varmass::symbolic::mechanics::Derivation;

use super::dispatch::dispatch;
use super::integrate::Outcome;
use super::output::{self, Summary, Table};
use super::plan::{self, Plan};
use crate::args::{RunArgs, Words};
use crate::error::CliError;
use crate::model::LoadedModel;

/// A run's `--input` and `--table` values, which the model is derived again for, with the
/// length and modification time of each file they name: a file rewritten between two runs
/// of one `Compiled` (a notebook writing another thrust curve to the same path) is read
/// again, as the tool, one run per process, always reads it.
#[derive(PartialEq)]
struct RunOptions {
    input: Vec<String>,
    table: Vec<String>,
    files: Vec<Option<(u64, SystemTime)>>,
}

impl RunOptions {
    fn new(input: &[String], table: &[String]) -> Self {
        let files = table
            .iter()
            .filter_map(|option| option.split_once('=').map(|(_, file)| file.trim()))
            .chain(
                input
                    .iter()
                    .filter_map(|option| option.split_once('=').map(|(_, law)| law.trim()))
                    .filter(|law| super::input_tables::is_table_file(law)),
            )
            .map(|file| {
                let metadata = std::fs::metadata(file).ok()?;
                Some((metadata.len(), metadata.modified().ok()?))
            })
            .collect();
        Self {
            input: input.to_vec(),
            table: table.to_vec(),
            files,
        }
    }
}

/// A derived model and its program, compiled at the first run and reused by the next.
pub struct Compiled {
    /// The model run: as loaded, or with the laws of the last run's `--input`s.
    model: LoadedModel,
    /// For a model that declares inputs or tables (each run's laws are put in its calls,
    /// each run's `--table` files in its tables): the model as loaded, kept once a run's
    /// laws or files made `model` differ from it (`None` while `model` is it: a run that
    /// gives none copies nothing), and the `--input`s and `--table`s the current `model`
    /// was derived with.
    declared: Option<(Option<LoadedModel>, Option<RunOptions>)>,
    /// The parameters the equations read, found once.
    used: Vec<String>,
    /// `None` before the first run, and after a run that failed before giving it back.
    program: Option<Program>,
    /// The last run's plan, with the arguments and the parameters' names it was made for.
    planned: Option<Planned>,
}

/// A plan, what it was made for (the arguments and the parameters' names) and the initial
/// `[q, q̇, m_s]` its arguments give.
struct Planned {
    made_for: (RunArgs, Vec<String>),
    plan: Plan,
    velocity_state: Vec<f64>,
}

impl Compiled {
    /// The model, not compiled yet (its program needs the first run's values).
    pub fn new(model: LoadedModel) -> Self {
        let used = model.derivation.used_parameters();
        let d = &model.derivation;
        let declared = (!d.inputs.is_empty() || !d.tables.is_empty()).then_some((None, None));
        Self {
            model,
            declared,
            used,
            program: None,
            planned: None,
        }
    }

    /// Reads the tables of `args.table` (`--table NAME=FILE`, docs/tables.md#runtime-tables)
    /// and puts the laws of `args.input` (`--input NAME=EXPR`) in the calls of the model's
    /// inputs (docs/inputs.md), deriving the model again when they, or the files they name,
    /// differ from the last run's; a missing law, a law for a model without inputs, a bad
    /// table file or name is the tool's input error, in the words of `args.words`.
    fn apply_laws(&mut self, args: &RunArgs) -> Result<(), CliError> {
        let (input, table) = (args.input.as_slice(), args.table.as_slice());
        let Some((declared, current)) = &mut self.declared else {
            // No inputs and no tables: nothing to do (no copy: an ensemble member passes
            // here), and any `--input` or `--table` is refused as `apply` would refuse it.
            if !table.is_empty() {
                super::tables::apply(self.model.clone(), table)?;
            }
            return match input.is_empty() {
                true => Ok(()),
                false => super::inputs::laws(input, &[], args.words).map(|_| ()),
            };
        };
        let options = RunOptions::new(input, table);
        if current.as_ref() == Some(&options) {
            return Ok(());
        }
        // The model as loaded, with no laws to put in and no files: nothing to derive again.
        let plain = input.is_empty() && table.is_empty() && self.model.derivation.inputs.is_empty();
        if declared.is_none() && plain {
            *current = Some(options);
            return Ok(());
        }
        let declared = declared.get_or_insert_with(|| self.model.clone());
        let tabled = super::tables::apply(declared.clone(), table)?;
        self.model = super::inputs::apply(tabled, input, args.words)?;
        *current = Some(options);
        self.used = self.model.derivation.used_parameters();
        self.program = None;
        self.planned = None;
        Ok(())
    }

    /// Derives the model again with or without its parameter Jacobian, as the run asks
    /// (`--sensitivity`, [`LoadedModel::with_sensitivities`]); a model with laws or tables
    /// has them put in again by `apply_laws`, which follows.
    fn match_sensitivities(&mut self, wanted: bool) -> Result<(), CliError> {
        if self.model.has_sensitivities() == wanted {
            return Ok(());
        }
        match &mut self.declared {
            Some((Some(declared), current)) => {
                *declared = declared.clone().with_sensitivities(wanted)?;
                *current = None;
            }
            Some((None, current)) => {
                self.model = self.model.clone().with_sensitivities(wanted)?;
                *current = None;
            }
            None => self.model = self.model.clone().with_sensitivities(wanted)?,
        }
        self.used = self.model.derivation.used_parameters();
        self.program = None;
        self.planned = None;
        Ok(())
    }

    /// The derived model.
    pub fn model(&self) -> &LoadedModel {
        &self.model
    }

    /// The program with the parameter values `values` (`warn` is told of those that enter
    /// nothing): compiled the first time, given the new values after. A value list that
    /// does not fit is the tool's [`CliError::Input`], naming a tag that would make an
    /// unknown name a parameter.
    fn program(
        &mut self,
        values: &[(String, f64)],
        words: Words,
        mut warn: impl FnMut(&str),
    ) -> Result<Program, CliError> {
        for warning in plan::unused_among(&self.model.derivation, &self.used, values) {
            warn(&warning);
        }
        // A parameter with a default in the model needs no `--set` (docs/components.md).
        let values = self.model.with_defaults(values);
        let borrowed: Vec<(&str, f64)> = values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let mut program = match self.program.take() {
            Some(program) => program,
            None => {
                let derivation = Derivation::clone(&self.model.derivation);
                Program::new(derivation, &borrowed).map_err(|e| self.refused(e, words))?
            }
        };
        let refilled = program.set_parameters(&borrowed);
        // Kept either way: a refused value list leaves the former values in place.
        if let Err(e) = refilled {
            self.program = Some(program);
            return Err(self.refused(e, words));
        }
        Ok(program)
    }

    /// A refused value list in the tool's words.
    fn refused(&self, e: varmass::interpret::ProgramError, words: Words) -> CliError {
        let m = &self.model;
        super::program_error(&m.ast, &m.with, &m.base, words, e)
    }

    /// The program of this model with the run's values and its checked plan: every
    /// mistake in the arguments found before any work, as the tool's
    /// [`CliError::Input`]. The plan stays here for the next run (see [`Compiled::plan`]);
    /// the program is the caller's until it gives it back.
    fn prepare(
        &mut self,
        args: &RunArgs,
        values: Vec<(String, f64)>,
        warn: impl FnMut(&str),
    ) -> Result<(Program, &mut Plan), CliError> {
        self.match_sensitivities(!args.sensitivity.is_empty() || args.rates)?;
        self.apply_laws(args)?;
        let program = self.program(&values, args.words, warn)?;
        match self.plan(args, values, &program) {
            Ok(planned) => Ok((program, &mut self.planned.insert(planned).plan)),
            Err(e) => {
                self.program = Some(program);
                Err(e)
            }
        }
    }

    /// `Compiled::prepare` for one use (a scene's first phase): the program and the plan.
    pub fn prepared(
        mut self,
        args: &RunArgs,
        values: Vec<(String, f64)>,
        warn: impl FnMut(&str),
    ) -> Result<(Program, Plan), CliError> {
        let (program, _) = self.prepare(args, values, warn)?;
        let planned = self.planned.take();
        let plan = planned.map(|p| p.plan);
        plan.map(|plan| (program, plan))
            .ok_or_else(|| CliError::Run("the run was not planned".to_string()))
    }

    /// The program alone, with the laws and tables of `args` and the values `values`, and
    /// its flows' names (a scene's later phase, whose plan is the first phase's).
    pub fn program_only(
        mut self,
        args: &RunArgs,
        values: &[(String, f64)],
    ) -> Result<(Program, Vec<String>), CliError> {
        self.apply_laws(args)?;
        let program = self.program(values, args.words, |_| {})?;
        let flows = program.derivation().flow_names.clone();
        Ok((program, flows))
    }

    /// Every check a run makes before its first step (`Compiled::prepare`), nothing
    /// integrated; the program is kept for the next run.
    pub fn check(&mut self, args: &RunArgs, values: Vec<(String, f64)>) -> Result<(), CliError> {
        let (mut program, plan) = self.prepare(args, values, |_| {})?;
        // The sensitivities' own checks (the method, recorded expressions), as `integrate`.
        let checked = match plan.differentiated() {
            true => super::sensitivity::prepare(&mut program, plan),
            false => Ok(()),
        };
        self.program = Some(program);
        checked
    }

    /// The program and plan ([`Compiled::prepare`]), then the integration in the
    /// monomorphized code for the model's sizes ([`dispatch`]), with a progress bar if
    /// `progress`: the outcome, not recorded yet, and its plan.
    fn integrate(
        &mut self,
        args: &RunArgs,
        progress: bool,
        values: Vec<(String, f64)>,
        warn: impl FnMut(&str),
    ) -> Result<(Outcome, &Plan), CliError> {
        let (mut program, plan) = self.prepare(args, values, warn)?;
        plan.progress = progress;
        if plan.differentiated() {
            super::sensitivity::prepare(&mut program, plan)?;
        }
        Ok((dispatch(program, plan)?, plan))
    }

    /// The one path from a model to a result, for `varmass run` and for the Python
    /// package's `Model.run`: the program, plan and integration
    /// (`Compiled::integrate`), then the recording and the summary (`finish`); the
    /// program is kept for the next run. A failed run gives the points recorded up to
    /// the failure with its error ([`Failed::table`]).
    pub fn execute(
        &mut self,
        args: &RunArgs,
        progress: bool,
        values: Vec<(String, f64)>,
        warn: impl FnMut(&str),
    ) -> Result<Completed, Failed> {
        let (mut outcome, plan) = self
            .integrate(args, progress, values, warn)
            .map_err(Failed::before)?;
        let done = finish(&mut outcome, plan, &args.stop_when);
        self.program = Some(outcome.program);
        done
    }

    /// The plan of a run with `args` and the parameter values `values`: the last run's
    /// refreshed with the values when it was made for the same arguments and parameter
    /// names ([`plan::refresh`] gives the same plan and the same refusals), else made anew;
    /// with what it is made for.
    fn plan(
        &mut self,
        args: &RunArgs,
        values: Vec<(String, f64)>,
        program: &Program,
    ) -> Result<Planned, CliError> {
        let reusable = self.planned.take().filter(|p| {
            let (made_args, names) = &p.made_for;
            p.plan.refreshable()
                && made_args == args
                && names.iter().eq(values.iter().map(|(n, _)| n))
        });
        if let Some(mut kept) = reusable {
            let refreshed =
                plan::refresh(&mut kept.plan, args, values, program, &kept.velocity_state);
            return match refreshed {
                Ok(()) => Ok(kept),
                Err(e) => {
                    // A refused refresh changes nothing in the plan: kept for the next values.
                    self.planned = Some(kept);
                    Err(e)
                }
            };
        }
        let names = values.iter().map(|(n, _)| n.clone()).collect();
        let plan = plan::plan_with(args, values, program, &self.model.selected)?;
        let velocity_state = plan::initial_velocities(args, program)?;
        Ok(Planned {
            made_for: (args.clone(), names),
            plan,
            velocity_state,
        })
    }

    /// The tool's `run` of this model with the parameter values given as numbers (`args.set`
    /// is not read) and nothing written to files: the same checks, plan, stepper, recording
    /// and messages ([`Compiled::execute`]). A run that fails returns its error; the points
    /// up to it are in [`Failed::table`].
    pub fn run(&mut self, parameters: &[(&str, f64)], args: &RunArgs) -> Result<Completed, Failed> {
        let values = typed(parameters).map_err(Failed::before)?;
        self.execute(args, false, values, |_| {})
    }

    /// [`Compiled::run`] for a caller that wants only where the run ended (an ensemble's
    /// member): the time and the recorded values at the last point, or the run's error;
    /// no summary is made (its text, the state's velocities among it, cost a member more
    /// than the rest of the recording).
    pub fn run_to_end(
        &mut self,
        parameters: &[(&str, f64)],
        args: &RunArgs,
    ) -> Result<(f64, Vec<f64>), CliError> {
        let values = typed(parameters)?;
        let (mut outcome, plan) = self.integrate(args, false, values, |_| {})?;
        // A member wants the end: rows before an unrecordable point are of no use.
        let table = recorded(&mut outcome, plan);
        self.program = Some(outcome.program);
        let no_point = || CliError::Run("the run returned no point".to_string());
        table
            .map_err(|failed| failed.error)?
            .last()
            .ok_or_else(no_point)
    }
}

/// `parameters` as owned pairs; a name given twice is refused as the tool refuses
/// `--set g=1 --set g=2` (the second value would silently win).
fn typed(parameters: &[(&str, f64)]) -> Result<Vec<(String, f64)>, CliError> {
    let mut values: Vec<(String, f64)> = Vec::with_capacity(parameters.len());
    for (name, value) in parameters {
        if values.iter().any(|(n, _)| n == name) {
            return Err(CliError::Input(format!(
                "`{name}` is set twice; give each parameter once"
            )));
        }
        values.push((name.to_string(), *value));
    }
    Ok(values)
}

/// The one finisher of a run: its recorded table ([`recorded`]), where it ended, which
/// `--stop-when` condition of `stop_when` ended it, its work and its summary — what the
/// tool prints and writes, and what a library caller gets.
fn finish(outcome: &mut Outcome, plan: &Plan, stop_when: &[String]) -> Result<Completed, Failed> {
    let table = recorded(outcome, plan)?;
    let no_point = || Failed::before(CliError::Run("the run returned no point".to_string()));
    let (time, state) = outcome.points.last().ok_or_else(no_point)?;
    let stopped_by = outcome.stopped_by.and_then(|index| stop_when.get(index));
    let statistics = outcome.statistics;
    let summary = Summary::new(
        &outcome.program,
        time,
        state,
        stopped_by.map(String::as_str),
        &statistics,
    )
    .near_gimbal_lock(outcome.closest_singular_attitude);
    Ok(Completed {
        table,
        end: (time, state.to_vec()),
        stopped_by: outcome.stopped_by,
        statistics,
        summary,
    })
}

/// The table of `plan`'s recorded quantities at every point of `outcome`; a run that failed
/// (or a point that cannot be recorded) is its error, with the rows before it.
fn recorded(outcome: &mut Outcome, plan: &Plan) -> Result<Table, Failed> {
    let failed = |(table, error)| Failed {
        error,
        table: Some(table),
    };
    let table = output::table(&outcome.program, &plan.record, outcome.points.iter());
    let table = match !plan.differentiated() {
        true => table,
        false => table.map(|t| super::sensitivity::with_derivatives(t, plan, &outcome.derivatives)),
    };
    match table {
        Err(partial) => Err(failed(partial.with_run_failure(outcome.failure.take()))),
        Ok(table) => match outcome.failure.take() {
            Some(error) => Err(failed((table, error))),
            None => Ok(table),
        },
    }
}

/// What a run computed, for a library caller (the Python package): what the tool's `run`
/// prints and writes, as values.
pub struct Completed {
    /// The recorded quantities at every output time (the start included).
    pub table: Table,
    /// The time and state `[q, p, m_s]` where the run ended.
    pub end: (f64, Vec<f64>),
    /// The index of the `stop_when` condition that ended the run, if one did.
    pub stopped_by: Option<usize>,
    /// The stepper's work.
    pub statistics: varmass::core::Statistics,
    /// The summary the tool prints (its text made when shown: `summary.to_string()`).
    pub summary: Summary,
}

/// A run of [`Compiled::run`] that failed: the error, and the points recorded up to the
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
