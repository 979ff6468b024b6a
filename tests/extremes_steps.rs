//! Extremes of the step (ARCHITECTURE.md#extremes): a long horizon of 10⁷ steps, and fixed steps at and past
//! the stability limit. Each test states what is expected.

mod validation_support;

use validation_support::{pendulums, Oscillator};
use varmass::core::nalgebra::Complex;
use varmass::core::steppers::{ImplicitMidpointConfig, VariationalConfig};
use varmass::core::Record;
use varmass::prelude::*;

/// m = k = 1: ω = 1 and H = (x² + p²)/2.
const UNIT: Oscillator = Oscillator { m0: 1.0, k: 1.0 };

/// H after `steps` steps of `stepper`, relative to H₀; and the largest |H/H₀ − 1| seen,
/// sampled every 1000 steps. Drives the stepper directly: a run would store every state
/// (10⁷ × 24 bytes).
fn energy_ratio<St>(mut stepper: St, steps: usize) -> (f64, f64)
where
    St: Stepper<1, 2, System = Oscillator>,
{
    let initial = UNIT.hamiltonian(0.0, stepper.state()).unwrap();
    let mut worst: f64 = 0.0;
    let mut ratio = 1.0;
    for step in 1..=steps {
        stepper.step().unwrap();
        if step % 1000 == 0 || step == steps {
            ratio = UNIT.hamiltonian(stepper.time(), stepper.state()).unwrap() / initial;
            worst = worst.max((ratio - 1.0).abs());
        }
    }
    (ratio, worst)
}

#[test]
fn rk4_drift_over_ten_million_steps_is_its_amplification_factor() {
    // Expectation: on ẋ = p, ṗ = −x RK4 multiplies |(x, p)| by |R(ih)| each step exactly,
    // |R(ih)|² = 1 − h⁶/72 + h⁸/576 (R the degree-4 Taylor polynomial of e^z), so after n
    // steps H/H₀ = |R(ih)|^(2n). With h = 0.1 and n = 10⁷ (1.6·10⁵ periods) that is
    // e^(−0.1389) ≈ 0.870: RK4 loses 13% of the energy. Rounding adds ~1e-16 per step,
    // so the prediction holds to ~1e-9: measured 3.7e-10; 4e-9 is asserted.
    let (step, steps) = (0.1, 10_000_000);
    let start = SVector::<f64, 2>::new(1.0, 0.0);
    let stepper = ClassicalRk4::new(&UNIT, 0.0, start, FixedStep { step }).unwrap();
    let (ratio, _) = energy_ratio(stepper, steps);
    let factor = 1.0 - step.powi(6) / 72.0 + step.powi(8) / 576.0;
    let predicted = factor.powi(steps as i32);
    assert!(
        ((ratio - predicted) / predicted).abs() < 4e-9,
        "{ratio} vs {predicted}"
    );
    assert!(1.0 - ratio > 0.1, "RK4 drift {}", 1.0 - ratio);
}

#[test]
fn symplectic_and_variational_stay_bounded_over_ten_million_steps() {
    // Expectation: the implicit midpoint rule conserves every quadratic invariant, so H of
    // this linear oscillator is kept to the Newton tolerance (1e-12 relative) and rounding
    // per step; the midpoint variational integrator is the same map here. Over 10⁷ steps the
    // error stays at the rounding level (measured 8.6e-13 and 1.7e-12), against RK4's 13%
    // loss over the same steps; 1e-11 and 2e-11 are asserted.
    let (step, steps) = (0.1, 10_000_000);
    let start = SVector::<f64, 2>::new(1.0, 0.0);
    let midpoint = ImplicitMidpoint::new(
        &UNIT,
        0.0,
        start,
        ImplicitMidpointConfig {
            step,
            ..Default::default()
        },
    )
    .unwrap();
    let (_, worst) = energy_ratio(midpoint, steps);
    assert!(worst < 1e-11, "implicit midpoint: {worst:e}");
    let variational = Variational::new(
        &UNIT,
        0.0,
        start,
        VariationalConfig {
            step,
            ..Default::default()
        },
    )
    .unwrap();
    let (_, worst) = energy_ratio(variational, steps);
    assert!(worst < 2e-11, "variational: {worst:e}");
}

