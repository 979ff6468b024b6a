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
// few thousand steps at most add up to ~1e-10; the quadrature of the power along the
// dense output (Gauss–Kronrod, run/energy.rs) adds nothing visible. Each system has its own bound, about ten times its measured
// residual, so that a regression by an order of magnitude fails.

#[test]
fn sled_budget_closes() {
    let sled = Sled::paper();
    let stepper = DormandPrince::new(&sled, 0.0, SVector::zeros(), tight(1e-12)).unwrap();
    let at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
    let residual = relative_residual(stepper, 1e3, &[at_50_m]);
    // Measured 4.8e-13 (9.0e-13 with Simpson's rule).
    assert!(residual < 5e-12, "{residual:e}");
}

#[test]
fn rocket_budget_closes_through_burnout() {
    let rocket = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1000.0);
    // Tolerance 1e-13 here: the power has terms of 1e8 W that nearly cancel. With Simpson's
    // rule (before the Gauss–Kronrod quadrature) the long steps DP takes on this smooth
    // motion made the quadrature error dominate the residual: 4e-11 at this tolerance.
    let stepper = DormandPrince::new(&rocket, 0.0, start, tight(1e-13)).unwrap();
    let residual = relative_residual(stepper, 1e3, &[Event::mass_reaches(0, 100.0)]);
    // Measured 3.3e-14.
    assert!(residual < 4e-13, "{residual:e}");
}

#[test]
fn leaking_pendulum_budget_closes_in_both_coordinates() {
    let (polar, cartesian) = pendulums();
    let (r0, theta0, m0) = (1.1, 0.5, 2.0);
    let start = SVector::from([r0, theta0, 0.0, 0.0, m0]);
    let stepper = DormandPrince::new(&polar, 0.0, start, tight(1e-12)).unwrap();
    let residual = relative_residual(stepper, 30.0, &[]);
    // Measured 6.5e-12 (polar) and 6.3e-12 (Cartesian).
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
    // residual must say so — otherwise the checks above could not fail. Measured 1.40: as
    // large as the run's whole energy range; asserted above a tenth of that.
    let (polar, _) = pendulums();
    let start = SVector::from([1.1, 0.5, 0.0, 0.0, 2.0]);
    let stepper = ExplicitEuler::new(&polar, 0.0, start, FixedStep { step: 1e-2 }).unwrap();
    let residual = relative_residual(stepper, 10.0, &[]);
    assert!(residual > 0.1, "{residual:e}");
}

/// The vertical rocket of `validation_support::Rocket` (`models/rocket.vms`, without
/// `[drag]`) with its Taylor recurrences, for the quadrature test below.
#[variable_mass_system(
    file = "models/rocket.vms",
    emit = ["hamiltonian", "power", "jacobian", "taylor"]
)]
#[derive(Clone, Copy, Debug)]
struct TaylorRocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// The largest |residual| of a burn of `stepper`'s rocket to t = 90 s (m from 1000 kg to
/// 100 kg), relative to max |H|, with the largest state error against Tsiolkovsky's closed
/// form (`Rocket::burning`), relative to the largest |y| or |v|.
fn rocket_residual_and_error<St: Stepper<1, 3>>(mut stepper: St, rocket: &Rocket) -> (f64, f64) {
    let record = Record {
        hamiltonian: true,
        energy_residual: true,
        ..Record::default()
    };
    let config = RunConfig::until(90.0).recording(record);
    let solution = run(&mut stepper, &config, &[]).unwrap();
    let scale = solution
        .hamiltonian
        .iter()
        .fold(0.0f64, |s, h| s.max(h.abs()));
    let residual = solution
        .energy_residual
        .iter()
        .fold(0.0f64, |w, r| w.max(r.abs()));
    let (mut error, mut size) = (0.0f64, 0.0f64);
    for (t, state) in solution.times.iter().zip(&solution.states) {
        let (y, v) = rocket.burning(1000.0, *t);
        error = error
            .max((state[0] - y).abs())
            .max((state[1] / state[2] - v).abs());
        size = size.max(y.abs()).max(v.abs());
    }
    (residual / scale, error / size)
}

#[test]
fn the_residual_is_no_quadrature_error_with_long_steps() {
    // Tsiolkovsky's burn, y(t) and v(t) in closed form (`Rocket::burning`, derived in
    // docs/mechanics.md#vertical-rocket): the state is right to ~1e-14, so the residual
    // ∫ P dt − (H − H₀) can only be the quadrature's error. DOP853 and Taylor take steps of
    // seconds here, over which Simpson's rule on P (the residual's former quadrature) was
    // off by ~1e-7 of H; quadrature over the dense output within each step
    // (run/energy.rs) leaves the state's own error.
    let rocket = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1000.0);
    let stepper = Dop853::new(&rocket, 0.0, start, tight(1e-12)).unwrap();
    let (residual, error) = rocket_residual_and_error(stepper, &rocket);
    eprintln!("DOP853: residual {residual:e}, state error {error:e}");
    let taylor_rocket = TaylorRocket {
        mu: rocket.mu,
        u_e: rocket.u_e,
        g: rocket.g,
    };
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(1e-12, 1e-12, Floor::Taylor).unwrap());
    let stepper = Taylor::new(&taylor_rocket, 0.0, start, control).unwrap();
    let (taylor_residual, taylor_error) = rocket_residual_and_error(stepper, &rocket);
    eprintln!("Taylor: residual {taylor_residual:e}, state error {taylor_error:e}");
    // Measured: state errors 3.4e-13 (DOP853) and 1.9e-14 (Taylor); residuals 1.6e-12
    // (DOP853) and 9.7e-14 (Taylor), from 1.5e-6 and 1.5e-5 with Simpson's rule. Bounds ten
    // times the measured values.
    assert!(
        error < 4e-12 && taylor_error < 2e-13,
        "{error:e} {taylor_error:e}"
    );
    assert!(residual < 1.6e-11, "{residual:e}");
    assert!(taylor_residual < 1e-12, "{taylor_residual:e}");
}
