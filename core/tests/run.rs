//! Runs record what was asked: H, the forces, the power and the energy-budget residual,
//! checked against the sled's closed forms, and the residual tracks the integration error.

mod support;

use support::problems::SledProblem;
use support::Problem;
use varmass_core::steppers::{
    AdaptiveControl, DormandPrince, ExplicitEuler, FixedStep, ImplicitMidpoint,
    ImplicitMidpointConfig, StepControl,
};
use varmass_core::{run, Record, RunConfig, Solution, Stepper, StopReason};

const EVERYTHING: Record = Record {
    hamiltonian: true,
    forces: true,
    power: true,
    energy_residual: true,
};

fn record_sled<St: Stepper<1, 2>>(stepper: &mut St, end_time: f64) -> Solution<1, 2> {
    run(
        stepper,
        &RunConfig::until(end_time).recording(EVERYTHING),
        &[],
    )
    .unwrap()
}

#[test]
fn recorded_extras_match_the_sleds_closed_forms() {
    let problem = SledProblem::standard();
    let sled = problem.system;
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-10,
        ..Default::default()
    });
    let mut stepper = DormandPrince::new(&sled, 0.0, problem.initial_state(), control).unwrap();
    let solution = record_sled(&mut stepper, problem.end_time);
    assert_eq!(solution.stop, StopReason::ReachedEnd);
    let points = solution.times.len();
    assert!(points > 2);
    for extra in [
        solution.hamiltonian.len(),
        solution.forces.len(),
        solution.power.len(),
        solution.energy_residual.len(),
    ] {
        assert_eq!(extra, points);
    }
    let (sin, cos) = sled.slope.sin_cos();
    for (k, state) in solution.states.iter().enumerate() {
        let (x, m) = (state[0], sled.mass_at(state[0]));
        let v = state[1] / m;
        // Eq. 21: H = p²/(2m) − m g x sin θ.
        let hamiltonian = state[1] * state[1] / (2.0 * m) - m * sled.gravity * x * sin;
        assert!(
            (solution.hamiltonian[k] - hamiltonian).abs() <= 1e-12 * hamiltonian.abs().max(1.0)
        );
        // Eqs. 22–23 and the mass-flux term ṁ ∂p/∂m = c ẋ².
        let forces = solution.forces[k];
        let scale = m * sled.gravity;
        assert!((forces.active[0] + sled.friction * m * sled.gravity * cos).abs() < 1e-12 * scale);
        assert!((forces.impact[0] + sled.accretion * v * v).abs() < 1e-12 * scale);
        assert!((forces.mass_flux[0] - sled.accretion * v * v).abs() < 1e-12 * scale);
        assert_eq!(forces.reactive_thrust[0], 0.0);
        // Energy budget (docs/mechanics.md#energy-budget): R2 and the mass-flux term cancel in q̇·(…), leaving
        // dH/dt = −f_d m g cos θ ẋ + ṁ ∂H/∂m|(q,p) with ṁ = c ẋ, ∂H/∂m = −ẋ²/2 − g x sin θ.
        let power = -sled.friction * m * sled.gravity * cos * v
            - sled.accretion * v * (0.5 * v * v + sled.gravity * x * sin);
        // The trait's default power is a central difference with step ε^(1/3): relative
        // error about ε^(2/3) ≈ 4e-11 times the curvature scale (measured ≤ 1.9e-11); 1e-9
        // leaves 50×. The absolute 1e-12·m g covers the start from rest, where power = 0.
        let tolerance = 1e-9 * (power.abs() + scale * v.abs()) + 1e-12 * scale;
        assert!(
            (solution.power[k] - power).abs() < tolerance,
            "{k}: {} vs {power}",
            solution.power[k]
        );
    }
    // With tolerances 1e-10 the residual ∫P dt − ΔH stays at the level of the state error:
    // measured 9.0e-8 J against |H| = 5.5e3 J, 1.6e-11 relative; 2e-10 asserted (12×).
    let final_hamiltonian = *solution.hamiltonian.last().unwrap();
    let residual = solution.energy_residual.last().unwrap().abs();
    assert!(residual < 2e-10 * final_hamiltonian.abs(), "{residual}");
    assert_eq!(solution.energy_residual[0], 0.0);
}

/// The residual measures the integration error, not the quadrature: it halves with the step
/// for Euler (first order) and quarters for the implicit midpoint rule (second order). The
/// bands are the convergence harness's (observed order p ± 0.1 on ratios 2ᵖ).
#[test]
fn energy_residual_converges_with_the_method_order() {
    let problem = SledProblem::standard();
    let sled = problem.system;
    let y0 = problem.initial_state();
    let end = problem.end_time;
    let euler_residual = |step: f64| {
        let mut stepper = ExplicitEuler::new(&sled, 0.0, y0, FixedStep { step }).unwrap();
        record_sled(&mut stepper, end)
            .energy_residual
            .last()
            .copied()
            .unwrap()
    };
    let midpoint_residual = |step: f64| {
        let config = ImplicitMidpointConfig {
            step,
            ..Default::default()
        };
        let mut stepper = ImplicitMidpoint::new(&sled, 0.0, y0, config).unwrap();
        record_sled(&mut stepper, end)
            .energy_residual
            .last()
            .copied()
            .unwrap()
    };
    let euler_order = (euler_residual(0.005) / euler_residual(0.0025)).log2();
    let midpoint_order = (midpoint_residual(0.02) / midpoint_residual(0.01)).log2();
    eprintln!("residual orders: Euler {euler_order}, midpoint {midpoint_order}");
    assert!((0.9..=1.1).contains(&euler_order), "{euler_order}");
    assert!((1.9..=2.1).contains(&midpoint_order), "{midpoint_order}");
}

