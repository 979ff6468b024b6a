//! Recording chosen observables at chosen output times through dense output: the values
//! match the closed form between steps, the work is the plain run's, named quantities are
//! the system's, and bad output times are typed errors.

mod support;

use support::problems::OscillatorProblem;
use support::Problem;
use varmass_core::nalgebra::SVector;
use varmass_core::steppers::{ClassicalRk4, DormandPrince, FixedStep, StepControl};
use varmass_core::{
    observe, run, Observable, RunConfig, StepErrorKind, Stepper, VariableMassSystem,
};

/// 31 output times over [0, 3], none of them on a step of h = 0.07.
fn output_times() -> Vec<f64> {
    (0..=30).map(|k| 0.1 * k as f64).collect()
}

/// The worst error of x and H at the output times against x = cos ωt and H = k/2.
fn worst_errors<St>(problem: &OscillatorProblem, stepper: &mut St) -> (f64, f64, usize)
where
    St: Stepper<1, 2>,
{
    let position = |_t: f64, state: &SVector<f64, 2>| state[0];
    let observables = [
        Observable::function("x", &position),
        Observable::hamiltonian(),
    ];
    let times = output_times();
    let recording = observe(stepper, &times, &observables).expect("the run succeeds");
    assert_eq!(recording.times, times);
    assert_eq!(recording.names, ["x", "H"]);
    let energy = 0.5 * problem.system.stiffness;
    let mut worst = (0.0f64, 0.0f64);
    for (index, &t) in times.iter().enumerate() {
        let x = recording.value(index, "x").expect("recorded");
        let h = recording.value(index, "H").expect("recorded");
        worst.0 = worst.0.max((x - problem.exact(t)[0]).abs());
        worst.1 = worst.1.max((h - energy).abs() / energy);
    }
    (worst.0, worst.1, recording.statistics.accepted_steps)
}

#[test]
fn dense_output_of_dormand_prince_matches_the_closed_form_between_steps() {
    let problem = OscillatorProblem::standard();
    let control = StepControl::default();
    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.initial_state(), control).unwrap();
    let (x, h, steps) = worst_errors(&problem, &mut stepper);
    // The same run without output times takes the same steps: output does not shorten them.
    let mut plain =
        DormandPrince::new(&problem.system, 0.0, problem.initial_state(), control).unwrap();
    let solution = run(&mut plain, &RunConfig::until(3.0), &[]).unwrap();
    assert_eq!(steps, solution.statistics.accepted_steps);
    // Measured with the default tolerances (1e-6 relative): x 4.4e-7, H 1.0e-6; the bound is
    // the tolerance times a margin of 10.
    assert!(x < 1e-5 && h < 1e-5, "x {x:e}, H {h:e}");
}

#[test]
fn hermite_interpolation_serves_a_stepper_without_dense_output() {
    let problem = OscillatorProblem::standard();
    let fixed = FixedStep { step: 0.07 };
    let start = problem.initial_state();
    let mut stepper = ClassicalRk4::new(&problem.system, 0.0, start, fixed).unwrap();
    let (x, h, steps) = worst_errors(&problem, &mut stepper);
    // ⌈3 / 0.07⌉ = 43 steps, the last one shortened to end at 3.
    assert_eq!(steps, 43);
    // RK4's own error at the ends of its steps, from a plain run.
    let mut plain = ClassicalRk4::new(&problem.system, 0.0, start, fixed).unwrap();
    let solution = run(&mut plain, &RunConfig::until(3.0), &[]).unwrap();
    let at_steps = solution
        .times
        .iter()
        .zip(&solution.states)
        .map(|(&t, state)| (state[0] - problem.exact(t)[0]).abs())
        .fold(0.0f64, f64::max);
    // Between the steps the cubic Hermite interpolant adds at most h⁴ max|x⁗|/384
    // = (ωh)⁴/384 = 1.0e-6 of the unit amplitude. Measured: x 1.6e-5, as at the steps'
    // ends (RK4's own error dominates); H 6.2e-6.
    let hermite_bound = (problem.frequency() * 0.07f64).powi(4) / 384.0;
    assert!(
        x <= at_steps + hermite_bound,
        "x {x:e}, at steps {at_steps:e}"
    );
    assert!(h < 1e-5, "H {h:e}");
}

#[test]
fn named_quantities_are_the_systems() {
    let problem = OscillatorProblem::standard();
    let mut stepper = DormandPrince::new(
        &problem.system,
        0.0,
        problem.initial_state(),
        StepControl::default(),
    )
    .unwrap();
    let recording = observe(&mut stepper, &[1.0, 2.0], &[Observable::power()]).unwrap();
    // A conservative oscillator: no power at all, to rounding.
    let power = recording.series("power");
    assert_eq!(power.len(), 2);
    let scale = problem.system.stiffness * problem.frequency();
    assert!(power.iter().all(|p| p.abs() < 1e-9 * scale), "{power:?}");
    assert_eq!(
        problem.system.power(0.0, &problem.initial_state()).unwrap(),
        0.0
    );
}

#[test]
fn bad_output_times_are_typed_errors_at_the_start() {
    let problem = OscillatorProblem::standard();
    let fixed = FixedStep { step: 0.1 };
    let cases: [(&[f64], &str); 3] = [
        (&[0.5, 0.2], "the output times are not ascending"),
        (&[-1.0, 1.0], "an output time is before the stepper's time"),
        (&[0.5, f64::NAN], "an output time is not finite"),
    ];
    for (times, reason) in cases {
        let mut stepper =
            ClassicalRk4::new(&problem.system, 0.0, problem.initial_state(), fixed).unwrap();
        let error = observe(&mut stepper, times, &[Observable::hamiltonian()]).unwrap_err();
        assert_eq!(error.kind, StepErrorKind::InvalidConfiguration { reason });
        assert_eq!(error.time, 0.0);
    }
}

#[test]
fn a_non_finite_observable_is_a_typed_error_with_its_time() {
    let problem = OscillatorProblem::standard();
    let fixed = FixedStep { step: 0.1 };
    let mut stepper =
        ClassicalRk4::new(&problem.system, 0.0, problem.initial_state(), fixed).unwrap();
    // ln(x) is NaN once x = cos 2t is negative, first at the output time 1.0 (cos 2 < 0).
    let log = |_t: f64, state: &SVector<f64, 2>| state[0].ln();
    let error = observe(
        &mut stepper,
        &[0.5, 1.0, 1.5],
        &[Observable::function("ln x", &log)],
    )
    .unwrap_err();
    assert_eq!(error.kind, StepErrorKind::NonFiniteState);
    assert_eq!(error.time, 1.0);
}
