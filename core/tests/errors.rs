//! Failures are typed errors with the time and the state, never a silent NaN. Each test
//! matches the kind of failure and the time it was found, against a time derived by hand.

mod support;

use nalgebra::Complex;
use support::problems::{KeplerProblem, OscillatorProblem, RocketProblem};
use support::{solve, Method, Problem};
use varmass_core::steppers::{
    AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, ExplicitEuler, FixedStep,
    ImplicitMidpoint, ImplicitMidpointConfig, NewtonConfig, StepControl,
};
use varmass_core::{run, RunConfig, StepError, StepErrorKind, Stepper};

/// How many steps it takes the standard oscillator (x(0) = 1, p(0) = 0, m = 2, ω = 2) to
/// overflow under a method that multiplies its amplitude by `amplification` per step: the
/// amplitude in (x, p/(mω)) grows by that factor each step and the momentum is mω = 4 times
/// the amplitude, so the state passes f64::MAX after ln(MAX/4)/ln|R| steps. The step that
/// fails is the next whole one.
fn predicted_overflow_steps(amplification: f64) -> f64 {
    (f64::MAX / 4.0).ln() / amplification.ln()
}

/// Explicit Euler multiplies the oscillator's amplitude by |R(iωh)| = √(1 + (ωh)²) per step;
/// with ωh = 20 the state passes f64::MAX after 236.4 steps. The error must name the time
/// and carry the state, and that time must be the end of step 237.
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
    // Measured: t = 2370, the end of step 237.
    let predicted = predicted_overflow_steps((1.0f64 + 20.0 * 20.0).sqrt());
    assert_eq!(time % step, 0.0, "{time}");
    assert_eq!(
        time / step,
        predicted.ceil(),
        "t = {time}, predicted {predicted}"
    );
    assert!(state.iter().any(|x| !x.is_finite()));
}

/// The same with Dormand–Prince forced to a fixed step 30 times its stability limit: ωh =
/// 100, where its stability function R(z) = Σₖ₌₀⁵ zᵏ/k! + z⁶/600 (the weights bᵀAᵏ⁻¹𝟙 of the
/// tableau) has |R| = 1.66e9, so the state passes f64::MAX after 33.4 steps. A stage, larger
/// than the state by powers of ωh, may overflow first, but within step 34.
#[test]
fn fixed_dormand_prince_past_stability_is_a_typed_error() {
    let problem = OscillatorProblem::standard();
    let step = 50.0;
    let stepper = DormandPrince::new(
        &problem.system,
        0.0,
        problem.exact(0.0),
        StepControl::Fixed(FixedStep { step }),
    )
    .unwrap();
    let error = support::integrate(stepper, 1e9).unwrap_err();
    assert_eq!(error.kind, StepErrorKind::NonFiniteState, "{error:?}");
    let z = Complex::new(0.0, 100.0);
    let mut factorial = 1.0;
    let mut taylor = Complex::new(0.0, 0.0);
    for k in 0..=5 {
        factorial *= f64::from(k.max(1));
        taylor += z.powi(k) / factorial;
    }
    let predicted = predicted_overflow_steps((taylor + z.powi(6) / 600.0).norm());
    // Measured: t = 1690, the stage at 4/5 of step 34 (1650 → 1700).
    let failing_step = (error.time / step).ceil();
    assert_eq!(
        failing_step,
        predicted.ceil(),
        "t = {}, predicted {predicted}",
        error.time
    );
}

/// A rocket run past burn-out (m = 1 − 0.05 t = 0 at t = 20) must end in a typed error at
/// the burn-out, with every stepper, never in a NaN state.
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
        assert_eq!(
            error.kind,
            StepErrorKind::System(varmass_core::SystemError::NonPositiveMass { index: 0 }),
            "{method:?}: {error:?}"
        );
        // At the end of the step to t = 20 (measured 20 + 1.4e-14 after 200 additions of
        // 0.1); for the implicit midpoint rule, whose mass at t = 20 is still rounding-
        // positive, at the midpoint of the next step (measured 20.05 + 1.5e-14), where its
        // predictor sits. 1e-12 allows for rounding.
        let expected = match method {
            Method::ImplicitMidpoint => 20.05,
            _ => 20.0,
        };
        assert!(
            (error.time - expected).abs() < 1e-12,
            "{method:?}: {error:?}"
        );
        // The reported state is the offending one: finite, with the mass at or below zero.
        let state = error.state;
        assert!(state.iter().all(|x| x.is_finite()), "{method:?}: {state}");
        assert!(
            state[2] <= 0.0,
            "{method:?}: mass {} in {error:?}",
            state[2]
        );
    }
}

