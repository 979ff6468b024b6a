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

/// A prediction asked of a fit (`--predict COND`, `--predict-until T`): the condition, and
/// the time its run may reach (`None`: ten times the data's span after the run's start).
#[derive(Clone, Debug, PartialEq)]
pub struct Predict {
    /// The condition that ends the run (`"z' < 0"`: the apogee), as `--stop-when` takes it.
    pub condition: String,
    /// The time the run may reach before the condition holds (`--predict-until`).
    pub until: Option<f64>,
}

/// The fitted run at a condition: the event's time and each data quantity there, each with
/// its standard error √(gᵀ Σ g).
#[derive(Clone, Debug, PartialEq)]
pub struct Prediction {
    /// The condition that ended the run.
    pub condition: String,
    /// The event's time on the model's clock, and its error.
    pub time: (f64, f64),
    /// The event's time on the data's clock, t + δ, and its error, when the data's offset
    /// ([`OFFSET`]) is fitted.
    pub clock: Option<(f64, f64)>,
    /// Each data quantity at the event (in the series' order): its name, value and error.
    pub quantities: Vec<(String, f64, f64)>,
}

impl Prediction {
    /// The report `varmass fit --predict` prints after the fit's.
    pub fn report(&self) -> String {
        let mut out = format!("predicted where `{}`:\n", self.condition);
        let _ = write!(out, "  t = {}", with_error(self.time.0, self.time.1));
        match self.clock {
            Some((clock, error)) => {
                let clock = with_error(clock, error);
                let _ = writeln!(out, " (the data's clock: {clock})");
            }
            None => out.push('\n'),
        }
        for (quantity, value, error) in &self.quantities {
            let _ = writeln!(out, "  {quantity} = {}", with_error(*value, *error));
        }
        out
    }
}

impl Predict {
    /// The time the run may reach: the one asked, else ten times the data's span after the
    /// run's start (at least 10).
    fn until(&self, problem: &Problem<'_>) -> f64 {
        let span = (problem.series.iter().flat_map(|s| s.times.iter()))
            .fold(problem.from, |end, t| end.max(*t))
            - problem.from;
        (self.until).unwrap_or(problem.from + 10.0 * span.max(1.0))
    }

    /// Refuses, before the fit, an end that is not after the run's start `from`.
    pub(super) fn check(&self, from: f64) -> Result<(), CliError> {
        match self.until {
            Some(until) if until > from => Ok(()),
            Some(until) => Err(CliError::Input(format!(
                "--predict-until {}: the prediction's run would end before it starts, at {}",
                shown(until),
                shown(from)
            ))),
            None => Ok(()),
        }
    }
}

/// The prediction `request` asks of the fit `fit` (`target`: the model's runs or the
/// scene's).
pub(super) fn predict(
    target: &mut impl Evaluate,
    problem: &Problem<'_>,
    fit: &Fit,
    request: &Predict,
) -> Result<Prediction, CliError> {
    let (condition, until) = (request.condition.as_str(), request.until(problem));
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
    let time = table.times()[last];
    let clock = (fit.unknowns.iter().any(|u| u.name == OFFSET))
        .then(|| (time + problem.offset(&theta), spread("t", 1.0)));
    let mut quantities = Vec::new();
    for quantity in problem.quantities() {
        let value = read(quantity).ok_or_else(|| CliError::Run("not recorded".to_string()))?;
        quantities.push((quantity.to_string(), value, spread(quantity, 0.0)));
    }
    Ok(Prediction {
        condition: condition.to_string(),
        time: (time, spread("t", 0.0)),
        clock,
        quantities,
    })
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