/// Runs `stepper` on the unit oscillator for `end` and returns the result.
fn oscillate<St>(mut stepper: St, end: f64) -> Result<Solution<1, 2>, StepError<2>>
where
    St: Stepper<1, 2, System = Oscillator>,
{
    Ok(run(&mut stepper, &RunConfig::until(end), &[])?)
}

/// |R(z)| for the stability polynomial R(z) = Σₖ coefficients[k] zᵏ.
fn amplification(coefficients: &[f64], z: Complex<f64>) -> f64 {
    coefficients
        .iter()
        .rev()
        .fold(Complex::new(0.0, 0.0), |sum, &c| sum * z + c)
        .norm()
}

#[test]
fn explicit_steps_past_the_stability_limit_fail_with_a_typed_error() {
    // Expectation: past the limit (ωh > 2√2 for RK4; any h for explicit Euler, |R|² = 1 + h²;
    // ωh ≳ 3.3 for Dormand–Prince) the amplitude grows geometrically until it overflows,
    // and the run ends with NonFiniteState carrying the time — not a NaN in the solution.
    // The stepper does not detect the growth itself: before the overflow the states are
    // finite garbage (see the leaking pendulum below), which the energy guard catches.
    // From amplitude 1 the state passes f64::MAX after n = ln(MAX)/ln|R(iωh)| steps, with R
    // the method's stability polynomial (Euler 1 + z; RK4 Σₖ₌₀⁴ zᵏ/k!; Dormand–Prince
    // Σₖ₌₀⁵ zᵏ/k! + z⁶/600, the weights bᵀAᵏ⁻¹𝟙 of its tableau). A stage can overflow a few
    // steps earlier: it exceeds the state by up to |1 + z + z²/2 + z³/4| = 5.1 for RK4 at
    // h = 3, i.e. ln 5.1/ln|R| = 4 steps. Measured failing steps against n: Euler 2048 vs
    // 2047.98, RK4 1733 vs 1735.7, Dormand–Prince 545 vs 545.9; asserted in [n − 4, n + 1].
    let start = SVector::<f64, 2>::new(1.0, 0.0);
    let end = 1e6;
    let euler = oscillate(
        ExplicitEuler::new(&UNIT, 0.0, start, FixedStep { step: 1.0 }).unwrap(),
        end,
    );
    let rk4 = oscillate(
        ClassicalRk4::new(&UNIT, 0.0, start, FixedStep { step: 3.0 }).unwrap(),
        end,
    );
    let dormand_prince = oscillate(
        DormandPrince::new(
            &UNIT,
            0.0,
            start,
            StepControl::Fixed(FixedStep { step: 4.0 }),
        )
        .unwrap(),
        end,
    );
    // Σ zᵏ/k! up to z⁵, then Dormand–Prince's z⁶/600; Euler and RK4 take a prefix.
    let polynomial = [
        1.0,
        1.0,
        1.0 / 2.0,
        1.0 / 6.0,
        1.0 / 24.0,
        1.0 / 120.0,
        1.0 / 600.0,
    ];
    let cases = [
        ("Euler", euler, 1.0, &polynomial[..2]),
        ("RK4", rk4, 3.0, &polynomial[..5]),
        ("DP fixed", dormand_prince, 4.0, &polynomial[..]),
    ];
    for (name, result, step, coefficients) in cases {
        let error = result.expect_err(name);
        assert_eq!(
            error.kind,
            StepErrorKind::NonFiniteState,
            "{name}: {error:?}"
        );
        let growth = amplification(coefficients, Complex::new(0.0, step));
        let predicted = f64::MAX.ln() / growth.ln();
        let failing_step = (error.time / step).ceil();
        assert!(
            (predicted - 4.0..=predicted + 1.0).contains(&failing_step),
            "{name}: failed in step {failing_step}, predicted overflow after {predicted}"
        );
    }
}

