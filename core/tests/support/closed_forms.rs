//! The closed-form references of the test problems, written once: the core tests
//! (`problems.rs` here) and the benchmarks (`benches/common/problems.rs`, which includes this
//! file by `#[path]`) measure their errors against these. Plain `f64` in and out, so the
//! file compiles in either crate whatever system type each pairs it with.

/// The sled from rest (docs/mechanics.md#sled-stable-form, eq. 24 in its stable form):
/// v²(x)/x = (2/3) a (3 + 3ε + ε²)/(1 + ε)², ε = c x/m0, with a = g (sin θ − f_d cos θ) the
/// driving acceleration and `accretion_ratio` = c/m0. Finite at x = 0 (v² ∝ x there).
pub fn sled_speed_squared_over_x(drive: f64, accretion_ratio: f64, x: f64) -> f64 {
    let epsilon = accretion_ratio * x;
    2.0 / 3.0 * drive * (3.0 + 3.0 * epsilon + epsilon * epsilon)
        / ((1.0 + epsilon) * (1.0 + epsilon))
}

/// The vertical rocket from rest with a constant burn rate μ, exhaust speed u_e, gravity g
/// and initial mass m0 (docs/mechanics.md#vertical-rocket): m = m0 − μt,
/// v = u_e ln(m0/m) − g t, y = u_e (t − (m/μ) ln(m0/m)) − ½ g t². Returns (y, v, m).
pub fn rocket_exact(burn_rate: f64, exhaust_speed: f64, gravity: f64, m0: f64, t: f64) -> [f64; 3] {
    let m = m0 - burn_rate * t;
    let log_ratio = (m0 / m).ln();
    let v = exhaust_speed * log_ratio - gravity * t;
    let y = exhaust_speed * (t - m / burn_rate * log_ratio) - 0.5 * gravity * t * t;
    [y, v, m]
}

/// The period 2π √(a³/k) of a Kepler ellipse of semi-major axis a, gravitational
/// parameter k.
pub fn kepler_period(semi_major_axis: f64, k: f64) -> f64 {
    2.0 * core::f64::consts::PI * (semi_major_axis.powi(3) / k).sqrt()
}

/// The eccentric anomaly E of a Kepler ellipse at time t from periapsis: Kepler's equation
/// E − e sin E = n t, n = √(k/a³), solved by Newton from E = n t. Returns (E, Ė).
pub fn kepler_anomaly(semi_major_axis: f64, eccentricity: f64, k: f64, t: f64) -> (f64, f64) {
    let e = eccentricity;
    let mean_motion = (k / semi_major_axis.powi(3)).sqrt();
    let mean_anomaly = mean_motion * t;
    let mut anomaly = mean_anomaly;
    for _ in 0..50 {
        let correction = (anomaly - e * anomaly.sin() - mean_anomaly) / (1.0 - e * anomaly.cos());
        anomaly -= correction;
        if correction.abs() < 1e-16 {
            break;
        }
    }
    (anomaly, mean_motion / (1.0 - e * anomaly.cos()))
}
