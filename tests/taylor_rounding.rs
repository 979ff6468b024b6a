//! Rounding over many Taylor steps: Kepler, e = 0.5, over three orbits. The stepper adds
//! each step's increment to the state by compensated summation and evaluates the series at
//! the step the clock takes (`core/src/steppers/taylor.rs`); issue 25 asks for ≤ 5e-15 here
//! (heyoka: 7.9e-15).
//!
//! With the tolerance's own steps (about 100 at 1e-14 … 1e-20) the error measured against
//! the reference below wanders between 9e-16 and 4e-14 from one tolerance to the next:
//! there each increment's own rounding (a few ulps of f(y) h, not summation) sets the
//! floor, which no summation recovers.

use std::f64::consts::PI;

use varmass::core::steppers::{Taylor, TaylorControl};
use varmass::core::StepOutcome;
use varmass::prelude::*;

/// The planet of the benchmarks (`benches/common/generated.rs`): polar coordinates through
/// a Cartesian position, constant mass.
#[variable_mass_system(
    "
    coordinates r, th
    mass m = m1
    body planet: mass m, position [r*cos(th), r*sin(th)]
    potential -k*m/r
",
    emit = ["taylor"]
)]
struct Kepler {
    m1: f64,
    k: f64,
}

const PLANET: Kepler = Kepler { m1: 1.5, k: 1.0 };

/// The low part of π in double-double (π = PI + PI_LOW to ~1e-32).
const PI_LOW: f64 = 1.224_646_799_147_353_2e-16;

/// Cartesian (x, y, ẋ, ẏ) of a polar state [r, θ, p_r, p_θ].
fn cartesian(y: &SVector<f64, 4>) -> [f64; 4] {
    let (r, (sin, cos)) = (y[0], y[1].sin_cos());
    let (dr, dth) = (y[2] / PLANET.m1, y[3] / (PLANET.m1 * r * r));
    [
        r * cos,
        r * sin,
        dr * cos - r * dth * sin,
        dr * sin + r * dth * cos,
    ]
}

/// The reference by hand. With a = k = 1 the period is 2π; the run stops at T = fl(6π),
/// δ = T − 6π (about 1e-15, from the double-double π) after the third return to
/// periapsis, where r = a(1 − e) = ½, v = √(k(1 + e)/(a(1 − e))) = √3 along +y and the
/// acceleration is −k/r² = −4 along x. To first order in δ (δ² ~ 1e-30 is far below
/// rounding): (x, y, ẋ, ẏ) = (½, √3 δ, −4δ, √3).
fn reference() -> (f64, [f64; 4]) {
    let end = 6.0 * PI;
    // 6·PI − fl(6·PI), exactly, by a fused multiply-add.
    let rounding = 6.0f64.mul_add(PI, -end);
    let delta = -rounding - 6.0 * PI_LOW;
    let v = 3f64.sqrt();
    (end, [0.5, v * delta, -4.0 * delta, v])
}

/// Order 30, 401 steps of T/400.5: the truncation error is far below rounding, so what is
/// left is how rounding accumulates. Measured error (the largest of position and velocity;
/// a = k = 1, so both are already relative to a and √(k/a)): 2.4e-15; 7.6e-14 with the
/// state summed by Horner's rule at the nominal step (before compensated summation), 2.4e-14
/// with only the clock's step, 8.7e-14 with only compensated summation; at 1001 steps
/// 1.1e-14 against 3.7e-13. Bound: 5e-15, the issue's.
#[test]
fn kepler_over_three_orbits_in_400_steps_at_order_30_is_within_5e_15() {
    let e: f64 = 0.5;
    let start = SVector::from([1.0 - e, 0.0, 0.0, PLANET.m1 * (1.0 - e * e).sqrt()]);
    let (end, expected) = reference();
    let control = TaylorControl::Fixed {
        order: 30,
        step: end / 400.5,
    };
    let mut stepper = Taylor::new(&PLANET, 0.0, start, control).expect("a valid start");
    stepper.set_stop_time(end).expect("ahead");
    while stepper.step().expect("the orbit runs") != StepOutcome::ReachedStopTime {}
    assert_eq!(stepper.time(), end);
    assert_eq!(stepper.statistics().accepted_steps, 401);
    let got = cartesian(stepper.state());
    let position = (got[0] - expected[0]).hypot(got[1] - expected[1]);
    let velocity = (got[2] - expected[2]).hypot(got[3] - expected[3]);
    eprintln!("position {position:e}, velocity {velocity:e}");
    assert!(
        position.max(velocity) <= 5e-15,
        "{position:e}, {velocity:e}"
    );
}
