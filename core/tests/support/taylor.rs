//! Taylor coefficients of the test systems, written by hand from their equations of motion
//! (each a few recurrences of Jorba & Zou 2005, §2), so the Taylor stepper can be tested on
//! the core's own problems. Each fills `c[0..]` from `c[0] = y0`.

use nalgebra::SVector;
use varmass_core::steppers::taylor::MAX_ORDER;

/// ẋ = p/m, ṗ = −k x.
pub fn oscillator(mass: f64, stiffness: f64, y0: &SVector<f64, 2>, c: &mut [SVector<f64, 2>]) {
    c[0] = *y0;
    for j in 0..c.len() - 1 {
        let next = (j + 1) as f64;
        let (x, p) = (c[j][0], c[j][1]);
        c[j + 1] = SVector::<f64, 2>::new(p / (mass * next), -stiffness * x / next);
    }
}

/// Σᵢ₌₀ʲ a[i] b[j−i].
fn cauchy(a: &[f64], b: &[f64], j: usize) -> f64 {
    (0..=j).map(|i| a[i] * b[j - i]).sum()
}

/// Polar Kepler, [r, θ, p_r, p_θ]: ṙ = p_r/m, θ̇ = p_θ u²/m, ṗ_r = p_θ² u³/m − k m u²,
/// ṗ_θ = 0, with u = 1/r (u r = 1).
pub fn kepler(mass: f64, gravity: f64, y0: &SVector<f64, 4>, c: &mut [SVector<f64, 4>]) {
    let zero = [0.0; MAX_ORDER + 1];
    let (mut r, mut p_theta, mut u, mut u2, mut u3, mut p2) = (zero, zero, zero, zero, zero, zero);
    c[0] = *y0;
    for j in 0..c.len() - 1 {
        r[j] = c[j][0];
        p_theta[j] = c[j][3];
        u[j] = if j == 0 {
            1.0 / r[0]
        } else {
            -(1..=j).map(|i| r[i] * u[j - i]).sum::<f64>() / r[0]
        };
        u2[j] = cauchy(&u, &u, j);
        u3[j] = cauchy(&u2, &u, j);
        p2[j] = cauchy(&p_theta, &p_theta, j);
        let next = (j + 1) as f64;
        c[j + 1] = SVector::<f64, 4>::new(
            c[j][2] / mass,
            cauchy(&p_theta, &u2, j) / mass,
            cauchy(&p2, &u3, j) / mass - gravity * mass * u2[j],
            0.0,
        ) / next;
    }
}

/// The sled, [x, p]: m = m0 + c x, ẋ = w with w m = p, ṗ = m g (sin θ − f_d cos θ) (the
/// impact force −c ẋ² and the mass flux +c ẋ² cancel in the true ṗ).
pub fn sled(
    (initial_mass, accretion, drive): (f64, f64, f64),
    y0: &SVector<f64, 2>,
    c: &mut [SVector<f64, 2>],
) {
    let zero = [0.0; MAX_ORDER + 1];
    let (mut m, mut w) = (zero, zero);
    c[0] = *y0;
    for j in 0..c.len() - 1 {
        m[j] = accretion * c[j][0] + if j == 0 { initial_mass } else { 0.0 };
        let sum: f64 = (1..=j).map(|i| m[i] * w[j - i]).sum();
        w[j] = (c[j][1] - sum) / m[0];
        let next = (j + 1) as f64;
        c[j + 1] = SVector::<f64, 2>::new(w[j], drive * m[j]) / next;
    }
}
