//! `varmass fit --predict COND`: the fitted model run on to a condition (an apogee,
//! `"z' < 0"`), and each fitted quantity there with its standard error propagated linearly
//! from the fit's covariance Σ of the unknowns: σ_X² = gᵀ Σ g, g = dX/dθ at the event, whose
//! time moves with θ (the run's `--stop-when` derivatives: dτ = −dC/Ċ). The data's time
//! offset, if fitted, moves only the event's time on the data's clock.

use std::fmt::Write as _;

use varmass::core::nalgebra::{DMatrix, DVector};

use super::{with_error, Evaluate, Fit, ModelRun, Problem, OFFSET};
use crate::error::CliError;
use crate::run::names::shown;
use crate::run::Table;
use crate::scene::{Request, Rerun};

/// The prediction's report: the event's time and each fitted quantity there, with errors
/// (`target`: the model's runs or the scene's).
pub(super) fn report(
    target: &mut impl Evaluate,
    problem: &Problem<'_>,
    fit: &Fit,
    condition: &str,
    until: f64,
) -> Result<String, CliError> {
    let theta = DVector::from_column_slice(&fit.values);
    let (table, stopped) = target.predicted(problem, &theta, (condition, until))?;
    if !stopped {
        return Err(CliError::Run(format!(
            "the fitted run did not reach `{condition}` before t = {} (--predict-until)",
            shown(until)
        )));
    }
    let table = &table;
    let last = table.times().len() - 1;
    let read =
        |name: &str| (table.names.iter().position(|c| c == name)).map(|c| table.column(c)[last]);
    let covariance = DMatrix::from_fn(fit.values.len(), fit.values.len(), |i, j| {
        fit.correlation[(i, j)] * fit.errors[i] * fit.errors[j]
    });
    // √(gᵀ Σ g) over every unknown: g_w = d(X)/d(w), and for the offset `on_clock` (1 for
    // the event's time on the data's clock, t + δ; 0 for the model's quantities).
    let spread = |quantity: &str, on_clock: f64| -> f64 {
        let g = (fit.unknowns.iter()).map(|u| match u.name == OFFSET {
            true => Some(on_clock),
            false => read(&format!("d({quantity})/d({})", u.name)),
        });
        match g.collect::<Option<Vec<f64>>>() {
            Some(g) => {
                let g = DVector::from_vec(g);
                (g.transpose() * &covariance * &g)[(0, 0)].max(0.0).sqrt()
            }
            None => f64::NAN,
        }
    };
    let mut out = format!("predicted where `{condition}`:\n");
    let time = table.times()[last];
    let _ = write!(out, "  t = {}", with_error(time, spread("t", 0.0)));
    match fit.unknowns.iter().any(|u| u.name == OFFSET) {
        true => {
            let clock = with_error(time + problem.offset(&theta), spread("t", 1.0));
            let _ = writeln!(out, " (the data's clock: {clock})");
        }
        false => out.push('\n'),
    }
    for quantity in problem.quantities() {
        let value = read(quantity).ok_or_else(|| CliError::Run("not recorded".to_string()))?;
        let shown = with_error(value, spread(quantity, 0.0));
        let _ = writeln!(out, "  {quantity} = {shown}");
    }
    Ok(out)
}

/// A model's run at θ on to `condition` before `until`: its table, and whether the
/// condition ended it.
pub(super) fn model_run_to(
    model: &mut ModelRun<'_>,
    problem: &Problem<'_>,
    theta: &DVector<f64>,
    (condition, until): (&str, f64),
) -> Result<(Table, bool), CliError> {
    let (mut args, values) = model.at(problem, theta);
    (args.at, args.rates) = (Vec::new(), false);
    args.stop_when = vec![condition.to_string()];
    args.until = Some(until);
    let done = model.compiled.execute(&args, false, values, |_| {});
    let done =
        done.map_err(|failed| CliError::Run(format!("the prediction's run: {}", failed.error)))?;
    Ok((done.table, done.stopped_by.is_some()))
}

/// A scene's run at θ on to `condition` before `until`, in place of its own `stop_when` and
/// `until`: its table, and whether the condition ended it.
pub(super) fn scene_run_to(
    rerun: &mut Rerun,
    problem: &Problem<'_>,
    theta: &DVector<f64>,
    stop: (&str, f64),
) -> Result<(Table, bool), CliError> {
    let (values, names) = super::scene::scene_values(problem, theta);
    let request = Request {
        sensitivities: &names,
        at: &[],
        rates: false,
        quiet: true,
    };
    let ran = rerun.run_to(&values, &problem.quantities(), &request, Some(stop));
    let ran = ran.map_err(|e| CliError::Run(format!("the prediction's run: {e}")))?;
    match ran.failure {
        Some(e) => Err(CliError::Run(format!("the prediction's run: {e}"))),
        None => Ok((ran.table, ran.stopped_by.is_some())),
    }
}
