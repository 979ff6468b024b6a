//! A run that fails keeps what it computed: the `RunError` carries the typed error and the
//! solution up to the last accepted point.

mod support;

use support::problems::RocketProblem;
use support::Problem;
use varmass_core::steppers::{AdaptiveControl, DormandPrince, StepControl};
use varmass_core::{run, RunConfig, StepError, StepErrorKind, StopReason};

/// The standard rocket (m0 = 1, μ = 0.05) burns out at t = 20; run to 30 it fails there
/// (`errors.rs` pins the time), and the points before the failure are kept: they follow the
/// closed form, end at or before the failure, and the solution says it failed.
#[test]
fn a_rocket_that_runs_out_keeps_its_points() {
    let problem = RocketProblem::standard();
    let control = StepControl::Adaptive(AdaptiveControl::default());
    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.initial_state(), control).unwrap();
    let failure = run(&mut stepper, &RunConfig::until(30.0), &[]).unwrap_err();
    // The error reads as before through the RunError.
    assert_eq!(
        failure.kind,
        StepErrorKind::System(varmass_core::SystemError::NonPositiveMass { index: 0 })
    );
    assert!(
        failure.time <= 20.0 && 20.0 - failure.time < 1e-13,
        "{failure:?}"
    );
    let partial = &failure.partial;
    assert_eq!(partial.stop, StopReason::Failed);
    assert!(partial.times.len() > 20, "{} points", partial.times.len());
    assert!(partial.times.windows(2).all(|w| w[0] < w[1]));
    let (last, _) = partial.last().expect("points");
    assert!(last <= failure.time, "last point {last} after the failure");
    // Every kept point is on the closed form where it is smooth (m ≥ 0.1 of m0 = 1, up to
    // t = 18), relative to the state's size: measured at most 2.2e-7 at the default
    // tolerance 1e-6; bound 1e-6.
    let smooth = partial.times.iter().zip(&partial.states);
    let mut worst: f64 = 0.0;
    for (&time, state) in smooth.filter(|(t, _)| **t <= 18.0) {
        let error = problem.error(time, state) / problem.exact(time).norm();
        worst = worst.max(error);
    }
    assert!(worst < 1e-6, "worst relative error {worst:e}");
    assert_eq!(
        partial.statistics,
        *varmass_core::Stepper::statistics(&stepper)
    );
    // `?` turns it into the StepError a caller returns.
    let as_step_error: StepError<3> = failure.clone().into();
    assert_eq!(as_step_error, failure.error);
}
