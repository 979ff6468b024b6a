//! The M1670 rocket on its pad, by hand: the lift-off time where the thrust equals the
//! weight, solved on the thrust table's linear pieces, and the mass m(t) = m₀ − I(t)/u_e;
//! shared by `tests/support_pad.rs` (the macro) and `cli/tests/support.rs` (the tool).
//!
//! The motor's thrust F(t) is the linear interpolant of the `.eng` points (from RASP's
//! implicit (0 s, 0 N)), ṁ = −F/u_e with u_e = total impulse / propellant mass, so
//! m(t) = m₀ − I(t)/u_e with I the exact trapezoid integral. While held, the free momentum
//! rate is ṗ^free = F − m g (p = m ẏ = 0, so the mass-flux term ṁ ẏ vanishes): the body lifts
//! where F(t) = m(t) g. On the piece [tᵢ, tᵢ₊₁] with F = Fᵢ + s τ (τ = t − tᵢ, s the piece's
//! slope) and I = Iᵢ + Fᵢ τ + s τ²/2, that is the quadratic
//!
//! ```text
//!   (g s / 2u_e) τ² + (s + g Fᵢ/u_e) τ + (Fᵢ − g m₀ + g Iᵢ/u_e) = 0,
//! ```
//!
//! whose first root in [0, tᵢ₊₁ − tᵢ] over the pieces in order is the lift-off time t_L.
//! From rest at t_L the free flight is Meshchersky's m v̇ = F − m g with ṁ = −F/u_e, so
//! v(t) = u_e ln(m(t_L)/m(t)) − g (t − t_L) (v̇ = −u_e ṁ/m − g integrated from v(t_L) = 0).

#![allow(dead_code)]

use varmass::core::table::{Interpolation, Motor};

/// Gravity, m/s².
pub const G: f64 = 9.80665;

/// The Cesaroni M1670 of `models/motors/`.
pub fn motor() -> Motor {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/motors/Cesaroni_M1670.eng"
    );
    let path = match std::path::Path::new(path).exists() {
        true => path.to_string(),
        false => concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/models/motors/Cesaroni_M1670.eng"
        )
        .to_string(),
    };
    Motor::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// m(t) = m₀ − I(t)/u_e.
pub fn mass(m0: f64, t: f64) -> f64 {
    let motor = motor();
    let impulse = Interpolation::Linear
        .interpolate(&motor.thrust)
        .antiderivative();
    m0 - impulse.value(t.clamp(0.0, impulse.domain().1)) / motor.exhaust_speed()
}

/// v(t) = u_e ln(m(t_L)/m(t)) − g (t − t_L) after a lift-off at t_L with mass m₀ at t = 0.
pub fn speed(m0: f64, lift_off: f64, t: f64) -> f64 {
    motor().exhaust_speed() * (mass(m0, lift_off) / mass(m0, t)).ln() - G * (t - lift_off)
}

/// t_L: the first root of F(t) = m(t) g on the table's linear pieces (the quadratic of the
/// header), or `None` if the thrust never reaches the weight.
pub fn thrust_equals_weight(m0: f64) -> Option<f64> {
    let motor = motor();
    let u_e = motor.exhaust_speed();
    let (t, f) = (motor.thrust.arguments(), motor.thrust.values());
    let mut burnt = 0.0;
    for i in 0..t.len() - 1 {
        let width = t[i + 1] - t[i];
        let s = (f[i + 1] - f[i]) / width;
        let (a, b, c) = (
            G * s / (2.0 * u_e),
            s + G * f[i] / u_e,
            f[i] - G * m0 + G * burnt / u_e,
        );
        let roots = match a == 0.0 {
            true => vec![-c / b],
            false => {
                let d = (b * b - 4.0 * a * c).sqrt();
                vec![(-b - d) / (2.0 * a), (-b + d) / (2.0 * a)]
            }
        };
        let first = roots
            .into_iter()
            .filter(|tau| (0.0..=width).contains(tau))
            .min_by(f64::total_cmp);
        if let Some(tau) = first {
            return Some(t[i] + tau);
        }
        burnt += 0.5 * (f[i] + f[i + 1]) * width;
    }
    None
}
