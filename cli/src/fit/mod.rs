//! `varmass fit`: a model's parameters (and initial values) fitted to measured data by
//! weighted least squares (docs/sensitivities.md#fitting). Each evaluation is one run of the
//! model with `--sensitivity` for every unknown, landing on the data's times, so that the
//! residuals r = (X(tᵢ; θ) − Xᵢ)/σ and their Jacobian ∂r/∂θ = (dX/dθ)(tᵢ)/σ come from one
//! integration; Levenberg–Marquardt ([`lm`]) moves θ. At the minimum the covariance of θ
//! is (JᵀJ)⁻¹, times the residuals' variance ‖r‖²/(m − n) when the data's σ is not given.

pub mod data;
pub mod lm;
mod plot;
mod predict;
mod scene;

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::Args;
use varmass::core::nalgebra::{DMatrix, DVector};

use crate::args::RunArgs;
use crate::error::CliError;
use crate::run::names::{named, number, shown};
use crate::run::{Compiled, Table};
use crate::scene::Rerun;
pub use data::Series;
pub use predict::{Predict, Prediction};
pub use scene::fit_file as fit_scene_file;

/// `varmass fit`'s arguments: a run's (the model, `--set` start values, `--init`, the
/// method and tolerance), the data and what to fit.
#[derive(Clone, Debug, Args)]
pub struct FitArgs {
    /// The run: its `--set` values are the start of the fitted ones (and the fixed values
    /// of the others); `--until` defaults to the data's last time.
    #[command(flatten)]
    pub run: RunArgs,
    /// The measured data: a CSV file with a header (`--time`'s column, then any others).
    #[arg(long, value_name = "PATH")]
    pub data: PathBuf,
    /// A model quantity and the data column that measures it, `y=Altitude (m)`
    /// (repeatable).
    #[arg(long = "column", value_name = "QUANTITY=COLUMN")]
    pub column: Vec<String>,
    /// The data's time column (default: the first).
    #[arg(long, value_name = "COLUMN")]
    pub time: Option<String>,
    /// A parameter to fit, or an initial value `init:x` (`init:x'`, `init:m`), optionally
    /// bounded, `k_d=0:1` (repeatable, up to 6).
    #[arg(long = "fit", value_name = "NAME[=LO:HI]")]
    pub fit: Vec<String>,
    /// The standard deviation of a quantity's data, `y=2.5` (weights 1/σ²; without it the
    /// errors are scaled by the residuals' own spread).
    #[arg(long = "sigma", value_name = "QUANTITY=VALUE")]
    pub sigma: Vec<String>,
    /// After the fit, run the fitted model on to this condition (`"z' < 0"`: the apogee)
    /// and report the data's quantities there with their standard errors.
    #[arg(long, value_name = "CONDITION")]
    pub predict: Option<String>,
    /// How long the prediction's run may go (default: ten times the data's span).
    #[arg(long, value_name = "T", requires = "predict")]
    pub predict_until: Option<f64>,
}

/// The unknown that is the data's time offset, t_data = t_model + offset (a log whose
/// clock started before ignition): `--fit data:offset=LO:HI`.
pub const OFFSET: &str = "data:offset";

/// An unknown: a parameter, an initial value (`init:x`) or the data's time offset
/// ([`OFFSET`]), with its bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct Unknown {
    /// The name as `--sensitivity` takes it.
    pub name: String,
    /// Lower and upper bounds (±∞ for none).
    pub bounds: (f64, f64),
}

impl Unknown {
    /// Parses `NAME` or `NAME=LO:HI`.
    pub fn parse(text: &str) -> Result<Self, CliError> {
        let Some((name, range)) = text.split_once('=') else {
            return Ok(Self {
                name: text.trim().to_string(),
                bounds: (f64::NEG_INFINITY, f64::INFINITY),
            });
        };
        let bad = || CliError::Input(format!("--fit {text}: expected NAME or NAME=LO:HI"));
        let (lo, hi) = range.split_once(':').ok_or_else(bad)?;
        let (lo, hi) = (number(lo.trim(), "--fit")?, number(hi.trim(), "--fit")?);
        if lo >= hi {
            return Err(bad());
        }
        Ok(Self {
            name: name.trim().to_string(),
            bounds: (lo, hi),
        })
    }
}

