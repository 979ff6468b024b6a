//! A purely relative tolerance (atol = 0) on a state with exactly-zero components: the error
//! norm must not become NaN (0/0) and reject every step.

mod support;

use support::problems::OscillatorProblem;
use support::Problem;
use varmass_core::steppers::{AdaptiveControl, DormandPrince, StepControl};
use varmass_core::{run, RunConfig, Stepper};

#[test]
fn purely_relative_tolerance_with_a_zero_component() {
    check_start(0.0);
}

#[test]
fn a_tiny_absolute_tolerance_does_not_overflow_the_first_step() {
    // ṗ / (atol + rtol·|p|) = 8/1e-300 overflows the norm of the first-step heuristic.
    check_start(1e-300);
}

fn check_start(absolute_tolerance: f64) {
    // x(0) = 1, p(0) = 0 exactly: the momentum's scale is rtol·|0| = 0 at the start.
    let problem = OscillatorProblem::standard();
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance,
        ..AdaptiveControl::default()
    });
    let mut stepper =
        DormandPrince::new(problem.system(), 0.0, problem.initial_state(), control).unwrap();
    let end = problem.end_time();
    let solution = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    let (time, state) = solution.last().unwrap();
    assert_eq!(time, end);
    // rtol 1e-10 per step over ~200 steps: measured 5.4e-11 at the end; 1e-9 leaves 20× for
    // other platforms' rounding, and an answer 1e-8 off fails (the amplitude is 1).
    assert!(
        problem.error(time, state) < 1e-9,
        "error {}",
        problem.error(time, state)
    );
    // Before the fix the first-step norm was NaN (atol = 0: the whole interval was tried
    // first and rejected eight times) or infinite (atol = 1e-300: a zero first step, a
    // StepSizeUnderflow). A start from the heuristic's small default needs only the few
    // rejections the strict relative control of p ≈ 0 causes.
    assert!(
        stepper.statistics().rejected_steps <= 4,
        "{:?}",
        stepper.statistics()
    );
}
