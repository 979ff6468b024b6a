//! Components under the macro (docs/components.md): `tests/data/components/twin_motor_rocket.vms`
//! uses the component `models/lib/motor_1d.vms` twice, as `left` and `right`, each burning
//! at μ with exhaust speed u_e. By hand, two motors of rate μ on one body are one motor of
//! rate 2μ: ṁ = −2μ, R1 = −2 μ u_e, and m ÿ = 2 μ u_e − m g (Meshchersky), so with m(t) =
//! m₀ − 2μ t its flight is Tsiolkovsky's with gravity loss, v(t) = u_e ln(m₀/m) − g t
//! (flown by `cli/tests/components.rs` on one motor). Here the composed model's state rate
//! is held to that by hand and to `models/rocket.vms` burning at 2μ.

use varmass::prelude::*;

#[variable_mass_system(file = "tests/data/components/twin_motor_rocket.vms")]
struct TwinMotorRocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

#[variable_mass_system(file = "models/rocket.vms", with = [])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// One motor whose exhaust speed keeps the component's default (2500 m/s): the struct has
/// no field `main_u_e`, so the default is a constant of the generated code.
#[variable_mass_system(
    "coordinates y
    units y: m, mu: kg/s, g: m/s^2
    body rocket: mass m, position [y]
    potential m*g*y
    use \"models/lib/motor_1d.vms\" as main: on = rocket, mu = mu
    mass m: state, rate -main_mu"
)]
struct DefaultMotor {
    mu: f64,
    g: f64,
}

const M0: f64 = 1000.0;

#[test]
fn two_motors_have_the_state_rate_of_one_burning_twice_as_fast() {
    let twin = TwinMotorRocket {
        mu: 5.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let one = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let mut worst: f64 = 0.0;
    for k in 0..200 {
        // States over a grid: heights, both directions of motion, masses down to a tenth.
        let k = f64::from(k);
        let m = M0 * (0.1 + 0.9 * (k * 0.37).fract());
        let v = 800.0 * (2.0 * (k * 0.61).fract() - 1.0);
        let state = SVector::<f64, 3>::new(1e4 * (k * 0.13).fract(), m * v, m);
        let a = twin.state_rate(0.0, &state).expect("a regular state");
        let b = one.state_rate(0.0, &state).expect("a regular state");
        // By hand: [ẏ, ṗ, ṁ] = [v, 2 μ u_e − m g − 2 μ v, −2μ] (p = m v, ṗ = m v̇ + ṁ v).
        let (mu, u_e, g) = (twin.mu, twin.u_e, twin.g);
        let hand = [v, 2.0 * mu * u_e - m * g - 2.0 * mu * v, -2.0 * mu];
        for i in 0..3 {
            let scale = hand[i].abs().max(one.mu * one.u_e);
            worst = worst.max((a[i] - b[i]).abs() / scale);
            worst = worst.max((a[i] - hand[i]).abs() / scale);
        }
    }
    // Measured: 1.5e-16 over both comparisons (the definitions left_mu = mu are inlined:
    // the rocket's arithmetic); the bound allows a few roundings.
    assert!(worst <= 1e-14, "worst relative difference {worst:e}");
}

#[test]
fn a_default_without_a_field_is_a_constant() {
    let rocket = DefaultMotor { mu: 10.0, g: 9.81 };
    let (m, v) = (800.0, 35.0);
    let state = SVector::<f64, 3>::new(120.0, m * v, m);
    let rate = rocket.state_rate(0.0, &state).expect("a regular state");
    // By hand, u_e = 2500 (the default): ṗ = μ u_e − m g − μ ẏ = 25000 − 7848 − 350.
    assert_eq!(rate[1], 25000.0 - 7848.0 - 350.0);
    assert_eq!(rate[2], -10.0);
}
