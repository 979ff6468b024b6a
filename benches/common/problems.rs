//! Each benchmark system with an initial value, an end time and its reference solution in
//! closed form (independent of every stepper), measured as a relative error. The closed
//! forms are the core tests' own (`core/tests/support/closed_forms.rs`, included here):
//! written once for both.

use varmass::core::nalgebra::{SVector, Vector3, Vector4};
use varmass::core::VariableMassSystem;

use super::closed_forms::{kepler_anomaly, kepler_period, rocket_exact, sled_speed_squared_over_x};
use super::generated::{Kepler, Rocket, Sled};

/// A system, where to start and stop, and the error of a final state against the reference.
pub trait Problem<const N: usize, const S: usize> {
    /// The system being integrated.
    type System: VariableMassSystem<N, S>;
    /// Name in tables and plots.
    const NAME: &'static str;
    /// The system.
    fn system(&self) -> &Self::System;
    /// The state at t = 0.
    fn initial_state(&self) -> SVector<f64, S>;
    /// Where the run stops.
    fn end_time(&self) -> f64;
    /// The relative error of `state` at `time` against the closed form.
    fn error(&self, time: f64, state: &SVector<f64, S>) -> f64;
}

/// The paper's sled (§4) from rest, run until x ≈ 50 m. The reference is the closed form
/// v²(x) (eq. 24, the stable form of docs/mechanics.md#sled-stable-form), so the error |v − v(x)|/v(x) at the numerical x does
/// not depend on where the run stops; the end time only makes it stop near 50 m.
pub struct SledProblem {
    /// The sled (the generated system; the hand-written twin shares its parameters).
    pub system: Sled,
    end_time: f64,
}

impl SledProblem {
    /// The parameters of the core tests: m0 = 20, c = 4, θ = 0.5, f_d = 0.1, so the mass
    /// grows elevenfold over 50 m (ε = c x/m0 = 10).
    pub fn standard() -> Self {
        let system = Sled {
            m0: 20.0,
            c: 4.0,
            g: 9.81,
            theta: 0.5,
            f_d: 0.1,
        };
        let mut problem = Self {
            system,
            end_time: 0.0,
        };
        problem.end_time = problem.time_to(50.0);
        problem
    }

    /// v²(x)/x = (2/3) g (sin θ − f_d cos θ) (3 + 3ε + ε²)/(1 + ε)², ε = c x/m0.
    fn speed_squared_over_x(&self, x: f64) -> f64 {
        let Sled {
            m0,
            c,
            g,
            theta,
            f_d,
        } = self.system;
        sled_speed_squared_over_x(g * (theta.sin() - f_d * theta.cos()), c / m0, x)
    }

    /// The closed-form speed at x.
    pub fn speed(&self, x: f64) -> f64 {
        (x * self.speed_squared_over_x(x)).sqrt()
    }

    /// t(X) = ∫₀ˣ dx / v(x). With x = u², dx/v = 2 du / √(v²/x), a smooth integrand, so
    /// composite Simpson with 2048 panels is accurate far beyond what the stop time needs.
    fn time_to(&self, distance: f64) -> f64 {
        let panels = 2048;
        let top = distance.sqrt();
        let h = top / panels as f64;
        let f = |u: f64| 2.0 / self.speed_squared_over_x(u * u).sqrt();
        let interior: f64 = (1..panels)
            .map(|i| {
                let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
                weight * f(i as f64 * h)
            })
            .sum();
        h / 3.0 * (f(0.0) + interior + f(top))
    }
}

