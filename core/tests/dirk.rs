//! The two diagonally implicit steppers — SDIRK4 (Hairer's `sdirk4.f`) and ESDIRK4(3)6L[2]SA
//! (Kennedy & Carpenter), one [`Dirk`] with two tableaus — against closed forms: the order
//! of convergence from step halving (fixed steps), the order of the dense output, the
//! tolerance reached adaptively, events located to 1e-10 in t, and the typed errors (Newton
//! failure, step-size underflow, a rocket out of propellant). Every test runs for both
//! methods with the same bounds; what was measured for each is in its comment. Their use
//! on a stiff scene is tested in the root crate (`tests/stiff_pendulum.rs`).
//!
//! On the linear oscillator the two fixed-step errors agree to 9 digits (2.569e-6 at 40
//! steps): both are L-stable of order 4 with implicit stages of γ = 1/4, which fixes the
//! stability function R(z) = P₄(z)/(1 − z/4)⁵, so they differ only on nonlinear problems.

mod support;

use std::any::type_name;
use std::f64::consts::PI;

use support::problems::{KeplerProblem, OscillatorProblem, RocketProblem};
use support::{integrate, Problem};
use varmass_core::steppers::{
    AdaptiveControl, Dirk, DirkMethod, DirkNewton, Esdirk43Method, FixedStep, Sdirk4Method,
    StepControl,
};
use varmass_core::{run, Direction, Event, RunConfig, StepErrorKind, Stepper, StopReason};

fn fixed(step: f64) -> StepControl {
    StepControl::Fixed(FixedStep { step })
}

fn tolerance(tolerance: f64) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..AdaptiveControl::sdirk4()
    })
}

/// The final error of `problem` in `steps` equal steps of method `T`.
fn final_error<T, const M: usize, P, const N: usize, const S: usize>(
    problem: &P,
    steps: usize,
) -> f64
where
    T: DirkMethod<M>,
    P: Problem<N, S>,
{
    let step = problem.end_time() / steps as f64;
    let (system, start) = (problem.system(), problem.initial_state());
    let stepper = Dirk::<_, T, N, S, M>::new(system, 0.0, start, fixed(step)).unwrap();
    let (time, state) = integrate(stepper, problem.end_time()).unwrap();
    problem.error(time, &state)
}

/// log₂(e(n)/e(2n)) for n = `coarsest` and 2n.
fn observed_order<T, const M: usize, P, const N: usize, const S: usize>(
    problem: &P,
    coarsest: usize,
) -> f64
where
    T: DirkMethod<M>,
    P: Problem<N, S>,
{
    let coarse = final_error::<T, M, P, N, S>(problem, coarsest);
    let fine = final_error::<T, M, P, N, S>(problem, 2 * coarsest);
    eprintln!("{} {}: {coarse:e} → {fine:e}", type_name::<T>(), P::NAME);
    (coarse / fine).log2()
}

/// Fourth order ± 0.3. Measured (oscillator 40 → 80 steps, rocket 40 → 80, Kepler 160 →
/// 320): SDIRK4 4.00, 4.11, 4.01; ESDIRK4(3) 4.00, 3.99, 3.99.
#[test]
fn fixed_steps_converge_with_order_four() {
    fn orders<T: DirkMethod<M>, const M: usize>() {
        let orders = [
            observed_order::<T, M, _, _, _>(&OscillatorProblem::standard(), 40),
            observed_order::<T, M, _, _, _>(&RocketProblem::standard(), 40),
            observed_order::<T, M, _, _, _>(&KeplerProblem::standard(), 160),
        ];
        eprintln!("{} orders {orders:?}", type_name::<T>());
        for order in orders {
            assert!((3.7..=4.3).contains(&order), "{orders:?}");
        }
    }
    orders::<Sdirk4Method, 5>();
    orders::<Esdirk43Method, 6>();
}

