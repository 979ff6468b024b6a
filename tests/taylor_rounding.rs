//! Rounding over many Taylor steps: Kepler, e = 0.5, over three orbits. The stepper adds
//! each step's increment to the state by compensated summation and evaluates the series at
//! the step the clock takes (`core/src/steppers/taylor.rs`); issue 25 asks for ≤ 5e-15 here
//! (heyoka: 7.9e-15 against the nominal orbit, 1.2e-14 at best against the orbit through
//! its stored start).
//!
//! With the tolerance's own steps (about 100 at 1e-14 … 1e-20) the error measured against
//! the reference below wanders between 9e-16 and 4e-14 from one tolerance to the next:
//! there the rounding of the first two Taylor coefficients (the rate and its derivative, a
//! few ulps each at every step, not summation) sets the floor, which no summation recovers
//! (`tests/kepler_floor.rs` attributes it: 1.3e-14 rms over 16 starts at 1e-16, 1.2e-16
//! with c₁ and c₂ in double-double).

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

/// The reference by hand, for the orbit through the start as stored. With a = k = 1 the
/// period is 2π; the run stops at T = fl(6π), δ = T − 6π (about 1e-15, from the
/// double-double π) after the third return to periapsis, where r = a(1 − e) = ½,
/// v = √(k(1 + e)/(a(1 − e))) = √3 along +y and the acceleration is −k/r² = −4 along x.
///
/// The start's p_θ = m √(1 − e²) is rounded, by a relative η (2.8e-17): the orbit through
/// it has v = √3 (1 + η) at the same periapsis, energy v²/2 − 2 = −½ + 3η, so
/// a′ = 1/(1 − 6η) ≈ 1 + 6η and period 2π (1 + 9η): it passes its third periapsis 54πη
/// later, and the run ends Δ = δ − 54πη after it (4.7e-15 from η alone, 8e-15 in
/// position: more than the integrator's own error, so it is part of the reference). To
/// first order in Δ and η (their squares ~ 1e-30 are far below rounding):
/// (x, y, ẋ, ẏ) = (½, v Δ, −4Δ, v).
fn reference(stored_momentum: f64) -> (f64, [f64; 4]) {
    let end = 6.0 * PI;
    // 6·PI − fl(6·PI), exactly, by a fused multiply-add.
    let rounding = 6.0f64.mul_add(PI, -end);
    let delta = -rounding - 6.0 * PI_LOW;
    // η: s = fl(√0.75) misses √0.75 by ρ = (0.75 − s²)/(2s) (the residual exact by a fused
    // multiply-add), and fl(1.5 s) misses 1.5 s by its own residual.
    let s = 0.75f64.sqrt();
    let rho = (-s).mul_add(s, 0.75) / (2.0 * s);
    let product = 1.5f64.mul_add(s, -stored_momentum);
    let eta = (-product - 1.5 * rho) / stored_momentum;
    let since = delta - 54.0 * PI * eta;
    let root3 = 3f64.sqrt();
    let v = root3 + root3 * eta;
    (end, [0.5, v * since, -4.0 * since, v])
}

/// Order 30, 401 steps of T/400.5: the truncation error is far below rounding, so what is
/// left is how rounding accumulates. Measured error against the orbit through the stored
/// start (the largest of position and velocity; a = k = 1, so both are already relative to
/// a and √(k/a)): 3.7e-14 (position 1.6e-14). Against the nominal orbit it was 2.4e-15
/// before this reference took the start's rounding in, with the quotients' coefficients
/// divided by a\[0\]; that was the integrator's 2.1e-14 and the start's 8e-15 cancelling, and
/// the same run measured 1.8e-14 once the reciprocal's coefficients were multiplied by
/// w\[0\] (one rounding more per order). Before compensated summation and the clock's step
/// the nominal error was 7.6e-14. What is left is each step's rate rounded in double (a few
/// ulps of f(y) h, times the phase's sensitivity to the energy, about 28 over three orbits),
/// which no summation recovers. Bound: 5e-14 (1.35 times the measured value); the issue's
/// 5e-15 is out of reach while c₁ and c₂ are rounded to double (`tests/kepler_floor.rs`).
#[test]
fn kepler_over_three_orbits_in_400_steps_at_order_30_is_within_5e_14_of_the_exact_orbit() {
    let e: f64 = 0.5;
    let start = SVector::from([1.0 - e, 0.0, 0.0, PLANET.m1 * (1.0 - e * e).sqrt()]);
    let (end, expected) = reference(start[3]);
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
        position.max(velocity) <= 5e-14,
        "{position:e}, {velocity:e}"
    );
}
