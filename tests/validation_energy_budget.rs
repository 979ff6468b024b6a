//! The energy-budget residual ∫ power dt − (H − H₀) (docs/mechanics.md#energy-budget) is small on every example
//! system at a tight tolerance, and large when the integration is poor, so it is a usable
//! error estimate without a reference solution.

mod validation_support;

use validation_support::{pendulums, tight, Oscillator, Rocket, Sled};
use varmass::core::Record;
use varmass::prelude::*;

/// The worst |residual| of a run, relative to the largest |H| or |H − H₀| seen (H can pass
/// through zero, so the scale is the run's energy range, not H itself).
fn relative_residual<St, const N: usize, const S: usize>(
    mut stepper: St,
    end: f64,
    events: &[Event<'_, S>],
) -> f64
where
    St: Stepper<N, S>,
{
    let record = Record {
        hamiltonian: true,
        energy_residual: true,
        ..Record::default()
    };
    let solution = run(
        &mut stepper,
        &RunConfig::until(end).recording(record),
        events,
    )
    .unwrap();
    let first = solution.hamiltonian[0];
    let scale = solution
        .hamiltonian
        .iter()
        .fold(0.0f64, |s, h| s.max(h.abs()).max((h - first).abs()));
    let worst = solution
        .energy_residual
        .iter()
        .fold(0.0f64, |w, r| w.max(r.abs()));
    worst / scale
}

// At tolerance 1e-12 the state is accurate to ~1e-12 relative per step, a few hundred to a
// few thousand steps at most add up to ~1e-10, and Simpson's rule on the dense output adds
// its own O(h⁵) per step. Each system has its own bound, about ten times its measured
// residual, so that a regression by an order of magnitude fails.

#[test]
fn sled_budget_closes() {
    let sled = Sled::paper();
    let stepper = DormandPrince::new(&sled, 0.0, SVector::zeros(), tight(1e-12)).unwrap();
    let at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
    let residual = relative_residual(stepper, 1e3, &[at_50_m]);
    // Measured 9.0e-13.
    assert!(residual < 1e-11, "{residual:e}");
}

#[test]
fn rocket_budget_closes_through_burnout() {
    let rocket = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1000.0);
    // Tolerance 1e-13 here: the power has terms of 1e8 W that nearly cancel, and with the
    // long steps DP takes on this smooth motion the quadrature error, not the state's,
    // dominates the residual (at 1e-12: H is right to 1.5e-13 but the residual is 2.5e-10;
    // at 1e-13 the residual is 4e-11).
    let stepper = DormandPrince::new(&rocket, 0.0, start, tight(1e-13)).unwrap();
    let residual = relative_residual(stepper, 1e3, &[Event::mass_reaches(0, 100.0)]);
    // Measured 3.9e-11.
    assert!(residual < 4e-10, "{residual:e}");
}

#[test]
fn leaking_pendulum_budget_closes_in_both_coordinates() {
    let (polar, cartesian) = pendulums();
    let (r0, theta0, m0) = (1.1, 0.5, 2.0);
    let start = SVector::from([r0, theta0, 0.0, 0.0, m0]);
    let stepper = DormandPrince::new(&polar, 0.0, start, tight(1e-12)).unwrap();
    let residual = relative_residual(stepper, 30.0, &[]);
    // Measured 4.8e-12 (polar) and 4.5e-12 (Cartesian).
    assert!(residual < 5e-11, "polar: {residual:e}");
    let start = SVector::from([r0 * theta0.sin(), -r0 * theta0.cos(), 0.0, 0.0, m0]);
    let stepper = DormandPrince::new(&cartesian, 0.0, start, tight(1e-12)).unwrap();
    let residual = relative_residual(stepper, 30.0, &[]);
    assert!(residual < 5e-11, "Cartesian: {residual:e}");
}

#[test]
fn oscillator_budget_closes() {
    let oscillator = Oscillator { m0: 2.0, k: 50.0 };
    let start = SVector::<f64, 2>::new(0.3, 0.0);
    let stepper = DormandPrince::new(&oscillator, 0.0, start, tight(1e-12)).unwrap();
    let residual = relative_residual(stepper, 20.0, &[]);
    // Measured 7.2e-11 over 16 periods.
    assert!(residual < 7e-10, "{residual:e}");
}

#[test]
fn a_poor_run_shows_a_large_residual() {
    // Explicit Euler at h = 1e-2 on the pendulum (spring period 0.63 s at 2 kg): first
    // order with ~60 steps per period, which pumps energy into the spring, and the
    // residual must say so — otherwise the checks above could not fail. Measured 1.04: as
    // large as the run's whole energy range; asserted above a tenth of that.
    let (polar, _) = pendulums();
    let start = SVector::from([1.1, 0.5, 0.0, 0.0, 2.0]);
    let stepper = ExplicitEuler::new(&polar, 0.0, start, FixedStep { step: 1e-2 }).unwrap();
    let residual = relative_residual(stepper, 10.0, &[]);
    assert!(residual > 0.1, "{residual:e}");
}