impl Problem<1, 2> for SledProblem {
    type System = Sled;
    const NAME: &'static str = "sled to 50 m";
    fn system(&self) -> &Sled {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 2> {
        SVector::<f64, 2>::zeros()
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    fn error(&self, _: f64, state: &SVector<f64, 2>) -> f64 {
        let x = state[0];
        let speed = state[1] / (self.system.m0 + self.system.c * x);
        let reference = self.speed(x);
        (speed - reference).abs() / reference
    }
}

/// The vertical rocket from rest, burning three quarters of its mass (m0 = 1, μ = 0.05,
/// u_e = 300, 15 s): m = m0 − μt, v = u_e ln(m0/m) − g t,
/// y = u_e (t − (m/μ) ln(m0/m)) − ½ g t² (docs/mechanics.md#vertical-rocket).
pub struct RocketProblem {
    /// The rocket.
    pub system: Rocket,
    /// Its initial mass.
    pub initial_mass: f64,
    /// When the run stops.
    pub end_time: f64,
}

impl RocketProblem {
    /// Thrust μ u_e = 15 against a weight of 9.81 at lift-off.
    pub fn standard() -> Self {
        Self {
            system: Rocket {
                mu: 0.05,
                u_e: 300.0,
                g: 9.81,
            },
            initial_mass: 1.0,
            end_time: 15.0,
        }
    }

    /// The closed form (y, v, m) at `time`.
    pub fn exact(&self, time: f64) -> Vector3<f64> {
        let Rocket { mu, u_e, g } = self.system;
        Vector3::from(rocket_exact(mu, u_e, g, self.initial_mass, time))
    }
}

impl Problem<1, 3> for RocketProblem {
    type System = Rocket;
    const NAME: &'static str = "rocket";
    fn system(&self) -> &Rocket {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 3> {
        Vector3::new(0.0, 0.0, self.initial_mass)
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    /// The largest relative error of height, speed and mass.
    fn error(&self, time: f64, state: &SVector<f64, 3>) -> f64 {
        let exact = self.exact(time);
        let numerical = Vector3::new(state[0], state[1] / state[2], state[2]);
        (0..3)
            .map(|i| (numerical[i] - exact[i]).abs() / exact[i].abs())
            .fold(0.0, f64::max)
    }
}

/// An ellipse of eccentricity 0.5 over three periods from periapsis; the reference solves
/// Kepler's equation E − e sin E = n t by Newton.
pub struct KeplerProblem {
    /// The planet.
    pub system: Kepler,
    /// Semi-major axis a.
    pub semi_major_axis: f64,
    /// Eccentricity e.
    pub eccentricity: f64,
}

impl KeplerProblem {
    /// m = 1.5, k = 1, a = 1, e = 0.5.
    pub fn standard() -> Self {
        Self {
            system: Kepler { m1: 1.5, k: 1.0 },
            semi_major_axis: 1.0,
            eccentricity: 0.5,
        }
    }

    fn period(&self) -> f64 {
        kepler_period(self.semi_major_axis, self.system.k)
    }

    /// Cartesian position and velocity (x, y, ẋ, ẏ) at `time`.
    pub fn exact(&self, time: f64) -> Vector4<f64> {
        let (a, e, k) = (self.semi_major_axis, self.eccentricity, self.system.k);
        let (anomaly, anomaly_rate) = kepler_anomaly(a, e, k, time);
        let b = a * (1.0 - e * e).sqrt();
        Vector4::new(
            a * (anomaly.cos() - e),
            b * anomaly.sin(),
            -a * anomaly.sin() * anomaly_rate,
            b * anomaly.cos() * anomaly_rate,
        )
    }

    /// Cartesian position and velocity of a polar state [r, θ, p_r, p_θ].
    fn cartesian(&self, state: &SVector<f64, 4>) -> Vector4<f64> {
        let m = self.system.m1;
        let (r, th) = (state[0], state[1]);
        let (dr, dth) = (state[2] / m, state[3] / (m * r * r));
        let (sin, cos) = th.sin_cos();
        Vector4::new(
            r * cos,
            r * sin,
            dr * cos - r * dth * sin,
            dr * sin + r * dth * cos,
        )
    }
}

impl Problem<2, 4> for KeplerProblem {
    type System = Kepler;
    const NAME: &'static str = "Kepler e=0.5 (3 orbits)";
    fn system(&self) -> &Kepler {
        &self.system
    }
    fn initial_state(&self) -> SVector<f64, 4> {
        let (a, e, k, m) = (
            self.semi_major_axis,
            self.eccentricity,
            self.system.k,
            self.system.m1,
        );
        let angular_momentum = (k * a * (1.0 - e * e)).sqrt();
        Vector4::new(a * (1.0 - e), 0.0, 0.0, m * angular_momentum)
    }
    fn end_time(&self) -> f64 {
        3.0 * self.period()
    }
    /// The larger of the position error over a and the velocity error over √(k/a).
    fn error(&self, time: f64, state: &SVector<f64, 4>) -> f64 {
        let difference = self.cartesian(state) - self.exact(time);
        let speed_scale = (self.system.k / self.semi_major_axis).sqrt();
        let position = difference.fixed_rows::<2>(0).norm() / self.semi_major_axis;
        let velocity = difference.fixed_rows::<2>(2).norm() / speed_scale;
        position.max(velocity)
    }
}
