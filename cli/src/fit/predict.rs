//! `varmass fit --predict COND`: the fitted model run on to a condition (an apogee,
//! `"z' < 0"`), and each fitted quantity there with its standard error propagated linearly
//! from the fit's covariance Σ of the unknowns: σ_X² = gᵀ Σ g, g = dX/dθ at the event, whose
//! time moves with θ (the run's `--stop-when` derivatives: dτ = −dC/Ċ). The data's time
//! offset, if fitted, moves only the event's time on the data's clock.

use std::fmt::Write as _;

use varmass::core::nalgebra::{DMatrix, DVector};

use super::{with_error, Fit, Problem, OFFSET};
use crate::args::RunArgs;
use crate::error::CliError;
use crate::run::names::shown;
use crate::run::Compiled;

/// The prediction's report: the event's time and each fitted quantity there, with errors.
pub fn report(
    compiled: &mut Compiled,
    problem: &Problem<'_>,
    fit: &Fit,
    condition: &str,
    until: f64,
) -> Result<String, CliError> {
    let theta = DVector::from_column_slice(&fit.values);
    let (mut args, values) = problem.at(&theta);
    (args.at, args.rates) = (Vec::new(), false);
    args.stop_when = vec![condition.to_string()];
    args.until = Some(until);
    let done = compiled.execute(&args, false, values, |_| {});
    let done =
        done.map_err(|failed| CliError::Run(format!("the prediction's run: {}", failed.error)))?;
    if done.stopped_by.is_none() {
        return Err(CliError::Run(format!(
            "the fitted run did not reach `{condition}` before t = {} (--predict-until)",
            shown(until)
        )));
    }
    let table = &done.table;
    let last = table.times().len() - 1;
    let read =
        |name: &str| (table.names.iter().position(|c| c == name)).map(|c| table.column(c)[last]);
    let (names, covariance) = model_covariance(fit, &args);
    let spread = |quantity: &str| -> Option<f64> {
        let g: Vec<f64> = (names.iter())
            .map(|w| read(&format!("d({quantity})/d({w})")))
            .collect::<Option<_>>()?;
        let g = DVector::from_vec(g);
        Some((g.transpose() * &covariance * &g)[(0, 0)].max(0.0).sqrt())
    };
    let spread = |quantity: &str| spread(quantity).unwrap_or(f64::NAN);
    let mut out = format!("predicted where `{condition}`:\n");
    let time = table.times()[last];
    let offset = problem.offset(&theta);
    let clock = match offset != 0.0 {
        true => format!(" (the data's clock: {})", shown(time + offset)),
        false => String::new(),
    };
    let _ = writeln!(out, "  t = {}{clock}", with_error(time, spread("t")));
    let mut seen: Vec<&str> = Vec::new();
    for s in problem.series {
        if seen.contains(&s.quantity.as_str()) {
            continue;
        }
        seen.push(&s.quantity);
        let value = read(&s.quantity).ok_or_else(|| CliError::Run("not recorded".to_string()))?;
        let shown = with_error(value, spread(&s.quantity));
        let _ = writeln!(out, "  {} = {shown}", s.quantity);
    }
    Ok(out)
}

/// The unknowns the run differentiates by (all but the offset) and their covariance, from
/// the fit's errors and correlations.
fn model_covariance(fit: &Fit, args: &RunArgs) -> (Vec<String>, DMatrix<f64>) {
    let kept: Vec<usize> = (0..fit.unknowns.len())
        .filter(|&i| fit.unknowns[i].name != OFFSET)
        .collect();
    let names = kept.iter().map(|&i| fit.unknowns[i].name.clone()).collect();
    debug_assert_eq!(args.sensitivity.len(), kept.len());
    let covariance = DMatrix::from_fn(kept.len(), kept.len(), |a, b| {
        let (i, j) = (kept[a], kept[b]);
        fit.correlation[(i, j)] * fit.errors[i] * fit.errors[j]
    });
    (names, covariance)
}