/// A fit's outcome.
#[derive(Clone, Debug)]
pub struct Fit {
    /// The unknowns.
    pub unknowns: Vec<Unknown>,
    /// Their start values.
    pub start: Vec<f64>,
    /// Their fitted values.
    pub values: Vec<f64>,
    /// Their standard errors.
    pub errors: Vec<f64>,
    /// Their correlations (n × n).
    pub correlation: DMatrix<f64>,
    /// The weighted residuals r at the fitted values, series by series.
    pub residuals: Vec<Vec<f64>>,
    /// The runs made.
    pub evaluations: usize,
    /// Whether Levenberg–Marquardt converged.
    pub converged: bool,
    /// The fitted run's table (the data's quantities and their derivatives at its times).
    pub table: Table,
    /// The prediction asked of the fit ([`Predict`]), or why it failed (the fit stands).
    pub prediction: Option<Result<Prediction, String>>,
}

/// What a fit holds fixed between evaluations: the run's start, the data and the unknowns.
#[derive(Clone, Copy)]
struct Problem<'a> {
    from: f64,
    series: &'a [Series],
    unknowns: &'a [Unknown],
}

/// A model file's runs ([`Compiled`]): the run `args` with the parameter values `values`.
struct ModelRun<'a> {
    compiled: &'a mut Compiled,
    args: &'a RunArgs,
    values: &'a [(String, f64)],
}

impl Problem<'_> {
    /// The data's time offset at θ (0 when it is not fitted).
    fn offset(&self, theta: &DVector<f64>) -> f64 {
        (self.unknowns.iter().zip(theta.iter()))
            .find(|(u, _)| u.name == OFFSET)
            .map_or(0.0, |(_, x)| *x)
    }

    /// The data's quantities, each once, in the series' order.
    fn quantities(&self) -> Vec<&str> {
        let mut quantities: Vec<&str> = Vec::new();
        for s in self.series {
            if !quantities.contains(&s.quantity.as_str()) {
                quantities.push(&s.quantity);
            }
        }
        quantities
    }

    /// The model time of the datum at `t` on the data's clock, offset by `offset`: t − δ,
    /// or the run's start where that is before it (a log's samples before ignition, the
    /// rocket on its pad, compared with the start's values: else an offset that moves the
    /// first data before `--from` would fail its trial run, a bound the fit did not name).
    fn model_time(&self, t: f64, offset: f64) -> f64 {
        (t - offset).max(self.from)
    }

    /// The data's times on the model's clock at θ, increasing, each once.
    fn times(&self, theta: &DVector<f64>) -> Vec<f64> {
        let offset = self.offset(theta);
        let mut times: Vec<f64> = (self.series.iter())
            .flat_map(|s| s.times.iter().map(|t| self.model_time(*t, offset)))
            .collect();
        times.sort_by(f64::total_cmp);
        times.dedup();
        times
    }

    /// The weighted residuals and their Jacobian at θ, and the run's table.
    fn evaluate(
        &self,
        target: &mut impl Evaluate,
        theta: &DVector<f64>,
    ) -> Result<(DVector<f64>, DMatrix<f64>, Table), String> {
        let table = target.table(self, theta)?;
        let offset = self.offset(theta);
        let n = self.unknowns.len();
        let (mut r, mut j) = (Vec::new(), Vec::new());
        for s in self.series {
            let sigma = s.sigma.unwrap_or(1.0);
            let column = |name: &str| table.names.iter().position(|c| c == name);
            let value = column(&s.quantity).ok_or("the quantity was not recorded")?;
            // ∂r/∂δ = −Ẋ(tᵢ − δ)/σ for the offset, (dX/dw)(tᵢ − δ)/σ for the others:
            // each unknown's column and whether it is the offset.
            let derivatives: Vec<(usize, bool)> = (self.unknowns.iter())
                .map(|u| match u.name == OFFSET {
                    true => column(&format!("d({})/d(t)", s.quantity)).map(|c| (c, true)),
                    false => {
                        column(&format!("d({})/d({})", s.quantity, u.name)).map(|c| (c, false))
                    }
                })
                .collect::<Option<_>>()
                .ok_or("a derivative was not recorded")?;
            for (t, x) in s.times.iter().zip(&s.values) {
                let time = self.model_time(*t, offset);
                let row = row_at(&table, time)?;
                r.push((table.column(value)[row] - x) / sigma);
                // Held at the start, a datum does not move with the offset.
                let held = time > t - offset;
                let jacobian = derivatives.iter().map(|&(d, offset)| match (offset, held) {
                    (true, true) => 0.0,
                    (true, false) => -table.column(d)[row],
                    (false, _) => table.column(d)[row],
                });
                j.extend(jacobian.map(|d| d / sigma));
            }
        }
        let m = r.len();
        Ok((
            DVector::from_vec(r),
            DMatrix::from_row_slice(m, n, &j),
            table,
        ))
    }
}

