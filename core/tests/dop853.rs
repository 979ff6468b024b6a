//! DOP853 against closed forms: the order of convergence from step halving (fixed steps),
//! the order of its dense output, the tolerance it reaches adaptively, its work counts,
//! events located to 1e-10 in t, and a rocket running out of propellant.

mod support;

use std::f64::consts::PI;

use nalgebra::SVector;
use support::problems::{KeplerProblem, OscillatorProblem, RocketProblem};
use support::{integrate, Problem};
use varmass_core::steppers::{AdaptiveControl, Dop853, FixedStep, StepControl};
use varmass_core::{run, Direction, Event, RunConfig, StepErrorKind, Stepper, StopReason};

fn fixed(step: f64) -> StepControl {
    StepControl::Fixed(FixedStep { step })
}

fn tolerance(tolerance: f64) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..AdaptiveControl::dop853()
    })
}

/// The final error of `problem` in `steps` equal steps.
fn final_error<P: Problem<N, S>, const N: usize, const S: usize>(problem: &P, steps: usize) -> f64 {
    let step = problem.end_time() / steps as f64;
    let stepper = Dop853::new(problem.system(), 0.0, problem.initial_state(), fixed(step)).unwrap();
    let (time, state) = integrate(stepper, problem.end_time()).unwrap();
    problem.error(time, &state)
}

/// log₂(e(n)/e(2n)) for n = `coarsest` and 2n.
fn observed_order<P: Problem<N, S>, const N: usize, const S: usize>(
    problem: &P,
    coarsest: usize,
) -> f64 {
    let (coarse, fine) = (
        final_error(problem, coarsest),
        final_error(problem, 2 * coarsest),
    );
    eprintln!("{}: {coarse:e} → {fine:e}", P::NAME);
    (coarse / fine).log2()
}

/// The Kepler orbit's first quarter period from periapsis (through the periapsis passage,
/// the fastest part of the orbit).
fn kepler_quarter_orbit() -> KeplerProblem {
    let mut problem = KeplerProblem::standard();
    problem.end_time = 0.25 * problem.period();
    problem
}

/// Eighth order ± 0.3, each problem at step counts in its asymptotic range (where the
/// observed order settles as the steps shrink) and above its rounding floor. Measured:
///
/// * oscillator 8.01 (16 → 32 steps; 1.5e-10 → 5.9e-13, floor ~1e-14);
/// * rocket 7.89 (12 → 24; 4.7e-8 → 2.0e-10; 7.58 at 6 → 12, where the 1/m growth towards
///   burn-out is not yet resolved). Its error is absolute in y ~ 1e3, so its floor is ~1e-11:
///   24 → 48 is already on it;
/// * Kepler, first quarter orbit, 7.94 (20 → 40; 4.8e-11 → 1.9e-13, floor ~2e-15). In steps
///   of √2 from 10 to 56 steps it reads 7.88, 7.85, 7.92, 7.95, 8.20 (the last on the floor).
///
/// The orbit's three quarters (`KeplerProblem::standard`) are not in their asymptotic range
/// anywhere above rounding: in steps of √2 from 14 to 160 steps the observed order reads
/// 10.3, 7.6, 8.6, 7.3, 7.3, 7.6, 7.4 (errors 6e-7 … 7e-14), and the floor, ~1.5e-14, comes at
/// 226 steps, before it settles. Not a defect of this code: `ode_solvers`' DOP853, written
/// independently from the same paper, gives the same errors to five digits at fixed steps
/// on the benchmarks' three-orbit Kepler problem, where the observed order wanders from 9 to
/// 12 and back to 7.4 before its floor. Half an orbit reads 7.6 over 40 … 113 steps;
/// only the quarter orbit reaches 8 above the floor, so it is the Kepler case here.
#[test]
fn fixed_steps_converge_with_order_eight() {
    let orders = [
        observed_order(&OscillatorProblem::standard(), 16),
        observed_order(&RocketProblem::standard(), 12),
        observed_order(&kepler_quarter_orbit(), 20),
    ];
    eprintln!("orders {orders:?}");
    for order in orders {
        assert!((7.7..=8.3).contains(&order), "{orders:?}");
    }
}