#[test]
fn rk4_at_the_stability_limit_neither_grows_nor_decays() {
    // At ωh = 2√2 exactly, |R(ih)|² = 1 − 512/72 + 4096/576 = 1: the energy is kept (to the
    // rounding of 2√2 in h, ~1e-16 per step), while just below the limit it decays.
    let start = SVector::<f64, 2>::new(1.0, 0.0);
    let limit = 2.0 * std::f64::consts::SQRT_2;
    let (at_limit, _) = energy_ratio(
        ClassicalRk4::new(&UNIT, 0.0, start, FixedStep { step: limit }).unwrap(),
        10_000,
    );
    // Measured 1.1e-11 after 10⁴ steps.
    assert!((at_limit - 1.0).abs() < 1e-10, "{at_limit}");
    // Just below, |R|² = 0.867 per step: 10⁴ steps give 10⁻⁶²¹, which underflows to 0
    // (measured 0).
    let (below, _) = energy_ratio(
        ClassicalRk4::new(&UNIT, 0.0, start, FixedStep { step: 0.99 * limit }).unwrap(),
        10_000,
    );
    assert!(below < 1e-300, "{below}");
}

#[test]
fn implicit_steps_far_past_the_explicit_limit_stay_bounded() {
    // The implicit midpoint rule is A-stable with |R(ih)| = 1: at ωh = 10 (35 times past the
    // explicit limit) it keeps H to the Newton tolerance, with a phase error of course.
    let start = SVector::<f64, 2>::new(1.0, 0.0);
    let config = ImplicitMidpointConfig {
        step: 10.0,
        ..Default::default()
    };
    let (_, worst) = energy_ratio(
        ImplicitMidpoint::new(&UNIT, 0.0, start, config).unwrap(),
        10_000,
    );
    // Measured 7.1e-15 over 10⁴ steps.
    assert!(worst < 1e-13, "{worst:e}");
}

#[test]
fn losing_mass_moves_a_fixed_step_past_the_stability_limit_silently() {
    // The leaking spring pendulum with RK4 at h = 0.2: the spring's ω = √(k/m) rises as the
    // bob empties, and ωh crosses 2√2 when m = k h²/8 = 1 kg, at t = 20 s. Past it the
    // amplitude grows by |R(iωh)| (≈ 7.6 a step at m = 0.75 kg), but from the rounding
    // level it needs far more than the remaining steps to overflow, so there is no typed
    // error: the states are finite garbage (r = 157 m at 25 s for a 1 m spring).
    // Expectation, and what a user must know: only the energy-budget residual reveals it,
    // 0.2 J before the crossing, millions of J after.
    let (polar, _) = pendulums();
    let start = SVector::from([1.1, 0.5, 0.0, 0.0, 2.0]);
    let residual_until = |end: f64| {
        let mut stepper = ClassicalRk4::new(&polar, 0.0, start, FixedStep { step: 0.2 }).unwrap();
        let record = Record {
            energy_residual: true,
            ..Record::default()
        };
        let solution = run(&mut stepper, &RunConfig::until(end).recording(record), &[]).unwrap();
        let (_, state) = solution.last().unwrap();
        (solution.energy_residual.last().unwrap().abs(), state[0])
    };
    // Measured: 0.196 J and r = 1.055 m at 19 s; 4.0e6 J and r = −157 m at 25 s.
    let (before, r_before) = residual_until(19.0);
    let (after, r_after) = residual_until(25.0);
    assert!(
        before < 0.3 && (r_before - 1.0).abs() < 0.2,
        "{before} J, r = {r_before}"
    );
    assert!(
        after > 1e6 && r_after.abs() > 100.0,
        "{after} J, r = {r_after}"
    );
}