/// The adaptive stepper treats a trial state with m ≤ 0 as a step too long and shrinks;
/// it cannot pass m = 0 at t = 20, and once the step underflows it reports the cause (the
/// mass) at the last time it reached.
#[test]
fn adaptive_rocket_past_burn_out_fails_at_burn_out() {
    let problem = RocketProblem::standard();
    let mut stepper = DormandPrince::new(
        &problem.system,
        0.0,
        problem.initial_state(),
        StepControl::Adaptive(AdaptiveControl::default()),
    )
    .unwrap();
    let error = run(&mut stepper, &RunConfig::until(30.0), &[]).unwrap_err();
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass_core::SystemError::NonPositiveMass { index: 0 })
    );
    // Measured 20 − 3.6e-15 (one unit in the last place of 20); ten units asserted.
    assert!(
        error.time <= 20.0 && 20.0 - error.time < 10.0 * 3.6e-15,
        "{error:?}"
    );
    assert!(stepper.state().iter().all(|x| x.is_finite()));
    assert!(stepper.state()[2] > 0.0);
}

/// A bad configuration is reported before any step, at the stepper's time and state.
#[test]
fn invalid_configurations_are_rejected_before_stepping() {
    let problem = OscillatorProblem::standard();
    let y0 = problem.exact(0.0);
    let is_invalid =
        |error: &StepError<2>| matches!(error.kind, StepErrorKind::InvalidConfiguration { .. });
    for step in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let error = ClassicalRk4::new(&problem.system, 0.0, y0, FixedStep { step }).unwrap_err();
        assert!(is_invalid(&error), "{step}: {error}");
        assert_eq!((error.time, error.state), (0.0, y0), "{step}");
    }
    let bad_tolerance = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: -1.0,
        ..Default::default()
    });
    let error = DormandPrince::new(&problem.system, 0.5, y0, bad_tolerance).unwrap_err();
    assert!(is_invalid(&error), "{error}");
    assert_eq!((error.time, error.state), (0.5, y0));
    // An end time before the start.
    let mut stepper = ClassicalRk4::new(&problem.system, 1.0, y0, FixedStep { step: 0.1 }).unwrap();
    let error = run(&mut stepper, &RunConfig::until(0.5), &[]).unwrap_err();
    assert!(is_invalid(&error), "{error}");
    assert_eq!((error.time, error.state), (1.0, y0));
    // Newton settings of an implicit stepper: no iteration allowed, or no usable tolerance.
    for newton in [
        NewtonConfig {
            max_iterations: 0,
            ..NewtonConfig::default()
        },
        NewtonConfig {
            relative_tolerance: 0.0,
            absolute_tolerance: 0.0,
            ..NewtonConfig::default()
        },
    ] {
        let config = ImplicitMidpointConfig { step: 0.1, newton };
        let error = ImplicitMidpoint::new(&problem.system, 0.25, y0, config).unwrap_err();
        assert!(is_invalid(&error), "{newton:?}: {error}");
        assert_eq!((error.time, error.state), (0.25, y0), "{newton:?}");
    }
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
    let error = ClassicalRk4::new(&rocket.system, 3.0, empty, FixedStep { step: 0.1 }).unwrap_err();
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass_core::SystemError::NonPositiveMass { index: 0 })
    );
    assert_eq!(error.time, 3.0);
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
    let error = run(&mut stepper, &config, &[]).unwrap_err().error;
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
/// converge (the stage equation has no nearby solution); the failure is typed, and reported
/// at the start of the step.
#[test]
fn newton_failure_is_a_typed_error() {
    let problem = KeplerProblem::standard();
    let error = solve(&problem, Method::ImplicitMidpoint, 1).unwrap_err();
    // Measured: NewtonDivergence after all 25 iterations.
    assert!(
        matches!(error.kind, StepErrorKind::NewtonDivergence { .. }),
        "{error:?}"
    );
    assert_eq!((error.time, error.state), (0.0, problem.initial_state()));
}