/// The dense output between steps: the error at the middle of the last step of a fixed-step
/// run of the oscillator. The continuous extension has order 7 (local error O(h⁸)) and the
/// run's global error is O(h⁸): the observed order is 8 in the asymptotic range, 7 at worst.
/// Measured: 8.15 (12 → 24 steps).
#[test]
fn dense_output_converges_with_order_seven_or_more() {
    let problem = OscillatorProblem::standard();
    let error = |steps: usize| {
        let step = problem.end_time / steps as f64;
        let mut stepper =
            Dop853::new(&problem.system, 0.0, problem.exact(0.0), fixed(step)).unwrap();
        stepper.set_stop_time(problem.end_time).unwrap();
        for _ in 0..steps {
            stepper.step().unwrap();
        }
        let middle = problem.end_time - 0.5 * step;
        let dense = stepper.dense_output(middle).unwrap();
        (dense - problem.exact(middle)).norm() / problem.exact(0.0).norm()
    };
    let (coarse, fine) = (error(12), error(24));
    let order = (coarse / fine).log2();
    eprintln!("dense: {coarse:e} → {fine:e}, order {order}");
    assert!((6.7..=8.3).contains(&order), "{order}");
}

/// Adaptive runs meet their tolerance on the Kepler orbit to within a small factor, and
/// a tighter tolerance costs more steps. Measured errors: 1e-8 → 9.1e-9 (14 steps),
/// 1e-11 → 9.4e-12 (30 steps).
#[test]
fn adaptive_runs_follow_the_tolerance() {
    let problem = KeplerProblem::standard();
    let mut previous_steps = 0;
    for tol in [1e-8, 1e-11] {
        let stepper = Dop853::new(
            &problem.system,
            0.0,
            problem.initial_state(),
            tolerance(tol),
        )
        .unwrap();
        let mut stepper = stepper.without_dense_output();
        let solution = run(&mut stepper, &RunConfig::until(problem.end_time), &[]).unwrap();
        let (time, state) = solution.last().unwrap();
        let error = problem.error(time, state);
        let steps = solution.statistics.accepted_steps;
        eprintln!("tol {tol:e}: error {error:e} in {steps} steps");
        assert!(error < 10.0 * tol && error > 0.01 * tol, "{error:e}");
        assert!(steps > previous_steps);
        assert!(!solution.statistics.stiffness_detected);
        previous_steps = steps;
    }
}

/// Fixed steps count exactly: one rate at the start, then 11 new stages and the FSAL rate
/// per step, and 3 more for the dense output.
#[test]
fn each_step_costs_twelve_rates_and_three_more_for_the_dense_output() {
    let problem = OscillatorProblem::standard();
    let count = |dense: bool| {
        let stepper = Dop853::new(&problem.system, 0.0, problem.exact(0.0), fixed(0.1)).unwrap();
        let stepper = if dense {
            stepper
        } else {
            stepper.without_dense_output()
        };
        let dense_available = stepper.dense_output(0.0).is_some();
        let mut stepper = stepper;
        stepper.set_stop_time(1.0).unwrap();
        for _ in 0..10 {
            stepper.step().unwrap();
        }
        (dense_available, *stepper.statistics())
    };
    let (dense, with) = count(true);
    let (none, without) = count(false);
    assert!(dense && !none);
    assert_eq!(with.accepted_steps, 10);
    assert_eq!(with.rate_evaluations, 1 + 10 * 15);
    assert_eq!(without.rate_evaluations, 1 + 10 * 12);
}

/// Located to 1e-10 in t on the dense output, with steps far longer than that.
const TIME_TOLERANCE: f64 = 1e-10;

