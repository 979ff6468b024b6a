//! Tables of the state where they jump at an end (docs/tables.md#knots-are-switches): the
//! switch at such a knot lies on the edge of the band of arguments a lookup snaps onto the
//! end, so that the crossing leaves the argument on the side the lookups read next. Each
//! model is a unit mass pushed by a table of its own position, x'' = G(x), `outside zero`.
//!
//! References (by hand):
//! - Box: G = 1 on [1, 2] (`tests/data/box_1_2.csv`), x(0) = 0, x'(0) = 1: coasting to
//!   x = 1 at t = 1, then x = 1 + τ + τ²/2 reaches 2 at τ = √3 − 1 with v = √3, so at
//!   t = 3: v = √3, x = 2 + √3 (3 − √3) = 3√3 − 1.
//! - Ramp then one: G = x on [0, 1], 1 on [1, 2] (`tests/data/ramp_then_one.csv`), x(0) = 0,
//!   x'(0) = 1: x = sinh t to x = 1 at t₁ = asinh 1 (v = √2), then v² = 2 + 2(x − 1)
//!   reaches 4 at x = 2 after τ = 2 − √2; v(3) = 2, x(3) = 2 + 2 (3 − t₁ − 2 + √2).
//! - The box from above: x(0) = 3, x'(0) = −1: x = 2 at t = 1, then x'' = 1 turns the
//!   mass round at x = 1.5 (t = 2) and it leaves through x = 2 at t = 3 with v = 1: at
//!   t = 4, x = 3, v = 1. It enters and leaves through the same jumping end.
//!
//! - The box through an affine argument, G(a·x + c): the data s ∈ [1, 2] are the x between
//!   (1 − c)/a and (2 − c)/a, a length L = 1/|a|, entered at x₁ (the nearer end, from
//!   x(0) = 0, x'(0) = 1: at t₁ = x₁); inside x'' = 1, so v² = 1 + 2 (x − x₁) (energy) and
//!   the mass leaves at v_f = √(1 + 2/|a|) after τ = v_f − 1 (τ + τ²/2 = L); at T past
//!   that, x = x₁ + L + v_f (T − t₁ − τ), v = v_f. A falling argument (a < 0) enters
//!   through the last knot and leaves through the first.
//!
//! Measured before the fix (review of 2026-11-26): the ramp by Dormand–Prince at tolerance
//! 1e-12 v = 2.000000000288 (the crossing left x an ulp past the knot, inside the band that
//! still reads the value before the jump); the box by RK4 at step 0.01 9.6e-4 off, by
//! Dormand–Prince 7.6e-4 (a redone step's last stage snapped onto the first knot).

use varmass::core::VariableMassSystem;
use varmass::prelude::variable_mass_system;

#[path = "table_support/ends.rs"]
mod support;

use support::{assert_near, End};

#[variable_mass_system(
    r#"
    coordinates x
    table G(s) = "tests/data/box_1_2.csv", outside zero
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*G(x)]
"#,
    emit = ["taylor"]
)]
struct Box {
    m0: f64,
}

#[variable_mass_system(
    r#"
    coordinates x
    table G(s) = "tests/data/ramp_then_one.csv", outside zero
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*G(x)]
"#,
    emit = ["taylor"]
)]
struct RampThenOne {
    m0: f64,
}

#[variable_mass_system(
    r#"
    coordinates x
    table G(s) = "tests/data/box_1_2.csv", outside zero
    mass m = m0
    body b: mass m, position [x]
    force b: [m0*G(a*x + c)]
"#,
    emit = ["taylor"]
)]
struct AffineBox {
    m0: f64,
    a: f64,
    c: f64,
}

const STEP: f64 = 0.01;

/// (x, v) at `end` from `start` by RK4 and Dormand–Prince at the fixed step [`STEP`], and
/// by Taylor, DOP853 and Dormand–Prince at the support's tolerance (1e-12).
fn ends<Sys: VariableMassSystem<1, 2>>(system: &Sys, start: [f64; 2], end: f64) -> Vec<End> {
    let mut found = support::fixed_ends(system, start, end, STEP).to_vec();
    found.extend(support::adaptive_ends(system, start, end));
    found
}