#[test]
fn the_energy_guard_turns_that_silent_instability_into_a_typed_error() {
    // The same run with `guarding_energy(0.1)`: the residual is ~1% of |H| before the
    // crossing at t = 20 s and grows geometrically after it, so the run must fail with
    // EnergyBudgetExceeded shortly after 20 s — not return the garbage of t = 25 s — and must
    // not fail before the crossing.
    let (polar, _) = pendulums();
    let start = SVector::from([1.1, 0.5, 0.0, 0.0, 2.0]);
    let mut stepper = ClassicalRk4::new(&polar, 0.0, start, FixedStep { step: 0.2 }).unwrap();
    let error = run(
        &mut stepper,
        &RunConfig::until(25.0).guarding_energy(0.1),
        &[],
    )
    .unwrap_err()
    .error;
    let StepError {
        time,
        kind: StepErrorKind::EnergyBudgetExceeded { residual, scale },
        ..
    } = error
    else {
        panic!("expected the energy guard, got {error:?}");
    };
    // Measured: t = 23.8 s, residual −3.07 J against a scale of 17.9 J.
    assert!(time > 20.0 && time <= 24.0, "t = {time}");
    assert!(residual.abs() > 0.1 * scale && residual.is_finite());
}

#[test]
fn an_implicit_step_too_long_for_newton_is_a_typed_error() {
    // The implicit midpoint rule at h = 2 on the leaking pendulum (three spring periods a
    // step, a nonlinear swing): the simplified Newton iteration from an explicit predictor
    // cannot converge. Expectation: NewtonDivergence (or a typed state error from a wild
    // iterate), not a silently wrong step.
    let (polar, _) = pendulums();
    let start = SVector::from([1.1, 0.5, 0.0, 0.0, 2.0]);
    let config = ImplicitMidpointConfig {
        step: 2.0,
        ..Default::default()
    };
    let mut stepper = ImplicitMidpoint::new(&polar, 0.0, start, config).unwrap();
    let result = run(&mut stepper, &RunConfig::until(30.0), &[]);
    let error = result.unwrap_err();
    // Measured: in the first step (the contraction rate passed 1 at the third iteration).
    assert!(
        matches!(error.kind, StepErrorKind::NewtonDivergence { .. }),
        "{error:?}"
    );
    assert_eq!((error.time, error.state), (0.0, start));
}

#[variable_mass_system(
    r#"
    coordinates y
    mass m = m0
    body b: mass m, position [y]
    potential m*g*y + c*acos(a)
"#
)]
struct NanEnergy {
    m0: f64,
    g: f64,
    c: f64,
    a: f64,
}

#[test]
fn a_nan_energy_residual_fails_the_guard() {
    // A free fall whose potential carries the constant c·acos(a): it has no gradient, so
    // the motion (ẏ = −g t) is finite, but with a = 2 the Hamiltonian, and so the budget's
    // residual ∫P dt − (H − H₀), is NaN. The guard compared |residual| > tolerance·scale,
    // false for NaN: the run ended "within budget". Expectation: EnergyBudgetExceeded with
    // the NaN residual at the first point checked, not a run that passes.
    let system = NanEnergy {
        m0: 1.0,
        g: 9.81,
        c: 1.0,
        a: 2.0,
    };
    let start = SVector::<f64, 2>::new(0.0, 0.0);
    let mut stepper = ClassicalRk4::new(&system, 0.0, start, FixedStep { step: 0.1 }).unwrap();
    let guarded = RunConfig::until(1.0).guarding_energy(0.1);
    let error = run(&mut stepper, &guarded, &[]).unwrap_err().error;
    let StepErrorKind::EnergyBudgetExceeded { residual, .. } = error.kind else {
        panic!("expected the energy guard, got {error:?}");
    };
    assert!(residual.is_nan() && error.time <= 0.1, "{error:?}");
}