/// A run stopped by an event can continue from it: restart the stepper at the event and
/// run on; the result matches the closed form as if never stopped.
#[test]
fn a_run_continues_after_a_restart_at_its_event() {
    use std::f64::consts::PI;
    use support::problems::OscillatorProblem;
    use varmass_core::{Direction, Event};

    let problem = OscillatorProblem::standard();
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..Default::default()
    });
    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.exact(0.0), control).unwrap();
    let events = [Event::state_reaches(0, 0.0, Direction::Falling)];
    let first = run(&mut stepper, &RunConfig::until(3.0), &events).unwrap();
    let (time, state) = first.last().unwrap();
    assert!((time - PI / 4.0).abs() < 1e-10);
    stepper.restart(time, *state).unwrap();
    // Restarted exactly on the crossing, g = 0 there does not re-trigger (or it would stop
    // at once); the next falling crossing, at 5π/4 ≈ 3.93, lies beyond the end.
    let second = run(&mut stepper, &RunConfig::until(3.0), &events).unwrap();
    assert_eq!(second.stop, StopReason::ReachedEnd);
    let (end, end_state) = second.last().unwrap();
    assert_eq!(end, 3.0);
    // Tolerances 1e-12 over 3 time units: well below 1e-8.
    assert!(
        (end_state - problem.exact(3.0)).norm() < 1e-8,
        "{end_state}"
    );
}

/// Runs `stepper`, which starts at t = 2, to t = 2: one point, no step, no evaluation (of
/// the rate or, for the implicit steppers, of the Jacobian or a Newton iteration).
fn run_to_start<St: Stepper<1, 2>>(mut stepper: St, name: &str) {
    let before = *stepper.statistics();
    let solution = run(&mut stepper, &RunConfig::until(2.0), &[]).unwrap();
    assert_eq!(solution.stop, StopReason::ReachedEnd, "{name}");
    assert_eq!(solution.times, vec![2.0], "{name}");
    assert_eq!(solution.statistics.accepted_steps, 0, "{name}");
    assert_eq!(*stepper.statistics(), before, "{name}: work done");
}

#[test]
fn a_run_to_the_current_time_takes_no_step() {
    // Before, the variational stepper divided by h = 0 and the others took a zero step.
    use varmass_core::steppers::{ClassicalRk4, Variational, VariationalConfig};
    let problem = SledProblem::standard();
    let (system, start) = (problem.system(), problem.initial_state());
    let fixed = FixedStep { step: 0.1 };
    run_to_start(
        ExplicitEuler::new(system, 2.0, start, fixed).unwrap(),
        "Euler",
    );
    run_to_start(ClassicalRk4::new(system, 2.0, start, fixed).unwrap(), "RK4");
    let config = VariationalConfig {
        step: 0.1,
        ..VariationalConfig::default()
    };
    run_to_start(
        Variational::new(system, 2.0, start, config).unwrap(),
        "variational",
    );
    let control = StepControl::Adaptive(AdaptiveControl::default());
    run_to_start(
        DormandPrince::new(system, 2.0, start, control).unwrap(),
        "Dormand–Prince",
    );
    let config = ImplicitMidpointConfig {
        step: 0.1,
        ..ImplicitMidpointConfig::default()
    };
    run_to_start(
        ImplicitMidpoint::new(system, 2.0, start, config).unwrap(),
        "implicit midpoint",
    );
}

#[test]
fn the_energy_guard_does_not_trip_where_h_vanishes() {
    // Free fall from rest at y = 0 (a rocket that does not burn): H = p²/2m + m g y is 0
    // along the whole motion while T and V grow. Measured against |H| alone, rounding would
    // trip the guard; against |p·q̇| too, a correct run passes at a strict tolerance.
    use support::systems::Rocket;
    let rocket = Rocket {
        burn_rate: 0.0,
        exhaust_speed: 0.0,
        gravity: 9.81,
    };
    let start = nalgebra::SVector::<f64, 3>::new(0.0, 0.0, 2.0);
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::default()
    });
    let mut stepper = DormandPrince::new(&rocket, 0.0, start, control).unwrap();
    let solution = run(
        &mut stepper,
        &RunConfig::until(5.0).guarding_energy(1e-6),
        &[],
    )
    .unwrap();
    assert_eq!(solution.stop, StopReason::ReachedEnd);
}

/// A run with the Taylor stepper locates an event on the series (its dense output): the
/// oscillator x = cos ωt (ω = 2) falls through 0 at π/4, found to the event tolerance.
#[test]
fn a_taylor_run_locates_its_event_on_the_series() {
    use std::f64::consts::PI;
    use support::problems::OscillatorProblem;
    use varmass_core::steppers::{Taylor, TaylorControl};
    use varmass_core::tolerance::{Floor, Tolerance};
    use varmass_core::{Direction, Event};

    let problem = OscillatorProblem::standard();
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(1e-14, 1e-14, Floor::Taylor).unwrap());
    let mut stepper = Taylor::new(&problem.system, 0.0, problem.exact(0.0), control).unwrap();
    let events = [Event::state_reaches(0, 0.0, Direction::Falling)];
    let solution = run(&mut stepper, &RunConfig::until(3.0), &events).unwrap();
    let (time, state) = solution.last().unwrap();
    eprintln!(
        "event at {time}, {} steps",
        solution.statistics.accepted_steps
    );
    // The steps (≈ 0.4 here) are far longer than the distance to π/4 from the last step
    // start, so the crossing is found inside a step. Measured |t − π/4| = 1e-16.
    assert!((time - PI / 4.0).abs() < 1e-12, "{time}");
    assert!((state - problem.exact(time)).norm() < 1e-12, "{state}");
}
