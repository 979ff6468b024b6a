//! A table's ends and a falling argument (docs/tables.md#outside-the-data and
//! #taylor-series): where `outside zero` meets a last value that is not zero the table jumps,
//! and a run restarting at that knot must read the value after the jump; a falling argument
//! must read the piece *below* each knot it reaches, also when a run starts on one. Each
//! model is a unit mass pushed by a table of t, x'' = F(a(t)), from rest at x = 0.
//!
//! References (by hand):
//! - Box: G = 1 on the data [1, 2] (`tests/data/box_1_2.csv`), 0 outside (`outside zero`):
//!   v = 0, 1 after t = 2; x(2) = ½, so at t = 3: x = ½ + 1 = 1.5, v = 1.
//! - Falling ramp: F(s) = max(0, s − 0.3) on the data (linear through (0.3, 0) and
//!   (2, 1.7) or (1, 0.7), held outside), s = 1 − t, so x'' = 0.7 − t up to t = 0.7 and 0
//!   after: v(1) = ∫₀^0.7 (0.7 − t) dt = 0.245, x(1) = 0.7·0.245 − 0.7³/6 + 0.245·0.3 =
//!   0.187 833…. On `ramp_below.csv` the argument crosses the knot 0.3 falling; on
//!   `ramp_to_one.csv` the run *starts* on the last knot (s = 1) and falls into the data.
//!
//! Measured before the fix (review of 2026-11-26): Taylor v = 1.1287 on the box (the step
//! leaving the last knot read the value before the jump for its whole series), 0.2284 and
//! 0.2619 on the falling ramps (the piece above the knot); Dormand–Prince v − 1 = 3.4e-10
//! at tolerance 1e-12 (the restart's first stage read the value before the jump).

use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{
    AdaptiveControl, Dop853, DormandPrince, StepControl, Taylor, TaylorControl,
};
use varmass::core::{run, RunConfig, Solution, VariableMassSystem};
use varmass::prelude::variable_mass_system;

#[variable_mass_system(
    r#"
    coordinates x
    table G(t) = "tests/data/box_1_2.csv", outside zero
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*G(t)]
"#,
    emit = ["taylor"]
)]
struct Box {
    m0: f64,
}

#[variable_mass_system(
    r#"
    coordinates x
    table F(s) = "tests/data/ramp_below.csv", outside hold
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*F(c - t)]
"#,
    emit = ["taylor"]
)]
struct FallingThroughAKnot {
    m0: f64,
    c: f64,
}

#[variable_mass_system(
    r#"
    coordinates x
    table F(s) = "tests/data/ramp_to_one.csv", outside hold
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*F(c - t)]
"#,
    emit = ["taylor"]
)]
struct FallingFromTheLastKnot {
    m0: f64,
    c: f64,
}

const TOLERANCE: f64 = 1e-12;

fn adaptive(base: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: TOLERANCE,
        absolute_tolerance: TOLERANCE,
        ..base
    })
}

/// (x, v) at `end` by Taylor, DOP853 and Dormand–Prince, from rest at x = 0.
fn ends<Sys: VariableMassSystem<1, 2>>(system: &Sys, end: f64) -> [(&'static str, [f64; 2]); 3] {
    let start = SVector::from([0.0, 0.0]);
    let config = RunConfig::until(end);
    let last = |solution: Solution<1, 2>| {
        let (_, state) = solution.last().unwrap();
        [state[0], state[1]]
    };
    let control = TaylorControl::adaptive(TOLERANCE, TOLERANCE);
    let mut taylor = Taylor::new(system, 0.0, start, control).unwrap();
    let mut dop853 = Dop853::new(system, 0.0, start, adaptive(AdaptiveControl::dop853())).unwrap();
    let mut dp =
        DormandPrince::new(system, 0.0, start, adaptive(AdaptiveControl::default())).unwrap();
    [
        ("taylor", last(run(&mut taylor, &config, &[]).unwrap())),
        ("dop853", last(run(&mut dop853, &config, &[]).unwrap())),
        ("dormand-prince", last(run(&mut dp, &config, &[]).unwrap())),
    ]
}

fn assert_near(found: [(&str, [f64; 2]); 3], expected: [f64; 2], bound: f64) {
    for (method, state) in found {
        for (value, exact) in state.iter().zip(expected) {
            let error = (value - exact).abs() / exact.abs();
            assert!(error <= bound, "{method}: {value} vs {exact} ({error:e})");
        }
    }
}

#[test]
fn a_run_leaving_a_jump_at_the_last_knot_reads_the_value_after_it() {
    // Measured: Taylor 2.2e-15 (x, v), DOP853 2.5e-12, Dormand–Prince 1.1e-11; bound 5e-11
    // (×5 the worst; before: Taylor 0.13, Dormand–Prince 3.4e-10).
    assert_near(ends(&Box { m0: 1.0 }, 3.0), [1.5, 1.0], 5e-11);
}

#[test]
fn a_falling_argument_reads_the_piece_below_the_knot() {
    // Measured: ≤ 3.0e-16 by every method; bound 1e-13 (before: Taylor v 7 % low).
    let found = ends(&FallingThroughAKnot { m0: 1.0, c: 1.0 }, 1.0);
    assert_near(found, [0.187_833_333_333_333_3, 0.245], 1e-13);
}

#[test]
fn a_run_starting_on_a_knot_with_a_falling_argument_reads_the_piece_below() {
    // Measured: ≤ 9.1e-16; bound 1e-13 (before: Taylor v 7 % high, the constant after the
    // data read for the first step).
    let found = ends(&FallingFromTheLastKnot { m0: 1.0, c: 1.0 }, 1.0);
    assert_near(found, [0.187_833_333_333_333_3, 0.245], 1e-13);
}
