//! Fidelity comparison: what leaving something out of a model costs in accuracy and saves
//! in time.
//!
//! A scene is run with two models of one physical system, the reference (full) one and a
//! reduced one (fewer effects, a constant-mass approximation, fewer coordinates), from
//! corresponding initial conditions; each run records the same named observables at the same
//! output times ([`crate::observe()`]). [`measure`] times a run; [`compare`] reports, per
//! observable, the difference reduced − reference at every output time and its largest
//! size, and the cost (steps, evaluations, wall time) of each model. A scene may have
//! several phases (a burn, then a coast): join their recordings with
//! [`Recording::append`] inside the measured closure.

use std::fmt;
use std::string::{String, ToString};
use std::time::{Duration, Instant};
use std::vec::Vec;

use crate::observe::Recording;

/// One model's run of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelRun {
    /// The model's name, for the table.
    pub name: String,
    /// What it recorded, and the stepper's work.
    pub recording: Recording,
    /// The wall time of the whole run (every phase).
    pub wall_time: Duration,
}

/// Runs `scene` (which returns its recording) and times it.
pub fn measure<E>(name: &str, scene: impl FnOnce() -> Result<Recording, E>) -> Result<ModelRun, E> {
    let started = Instant::now();
    let recording = scene()?;
    Ok(ModelRun {
        name: name.to_string(),
        recording,
        wall_time: started.elapsed(),
    })
}

/// How one observable differs between the models.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    /// The observable.
    pub name: String,
    /// Reduced − reference at every output time.
    pub values: Vec<f64>,
    /// The largest |reduced − reference|.
    pub max_abs: f64,
    /// The output time where it is largest.
    pub at_time: f64,
    /// `max_abs` over the largest |reference| value (0 when the reference is 0 throughout).
    pub max_relative: f64,
}

/// The cost of one model's run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cost {
    /// Accepted steps.
    pub steps: usize,
    /// Evaluations of the state rate.
    pub evaluations: usize,
    /// Wall time.
    pub wall_time: Duration,
}

impl Cost {
    fn of(run: &ModelRun) -> Cost {
        Cost {
            steps: run.recording.statistics.accepted_steps,
            evaluations: run.recording.statistics.rate_evaluations,
            wall_time: run.wall_time,
        }
    }
}

/// Two models of one scene compared.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// The reference model's name.
    pub reference: String,
    /// The reduced model's name.
    pub reduced: String,
    /// The output times.
    pub times: Vec<f64>,
    /// One entry per observable of the reference, in its order.
    pub differences: Vec<Difference>,
    /// The reference model's cost.
    pub reference_cost: Cost,
    /// The reduced model's cost.
    pub reduced_cost: Cost,
}

impl Comparison {
    /// The difference of observable `name`, if it was compared.
    pub fn difference(&self, name: &str) -> Option<&Difference> {
        self.differences.iter().find(|d| d.name == name)
    }
}

/// Why two runs cannot be compared.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FidelityError {
    /// The runs recorded at different output times.
    #[error("the runs recorded at different output times ({reference} and {reduced} points)")]
    DifferentTimes {
        /// Points in the reference run.
        reference: usize,
        /// Points in the reduced run.
        reduced: usize,
    },
    /// The reduced run did not record an observable of the reference.
    #[error("the reduced model did not record `{0}`")]
    MissingObservable(String),
}

/// Compares `reduced` with `reference` on every observable of the reference.
pub fn compare(reference: &ModelRun, reduced: &ModelRun) -> Result<Comparison, FidelityError> {
    let (a, b) = (&reference.recording, &reduced.recording);
    if a.times != b.times {
        return Err(FidelityError::DifferentTimes {
            reference: a.times.len(),
            reduced: b.times.len(),
        });
    }
    let differences = a
        .names
        .iter()
        .map(|name| difference(a, b, name))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Comparison {
        reference: reference.name.clone(),
        reduced: reduced.name.clone(),
        times: a.times.clone(),
        differences,
        reference_cost: Cost::of(reference),
        reduced_cost: Cost::of(reduced),
    })
}

/// Observable `name` of `reduced` against `reference` (same times).
fn difference(
    reference: &Recording,
    reduced: &Recording,
    name: &str,
) -> Result<Difference, FidelityError> {
    if !reduced.names.iter().any(|n| n == name) {
        return Err(FidelityError::MissingObservable(name.to_string()));
    }
    let (a, b) = (reference.series(name), reduced.series(name));
    let values: Vec<f64> = b.iter().zip(&a).map(|(b, a)| b - a).collect();
    let (mut max_abs, mut at_time) = (0.0f64, reference.times.first().copied().unwrap_or(0.0));
    for (value, &time) in values.iter().zip(&reference.times) {
        if value.abs() > max_abs {
            (max_abs, at_time) = (value.abs(), time);
        }
    }
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let max_relative = if scale > 0.0 { max_abs / scale } else { 0.0 };
    Ok(Difference {
        name: name.to_string(),
        values,
        max_abs,
        at_time,
        max_relative,
    })
}

/// A table: per observable the largest difference (absolute, where, relative to the
/// reference's range) and the difference at the last output time; then the costs.
impl fmt::Display for Comparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{} against {}", self.reduced, self.reference)?;
        writeln!(
            f,
            "  {:<22} {:>12} {:>9} {:>10} {:>12}",
            "observable", "max |diff|", "at t", "relative", "diff at end"
        )?;
        for d in &self.differences {
            let last = d.values.last().copied().unwrap_or(0.0);
            writeln!(
                f,
                "  {:<22} {:>12.4e} {:>9.2} {:>10.2e} {:>12.4e}",
                d.name, d.max_abs, d.at_time, d.max_relative, last
            )?;
        }
        for (name, cost) in [
            (&self.reference, self.reference_cost),
            (&self.reduced, self.reduced_cost),
        ] {
            writeln!(
                f,
                "  cost of {:<30} {:>7} steps {:>8} evaluations {:>10.3} ms",
                name,
                cost.steps,
                cost.evaluations,
                cost.wall_time.as_secs_f64() * 1e3
            )?;
        }
        Ok(())
    }
}
