//! The Taylor stepper's adaptive control (Jorba & Zou 2005, §3.2): the order grows with the
//! tolerance as ⌈−½ ln ε + 1⌉, no step is rejected, the achieved error follows the
//! tolerance down to Kepler at 5e-15, and the dense output (the series itself) is as
//! accurate inside a step as at its ends.

mod support;

use support::problems::{KeplerProblem, OscillatorProblem};
use support::{integrate, Problem};
use varmass_core::steppers::{Taylor, TaylorControl};
use varmass_core::tolerance::{Floor, Tolerance};
use varmass_core::{StepOutcome, Stepper};

/// The error at the end of Kepler (e = 0.5, three quarters of an orbit) with tolerance
/// `tolerance` (relative and absolute), the order used and the statistics.
fn kepler(tolerance: f64) -> (f64, usize, varmass_core::Statistics) {
    let problem = KeplerProblem::standard();
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(tolerance, tolerance, Floor::Taylor).unwrap());
    let stepper = Taylor::new(&problem.system, 0.0, problem.initial_state(), control).unwrap();
    let mut stepper = stepper;
    stepper.set_stop_time(problem.end_time).unwrap();
    while stepper.step().unwrap() != StepOutcome::ReachedStopTime {}
    let error = problem.error(stepper.time(), stepper.state());
    (error, stepper.order(), *stepper.statistics())
}

#[test]
fn order_and_error_follow_the_tolerance_without_rejections() {
    let mut previous_steps = 0;
    for (tolerance, order, bound) in [
        // (ε, ⌈−½ ln ε + 1⌉, the bound on the achieved error with the measured value)
        (1e-6, 8, 1e-6),    // measured 1.9e-7
        (1e-9, 12, 1e-9),   // measured 3.6e-11
        (1e-12, 15, 1e-12), // measured 7.2e-14
        (1e-15, 19, 5e-15), // measured 9.6e-16
    ] {
        let (error, used, statistics) = kepler(tolerance);
        eprintln!("tolerance {tolerance:e}: order {used}, error {error:e}, {statistics:?}");
        assert_eq!(used, order, "tolerance {tolerance:e}");
        assert!(error <= bound, "tolerance {tolerance:e}: error {error:e}");
        assert_eq!(statistics.rejected_steps, 0);
        assert_eq!(statistics.rate_evaluations, statistics.accepted_steps);
        // The order absorbs the tolerance: steps grow slowly (J&Z: about linearly in
        // −ln ε / p, i.e. nearly constant).
        assert!(statistics.accepted_steps >= previous_steps);
        previous_steps = statistics.accepted_steps;
    }
    // Measured: 22 steps at 1e-6, 23 at 1e-9, 1e-12 and 1e-15.
    assert!(previous_steps <= 30, "{previous_steps} steps at 1e-15");
}

#[test]
fn dense_output_is_the_series_and_as_accurate_inside_a_step() {
    let problem = OscillatorProblem::standard();
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(1e-13, 1e-13, Floor::Taylor).unwrap());
    let mut stepper = Taylor::new(&problem.system, 0.0, problem.exact(0.0), control).unwrap();
    // Before the first step the dense output is the current state.
    assert_eq!(stepper.dense_output(0.0), Some(problem.exact(0.0)));
    let mut worst: f64 = 0.0;
    for _ in 0..20 {
        stepper.step().unwrap();
        let (t0, t1) = (stepper.progress().previous_time(), stepper.time());
        assert!(t1 - t0 > 0.1, "step {}", t1 - t0);
        // At the end of the step the dense output is the new state, bit for bit.
        assert_eq!(stepper.dense_output(t1), Some(*stepper.state()));
        assert_eq!(
            stepper.dense_output(t0),
            Some(*stepper.progress().previous_state())
        );
        for s in [0.17, 0.5, 0.83] {
            let t = t0 + s * (t1 - t0);
            let gap = (stepper.dense_output(t).unwrap() - problem.exact(t)).norm();
            worst = worst.max(gap);
        }
    }
    // Measured 1.3e-14 over 20 steps (mostly the error carried from the step ends);
    // bound 1e-13.
    assert!(worst < 1e-13, "{worst:e}");
}

#[test]
fn fixed_order_one_is_explicit_euler() {
    let problem = OscillatorProblem::standard();
    let y0 = problem.exact(0.0);
    let control = TaylorControl::Fixed {
        order: 1,
        step: 0.01,
    };
    let stepper = Taylor::new(&problem.system, 0.0, y0, control).unwrap();
    let (_, taylor) = integrate(stepper, 0.5).unwrap();
    let euler = varmass_core::steppers::ExplicitEuler::new(
        &problem.system,
        0.0,
        y0,
        varmass_core::steppers::FixedStep { step: 0.01 },
    )
    .unwrap();
    let (_, euler) = integrate(euler, 0.5).unwrap();
    // Both compute y + h f(y) with f from the same formulas, so agree to rounding.
    assert!((taylor - euler).norm() < 1e-13, "{taylor} vs {euler}");
}

#[test]
fn the_first_step_is_jorba_and_zous_from_the_last_two_coefficients() {
    // The oscillator m = 2, k = 8 (ω = 2) from x = 1, p = 0: x = cos 2t, p = −4 sin 2t, so
    // the coefficients at t = 0 are x[j] = ±2ʲ/j! (j even) and p[j] = ±4·2ʲ/j! (j odd), and
    // ‖y[j]‖∞ is the one that is not 0. ‖y‖∞ = 1, so rtol ‖y‖∞ ≤ atol: absolute mode,
    // ρⱼ = (1/‖y[j]‖∞)^(1/j), and J&Z's step (eqs. 3.9–3.12) is
    // h = min(ρₚ₋₁, ρₚ) e⁻² e^(−0.7/(p−1)), p = ⌈−½ ln ε + 1⌉ (8, 12, 15 below). The
    // stepper takes it as exp(min(ln ρ)) times the factor (issue 38); pow and exp(ln)
    // agree to a few ulps (measured: 1.6e-16, 0 and 1.5e-16 relative; bound 2e-15).
    let problem = OscillatorProblem::standard();
    for (tolerance, order) in [(1e-6, 8), (1e-9, 12), (1e-12, 15)] {
        let factorial = |j: usize| (1..=j).map(|i| i as f64).product::<f64>();
        let norm = |j: usize| {
            let scale = if j.is_multiple_of(2) { 1.0 } else { 4.0 };
            scale * 2f64.powi(j as i32) / factorial(j)
        };
        let radius = |j: usize| (1.0 / norm(j)).powf(1.0 / j as f64);
        let p = order as f64;
        let expected = radius(order - 1).min(radius(order)) * (-2.0 - 0.7 / (p - 1.0)).exp();
        let control = TaylorControl::adaptive(
            Tolerance::for_floor(tolerance, tolerance, Floor::Taylor).unwrap(),
        );
        let mut stepper = Taylor::new(&problem.system, 0.0, problem.exact(0.0), control).unwrap();
        stepper.step().unwrap();
        assert_eq!(stepper.order(), order, "tolerance {tolerance:e}");
        let h = stepper.time();
        let gap = (h - expected).abs() / expected;
        eprintln!("tolerance {tolerance:e}: h {h}, J&Z {expected}, relative gap {gap:e}");
        assert!(
            gap <= 2e-15,
            "tolerance {tolerance:e}: h {h} against {expected} ({gap:e})"
        );
    }
}