#[test]
fn a_box_of_the_state_entered_and_left_by_its_jumping_ends() {
    // G = 1 is constant on the data: every method is exact there but for rounding.
    // Measured: ≤ 1.2e-14 (x, v, every method); bound 8e-14 (before: RK4 9.6e-4,
    // Dormand–Prince fixed 7.6e-4).
    let three = 3f64.sqrt();
    let found = ends(&Box { m0: 1.0 }, [0.0, 1.0], 3.0);
    assert_near(&found, [3.0 * three - 1.0, three], |_| 8e-14);
}

#[test]
fn a_box_of_the_state_entered_and_left_through_the_same_jumping_end() {
    // Measured: ≤ 1.6e-14 (every method); bound 8e-14 (before the series read the band
    // above the last knot as the data's, Taylor was 12 % off).
    let found = ends(&Box { m0: 1.0 }, [3.0, -1.0], 4.0);
    assert_near(&found, [3.0, 1.0], |_| 8e-14);
}

#[test]
fn a_ramp_of_the_state_left_by_its_jumping_end() {
    // x = sinh t on the ramp: the fixed steps err by their truncation there, the adaptive
    // runs by their tolerance. Measured (x, v): RK4 2.9e-11, Dormand–Prince fixed 4.2e-14,
    // at 1e-12 Dormand–Prince 1.1e-13 and DOP853 5.2e-14, Taylor 6.7e-16; bounds ×5
    // (before: Dormand–Prince at 1e-12 v 1.4e-10 off, 290× the tolerance).
    let t1 = 1f64.asinh();
    let found = ends(&RampThenOne { m0: 1.0 }, [0.0, 1.0], 3.0);
    let x3 = 2.0 + 2.0 * (3.0 - t1 - 2.0 + 2f64.sqrt());
    let bound = |method: &str| match method {
        "rk4 fixed" => 1.5e-10,
        "taylor" => 5e-15,
        _ => 6e-13,
    };
    assert_near(&found, [x3, 2.0], bound);
}

/// (x, v) at `end` of the mass entering the box of G(a·x + c) from x(0) = 0, x'(0) = 1
/// (the module's comment), `end` past its exit.
fn through_affine_box(a: f64, c: f64, end: f64) -> [f64; 2] {
    let length = 1.0 / a.abs();
    let entry = ((1.0 - c) / a).min((2.0 - c) / a);
    let leaving = (1.0 + 2.0 * length).sqrt();
    let inside = leaving - 1.0;
    assert!(
        entry >= 0.0 && entry + inside < end,
        "the run must cross the whole box"
    );
    [entry + length + leaving * (end - entry - inside), leaving]
}

#[test]
fn a_box_of_a_slowly_varying_argument_of_the_state_is_switched_where_the_lookup_jumps() {
    // s = a·x + c moves by an ulp of itself only over ~1/(|a|·ẋ) ulps of t: the crossing
    // located to a rounding of t did not move s, the step crossing the box stood (its first
    // stage reading the side before the jump) and the switch, never re-anchored, missed the
    // exit. Measured before the fix (v, RK4 and Dormand–Prince at step 0.01): a = 0.01
    // 5.5e-5 and 2.5e-4, a = −0.01 the same, a = 0.001 5.7e-5 and 4.4e-5; a = 100 exact.
    // Measured after, the largest of (x, v) over the methods: a = ±0.01 3.5e-14, a = 0.001
    // 1.2e-13 (x, the roundings of 4 600 steps; v ≤ 1.7e-14), a = 100 1.1e-15; bounds ×4–7.
    for (a, c, end, bound) in [
        (0.01, 0.995, 16.0, 1.5e-13),
        (-0.01, 2.005, 16.0, 1.5e-13),
        (0.001, 0.9995, 46.0, 5e-13),
        (100.0, 0.5, 2.0, 8e-15),
    ] {
        let found = ends(&AffineBox { m0: 1.0, a, c }, [0.0, 1.0], end);
        assert_near(&found, through_affine_box(a, c, end), |_| bound);
    }
}
