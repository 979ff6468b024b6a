//! The steppers' inner loop allocates nothing: a counting global allocator sees zero
//! allocations during N calls of `step()` after setup, for every stepper.

#[path = "support/counting.rs"]
mod counting;
mod support;

use counting::allocations;
use support::problems::{KeplerProblem, RocketProblem};
use support::Problem;
use varmass_core::nalgebra::SVector;
use varmass_core::steppers::{
    AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, Esdirk43, ExplicitEuler, FixedStep,
    ImplicitMidpoint, ImplicitMidpointConfig, Sdirk4, StepControl, Taylor, TaylorControl,
    Variational, VariationalConfig,
};
use varmass_core::tolerance::{Floor, Tolerance};
use varmass_core::{observe, Observable, Stepper};

/// Allocations made during `steps` calls of `step()` (after the stepper is built).
fn allocations_while_stepping<St, const N: usize, const S: usize>(
    mut stepper: St,
    steps: usize,
) -> usize
where
    St: Stepper<N, S>,
{
    let before = allocations();
    for _ in 0..steps {
        if stepper.step().is_err() {
            // Cannot happen on these problems; make it fail the test without a panic
            // message that would itself allocate before the count is read.
            return usize::MAX;
        }
    }
    allocations() - before
}

#[test]
fn steppers_do_not_allocate_per_step() {
    // The counter must see allocations at all, or the test could not fail.
    let probe = allocations();
    let boxed = std::hint::black_box(Box::new(1.0));
    assert!(allocations() > probe);
    drop(boxed);

    let kepler = KeplerProblem::standard();
    let (system, y0) = (&kepler.system, kepler.initial_state());
    let fixed = FixedStep { step: 1e-3 };
    let steps = 1000;
    let counts = [
        (
            "Euler",
            allocations_while_stepping(ExplicitEuler::new(system, 0.0, y0, fixed).unwrap(), steps),
        ),
        (
            "RK4",
            allocations_while_stepping(ClassicalRk4::new(system, 0.0, y0, fixed).unwrap(), steps),
        ),
        (
            "Dormand–Prince",
            allocations_while_stepping(
                DormandPrince::new(system, 0.0, y0, StepControl::default()).unwrap(),
                steps,
            ),
        ),
        (
            "DOP853",
            allocations_while_stepping(
                Dop853::new(
                    system,
                    0.0,
                    y0,
                    StepControl::Adaptive(AdaptiveControl::dop853()),
                )
                .unwrap(),
                steps,
            ),
        ),
        (
            "SDIRK4",
            allocations_while_stepping(
                Sdirk4::new(
                    system,
                    0.0,
                    y0,
                    StepControl::Adaptive(AdaptiveControl::sdirk4()),
                )
                .unwrap(),
                steps,
            ),
        ),
        (
            "ESDIRK4(3)",
            allocations_while_stepping(
                Esdirk43::new(
                    system,
                    0.0,
                    y0,
                    StepControl::Adaptive(AdaptiveControl::sdirk4()),
                )
                .unwrap(),
                steps,
            ),
        ),
        (
            "Taylor",
            allocations_while_stepping(
                Taylor::new(
                    system,
                    0.0,
                    y0,
                    TaylorControl::adaptive(
                        Tolerance::for_floor(1e-12, 1e-12, Floor::Taylor).unwrap(),
                    ),
                )
                .unwrap(),
                steps,
            ),
        ),
        (
            "implicit midpoint",
            allocations_while_stepping(
                ImplicitMidpoint::new(system, 0.0, y0, ImplicitMidpointConfig::default()).unwrap(),
                steps,
            ),
        ),
    ];
    // The variational stepper on the rocket, which has a state mass (S = 3).
    let rocket = RocketProblem::standard();
    let variational = allocations_while_stepping(
        Variational::new(
            &rocket.system,
            0.0,
            rocket.initial_state(),
            VariationalConfig::default(),
        )
        .unwrap(),
        steps,
    );
    for (name, count) in counts {
        assert_eq!(count, 0, "{name} allocated");
    }
    assert_eq!(variational, 0, "variational allocated");
}

/// Allocations made by one `observe` of `times` with a fixed RK4 step `step`.
fn allocations_while_observing(step: f64, times: &[f64]) -> usize {
    let kepler = KeplerProblem::standard();
    let (system, y0) = (&kepler.system, kepler.initial_state());
    let Ok(mut stepper) = ClassicalRk4::new(system, 0.0, y0, FixedStep { step }) else {
        return usize::MAX;
    };
    let radius = |_t: f64, state: &SVector<f64, 4>| state[0].hypot(state[1]);
    let observables = [
        Observable::function("r", &radius),
        Observable::hamiltonian(),
    ];
    let before = allocations();
    let recorded = observe(&mut stepper, times, &observables);
    let count = allocations() - before;
    match recorded {
        Ok(recording) if recording.times.len() == times.len() => count,
        _ => usize::MAX,
    }
}

#[test]
fn observing_allocates_the_recording_once_whatever_the_number_of_steps() {
    let times: Vec<f64> = (1..=50).map(|k| 0.02 * k as f64).collect();
    // 1000 and 10 000 steps to t = 1: the same allocations (the recording's vectors and the
    // names), so none is made per step or per output.
    let coarse = allocations_while_observing(1e-3, &times);
    let fine = allocations_while_observing(1e-4, &times);
    assert_eq!(coarse, fine);
    // By construction 5: the times, the values, the vector of names and its two strings.
    assert!(coarse <= 5, "{coarse} allocations");
}
