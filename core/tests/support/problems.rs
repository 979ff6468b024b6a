//! Each test system paired with its reference solution (closed forms, independent of any
//! stepper; those the benchmarks share are in `closed_forms.rs`).

use nalgebra::{SVector, Vector2, Vector3, Vector4};

use super::closed_forms::{kepler_anomaly, kepler_period, rocket_exact, sled_speed_squared_over_x};
use super::systems::{Kepler, Oscillator, Rocket, Sled};
use super::Problem;

/// x(0) = 1, ẋ(0) = 0: x = cos ωt, p = −m ω sin ωt.
pub struct OscillatorProblem {
    pub system: Oscillator,
    pub end_time: f64,
}

impl OscillatorProblem {
    pub fn standard() -> Self {
        Self {
            system: Oscillator {
                mass: 2.0,
                stiffness: 8.0,
            },
            end_time: 3.0,
        }
    }
    pub fn frequency(&self) -> f64 {
        (self.system.stiffness / self.system.mass).sqrt()
    }
    pub fn exact(&self, time: f64) -> SVector<f64, 2> {
        let omega = self.frequency();
        Vector2::new(
            (omega * time).cos(),
            -self.system.mass * omega * (omega * time).sin(),
        )
    }
}

impl Problem<1, 2> for OscillatorProblem {
    type System = Oscillator;
    const NAME: &'static str = "oscillator";
    fn system(&self) -> &Oscillator {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 2> {
        self.exact(0.0)
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    fn error(&self, time: f64, state: &SVector<f64, 2>) -> f64 {
        let difference = state - self.exact(time);
        // Momentum in units of m ω so both components weigh alike.
        Vector2::new(
            difference[0],
            difference[1] / (self.system.mass * self.frequency()),
        )
        .norm()
    }
}

/// An ellipse of semi-major axis a and eccentricity e, starting at periapsis; the reference
/// comes from Kepler's equation E − e sin E = n t solved by Newton.
pub struct KeplerProblem {
    pub system: Kepler,
    pub semi_major_axis: f64,
    pub eccentricity: f64,
    pub end_time: f64,
}

impl KeplerProblem {
    /// e = 0.5 over three quarters of a period (so θ stays below 2π for the reference).
    pub fn standard() -> Self {
        let mut problem = Self {
            system: Kepler {
                mass: 1.5,
                gravity: 1.0,
            },
            semi_major_axis: 1.0,
            eccentricity: 0.5,
            end_time: 0.0,
        };
        problem.end_time = 0.75 * problem.period();
        problem
    }
    pub fn period(&self) -> f64 {
        kepler_period(self.semi_major_axis, self.system.gravity)
    }
    pub fn exact(&self, time: f64) -> SVector<f64, 4> {
        let (a, e, k, m) = (
            self.semi_major_axis,
            self.eccentricity,
            self.system.gravity,
            self.system.mass,
        );
        let (anomaly, anomaly_rate) = kepler_anomaly(a, e, k, time);
        let r = a * (1.0 - e * anomaly.cos());
        let radial_speed = a * e * anomaly.sin() * anomaly_rate;
        let theta = 2.0
            * ((1.0 + e).sqrt() * (anomaly / 2.0).sin())
                .atan2((1.0 - e).sqrt() * (anomaly / 2.0).cos());
        let angular_momentum = (k * a * (1.0 - e * e)).sqrt();
        Vector4::new(r, theta, m * radial_speed, m * angular_momentum)
    }
}

impl Problem<2, 4> for KeplerProblem {
    type System = Kepler;
    const NAME: &'static str = "Kepler";
    fn system(&self) -> &Kepler {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 4> {
        self.exact(0.0)
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    fn error(&self, time: f64, state: &SVector<f64, 4>) -> f64 {
        let difference = state - self.exact(time);
        let m = self.system.mass;
        Vector4::new(
            difference[0],
            difference[1],
            difference[2] / m,
            difference[3] / m,
        )
        .norm()
    }
}

/// The paper's sled from rest at x = 0. The reference is the closed form v²(x) (eq. 24 and
/// docs/mechanics.md#sled-stable-form): the error is |ẋ² − v²(x)| at the numerical x.
pub struct SledProblem {
    pub system: Sled,
    pub end_time: f64,
}

impl SledProblem {
    pub fn standard() -> Self {
        Self {
            system: Sled {
                initial_mass: 20.0,
                accretion: 4.0,
                gravity: 9.81,
                slope: 0.5,
                friction: 0.1,
            },
            end_time: 4.0,
        }
    }

    /// v²(x) of the corrected equation m ẍ = m g (sin θ − f_d cos θ) − c ẋ²:
    /// (2/3) a x (3 + 3ε + ε²)/(1 + ε)², ε = c x/m0.
    pub fn speed_squared(&self, x: f64) -> f64 {
        let ratio = self.system.accretion / self.system.initial_mass;
        x * sled_speed_squared_over_x(self.system.drive(), ratio, x)
    }

    /// v²(x) of the wrong equation that eq. 19 taken literally gives, m ẍ = … − 2c ẋ²:
    /// from d(v² m⁴)/dx = 2 a m⁴, v² = (2/5) a x (5 + 10ε + 10ε² + 5ε³ + ε⁴)/(1 + ε)⁴.
    pub fn literal_speed_squared(&self, x: f64) -> f64 {
        let e = self.system.accretion * x / self.system.initial_mass;
        let numerator = 5.0 + e * (10.0 + e * (10.0 + e * (5.0 + e)));
        2.0 / 5.0 * self.system.drive() * x * numerator / (1.0 + e).powi(4)
    }

    /// ẋ² of a state.
    pub fn numerical_speed_squared(&self, state: &SVector<f64, 2>) -> f64 {
        let v = state[1] / self.system.mass_at(state[0]);
        v * v
    }
}

impl Problem<1, 2> for SledProblem {
    type System = Sled;
    const NAME: &'static str = "sled";
    fn system(&self) -> &Sled {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 2> {
        Vector2::zeros()
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    fn error(&self, _: f64, state: &SVector<f64, 2>) -> f64 {
        (self.numerical_speed_squared(state) - self.speed_squared(state[0])).abs()
    }
}

/// Vertical rocket from rest, constant burn rate: m = m0 − μt, v = u_e ln(m0/m) − g t,
/// y = u_e (t − (m/μ) ln(m0/m)) − ½ g t².
pub struct RocketProblem {
    pub system: Rocket,
    pub initial_mass: f64,
    pub end_time: f64,
}

impl RocketProblem {
    /// Burn-out at t = 20; thrust μ u_e = 15 against weight 9.81 at lift-off; the run ends
    /// at m = m0/4, where 1/m varies enough to exercise the steppers.
    pub fn standard() -> Self {
        Self {
            system: Rocket {
                burn_rate: 0.05,
                exhaust_speed: 300.0,
                gravity: 9.81,
            },
            initial_mass: 1.0,
            end_time: 15.0,
        }
    }
    pub fn exact(&self, time: f64) -> SVector<f64, 3> {
        let Rocket {
            burn_rate,
            exhaust_speed,
            gravity,
        } = self.system;
        let [y, v, m] = rocket_exact(burn_rate, exhaust_speed, gravity, self.initial_mass, time);
        Vector3::new(y, m * v, m)
    }
}

impl Problem<1, 3> for RocketProblem {
    type System = Rocket;
    const NAME: &'static str = "rocket";
    fn system(&self) -> &Rocket {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 3> {
        self.exact(0.0)
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    fn error(&self, time: f64, state: &SVector<f64, 3>) -> f64 {
        (state - self.exact(time)).norm()
    }
}
