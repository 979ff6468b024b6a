//! The same physics as `generated.rs`, written by hand in plain Rust: the trait's required
//! methods plus a `state_rate` with the least arithmetic a person would write for the same
//! parameter struct (trigonometric factors computed per call, as the formulas read; nothing
//! cached between calls, since the generated code cannot cache either).

use varmass::core::nalgebra::{SMatrix, SVector, Vector1, Vector2, Vector3, Vector4};
use varmass::core::{SystemError, VariableMassSystem};

use super::generated::{Kepler, Rocket, Sled};

/// The sled by hand: m = m0 + c x, ẋ = p/m and, since the snow arrives at rest, the true
/// ṗ = m g (sin θ − f_d cos θ) (docs/mechanics.md#the-sled, after eq. 24).
#[derive(Clone, Copy, Debug)]
pub struct HandSled(pub Sled);

impl VariableMassSystem<1, 2> for HandSled {
    const COORDINATES: [&'static str; 1] = ["x"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, s: &SVector<f64, 2>) -> f64 {
        self.0.m0 + self.0.c * s[0]
    }
    fn mass_rate(&self, _: usize, _: f64, vs: &SVector<f64, 2>) -> f64 {
        self.0.c * vs[1]
    }
    fn mass_matrix(&self, t: f64, s: &SVector<f64, 2>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(self.mass(0, t, s))
    }
    fn momenta(&self, t: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(self.mass(0, t, vs) * vs[1])
    }
    fn lagrangian(&self, t: f64, vs: &SVector<f64, 2>) -> f64 {
        let m = self.mass(0, t, vs);
        0.5 * m * vs[1] * vs[1] + m * self.0.g * vs[0] * self.0.theta.sin()
    }
    fn lagrangian_gradient(&self, t: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(self.mass(0, t, vs) * self.0.g * self.0.theta.sin())
    }
    fn active_force(&self, t: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(-self.0.f_d * self.mass(0, t, vs) * self.0.g * self.0.theta.cos())
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn impact_force(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(-self.0.c * vs[1] * vs[1])
    }
    fn mass_flux_force(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(self.0.c * vs[1] * vs[1])
    }
    fn accelerations(&self, t: f64, vs: &SVector<f64, 2>) -> Result<SVector<f64, 1>, SystemError> {
        let Sled {
            c, g, theta, f_d, ..
        } = self.0;
        let m = self.mass(0, t, vs);
        Ok(Vector1::new(
            g * (theta.sin() - f_d * theta.cos()) - c * vs[1] * vs[1] / m,
        ))
    }
    #[inline]
    fn state_rate(&self, _: f64, s: &SVector<f64, 2>) -> Result<SVector<f64, 2>, SystemError> {
        let Sled {
            m0,
            c,
            g,
            theta,
            f_d,
        } = self.0;
        let m = m0 + c * s[0];
        Ok(Vector2::new(
            s[1] / m,
            m * g * (theta.sin() - f_d * theta.cos()),
        ))
    }
}

/// The rocket by hand: state [y, p, m], ẏ = p/m, ṗ = −m g + μ u_e − μ ẏ, ṁ = −μ.
#[derive(Clone, Copy, Debug)]
pub struct HandRocket(pub Rocket);

impl VariableMassSystem<1, 3> for HandRocket {
    const COORDINATES: [&'static str; 1] = ["y"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, s: &SVector<f64, 3>) -> f64 {
        s[2]
    }
    fn mass_rate(&self, _: usize, _: f64, _: &SVector<f64, 3>) -> f64 {
        -self.0.mu
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 3>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(s[2])
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(vs[2] * vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 3>) -> f64 {
        0.5 * vs[2] * vs[1] * vs[1] - vs[2] * self.0.g * vs[0]
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-vs[2] * self.0.g)
    }
    fn active_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.0.mu * self.0.u_e)
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn mass_flux_force(&self, _: f64, vs: &SVector<f64, 3>) -> SVector<f64, 1> {
        Vector1::new(-self.0.mu * vs[1])
    }
    fn accelerations(&self, _: f64, vs: &SVector<f64, 3>) -> Result<SVector<f64, 1>, SystemError> {
        Ok(Vector1::new(-self.0.g + self.0.mu * self.0.u_e / vs[2]))
    }
    #[inline]
    fn state_rate(&self, _: f64, s: &SVector<f64, 3>) -> Result<SVector<f64, 3>, SystemError> {
        let Rocket { mu, u_e, g } = self.0;
        let (p, m) = (s[1], s[2]);
        let v = p / m;
        Ok(Vector3::new(v, -m * g + mu * (u_e - v), -mu))
    }
}

/// Kepler by hand, polar: ṙ = p_r/m, θ̇ = p_θ/(m r²), ṗ_r = p_θ²/(m r³) − k m/r², ṗ_θ = 0.
#[derive(Clone, Copy, Debug)]
pub struct HandKepler(pub Kepler);

impl VariableMassSystem<2, 4> for HandKepler {
    const COORDINATES: [&'static str; 2] = ["r", "th"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, _: &SVector<f64, 4>) -> f64 {
        self.0.m1
    }
    fn mass_rate(&self, _: usize, _: f64, _: &SVector<f64, 4>) -> f64 {
        0.0
    }
    fn mass_matrix(&self, _: f64, s: &SVector<f64, 4>) -> SMatrix<f64, 2, 2> {
        SMatrix::<f64, 2, 2>::new(self.0.m1, 0.0, 0.0, self.0.m1 * s[0] * s[0])
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 4>) -> SVector<f64, 2> {
        Vector2::new(self.0.m1 * vs[2], self.0.m1 * vs[0] * vs[0] * vs[3])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 4>) -> f64 {
        let (r, dr, dth) = (vs[0], vs[2], vs[3]);
        0.5 * self.0.m1 * (dr * dr + r * r * dth * dth) + self.0.k * self.0.m1 / r
    }
    fn lagrangian_gradient(&self, _: f64, vs: &SVector<f64, 4>) -> SVector<f64, 2> {
        let (r, dth) = (vs[0], vs[3]);
        Vector2::new(
            self.0.m1 * r * dth * dth - self.0.k * self.0.m1 / (r * r),
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
        let (r, dr, dth) = (vs[0], vs[2], vs[3]);
        Ok(Vector2::new(
            r * dth * dth - self.0.k / (r * r),
            -2.0 * dr * dth / r,
        ))
    }
    #[inline]
    fn state_rate(&self, _: f64, s: &SVector<f64, 4>) -> Result<SVector<f64, 4>, SystemError> {
        let Kepler { m1: m, k } = self.0;
        let (r, p_r, p_th) = (s[0], s[2], s[3]);
        let inverse_r = 1.0 / r;
        let th_dot = p_th / (m * r * r);
        Ok(Vector4::new(
            p_r / m,
            th_dot,
            p_th * th_dot * inverse_r - k * m * inverse_r * inverse_r,
            0.0,
        ))
    }
}