/// The dense output at the middle of the last step of a fixed-step run: the continuous
/// extension has order 3 (local error O(h⁴)), so the observed order is 4 at most and 3 at
/// least. Measured (40 → 80 steps, the global error dominates): SDIRK4 3.95, ESDIRK4(3)
/// 3.94.
#[test]
fn dense_output_converges_with_order_three_or_more() {
    fn dense<T: DirkMethod<M>, const M: usize>() {
        let problem = OscillatorProblem::standard();
        let error = |steps: usize| {
            let step = problem.end_time / steps as f64;
            let start = problem.exact(0.0);
            let mut stepper =
                Dirk::<_, T, _, _, M>::new(&problem.system, 0.0, start, fixed(step)).unwrap();
            stepper.set_stop_time(problem.end_time).unwrap();
            for _ in 0..steps {
                stepper.step().unwrap();
            }
            let middle = problem.end_time - 0.5 * step;
            let dense = stepper.dense_output(middle).unwrap();
            (dense - problem.exact(middle)).norm() / problem.exact(0.0).norm()
        };
        let (coarse, fine) = (error(40), error(80));
        let order = (coarse / fine).log2();
        eprintln!(
            "{} dense: {coarse:e} → {fine:e}, order {order}",
            type_name::<T>()
        );
        assert!((2.7..=4.3).contains(&order), "{order}");
    }
    dense::<Sdirk4Method, 5>();
    dense::<Esdirk43Method, 6>();
}

/// The global error of adaptive runs on the Kepler orbit is proportional to the tolerance
/// (the control is local); the bound is 100 × the tolerance, and a 1000× tighter tolerance
/// must give an error at least 300× smaller. Measured: SDIRK4 1.6e-5 at 1e-6 (38 steps),
/// 2.7e-9 at 1e-9 (211 steps); ESDIRK4(3) 5.3e-5 (21 steps), 7.5e-8 (103 steps, 705×
/// smaller: its filtered third-order estimate lets the steps grow longer).
#[test]
fn adaptive_runs_follow_the_tolerance() {
    fn adaptive<T: DirkMethod<M>, const M: usize>() {
        let problem = KeplerProblem::standard();
        let mut previous_steps = 0;
        let mut previous_error = f64::INFINITY;
        for tol in [1e-6, 1e-9] {
            let start = problem.initial_state();
            let mut stepper =
                Dirk::<_, T, _, _, M>::new(&problem.system, 0.0, start, tolerance(tol)).unwrap();
            let solution = run(&mut stepper, &RunConfig::until(problem.end_time), &[]).unwrap();
            let (time, state) = solution.last().unwrap();
            let error = problem.error(time, state);
            let statistics = solution.statistics;
            eprintln!(
                "{} tol {tol:e}: error {error:e}, {statistics:?}",
                type_name::<T>()
            );
            assert!(error < 100.0 * tol, "{error:e}");
            assert!(error < previous_error / 300.0 || previous_error.is_infinite());
            previous_error = error;
            assert!(statistics.accepted_steps > previous_steps);
            assert!(statistics.jacobian_evaluations >= 1);
            assert!(statistics.newton_iterations >= 5 * statistics.accepted_steps);
            previous_steps = statistics.accepted_steps;
        }
    }
    adaptive::<Sdirk4Method, 5>();
    adaptive::<Esdirk43Method, 6>();
}

/// Located to 1e-10 in t on the dense output.
const TIME_TOLERANCE: f64 = 1e-10;

/// x = cos 2t: the first zero at π/4. Measured: ESDIRK4(3) within 2.8e-12.
#[test]
fn oscillator_zero_crossing_is_located_on_the_dense_output() {
    fn crossing<T: DirkMethod<M>, const M: usize>() {
        let problem = OscillatorProblem::standard();
        let start = problem.exact(0.0);
        let mut stepper =
            Dirk::<_, T, _, _, M>::new(&problem.system, 0.0, start, tolerance(1e-12)).unwrap();
        let events = [Event::state_reaches(0, 0.0, Direction::Falling)];
        let solution = run(&mut stepper, &RunConfig::until(10.0), &events).unwrap();
        assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
        let hit = solution.events[0];
        eprintln!(
            "{} crossing: {:e} after {} steps",
            type_name::<T>(),
            hit.time - PI / 4.0,
            solution.statistics.accepted_steps
        );
        assert!((hit.time - PI / 4.0).abs() < TIME_TOLERANCE, "{}", hit.time);
    }
    crossing::<Sdirk4Method, 5>();
    crossing::<Esdirk43Method, 6>();
}

