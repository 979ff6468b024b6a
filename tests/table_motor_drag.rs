//! The M1670 rocket with quadratic drag generated from `models/motor_rocket_drag.vms`
//! against the same rocket written by hand (`benches/common/motor_rocket.rs`, shared with
//! the tables bench, which times the pair): state rates equal to rounding at states along a
//! flight, and the flight's apex equal to the tolerance.
//!
//! By hand (the common file's comment): state [y, p, m], ẏ = p/m,
//! ṗ = F − m g − (F/u_e)·v − k_d v|v|, ṁ = −F/u_e with F the linear M1670 table, zero
//! after burnout.

#[path = "../benches/common/motor_rocket.rs"]
#[allow(dead_code)]
mod motor_rocket;

use motor_rocket::MotorRocket;
use varmass::core::nalgebra::{SVector, Vector3};
use varmass::core::steppers::{AdaptiveControl, Dop853, StepControl};
use varmass::core::{run, Direction, Event, RunConfig, VariableMassSystem};
use varmass::prelude::variable_mass_system;

#[variable_mass_system(file = "models/motor_rocket_drag.vms")]
struct DragRocket {
    u_e: f64,
    g: f64,
    k_d: f64,
}

fn pair() -> (MotorRocket, DragRocket) {
    let hand = MotorRocket::m1670();
    let generated = DragRocket {
        u_e: hand.exhaust_speed,
        g: motor_rocket::G,
        k_d: hand.drag,
    };
    (hand, generated)
}

#[test]
fn generated_and_hand_written_state_rates_agree() {
    // Measured: ≤ 1.6e-15 relative (to max(|a|, |b|, 1)) over 600 states of a flight-like
    // path (t every 0.01 s, so on and between the knots); bound 1e-14.
    let (hand, generated) = pair();
    let mut worst = 0.0_f64;
    for k in 0..600 {
        let t = k as f64 * 0.01;
        let m = 20.0 - 3.101 * (t / 3.9).min(1.0);
        let v = 80.0 * t - 4.0 * t * t - 30.0;
        let state = Vector3::new(v * t / 2.0, m * v, m);
        let a = hand.state_rate(t, &state).unwrap();
        let b = generated.state_rate(t, &state).unwrap();
        for i in 0..3 {
            worst = worst.max((a[i] - b[i]).abs() / a[i].abs().max(b[i].abs()).max(1.0));
        }
    }
    assert!(worst <= 1e-14, "{worst:e}");
}

/// The apex (time, altitude) of a DOP853 run at tolerance 1e-11 from lift-off.
fn apex<Sys: VariableMassSystem<1, 3>>(system: &Sys) -> (f64, f64) {
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-11,
        absolute_tolerance: 1e-11,
        ..AdaptiveControl::dop853()
    });
    let start: SVector<f64, 3> = Vector3::new(0.0, 0.0, 20.0);
    let mut stepper = Dop853::new(system, 0.0, start, control).unwrap();
    let at_apex = Event::state_reaches(1, 0.0, Direction::Falling);
    let solution = run(&mut stepper, &RunConfig::until(60.0), &[at_apex]).unwrap();
    let hit = solution.events[0];
    (hit.time, hit.state[0])
}

#[test]
fn the_two_fly_to_the_same_apex() {
    // The hand-written rocket has no stop times (its steps cross the knots blindly), the
    // generated one lands on each: measured 25.5132 s, 3213.25 m for both, apart by 2.1e-9 s
    // and 2.0e-10 relative in height; bounds 1e-6 s and 1e-8 relative.
    let (hand, generated) = pair();
    let (t_hand, y_hand) = apex(&hand);
    let (t_generated, y_generated) = apex(&generated);
    assert!(
        (t_hand - t_generated).abs() <= 1e-6,
        "{t_hand} {t_generated}"
    );
    assert!(
        (y_hand - y_generated).abs() <= 1e-8 * y_hand,
        "{y_hand} {y_generated}"
    );
    assert!((t_generated - 25.5132).abs() < 1e-4 && (y_generated - 3213.25).abs() < 1e-2);
}