/// What a fit runs at each θ: a model file (`varmass run`'s run, [`Compiled`]) or a scene
/// file ([`Rerun`]).
trait Evaluate {
    /// The run at θ of `problem`: its table, landing on the data's times, with the data's
    /// quantities and their derivatives by each unknown.
    fn table(&mut self, problem: &Problem<'_>, theta: &DVector<f64>) -> Result<Table, String>;

    /// The run at θ on to `stop`, a condition before a time (`--predict`), recording the
    /// data's quantities and their derivatives at the event: its table, and whether the
    /// condition ended it.
    fn predicted(
        &mut self,
        problem: &Problem<'_>,
        theta: &DVector<f64>,
        stop: (&str, f64),
    ) -> Result<(Table, bool), CliError>;
}

impl ModelRun<'_> {
    /// The run's arguments and parameter values at θ of `problem`: the unknowns'
    /// sensitivities, and the quantities' rates when the offset is fitted
    /// (∂X(tᵢ − δ)/∂δ = −Ẋ).
    fn at(&self, problem: &Problem<'_>, theta: &DVector<f64>) -> (RunArgs, Vec<(String, f64)>) {
        let mut args = self.args.clone();
        let mut values = self.values.to_vec();
        for (u, x) in problem.unknowns.iter().zip(theta.iter()) {
            if u.name == OFFSET {
                continue;
            }
            match u.name.strip_prefix("init:").map(str::trim) {
                Some(entry) => {
                    args.init
                        .retain(|i| i.split_once('=').is_none_or(|(n, _)| n.trim() != entry));
                    args.init.push(format!("{entry}={x:?}"));
                }
                None => match values.iter_mut().find(|(n, _)| *n == u.name) {
                    Some(slot) => slot.1 = *x,
                    None => values.push((u.name.clone(), *x)),
                },
            }
        }
        args.sensitivity = (problem.unknowns.iter())
            .filter(|u| u.name != OFFSET)
            .map(|u| u.name.clone())
            .collect();
        args.rates = problem.unknowns.iter().any(|u| u.name == OFFSET);
        args.record = vec![problem.quantities().join(",")];
        let times = problem.times(theta);
        // A run at least as long as the data (the offset may move them past `--until`).
        args.until = match (args.until, times.last()) {
            (Some(until), Some(last)) => Some(until.max(*last)),
            (until, last) => until.or(last.copied()),
        };
        args.at = times;
        (args, values)
    }
}

impl Evaluate for ModelRun<'_> {
    fn table(&mut self, problem: &Problem<'_>, theta: &DVector<f64>) -> Result<Table, String> {
        let (args, values) = self.at(problem, theta);
        let done = self.compiled.execute(&args, false, values, |_| {});
        Ok(done.map_err(|failed| failed.error.to_string())?.table)
    }

    fn predicted(
        &mut self,
        problem: &Problem<'_>,
        theta: &DVector<f64>,
        stop: (&str, f64),
    ) -> Result<(Table, bool), CliError> {
        predict::model_run_to(self, problem, theta, stop)
    }
}

/// The row of `table` at the time `t` (the run lands on every datum's time).
fn row_at(table: &Table, t: f64) -> Result<usize, String> {
    let times = table.times();
    match times.binary_search_by(|x| x.total_cmp(&t)) {
        Ok(row) => Ok(row),
        Err(_) => Err(format!(
            "the run has no point at the datum's time {} (it ended at {}: a stop condition \
             before the data's end?)",
            shown(t),
            shown(times.last().copied().unwrap_or(f64::NAN))
        )),
    }
}