/// A step whose end t + h overflows f64 is refused before it is taken, at the (finite)
/// start time and state, instead of accepting a state at t = ∞ (found by the `evaluate`
/// fuzz target: a start at 1.7e308 with h = 1e300 reported a failure "at t = inf").
#[test]
fn a_step_past_the_largest_time_is_a_typed_error_at_the_start() {
    let problem = OscillatorProblem::standard();
    let system = &problem.system;
    let y0 = problem.exact(0.0);
    let t0 = 1.79e308; // f64::MAX ≈ 1.7977e308: t0 + 1e306 overflows, t0 + 1e290 does not
    let fixed = FixedStep { step: 1e306 };
    let errors = [
        ExplicitEuler::new(system, t0, y0, fixed).unwrap().step(),
        ClassicalRk4::new(system, t0, y0, fixed).unwrap().step(),
        DormandPrince::new(system, t0, y0, StepControl::Fixed(fixed))
            .unwrap()
            .step(),
        Dop853::new(system, t0, y0, StepControl::Fixed(fixed))
            .unwrap()
            .step(),
        ImplicitMidpoint::new(
            system,
            t0,
            y0,
            ImplicitMidpointConfig {
                step: 1e306,
                ..Default::default()
            },
        )
        .unwrap()
        .step(),
    ];
    for (method, result) in errors.into_iter().enumerate() {
        let error = result.expect_err("a step to t = ∞ must fail");
        assert_eq!(
            error.kind,
            StepErrorKind::NonFiniteTime { step: 1e306 },
            "method {method}: {error:?}"
        );
        assert_eq!(error.time, t0, "method {method}");
        assert_eq!(error.state, y0, "method {method}");
    }
}

/// The Taylor stepper refuses a system without Taylor coefficients and bad settings at
/// construction, and reports a failure of the expansion with the time and state.
#[test]
fn taylor_configuration_and_expansion_errors_are_typed() {
    use varmass_core::steppers::{Taylor, TaylorControl};
    use varmass_core::tolerance::{Floor, Tolerance};
    let is_invalid =
        |error: &StepError<3>| matches!(error.kind, StepErrorKind::InvalidConfiguration { .. });
    // The hand-written rocket provides no Taylor coefficients.
    let rocket = RocketProblem::standard();
    let y0 = rocket.initial_state();
    let error = Taylor::new(&rocket.system, 1.5, y0, TaylorControl::default()).unwrap_err();
    assert!(is_invalid(&error), "{error}");
    assert_eq!((error.time, error.state), (1.5, y0));
    assert!(
        error.to_string().contains("emit = [..., \"taylor\"]"),
        "{error}"
    );
    let oscillator = OscillatorProblem::standard();
    let y0 = oscillator.exact(0.0);
    for control in [
        TaylorControl::Fixed {
            order: 0,
            step: 0.1,
        },
        TaylorControl::Fixed {
            order: 33,
            step: 0.1,
        },
        TaylorControl::Fixed {
            order: 4,
            step: -0.1,
        },
        TaylorControl::Fixed {
            order: 4,
            step: f64::NAN,
        },
        TaylorControl::Adaptive {
            tolerance: Tolerance::new(1e-6, 1e-9).unwrap(),
            max_step: 0.0,
        },
        // Usable by the head, finer than the double stepper's floor (1e-15).
        TaylorControl::adaptive(Tolerance::for_floor(5e-16, 5e-16, Floor::TaylorHead).unwrap()),
    ] {
        let error = Taylor::new(&oscillator.system, 0.5, y0, control).unwrap_err();
        assert!(
            matches!(error.kind, StepErrorKind::InvalidConfiguration { .. }),
            "{control:?}: {error}"
        );
        assert_eq!((error.time, error.state), (0.5, y0), "{control:?}");
    }
    // Unusable tolerances never reach the stepper: `Tolerance` refuses them.
    for (relative, absolute) in [(-1.0, 1e-9), (0.0, 0.0), (f64::NAN, 1e-9)] {
        assert!(Tolerance::for_floor(relative, absolute, Floor::Taylor).is_err());
    }
    // Kepler at r = 0: the expansion fails (1/r), reported at the start of the step.
    let kepler = KeplerProblem::standard();
    let mut singular = kepler.initial_state();
    let control = TaylorControl::adaptive(Tolerance::for_floor(1e-9, 1e-9, Floor::Taylor).unwrap());
    singular[0] = 0.0;
    let error = Taylor::new(&kepler.system, 0.25, singular, control).unwrap_err();
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass_core::SystemError::SingularMassMatrix)
    );
    assert_eq!(error.time, 0.25);
    // A fixed step far past the series' radius: h²⁰ = 1e400 overflows the sum to a
    // non-finite state, a typed error at the end of the step, never a silent NaN.
    let control = TaylorControl::Fixed {
        order: 20,
        step: 1e20,
    };
    let mut stepper = Taylor::new(&kepler.system, 0.0, kepler.initial_state(), control).unwrap();
    let error = stepper.step().unwrap_err();
    assert_eq!(error.kind, StepErrorKind::NonFiniteState, "{error}");
    assert_eq!(error.time, 1e20);
    assert_eq!(stepper.time(), 0.0);
}
