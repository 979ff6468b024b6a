//! Failures are typed errors with the time and the state, never a silent NaN.

mod support;

use support::problems::{KeplerProblem, OscillatorProblem, RocketProblem};
use support::{solve, Method, Problem};
use varmass_core::steppers::{
    AdaptiveControl, ClassicalRk4, DormandPrince, ExplicitEuler, FixedStep, StepControl,
};
use varmass_core::{run, RunConfig, StepError, StepErrorKind, Stepper};

/// Explicit Euler multiplies the oscillator's amplitude by √(1 + (ωh)²) per step; with
/// ωh = 20 it overflows after about 240 steps. The error must name the time and carry the
/// state, and that time must be a step time.
#[test]
fn a_step_far_past_the_stability_limit_gives_non_finite_state() {
    let problem = OscillatorProblem::standard();
    let step = 10.0;
    let stepper =
        ExplicitEuler::new(&problem.system, 0.0, problem.exact(0.0), FixedStep { step }).unwrap();
    let error = support::integrate(stepper, 1e6).unwrap_err();
    let StepError {
        time,
        state,
        kind: StepErrorKind::NonFiniteState,
    } = error
    else {
        panic!("expected NonFiniteState, got {error:?}");
    };
    assert!(time.is_finite() && time > 0.0);
    assert_eq!(time % step, 0.0, "{time}");
    assert!(state.iter().any(|x| !x.is_finite()));
}

/// The same with Dormand–Prince forced to a fixed step 30 times its stability limit.
#[test]
fn fixed_dormand_prince_past_stability_is_a_typed_error() {
    let problem = OscillatorProblem::standard();
    let stepper = DormandPrince::new(
        &problem.system,
        0.0,
        problem.exact(0.0),
        StepControl::Fixed(FixedStep { step: 50.0 }),
    )
    .unwrap();
    let error = support::integrate(stepper, 1e9).unwrap_err();
    assert!(
        matches!(error.kind, StepErrorKind::NonFiniteState),
        "{error:?}"
    );
    assert!(error.time.is_finite());
}

/// A rocket run past burn-out (m = 0 at t = 20) must end in a typed error at or before the
/// burn-out, with every stepper, never in a NaN state.
#[test]
fn rocket_out_of_propellant_is_a_typed_error_for_every_stepper() {
    let mut problem = RocketProblem::standard();
    problem.end_time = 30.0;
    let steps = 300; // h = 0.1: t = 20 is a step time, where m = 0 exactly (up to rounding)
    for method in Method::ALL {
        let error = match solve(&problem, method, steps) {
            Ok((time, state)) => panic!("{method:?} ran through burn-out: {time} {state}"),
            Err(error) => error,
        };
        let time = error.time;
        eprintln!("{method:?}: {error}");
        assert!(time <= 20.0 + 0.1 + 1e-9, "{method:?}: {error:?}");
        assert!(
            matches!(
                error.kind,
                StepErrorKind::NonPositiveMass { index: 0 }
                    | StepErrorKind::SingularMassMatrix
                    | StepErrorKind::NewtonDivergence { .. }
            ),
            "{method:?}: {error:?}"
        );
        // The reported state is the offending one: finite, with the mass at or below zero,
        // except for a Newton failure, which reports the (valid) start of its step.
        let state = error.state;
        assert!(state.iter().all(|x| x.is_finite()), "{method:?}: {state}");
        if !matches!(error.kind, StepErrorKind::NewtonDivergence { .. }) {
            assert!(
                state[2] <= 0.0,
                "{method:?}: mass {} in {error:?}",
                state[2]
            );
        }
    }
}

/// The adaptive stepper treats a trial state with m ≤ 0 as a step too long and shrinks;
/// it cannot pass m = 0, so it ends with a typed error close to burn-out.
#[test]
fn adaptive_rocket_past_burn_out_fails_near_burn_out() {
    let problem = RocketProblem::standard();
    let mut stepper = DormandPrince::new(
        &problem.system,
        0.0,
        problem.initial_state(),
        StepControl::Adaptive(AdaptiveControl::default()),
    )
    .unwrap();
    let error = run(&mut stepper, &RunConfig::until(30.0), &[]).unwrap_err();
    let time = error.time;
    eprintln!("adaptive: {error}, {:?}", stepper.statistics());
    assert!((19.0..=20.0).contains(&time), "{error:?}");
    assert!(stepper.state().iter().all(|x| x.is_finite()));
    assert!(stepper.state()[2] > 0.0);
}

#[test]
fn invalid_configurations_are_rejected_before_stepping() {
    let problem = OscillatorProblem::standard();
    let y0 = problem.exact(0.0);
    for step in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let error = ClassicalRk4::new(&problem.system, 0.0, y0, FixedStep { step }).unwrap_err();
        assert!(
            matches!(error.kind, StepErrorKind::InvalidConfiguration { .. }),
            "{step}: {error}"
        );
    }
    let bad_tolerance = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: -1.0,
        ..Default::default()
    });
    assert!(DormandPrince::new(&problem.system, 0.0, y0, bad_tolerance).is_err());
    // An end time before the start.
    let mut stepper = ClassicalRk4::new(&problem.system, 1.0, y0, FixedStep { step: 0.1 }).unwrap();
    assert!(run(&mut stepper, &RunConfig::until(0.5), &[]).is_err());
    // A non-finite initial state is reported with its time.
    let mut nan_state = y0;
    nan_state[1] = f64::NAN;
    let error =
        ClassicalRk4::new(&problem.system, 2.0, nan_state, FixedStep { step: 0.1 }).unwrap_err();
    assert_eq!(error.kind, StepErrorKind::NonFiniteState);
    assert_eq!(error.time, 2.0);
    // A non-positive initial mass, with its index.
    let rocket = RocketProblem::standard();
    let mut empty = rocket.initial_state();
    empty[2] = 0.0;
    let error = ClassicalRk4::new(&rocket.system, 0.0, empty, FixedStep { step: 0.1 }).unwrap_err();
    assert!(
        matches!(error.kind, StepErrorKind::NonPositiveMass { index: 0 }),
        "{error:?}"
    );
}

#[test]
fn too_many_steps_is_reported_with_the_time_reached() {
    let problem = OscillatorProblem::standard();
    let mut stepper = ClassicalRk4::new(
        &problem.system,
        0.0,
        problem.exact(0.0),
        FixedStep { step: 0.1 },
    )
    .unwrap();
    let config = RunConfig {
        max_steps: 5,
        ..RunConfig::until(10.0)
    };
    let error = run(&mut stepper, &config, &[]).unwrap_err();
    let StepError {
        time,
        kind: StepErrorKind::TooManySteps { max_steps },
        ..
    } = error
    else {
        panic!("{error:?}");
    };
    assert_eq!(max_steps, 5);
    assert!((time - 0.5).abs() < 1e-12, "{time}");
}

/// Newton on the implicit midpoint rule with a step of a whole Kepler period cannot
/// converge (the stage equation has no nearby solution); the failure is typed.
#[test]
fn newton_failure_is_a_typed_error() {
    let problem = KeplerProblem::standard();
    let error = solve(&problem, Method::ImplicitMidpoint, 1).unwrap_err();
    eprintln!("Newton: {error}");
    assert!(error.time == 0.0, "{error:?}");
    assert!(
        matches!(
            error.kind,
            StepErrorKind::NewtonDivergence { .. }
                | StepErrorKind::NonFiniteState
                | StepErrorKind::SingularMassMatrix
        ),
        "{error:?}"
    );
}
