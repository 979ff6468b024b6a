//! The six-degree-of-freedom jet-damping case (issue 36): a rocket in vacuum, burning for
//! 4 s, pitching at 0.1 rad/s at ignition, its exhaust axial from a nozzle on its axis at l
//! below the centre of mass, against Thomson's closed form — a regression test for the
//! factor that RocketPy's 6-DOF gets wrong (it uses l²/4 for l², docs/validation.md).
//!
//! By hand (W. T. Thomson, *Introduction to Space Dynamics*, §7.8; docs/mechanics.md#jet-damping):
//! with the reference point at the centre of mass, the transverse inertia A = m k² (the mass
//! lost uniformly, so k stays), ṁ = −μ, and only a pitch rate ω about body x, the pitch
//! equation is d(A ω)/dt = −μ l² ω (the exhaust carries away the angular momentum of its
//! transverse velocity ω l at the nozzle, μ l² ω; the mass's own loss from A is in
//! d(Aω)/dt through Ȧ = −μ k²), so
//!
//! ```text
//! A ω̇ = −μ (l² − k²) ω,   A = m k²,   dt = −dm/μ   ⇒   ω = ω₀ (A/A₀)^n,   n = (l² − k²)/k²
//! θ(t) = ω₀ m₀/(μ (n + 1)) · (1 − (m/m₀)^(n+1))
//! ```
//!
//! With A = B and ω along x at the start, Euler's equations keep ω along x (the gyroscopic
//! terms (A − C) ω_y ω_z vanish), so the closed form is the whole motion of the attitude;
//! the thrust μ u_e along the axis moves the centre of mass and does not enter it.

use varmass::core::nalgebra::SVector;
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// The rocket, derived at run time by the interpreter (its Taylor recurrences are the
/// tape's: no compile-time emission to build).
const VACUUM_ROCKET: &str = "
coordinates x, y, z, e0, e1, e2, e3
mass m: state, rate -mu
inertia A = m*k^2
inertia C = m*kc^2
rigid rocket: mass m, inertia [A, A, C], position [x, y, z], orientation quaternion(e0, e1, e2, e3)
outflow rocket: rate mu, at [0, 0, -l], relative_velocity body [0, 0, -u_e]
";

/// The rocket's system with its parameters.
fn vacuum_rocket() -> TapeSystem<7, 15> {
    let derivation = derive_source(VACUUM_ROCKET, Parameters::Inferred).unwrap_or_else(|errors| {
        let messages: Vec<String> = errors.iter().map(|e| e.render(VACUUM_ROCKET)).collect();
        panic!("{}", messages.join("\n"))
    });
    let parameters = [("mu", MU), ("k", K), ("kc", 0.1), ("l", L), ("u_e", 2000.0)];
    TapeSystem::new(Program::new(derivation, &parameters).expect("program")).expect("sizes")
}

/// Calisto-like: 20 kg at ignition, 1 kg/s for 4 s, k = 0.6 m, the nozzle 1.2 m below the
/// centre of mass: n = (1.44 − 0.36)/0.36 = 3.
const M0: f64 = 20.0;
const MU: f64 = 1.0;
const K: f64 = 0.6;
const L: f64 = 1.2;
const OMEGA0: f64 = 0.1;
const BURN: f64 = 4.0;

/// The closed form at t: (ω, θ).
fn thomson(t: f64) -> (f64, f64) {
    let n = (L * L - K * K) / (K * K);
    let ratio = (M0 - MU * t) / M0;
    let theta = OMEGA0 * M0 / (MU * (n + 1.0)) * (1.0 - ratio.powf(n + 1.0));
    (OMEGA0 * ratio.powf(n), theta)
}

/// The body rate about x and the pitch angle of a state, from the quaternion (a rotation
/// about x alone: q = (cos θ/2, sin θ/2, 0, 0), ω_x = 2(e0 ė1 − e1 ė0)/|q|²).
fn pitch(system: &TapeSystem<7, 15>, t: f64, state: &SVector<f64, 15>) -> (f64, f64) {
    let v = system.velocity_state(t, state).unwrap();
    let (e0, e1) = (state[3], state[4]);
    let (de0, de1) = (v[7 + 3], v[7 + 4]);
    let n = e0 * e0 + e1 * e1 + state[5].powi(2) + state[6].powi(2);
    (2.0 * (e0 * de1 - e1 * de0) / n, 2.0 * e1.atan2(e0))
}

#[test]
fn the_pitch_rate_decays_as_thomsons_closed_form_through_a_4_s_burn() {
    let system = vacuum_rocket();
    // At rest but for the pitch rate: q = (1, 0, 0, 0), q̇ = ½ q ⊗ (0, ω₀, 0, 0).
    let mut velocity = SVector::<f64, 15>::zeros();
    velocity[3] = 1.0;
    velocity[7 + 4] = 0.5 * OMEGA0;
    velocity[14] = M0;
    let start = system.momentum_state(0.0, &velocity);
    // The Taylor stepper on the interpreter's recurrences, at 1e-14 (DOP853 at its floor of 1e-13
    // reaches 1.9e-12, the global error of a 4 s run).
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(1e-14, 1e-14, Floor::Taylor).unwrap());
    let mut stepper = Taylor::new(&system, 0.0, start, control).unwrap();
    // Every 0.1 s to the end of the burn, each run continuing the last.
    let (mut worst_omega, mut worst_theta) = (0.0_f64, 0.0_f64);
    for k in 1..=40 {
        let t = f64::from(k) * BURN / 40.0;
        let solution = run(&mut stepper, &RunConfig::until(t).continuing(), &[]).unwrap();
        let (end, state) = solution.last().expect("a point");
        assert_eq!(end, t);
        let (omega, theta) = pitch(&system, t, state);
        let (exact_omega, exact_theta) = thomson(t);
        worst_omega = worst_omega.max((omega - exact_omega).abs() / exact_omega);
        worst_theta = worst_theta.max((theta - exact_theta).abs() / exact_theta);
    }
    let (omega, theta) = thomson(BURN);
    println!(
        "after {BURN} s: ω = {omega} rad/s, θ = {}°; worst ω {worst_omega:e}, θ {worst_theta:e}",
        theta.to_degrees()
    );
    // Measured: ω 8.9e-14, θ 2.5e-14 relative (θ(4 s) = 16.914°, ω(4 s) = 0.0512 rad/s);
    // the bound 1e-12 is the issue's, 11× the measured ω.
    assert!(worst_omega < 1e-12, "ω relative error {worst_omega:e}");
    assert!(worst_theta < 1e-12, "θ relative error {worst_theta:e}");
}