/// Fits `unknowns` of the model `compiled` to `series`: the run `args` with the parameter
/// values `values` (the unknowns' start among them, or the model's defaults); then the
/// prediction `predict` asks, if any, of the fitted model ([`Fit::prediction`]).
pub fn fit(
    compiled: &mut Compiled,
    args: &RunArgs,
    values: Vec<(String, f64)>,
    series: &[Series],
    unknowns: &[Unknown],
    predict: Option<&Predict>,
) -> Result<Fit, CliError> {
    not_too_many(unknowns)?;
    predict.map_or(Ok(()), |p| p.check(args.from))?;
    let values = compiled.model().with_defaults(&values);
    let start = start_values(args, &values, unknowns)?;
    let problem = Problem {
        from: args.from,
        series,
        unknowns,
    };
    let mut run = ModelRun {
        compiled,
        args,
        values: &values,
    };
    let fitted = solve(&mut run, problem, start)?;
    Ok(predicted(&mut run, problem, fitted, predict))
}

/// Fits `unknowns` of the scene `rerun` to `series`, each datum within the scene's span
/// (docs/sensitivities.md#fitting-a-scene): the start values are the scene's (its `[set]`
/// or the model's defaults, its `[init]`); then the prediction `predict` asks, if any, of
/// the fitted scene ([`Fit::prediction`]).
pub fn fit_scene(
    rerun: &mut Rerun,
    series: &[Series],
    unknowns: &[Unknown],
    predict: Option<&Predict>,
) -> Result<Fit, CliError> {
    not_too_many(unknowns)?;
    let start = scene::start_values(rerun, unknowns)?;
    let problem = Problem {
        from: rerun.span()?.0,
        series,
        unknowns,
    };
    predict.map_or(Ok(()), |p| p.check(problem.from))?;
    // The scene's refusals before any step keep their words and their exit code.
    let theta = DVector::from_vec(start.clone());
    scene::table(rerun, &problem, &theta).map_err(|e| match e {
        CliError::Input(_) | CliError::Model { .. } => e,
        e => CliError::Run(format!("the fit's first run failed: {e}")),
    })?;
    let fitted = solve(rerun, problem, start)?;
    Ok(predicted(rerun, problem, fitted, predict))
}

/// `fitted` with the prediction `predict` asks of it, run by `target` (its failure kept as
/// its message: the fit stands).
fn predicted(
    target: &mut impl Evaluate,
    problem: Problem<'_>,
    mut fitted: Fit,
    predict: Option<&Predict>,
) -> Fit {
    fitted.prediction = predict.map(|request| {
        predict::predict(target, &problem, &fitted, request).map_err(|e| e.to_string())
    });
    fitted
}

/// Refuses more unknowns than a run's sensitivity columns.
fn not_too_many(unknowns: &[Unknown]) -> Result<(), CliError> {
    let most = crate::run::sensitivity::MAX_SENSITIVITIES;
    match unknowns.len() > most {
        true => Err(CliError::Input(format!(
            "--fit is given {} times; a fit takes at most {most} unknowns (each is a \
             sensitivity column of every run)",
            unknowns.len()
        ))),
        false => Ok(()),
    }
}

/// Levenberg–Marquardt from `start` on `problem`, run by `target`; the fit at the minimum.
fn solve(
    target: &mut impl Evaluate,
    problem: Problem<'_>,
    start: Vec<f64>,
) -> Result<Fit, CliError> {
    let (series, unknowns) = (problem.series, problem.unknowns);
    weights_known(series)?;
    let data: usize = series.iter().map(|s| s.times.len()).sum();
    if data <= unknowns.len() {
        return Err(CliError::Input(format!(
            "{data} data cannot determine {} unknowns",
            unknowns.len()
        )));
    }
    let mut first_error = None;
    let bounds: (DVector<f64>, DVector<f64>) = (
        DVector::from_iterator(unknowns.len(), unknowns.iter().map(|u| u.bounds.0)),
        DVector::from_iterator(unknowns.len(), unknowns.iter().map(|u| u.bounds.1)),
    );
    let minimum = lm::minimize(
        |theta| {
            let evaluated = problem.evaluate(target, theta).map(|(r, j, _)| (r, j));
            if let (Err(e), None) = (&evaluated, &first_error) {
                first_error = Some(e.clone());
            }
            evaluated
        },
        DVector::from_vec(start.clone()),
        (&bounds.0, &bounds.1),
        lm::Settings::default(),
    )
    .map_err(|e| CliError::Run(format!("the fit's first run failed: {e}")))?;
    if !minimum.converged {
        if let Some(e) = first_error {
            return Err(CliError::Run(format!(
                "the fit did not converge in {} runs; a trial run failed: {e}",
                minimum.evaluations
            )));
        }
    }
    let (_, _, table) = problem
        .evaluate(target, &minimum.theta)
        .map_err(CliError::Run)?;
    summarize(minimum, problem, start, table)
}

