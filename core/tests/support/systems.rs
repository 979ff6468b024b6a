//! The test systems, implemented by hand from their Lagrangians.

use nalgebra::{SMatrix, SVector, Vector1, Vector2};
use varmass_core::{SystemError, VariableMassSystem};

/// Harmonic oscillator, constant mass: L = ½ m ẋ² − ½ k x². State [x, p].
#[derive(Clone, Copy, Debug)]
pub struct Oscillator {
    pub mass: f64,
    pub stiffness: f64,
}

impl VariableMassSystem<1, 2> for Oscillator {
    const COORDINATES: [&'static str; 1] = ["x"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, _: &SVector<f64, 2>) -> f64 {
        self.mass
    }
    fn mass_rate(&self, _: usize, _: f64, _: &SVector<f64, 2>) -> f64 {
        0.0
    }
    fn mass_matrix(&self, _: f64, _: &SVector<f64, 2>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(self.mass)
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(self.mass * vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 2>) -> f64 {
        0.5 * self.mass * vs[1] * vs[1] - 0.5 * self.stiffness * vs[0] * vs[0]
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(-self.stiffness * vs[0])
    }
    fn active_force(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn mass_flux_force(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn accelerations(&self, _: f64, vs: &SVector<f64, 2>) -> Result<SVector<f64, 1>, SystemError> {
        Ok(Vector1::new(-self.stiffness * vs[0] / self.mass))
    }
    fn taylor_coefficients(
        &self,
        _: f64,
        state: &SVector<f64, 2>,
        c: &mut [SVector<f64, 2>],
        _: &mut varmass_core::steppers::taylor::series::Scratch,
    ) -> Option<Result<(), SystemError>> {
        super::taylor::oscillator(self.mass, self.stiffness, state, c);
        Some(Ok(()))
    }
}

/// Kepler problem in polar coordinates (r, θ), constant mass, gravitational parameter k:
/// L = ½ m (ṙ² + r² θ̇²) + k m / r. State [r, θ, p_r, p_θ].
#[derive(Clone, Copy, Debug)]
pub struct Kepler {
    pub mass: f64,
    pub gravity: f64,
}

impl VariableMassSystem<2, 4> for Kepler {
    const COORDINATES: [&'static str; 2] = ["r", "theta"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, _: &SVector<f64, 4>) -> f64 {
        self.mass
    }
    fn mass_rate(&self, _: usize, _: f64, _: &SVector<f64, 4>) -> f64 {
        0.0
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 4>) -> SMatrix<f64, 2, 2> {
        SMatrix::<f64, 2, 2>::new(self.mass, 0.0, 0.0, self.mass * s[0] * s[0])
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 4>) -> SVector<f64, 2> {
        Vector2::new(self.mass * vs[2], self.mass * vs[0] * vs[0] * vs[3])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 4>) -> f64 {
        let (r, dr, dtheta) = (vs[0], vs[2], vs[3]);
        0.5 * self.mass * (dr * dr + r * r * dtheta * dtheta) + self.gravity * self.mass / r
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 4>) -> SVector<f64, 2> {
        let (r, dtheta) = (vs[0], vs[3]);
        Vector2::new(
            self.mass * r * dtheta * dtheta - self.gravity * self.mass / (r * r),
            0.0,
        )
    }
    fn active_force(&self, _: f64, _: &SVector<f64, 4>) -> SVector<f64, 2> {
        Vector2::zeros()
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 4>) -> SVector<f64, 2> {
        Vector2::zeros()
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 4>) -> SVector<f64, 2> {
        Vector2::zeros()
    }
    fn mass_flux_force(&self, _: f64, _: &SVector<f64, 4>) -> SVector<f64, 2> {
        Vector2::zeros()
    }
    fn accelerations(&self, _: f64, vs: &SVector<f64, 4>) -> Result<SVector<f64, 2>, SystemError> {
        let (r, dr, dtheta) = (vs[0], vs[2], vs[3]);
        if r == 0.0 {
            return Err(SystemError::SingularMassMatrix);
        }
        Ok(Vector2::new(
            r * dtheta * dtheta - self.gravity / (r * r),
            -2.0 * dr * dtheta / r,
        ))
    }
    fn taylor_coefficients(
        &self,
        _: f64,
        state: &SVector<f64, 4>,
        c: &mut [SVector<f64, 4>],
        _: &mut varmass_core::steppers::taylor::series::Scratch,
    ) -> Option<Result<(), SystemError>> {
        if state[0] == 0.0 {
            return Some(Err(SystemError::SingularMassMatrix));
        }
        super::taylor::kepler(self.mass, self.gravity, state, c);
        Some(Ok(()))
    }
}

/// The paper's sled (§4): m = m0 + c x, L = ½ m ẋ² + m g x sin θ (eq. 20),
/// Q* = −f_d m g cos θ (eq. 22), R2 = −c ẋ² (eq. 23). State [x, p].
#[derive(Clone, Copy, Debug)]
pub struct Sled {
    pub initial_mass: f64,
    pub accretion: f64,
    pub gravity: f64,
    pub slope: f64,
    pub friction: f64,
}

impl Sled {
    pub fn mass_at(&self, x: f64) -> f64 {
        self.initial_mass + self.accretion * x
    }
    /// g (sin θ − f_d cos θ), the driving acceleration.
    pub fn drive(&self) -> f64 {
        self.gravity * (self.slope.sin() - self.friction * self.slope.cos())
    }
}

impl VariableMassSystem<1, 2> for Sled {
    const COORDINATES: [&'static str; 1] = ["x"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, s: &SVector<f64, 2>) -> f64 {
        self.mass_at(s[0])
    }
    fn mass_rate(&self, _: usize, _: f64, vs: &SVector<f64, 2>) -> f64 {
        self.accretion * vs[1]
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 2>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(self.mass_at(s[0]))
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(self.mass_at(vs[0]) * vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 2>) -> f64 {
        let m = self.mass_at(vs[0]);
        0.5 * m * vs[1] * vs[1] + m * self.gravity * vs[0] * self.slope.sin()
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        // Frozen mass: ∂*L/∂x = m g sin θ, no c-term.
        Vector1::new(self.mass_at(vs[0]) * self.gravity * self.slope.sin())
    }
    fn active_force(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(-self.friction * self.mass_at(vs[0]) * self.gravity * self.slope.cos())
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn impact_force(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(-self.accretion * vs[1] * vs[1])
    }
    fn mass_flux_force(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        // ṁ ∂*p/∂m = (c ẋ) ẋ.
        Vector1::new(self.accretion * vs[1] * vs[1])
    }
    fn accelerations(&self, _: f64, vs: &SVector<f64, 2>) -> Result<SVector<f64, 1>, SystemError> {
        let m = self.mass_at(vs[0]);
        Ok(Vector1::new(
            self.drive() - self.accretion * vs[1] * vs[1] / m,
        ))
    }
    fn taylor_coefficients(
        &self,
        _: f64,
        state: &SVector<f64, 2>,
        c: &mut [SVector<f64, 2>],
        _: &mut varmass_core::steppers::taylor::series::Scratch,
    ) -> Option<Result<(), SystemError>> {
        let parameters = (self.initial_mass, self.accretion, self.drive());
        super::taylor::sled(parameters, state, c);
        Some(Ok(()))
    }
}

/// Vertical rocket, state mass m with ṁ = −μ, exhaust at −u_e relative:
/// L = ½ m ẏ² − m g y, R1 = −μ u_e, Σ ṁ ∂p/∂m = −μ ẏ. State [y, p, m].
#[derive(Clone, Copy, Debug)]
pub struct Rocket {
    pub burn_rate: f64,
    pub exhaust_speed: f64,
    pub gravity: f64,
}

impl VariableMassSystem<1, 3> for Rocket {
    const COORDINATES: [&'static str; 1] = ["y"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, s: &SVector<f64, 3>) -> f64 {
        s[2]
    }
    fn mass_rate(&self, _: usize, _: f64, _: &SVector<f64, 3>) -> f64 {
        -self.burn_rate
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 3>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(s[2])
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(vs[2] * vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 3>) -> f64 {
        0.5 * vs[2] * vs[1] * vs[1] - vs[2] * self.gravity * vs[0]
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-vs[2] * self.gravity)
    }
    fn active_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.burn_rate * self.exhaust_speed)
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn mass_flux_force(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.burn_rate * vs[1])
    }
    fn accelerations(&self, _: f64, vs: &SVector<f64, 3>) -> Result<SVector<f64, 1>, SystemError> {
        if vs[2] <= 0.0 {
            return Err(SystemError::NonPositiveMass { index: 0 });
        }
        Ok(Vector1::new(
            -self.gravity + self.burn_rate * self.exhaust_speed / vs[2],
        ))
    }
}
