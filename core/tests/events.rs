//! Events located on the dense output, against times known independently of any stepper:
//! the oscillator's zero crossings, the rocket reaching a height (closed form y(t)), the
//! sled reaching x = 50 m (t from a quadrature of 1/v(x) of the closed form), and a mass
//! threshold.

mod support;

use std::f64::consts::PI;

use support::problems::{OscillatorProblem, RocketProblem, SledProblem};
use support::Problem;
use varmass_core::steppers::{
    AdaptiveControl, ClassicalRk4, DormandPrince, FixedStep, StepControl,
};
use varmass_core::{run, Direction, Event, EventAction, RunConfig, StopReason};

/// Located to 1e-10 in t, as the brief demands. The adaptive runs use tolerances of 1e-13
/// so the state (and its fourth-order dense output) is accurate well below that.
const TIME_TOLERANCE: f64 = 1e-10;

fn tight() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-13,
        ..Default::default()
    })
}

#[test]
fn oscillator_zero_crossing_stops_the_run() {
    let problem = OscillatorProblem::standard(); // x = cos 2t
    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.exact(0.0), tight()).unwrap();
    let events = [Event::state_reaches(0, 0.0, Direction::Falling)];
    let solution = run(&mut stepper, &RunConfig::until(10.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let hit = solution.events[0];
    assert!((hit.time - PI / 4.0).abs() < TIME_TOLERANCE, "{}", hit.time);
    assert_eq!(solution.last().unwrap().0, hit.time);
}

#[test]
fn recorded_crossings_are_all_located() {
    let problem = OscillatorProblem::standard();
    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.exact(0.0), tight()).unwrap();
    let events = [Event {
        action: EventAction::Record,
        ..Event::state_reaches(0, 0.0, Direction::Either)
    }];
    let solution = run(&mut stepper, &RunConfig::until(10.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::ReachedEnd);
    // Zeros of cos 2t in (0, 10): π/4 + kπ/2 for k = 0…5.
    assert_eq!(solution.events.len(), 6, "{:?}", solution.events);
    for (k, hit) in solution.events.iter().enumerate() {
        let expected = PI / 4.0 + k as f64 * PI / 2.0;
        assert!(
            (hit.time - expected).abs() < TIME_TOLERANCE,
            "{k}: {}",
            hit.time
        );
    }
}

/// Without its own dense output a stepper's events use the cubic Hermite interpolant; its
/// O(h⁴) error with h = 0.01 (about 4e-10 here, and RK4's own error is 1e-9) bounds the
/// accuracy.
#[test]
fn fixed_step_events_use_hermite_interpolation() {
    let problem = OscillatorProblem::standard();
    let mut stepper = ClassicalRk4::new(
        &problem.system,
        0.0,
        problem.exact(0.0),
        FixedStep { step: 0.01 },
    )
    .unwrap();
    let events = [Event::state_reaches(0, 0.0, Direction::Falling)];
    let solution = run(&mut stepper, &RunConfig::until(10.0), &events).unwrap();
    let hit = solution.events[0];
    eprintln!("hermite: {:e}", hit.time - PI / 4.0);
    assert!((hit.time - PI / 4.0).abs() < 1e-8, "{}", hit.time);
    // The event lies inside a step, not on a step boundary.
    assert!(((hit.time / 0.01) - (hit.time / 0.01).round()).abs() > 1e-3);
}

#[test]
fn rocket_reaches_a_height() {
    let problem = RocketProblem::standard();
    let height = 1000.0;
    // The reference time: bisection on the closed form y(t), which is increasing here.
    let (mut low, mut high) = (1.0, 15.0);
    assert!(problem.exact(low)[0] < height && problem.exact(high)[0] > height);
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if problem.exact(middle)[0] < height {
            low = middle;
        } else {
            high = middle;
        }
    }
    let expected = 0.5 * (low + high);

    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.exact(0.0), tight()).unwrap();
    let events = [Event::state_reaches(0, height, Direction::Rising)];
    let solution = run(&mut stepper, &RunConfig::until(15.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let time = solution.events[0].time;
    eprintln!("rocket: t = {time} vs {expected}");
    assert!(
        (time - expected).abs() < TIME_TOLERANCE,
        "{time} vs {expected}"
    );
}

#[test]
fn sled_reaches_fifty_metres_against_the_closed_form() {
    let problem = SledProblem::standard();
    let target: f64 = 50.0;
    // t(50) = ∫₀⁵⁰ dx / v(x) with v from the closed form. With x = u² the integrand
    // 2u / v(u²) is smooth (v ~ √x near 0); composite Simpson with 20 000 panels has an
    // error far below 1e-12.
    let upper = target.sqrt();
    let panels = 20_000;
    let width = upper / panels as f64;
    let integrand = |u: f64| {
        if u == 0.0 {
            // lim 2u / v(u²) = 2 / √(2 a) as u → 0, since v² → 2 a x.
            2.0 / (2.0 * problem.system.drive()).sqrt()
        } else {
            2.0 * u / problem.speed_squared(u * u).sqrt()
        }
    };
    let mut sum = integrand(0.0) + integrand(upper);
    for k in 1..panels {
        sum += integrand(k as f64 * width) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    let expected = sum * width / 3.0;

    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.initial_state(), tight()).unwrap();
    let events = [Event::state_reaches(0, target, Direction::Rising)];
    let solution = run(&mut stepper, &RunConfig::until(60.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let hit = solution.events[0];
    eprintln!(
        "sled: t = {} vs {expected}, steps {:?}",
        hit.time, solution.statistics
    );
    assert!(
        (hit.time - expected).abs() < TIME_TOLERANCE,
        "{} vs {expected}",
        hit.time
    );
    // And the speed there is the closed form's (eq. 24).
    let speed_squared = problem.numerical_speed_squared(&hit.state);
    let exact = problem.speed_squared(target);
    assert!(
        ((speed_squared - exact) / exact).abs() < 1e-10,
        "{speed_squared} vs {exact}"
    );
}

#[test]
fn mass_event_stops_the_rocket_before_burn_out() {
    let problem = RocketProblem::standard();
    let mut stepper =
        DormandPrince::new(&problem.system, 0.0, problem.exact(0.0), tight()).unwrap();
    // m = 1 − 0.05 t reaches 0.1 at t = 18, before burn-out at t = 20.
    let events = [Event::mass_reaches(0, 0.1)];
    let solution = run(&mut stepper, &RunConfig::until(30.0), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (time, state) = solution.last().unwrap();
    eprintln!("mass: {:e}", time - 18.0);
    assert!((time - 18.0).abs() < TIME_TOLERANCE, "{time}");
    assert!(state.iter().all(|x| x.is_finite()));
    assert!((state - problem.exact(18.0)).norm() < 1e-6 * problem.exact(18.0).norm());
}