/// Refuses series whose weights cannot be compared: without σ a series is weighed in its
/// own units, so several series need theirs (`--sigma`); one series alone without σ has
/// its σ estimated from the residuals (the covariance scaled by ‖r‖²/(m − n)).
fn weights_known(series: &[Series]) -> Result<(), CliError> {
    let unknown: Vec<&str> = (series.iter())
        .filter(|s| s.sigma.is_none())
        .map(|s| s.quantity.as_str())
        .collect();
    match series.len() > 1 && !unknown.is_empty() {
        true => Err(CliError::Input(format!(
            "several data columns are weighed against each other by their σ: give --sigma \
             for {}",
            unknown.join(", ")
        ))),
        false => Ok(()),
    }
}

/// The unknowns' start values: a parameter's from `values`, an initial value's from
/// `args.init`.
fn start_values(
    args: &RunArgs,
    values: &[(String, f64)],
    unknowns: &[Unknown],
) -> Result<Vec<f64>, CliError> {
    let missing = |name: &str, flag: &str| {
        CliError::Input(format!("--fit {name}: give its start value with {flag}"))
    };
    let mut start = Vec::new();
    for u in unknowns {
        if u.name == OFFSET {
            start.push(start_offset(std::slice::from_ref(u)));
            continue;
        }
        let value = match u.name.strip_prefix("init:").map(str::trim) {
            Some(entry) => args
                .init
                .iter()
                .filter_map(|i| i.split_once('='))
                .find(|(n, _)| n.trim() == entry)
                .map(|(n, v)| named(&u.name, "--init", n, v).map(|(_, v)| v))
                .transpose()?
                .ok_or_else(|| missing(&u.name, &format!("--init {entry}=VALUE")))?,
            None => (values.iter().find(|(n, _)| *n == u.name))
                .map(|(_, v)| *v)
                .ok_or_else(|| missing(&u.name, &format!("--set {}=VALUE", u.name)))?,
        };
        start.push(value.clamp(u.bounds.0, u.bounds.1));
    }
    Ok(start)
}

/// The fit's values, errors and correlations from the minimum.
fn summarize(
    minimum: lm::Minimum,
    problem: Problem<'_>,
    start: Vec<f64>,
    table: Table,
) -> Result<Fit, CliError> {
    let (m, n) = minimum.jacobian.shape();
    let normal = minimum.jacobian.transpose() * &minimum.jacobian;
    let inverse = normal
        .clone()
        .try_inverse()
        .filter(|i| i.iter().all(|x| x.is_finite()));
    let Some(mut covariance) = inverse else {
        let names: Vec<&str> = problem.unknowns.iter().map(|u| u.name.as_str()).collect();
        return Err(CliError::Run(format!(
            "the data do not determine {} separately: JᵀJ is singular at the fit",
            names.join(", ")
        )));
    };
    if problem.series.iter().any(|s| s.sigma.is_none()) {
        covariance *= minimum.residuals.norm_squared() / (m - n) as f64;
    }
    let errors: Vec<f64> = covariance
        .diagonal()
        .iter()
        .map(|v| v.max(0.0).sqrt())
        .collect();
    let correlation = DMatrix::from_fn(n, n, |i, j| covariance[(i, j)] / (errors[i] * errors[j]));
    let mut residuals = Vec::new();
    let mut rest = minimum.residuals.as_slice();
    for s in problem.series {
        let (head, tail) = rest.split_at(s.times.len());
        residuals.push(head.to_vec());
        rest = tail;
    }
    Ok(Fit {
        unknowns: problem.unknowns.to_vec(),
        start,
        values: minimum.theta.iter().copied().collect(),
        errors,
        correlation,
        residuals,
        evaluations: minimum.evaluations + 1,
        converged: minimum.converged,
        table,
        prediction: None,
    })
}