/// Run past burn-out (m = 0 at t = 20): with a mass event the run ends in it; without,
/// it ends in a typed error at burn-out with a finite state. Never a NaN.
#[test]
fn rocket_out_of_propellant_ends_in_the_event_or_a_typed_error() {
    fn burn_out<T: DirkMethod<M>, const M: usize>() {
        let problem = RocketProblem::standard();
        let start = problem.exact(0.0);
        let new = || Dirk::<_, T, _, _, M>::new(&problem.system, 0.0, start, tolerance(1e-10));
        let mut stepper = new().unwrap();
        let events = [Event::mass_reaches(0, 1e-3)];
        let solution = run(&mut stepper, &RunConfig::until(30.0), &events).unwrap();
        assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
        let (time, state) = solution.last().unwrap();
        // m = 1 − 0.05 t reaches 1e-3 at t = 19.98.
        assert!((time - 19.98).abs() < TIME_TOLERANCE, "{time}");
        assert!(state.iter().all(|x| x.is_finite()), "{state}");

        let mut stepper = new().unwrap();
        let error = run(&mut stepper, &RunConfig::until(30.0), &[]).unwrap_err();
        eprintln!("{} past burn-out: {error}", type_name::<T>());
        let time = error.time;
        assert!((19.0..=20.0).contains(&time), "{error:?}");
        assert!(
            matches!(
                error.kind,
                StepErrorKind::System(varmass_core::SystemError::NonPositiveMass { index: 0, .. })
                    | StepErrorKind::System(varmass_core::SystemError::SingularMassMatrix)
                    | StepErrorKind::NewtonDivergence { .. }
            ),
            "{error:?}"
        );
        let state = &error.state;
        assert!(state.iter().all(|x| !x.is_nan()), "{state}");
    }
    burn_out::<Sdirk4Method, 5>();
    burn_out::<Esdirk43Method, 6>();
}

/// A fixed step of half the Kepler period with two Newton iterations allowed cannot
/// converge: the step fails with a typed Newton error at its start, t = 0. One iteration
/// is refused as a configuration.
#[test]
fn newton_failure_is_a_typed_error_at_the_start_of_the_step() {
    fn newton<T: DirkMethod<M>, const M: usize>() {
        let problem = KeplerProblem::standard();
        let step = 0.5 * problem.period();
        let start = problem.initial_state();
        let new = || Dirk::<_, T, _, _, M>::new(&problem.system, 0.0, start, fixed(step));
        let two = DirkNewton {
            max_iterations: 2,
            ..DirkNewton::default()
        };
        let stepper = new().unwrap().with_newton(two).unwrap();
        let error = integrate(stepper, problem.end_time).unwrap_err();
        eprintln!("{} {error:?}", type_name::<T>());
        assert!(
            matches!(error.kind, StepErrorKind::NewtonDivergence { .. }) && error.time == 0.0,
            "{error:?}"
        );
        let one = DirkNewton {
            max_iterations: 1,
            ..DirkNewton::default()
        };
        let error = new().unwrap().with_newton(one).unwrap_err();
        assert!(matches!(
            error.kind,
            StepErrorKind::InvalidConfiguration { .. }
        ));
    }
    newton::<Sdirk4Method, 5>();
    newton::<Esdirk43Method, 6>();
}

/// A step too small to advance the time is a typed underflow error at the start time,
/// carrying the step: at t = 1e20 a step of 1e-3 rounds away (the spacing of doubles
/// there is 16 384).
#[test]
fn a_step_that_cannot_advance_the_time_is_a_typed_underflow() {
    fn underflow<T: DirkMethod<M>, const M: usize>() {
        let problem = OscillatorProblem::standard();
        let start_time = 1e20;
        let control = StepControl::Adaptive(AdaptiveControl {
            initial_step: Some(1e-3),
            ..AdaptiveControl::sdirk4()
        });
        let start = problem.exact(0.0);
        let stepper =
            Dirk::<_, T, _, _, M>::new(&problem.system, start_time, start, control).unwrap();
        let error = integrate(stepper, start_time + 1e6).unwrap_err();
        assert_eq!(error.time, start_time, "{error:?}");
        assert_eq!(
            error.kind,
            StepErrorKind::StepSizeUnderflow { step: 1e-3 },
            "{error:?}"
        );
        assert_eq!(error.state, start);
    }
    underflow::<Sdirk4Method, 5>();
    underflow::<Esdirk43Method, 6>();
}
