//! The closed form of a rocket launched from an inclined rail (tests/rail.rs and
//! cli/tests/rail.rs; the derivation is in tests/rail.rs's header): the lift-off from the
//! rail's bottom, the slide up the rail s(τ), ṡ(τ), and the exit where s = L. The rocket of
//! models/rocket_on_rail.toml.
#![allow(dead_code)] // each test file uses a part

pub const MU: f64 = 5.0;
pub const U_E: f64 = 1000.0;
pub const G: f64 = 9.81;
/// Dry and propellant mass at the start, kg: 5396 N of weight along the rail against 5000 N
/// of thrust, so the rocket rests on its pad for 6.5 s.
pub const M_D: f64 = 450.0;
pub const M_P: f64 = 100.0;
/// The rail: 80° above the horizontal, leaning towards +x; 5 m of travel.
pub const INCLINATION: f64 = 80.0 * std::f64::consts::PI / 180.0;
pub const LENGTH: f64 = 5.0;

/// The closed form: lift-off time, and s(τ), ṡ(τ) after it.
pub fn lift_off() -> f64 {
    (M_D + M_P - MU * U_E / (G * INCLINATION.sin())) / MU
}

pub fn slide(tau: f64) -> (f64, f64) {
    let m_l = M_D + M_P - MU * lift_off();
    let m = m_l - MU * tau;
    let gs = G * INCLINATION.sin();
    let s = U_E * (tau + m / MU * (m / m_l).ln()) - 0.5 * gs * tau * tau;
    (s, U_E * (m_l / m).ln() - gs * tau)
}

/// The exit: s(τ) = L by Newton's method on the closed form.
pub fn exit() -> f64 {
    let mut tau = 7.0;
    for _ in 0..50 {
        let (s, v) = slide(tau);
        tau -= (s - LENGTH) / v;
    }
    lift_off() + tau
}