/// `varmass fit`: reads the data, fits, writes the fitted run's CSV and the plot of the fit
/// over the data if asked; returns the report.
pub fn run(args: &FitArgs) -> Result<String, CliError> {
    run_given(args, &[])
}

/// [`run`], `given` the ids of the flags on the command line: a scene file refuses those of
/// a run's settings, which it gives itself (whatever their value).
pub fn run_given(args: &FitArgs, given: &[String]) -> Result<String, CliError> {
    if args.fit.is_empty() || args.column.is_empty() {
        return Err(CliError::Input(
            "a fit needs --fit NAME (what to fit) and --column QUANTITY=COLUMN (what the data \
             measure)"
                .to_string(),
        ));
    }
    let unknowns: Vec<Unknown> = args
        .fit
        .iter()
        .map(|f| Unknown::parse(f))
        .collect::<Result<_, _>>()?;
    if crate::scene::is_scene(&args.run.model.file) {
        return scene::run(args, given, &unknowns);
    }
    let (series, left_out, window) = series_of(args, &unknowns)?;
    let model = crate::model::load(&args.run.model)?;
    let values = crate::run::plan::parameters(&args.run)?;
    let mut compiled = Compiled::new(model);
    let predict = request(args);
    let fitted = fit(
        &mut compiled,
        &args.run,
        values,
        &series,
        &unknowns,
        predict.as_ref(),
    )?;
    finish(args, &fitted, &series, (left_out, window))
}

/// The prediction `--predict` (`--predict-until`) asks, if any.
fn request(args: &FitArgs) -> Option<Predict> {
    (args.predict.clone()).map(|condition| Predict {
        condition,
        until: args.predict_until,
    })
}

/// The fit's report, its CSV and plot written as `args` asks, its prediction, and the note
/// of the data left out; a prediction that failed is the error, after the fit's report
/// (which is not lost with it).
fn finish(
    args: &FitArgs,
    fitted: &Fit,
    series: &[Series],
    (left_out, window): (usize, Window),
) -> Result<String, CliError> {
    let mut out = written(args, fitted, series)?;
    match (&fitted.prediction, &args.predict) {
        (Some(Ok(prediction)), _) => out += &prediction.report(),
        (Some(Err(e)), Some(condition)) => {
            return Err(CliError::Run(format!("{out}--predict `{condition}`: {e}")))
        }
        _ => {}
    }
    Ok(out + &left_out_note(left_out, window))
}

/// The fitted run's CSV and the plot of the fit over the data written as `args` asks; the
/// report.
fn written(args: &FitArgs, fitted: &Fit, series: &[Series]) -> Result<String, CliError> {
    if let Some(path) = &args.run.csv {
        crate::run::output::write_csv(&fitted.table, path)?;
    }
    if let Some(path) = &args.run.plot {
        let title = args.run.model.file.display().to_string();
        plot::plot(fitted, series, &title, path)?;
    }
    Ok(report(fitted, series))
}

/// How many data were left out of the run's span `window` (on the data's clock), if any.
fn left_out_note(left_out: usize, window: Window) -> String {
    if left_out == 0 {
        return String::new();
    }
    let until = window.1.map_or("the data's end".to_string(), shown);
    format!(
        "{left_out} data outside the run ({} to {until} on the data's clock) were left out\n",
        shown(window.0)
    )
}

/// The data's time offset at the fit's start: 0, or its bound nearest 0 (0 without it).
fn start_offset(unknowns: &[Unknown]) -> f64 {
    (unknowns.iter().find(|u| u.name == OFFSET))
        .map_or(0.0, |u| 0.0_f64.clamp(u.bounds.0, u.bounds.1))
}

/// The span of the data kept, on the data's clock: from, until (`None`: the data's end).
type Window = (f64, Option<f64>);

