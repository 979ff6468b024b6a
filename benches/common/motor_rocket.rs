//! The rocket of issue 21's example, written by hand: vertical flight on the M1670's measured
//! thrust (a linear table, `outside zero`), the mass following the curve at the rocketry
//! tools' constant exhaust speed (ṁ = −F/u_e, u_e = total impulse / propellant mass) and
//! quadratic drag −k_d v|v|. The reference for "the generated state rate within 1.3× of a
//! hand-written one with the same interpolation", whose generated side is
//! `models/motor_rocket_drag.vms` (`benches/tables.rs`; `tests/table_motor_drag.rs` holds
//! the two to rounding).
//!
//! State [y, p, m]: ẏ = p/m, ṗ = F − m g − (F/u_e)·v − k_d v|v| (the momentum carried away
//! by the exhaust, −ṁ v, is in ṗ = ṁ v + m v̇), ṁ = −F/u_e.

use varmass::core::nalgebra::{SMatrix, SVector, Vector1, Vector3};
use varmass::core::{SystemError, VariableMassSystem};
use varmass_table::{Interpolation, Motor, Outside, Table};

/// Gravity, m/s².
pub const G: f64 = 9.80665;

/// The rocket: the thrust table and its constants.
pub struct MotorRocket {
    /// F(t), N.
    pub thrust: Table,
    /// u_e, m/s.
    pub exhaust_speed: f64,
    /// k_d = ½ ρ C_d A, kg/m: sea-level air, C_d 0.5, a 98 mm airframe.
    pub drag: f64,
    /// Lift-off mass, kg: the loaded M1670 (5.231 kg) in a 14.769 kg airframe.
    pub lift_off_mass: f64,
}

impl MotorRocket {
    /// The rocket on `models/motors/Cesaroni_M1670.eng`.
    pub fn m1670() -> Self {
        // Relative to this file, so that the benches and the tests (which include it) read
        // the same data.
        let text = include_str!("../../models/motors/Cesaroni_M1670.eng");
        let motor = Motor::parse(text).expect("a well-formed RASP file");
        let area = std::f64::consts::PI * 0.049 * 0.049;
        Self {
            thrust: Table::new(&motor.thrust, Interpolation::Linear, Outside::Zero),
            exhaust_speed: motor.exhaust_speed(),
            drag: 0.5 * 1.225 * 0.5 * area,
            lift_off_mass: 20.0,
        }
    }

    /// The state at lift-off.
    pub fn initial_state(&self) -> SVector<f64, 3> {
        Vector3::new(0.0, 0.0, self.lift_off_mass)
    }

    /// F(t), N: `outside zero` gives every finite t a value; a NaN time is a bug upstream.
    fn force(&self, t: f64) -> f64 {
        self.thrust.value(t).expect("a finite time")
    }
}

impl VariableMassSystem<1, 3> for MotorRocket {
    const COORDINATES: [&'static str; 1] = ["y"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, s: &SVector<f64, 3>) -> f64 {
        s[2]
    }
    fn mass_rate(&self, _: usize, t: f64, _: &SVector<f64, 3>) -> f64 {
        -self.force(t) / self.exhaust_speed
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 3>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(s[2])
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(vs[2] * vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 3>) -> f64 {
        0.5 * vs[2] * vs[1] * vs[1] - vs[2] * G * vs[0]
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-vs[2] * G)
    }
    fn active_force(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.drag * vs[1] * vs[1].abs())
    }
    fn reactive_thrust(&self, t: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.force(t))
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn mass_flux_force(&self, t: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(self.mass_rate(0, t, vs) * vs[1])
    }
    fn accelerations(&self, t: f64, vs: &SVector<f64, 3>) -> Result<SVector<f64, 1>, SystemError> {
        let v = vs[1];
        Ok(Vector1::new(
            (self.force(t) - self.drag * v * v.abs()) / vs[2] - G,
        ))
    }
    #[inline]
    fn state_rate(&self, t: f64, s: &SVector<f64, 3>) -> Result<SVector<f64, 3>, SystemError> {
        let (p, m) = (s[1], s[2]);
        let (force, v) = (self.force(t), p / m);
        let rate = force / self.exhaust_speed;
        let momentum_rate = force - m * G - rate * v - self.drag * v * v.abs();
        Ok(Vector3::new(v, momentum_rate, -rate))
    }
}