#[test]
fn oscillator_zero_crossing_is_located_on_the_dense_output() {
    let problem = OscillatorProblem::standard(); // x = cos 2t: first zero at π/4
    let mut stepper =
        Dop853::new(&problem.system, 0.0, problem.exact(0.0), tolerance(1e-12)).unwrap();
    let events = [Event::state_reaches(0, 0.0, Direction::Falling)];
    let solution = run(&mut stepper, &RunConfig::until(10.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let hit = solution.events[0];
    let statistics = solution.statistics;
    eprintln!(
        "crossing: {:e} after {} steps",
        hit.time - PI / 4.0,
        statistics.accepted_steps
    );
    // The steps are long (a handful over π/4), so the cubic Hermite fallback would not do.
    assert!(statistics.accepted_steps < 20, "{statistics:?}");
    assert!((hit.time - PI / 4.0).abs() < TIME_TOLERANCE, "{}", hit.time);
}

#[test]
fn rocket_height_event_against_the_closed_form() {
    let problem = RocketProblem::standard();
    let height = 2000.0;
    // y(t) from the closed form is increasing: bisection gives the reference time.
    let (mut low, mut high) = (0.0, 19.0);
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if problem.exact(middle)[0] < height {
            low = middle;
        } else {
            high = middle;
        }
    }
    let mut stepper =
        Dop853::new(&problem.system, 0.0, problem.exact(0.0), tolerance(1e-12)).unwrap();
    let events = [Event::state_reaches(0, height, Direction::Rising)];
    let solution = run(&mut stepper, &RunConfig::until(30.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let time = solution.events[0].time;
    eprintln!("height: {:e}", time - low);
    assert!((time - low).abs() < TIME_TOLERANCE, "{time} vs {low}");
}

/// Run past burn-out (m = 0 at t = 20): with a mass event, the run ends in it; without,
/// the adaptive stepper shrinks its steps towards burn-out and ends in a typed error
/// there, with a finite state. Never a NaN.
#[test]
fn rocket_out_of_propellant_ends_in_the_event_or_a_typed_error() {
    let problem = RocketProblem::standard();
    let start = problem.exact(0.0);
    let mut stepper = Dop853::new(&problem.system, 0.0, start, tolerance(1e-10)).unwrap();
    let events = [Event::mass_reaches(0, 1e-3)];
    let solution = run(&mut stepper, &RunConfig::until(30.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (time, state) = solution.last().unwrap();
    // m = 1 − 0.05 t reaches 1e-3 at t = 19.98.
    assert!((time - 19.98).abs() < TIME_TOLERANCE, "{time}");
    assert!(state.iter().all(|x| x.is_finite()), "{state}");

    let mut stepper = Dop853::new(&problem.system, 0.0, start, tolerance(1e-10)).unwrap();
    let error = run(&mut stepper, &RunConfig::until(30.0), &[]).unwrap_err();
    eprintln!("past burn-out: {error}");
    // The error's time is that of the failed trial state, t₀ + h, which rounding may put
    // an ulp or so past burn-out (measured: 20 + 1 ulp = 20.000000000000004).
    let time = error.time;
    assert!(
        (19.0..=20.0 * (1.0 + 4.0 * f64::EPSILON)).contains(&time),
        "{error:?}"
    );
    assert!(
        matches!(
            error.kind,
            StepErrorKind::System(varmass_core::SystemError::NonPositiveMass { index: 0, .. })
                | StepErrorKind::System(varmass_core::SystemError::SingularMassMatrix)
                | StepErrorKind::StepSizeUnderflow { .. }
                | StepErrorKind::NonFiniteState
        ),
        "{error:?}"
    );
    let state: &SVector<f64, 3> = &error.state;
    assert!(
        !state.iter().any(|x| x.is_nan()),
        "a NaN in the error's state {state}"
    );
}