/// The data series of `args` (`--data`, `--column`, `--time`, `--sigma`), kept within the
/// run's span on the data's clock (at the offset's start value, 0 or its bound nearest 0):
/// the series, how many data were left out, and that window.
fn series_of(
    args: &FitArgs,
    unknowns: &[Unknown],
) -> Result<(Vec<Series>, usize, Window), CliError> {
    let text = std::fs::read_to_string(&args.data).map_err(|source| CliError::Read {
        path: args.data.clone(),
        source,
    })?;
    let pairs: Vec<(String, String)> = (args.column.iter())
        .map(|c| {
            c.split_once('=')
                .map(|(q, c)| (q.trim().to_string(), c.trim().to_string()))
        })
        .collect::<Option<_>>()
        .ok_or_else(|| CliError::Input("--column: expected QUANTITY=COLUMN".to_string()))?;
    if let Some((_, pair)) = (pairs.iter().enumerate()).find(|(i, p)| pairs[..*i].contains(p)) {
        return Err(CliError::Input(format!(
            "--column {}={} is given twice: its data would count twice (errors √2 too small)",
            pair.0, pair.1
        )));
    }
    let mut series = data::read(&text, &args.data, args.time.as_deref(), &pairs)?;
    let shift = start_offset(unknowns);
    let window = (args.run.from + shift, args.run.until.map(|u| u + shift));
    let left_out = data::window(&mut series, window.0, window.1);
    for sigma in &args.sigma {
        let (quantity, value) = crate::run::names::assignment(sigma, "--sigma")?;
        let mut measured = series
            .iter_mut()
            .filter(|s| s.quantity == quantity)
            .peekable();
        if measured.peek().is_none() {
            return Err(CliError::Input(format!(
                "--sigma {sigma}: `{quantity}` is no --column quantity"
            )));
        }
        measured.for_each(|s| s.sigma = Some(value));
    }
    Ok((series, left_out, window))
}

/// `value ± error`, the error to two significant digits and the value to the same decimal
/// place (`300.78 ± 0.95`), in exponent form beyond 1e-4…1e7.
fn with_error(value: f64, error: f64) -> String {
    if !(error.is_finite() && error > 0.0 && value.is_finite()) {
        return format!("{} ± {}", shown(value), shown(error));
    }
    let decimals = 1 - error.log10().floor() as i32;
    if (0..=8).contains(&decimals) && value.abs() < 1e7 {
        let d = decimals as usize;
        return format!("{value:.d$} ± {error:.d$}");
    }
    // As many significant digits of the value as reach the error's second.
    let magnitude = value.abs().max(error).log10().floor() as i32;
    let digits = (magnitude - error.log10().floor() as i32 + 1).clamp(1, 16) as usize;
    format!("{value:.digits$e} ± {error:.1e}")
}

/// The report `varmass fit` prints.
pub fn report(fit: &Fit, series: &[Series]) -> String {
    let mut out = String::new();
    let data: usize = series.iter().map(|s| s.times.len()).sum();
    let state = if fit.converged {
        "converged"
    } else {
        "did NOT converge"
    };
    let _ = writeln!(
        out,
        "fitted {} unknowns to {data} data in {} runs ({state}):",
        fit.values.len(),
        fit.evaluations
    );
    for (i, u) in fit.unknowns.iter().enumerate() {
        let bound = match fit.values[i] == u.bounds.0 || fit.values[i] == u.bounds.1 {
            true => "  (at its bound: the error assumes it free)",
            false => "",
        };
        let _ = writeln!(
            out,
            "  {} = {} (start {}){bound}",
            u.name,
            with_error(fit.values[i], fit.errors[i]),
            shown(fit.start[i])
        );
    }
    if fit.values.len() > 1 {
        let _ = writeln!(out, "correlations:");
        for (i, u) in fit.unknowns.iter().enumerate() {
            let row: Vec<String> = (0..fit.values.len())
                .map(|j| format!("{:+.3}", fit.correlation[(i, j)]))
                .collect();
            let _ = writeln!(out, "  {:>12}  {}", u.name, row.join("  "));
        }
    }
    for (s, r) in series.iter().zip(&fit.residuals) {
        let sigma = s.sigma.unwrap_or(1.0);
        let rms = (r.iter().map(|x| x * x).sum::<f64>() / r.len() as f64).sqrt() * sigma;
        let _ = writeln!(
            out,
            "residuals of {}: rms {} over {} data",
            s.quantity,
            shown(rms),
            r.len()
        );
    }
    out
}
