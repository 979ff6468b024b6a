//! The closed form of a rocket launched from an inclined rail (tests/rail.rs and
//! cli/tests/rail.rs; the derivation is in tests/rail.rs's header): the lift-off from the
//! rail's bottom, the slide up the rail s(τ), ṡ(τ), and the exit where s = L. The rocket of
//! models/rocket_on_rail.toml. With its parameters free, the flight after the exit
//! ([`flight`]) and a derivative of it ([`richardson`]), for the sensitivities
//! (tests/sensitivities_supports.rs, cli/tests/sensitivity.rs).
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

/// The rail's direction d = (cos i, 0, sin i).
pub fn direction() -> [f64; 3] {
    [INCLINATION.cos(), 0.0, INCLINATION.sin()]
}

/// The rocket launched from the rail by hand, p = [m0, μ, g, u_e], at t after the exit:
/// (x, z, ẋ, ż). Along the rail m s̈ = μ u_e − m g sin i: held until m_L = μ u_e/(g sin i), at
/// t_L = (m0 − m_L)/μ; sliding, with τ = t − t_L and m = m_L − μτ,
/// ṡ = u_e ln(m_L/m) − g sin i τ and s = u_e (τ + (m/μ) ln(m/m_L)) − ½ g sin i τ²; the exit
/// where s = L (Newton), at t_e with speed ṡ_e and mass m_e. Free after it, with
/// σ = t − t_e and m = m_e − μσ, the thrust still along d and the weight down:
///
///   v = (ṡ_e + u_e ln(m_e/m)) d − g σ ẑ,
///   r = (L + ṡ_e σ + u_e (σ + (m/μ) ln(m/m_e))) d − ½ g σ² ẑ.
pub fn flight(p: &[f64; 4], t: f64) -> [f64; 4] {
    let [m0, mu, g, u_e] = *p;
    let gs = g * INCLINATION.sin();
    let m_l = mu * u_e / gs;
    let t_l = (m0 - m_l) / mu;
    let slide = |tau: f64| {
        let m = m_l - mu * tau;
        let s = u_e * (tau + m / mu * (m / m_l).ln()) - 0.5 * gs * tau * tau;
        (s, u_e * (m_l / m).ln() - gs * tau)
    };
    let mut tau = 7.0;
    for _ in 0..60 {
        let (s, v) = slide(tau);
        tau -= (s - LENGTH) / v;
    }
    let (_, speed) = slide(tau);
    let m_e = m_l - mu * tau;
    let sigma = t - t_l - tau;
    let m = m_e - mu * sigma;
    let along_v = speed + u_e * (m_e / m).ln();
    let along_r = LENGTH + speed * sigma + u_e * (sigma + m / mu * (m / m_e).ln());
    let [dx, _, dz] = direction();
    [
        along_r * dx,
        along_r * dz - 0.5 * g * sigma * sigma,
        along_v * dx,
        along_v * dz - g * sigma,
    ]
}

/// ∂F/∂p_i of a closed form F at `p` by Richardson's extrapolation of central differences
/// at steps h and h/2 (h = 1e-4 |p_i|): the error O(h⁴) ~ 1e-16 relative, rounding ~1e-11.
pub fn richardson<const K: usize, const P: usize>(
    f: impl Fn(&[f64; P]) -> [f64; K],
    p: &[f64; P],
    i: usize,
) -> [f64; K] {
    let central = |h: f64| {
        let (mut up, mut down) = (*p, *p);
        up[i] += h;
        down[i] -= h;
        let (a, b) = (f(&up), f(&down));
        core::array::from_fn::<f64, K, _>(|k| (a[k] - b[k]) / (2.0 * h))
    };
    let h = 1e-4 * p[i].abs();
    let (coarse, fine) = (central(h), central(h / 2.0));
    core::array::from_fn(|k| (4.0 * fine[k] - coarse[k]) / 3.0)
}
