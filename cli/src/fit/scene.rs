//! `varmass fit SCENE.toml` (docs/sensitivities.md#fitting-a-scene): the unknowns of a scene
//! — a rocket on its rail, through its changes of phase — fitted to data. Each evaluation
//! runs the scene with the unknowns' values in its `[set]` and `[init]` and their
//! sensitivity columns (docs/sensitivities.md#scenes), every phase landing on the data's
//! times; the residuals, the Levenberg–Marquardt and the report are a model file's.

use varmass::core::nalgebra::DVector;

use std::path::Path;

use super::{
    data, finish, fit_scene, request, series_of, start_offset, Evaluate, Fit, FitArgs, Predict,
    Problem, Series,
};
use super::{Unknown, OFFSET};
use crate::error::CliError;
use crate::run::Table;
use crate::scene::{Request, Rerun};

/// The flags that go with a scene file: the file and where the output goes (the scene
/// gives its own run settings), what the fit reads and fits, and the prediction.
const SCENE_FLAGS: [&str; 10] = [
    "file",
    "csv",
    "plot",
    "data",
    "column",
    "time",
    "fit",
    "sigma",
    "predict",
    "predict_until",
];

/// `varmass fit SCENE.toml`: the fit's report (`given`: the ids of the flags on the command
/// line).
pub fn run(args: &FitArgs, given: &[String], unknowns: &[Unknown]) -> Result<String, CliError> {
    let file = args.run.model.file.display().to_string();
    if let Some(id) = given.iter().find(|id| !SCENE_FLAGS.contains(&id.as_str())) {
        return Err(CliError::Input(format!(
            "--{}: not taken with a scene file (`{file}`), which gives the run's settings \
             itself (docs/scenes.md); a scene's fit takes only --data, --column, --time, \
             --fit, --sigma, --csv, --plot and --predict (--predict-until)",
            id.replace('_', "-"),
        )));
    }
    let mut rerun = Rerun::new(&args.run.model.file)?;
    let (from, until) = rerun.span()?;
    let mut scoped = args.clone();
    (scoped.run.from, scoped.run.until) = (from, Some(until));
    let (series, left_out, window) = series_of(&scoped, unknowns)?;
    let fitted = fit_scene(&mut rerun, &series, unknowns, request(args).as_ref())?;
    finish(&scoped, &fitted, &series, (left_out, window))
}

/// Fits `unknowns` of the scene file at `path` to `series` and predicts what `predict`
/// asks, if any (the Python package's `Scene.fit`): the fit, and how many data lay outside
/// the scene's span and were left out.
pub fn fit_file(
    path: &Path,
    mut series: Vec<Series>,
    unknowns: &[Unknown],
    predict: Option<&Predict>,
) -> Result<(Fit, usize), CliError> {
    let mut rerun = Rerun::new(path)?;
    let (from, until) = rerun.span()?;
    let shift = start_offset(unknowns);
    let left_out = data::window(&mut series, from + shift, Some(until + shift));
    Ok((fit_scene(&mut rerun, &series, unknowns, predict)?, left_out))
}

/// The unknowns' start values: the scene's own, each within its bounds (the data's time
/// offset from 0).
pub fn start_values(rerun: &mut Rerun, unknowns: &[Unknown]) -> Result<Vec<f64>, CliError> {
    let scene = rerun.path().display().to_string();
    let mut start = Vec::new();
    for u in unknowns {
        if u.name == OFFSET {
            start.push(start_offset(std::slice::from_ref(u)));
            continue;
        }
        let Some(value) = rerun.start_value(&u.name)? else {
            let table = match u.name.starts_with("init:") {
                true => "[init]",
                false => "[set]",
            };
            return Err(CliError::Input(format!(
                "--fit {}: `{scene}` gives it no value to start from; write one in its \
                 `{table}`",
                u.name
            )));
        };
        start.push(value.clamp(u.bounds.0, u.bounds.1));
    }
    Ok(start)
}

/// The scene's run at θ of `problem`: the unknowns' values in its `[set]` and `[init]`,
/// their columns, the data's quantities recorded and their times landed on; with the
/// data's time offset among the unknowns, the quantities' rates too (∂X(tᵢ − δ)/∂δ = −Ẋ).
pub(super) fn table(
    rerun: &mut Rerun,
    problem: &Problem<'_>,
    theta: &DVector<f64>,
) -> Result<Table, CliError> {
    let (values, names) = scene_values(problem, theta);
    let times = problem.times(theta);
    let request = Request {
        sensitivities: &names,
        at: &times,
        rates: problem.unknowns.iter().any(|u| u.name == OFFSET),
        quiet: rerun.runs() > 0,
    };
    let ran = rerun.run(&values, &problem.quantities(), &request)?;
    match ran.failure {
        Some(failure) => Err(failure),
        None => Ok(ran.table),
    }
}

/// The unknowns' values at θ that a scene's run takes (all but the data's offset), and
/// their names (the run's sensitivity columns).
pub(super) fn scene_values(
    problem: &Problem<'_>,
    theta: &DVector<f64>,
) -> (Vec<(String, f64)>, Vec<String>) {
    let values: Vec<(String, f64)> = (problem.unknowns.iter().zip(theta.iter()))
        .filter(|(u, _)| u.name != OFFSET)
        .map(|(u, x)| (u.name.clone(), *x))
        .collect();
    let names = values.iter().map(|(n, _)| n.clone()).collect();
    (values, names)
}

impl Evaluate for Rerun {
    fn table(&mut self, problem: &Problem<'_>, theta: &DVector<f64>) -> Result<Table, String> {
        table(self, problem, theta).map_err(|e| e.to_string())
    }

    fn predicted(
        &mut self,
        problem: &Problem<'_>,
        theta: &DVector<f64>,
        stop: (&str, f64),
    ) -> Result<(Table, bool), CliError> {
        super::predict::scene_run_to(self, problem, theta, stop)
    }
}
