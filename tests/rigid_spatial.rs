//! Spatial rigid bodies (docs/mechanics.md#rigid-bodies) against closed forms: the
//! torque-free axisymmetric body in two Euler sequences, the heavy symmetric top on its
//! steady precession, and a spinning body with an axial exhaust (Thomson's jet damping in
//! space). The body rates are computed here from the textbook formulas of each sequence,
//! independently of the derivation's own.

use varmass::core::nalgebra::{Matrix3, Vector3};
use varmass::interpret::{Program, Quantity};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

fn program(source: &str, parameters: &[(&str, f64)]) -> Program {
    let derivation = derive_source(source, Parameters::Inferred).unwrap_or_else(|errors| {
        let messages: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
        panic!("{}", messages.join("\n"))
    });
    Program::new(derivation, parameters).expect("program")
}

/// Body rates of the intrinsic sequences from the textbooks (Goldstein §4.9 for zxz;
/// the aerospace yaw-pitch-roll ψ, θ, φ for zyx): ω = B(angles) · rates.
fn body_rates(sequence: &str, a: [f64; 3], rates: [f64; 3]) -> Vector3<f64> {
    let [d1, d2, d3] = rates;
    match sequence {
        // ψ (yaw), θ (pitch), φ (roll)
        "zyx" => {
            let (_, th, ph) = (a[0], a[1], a[2]);
            Vector3::new(
                d3 - d1 * th.sin(),
                d2 * ph.cos() + d1 * ph.sin() * th.cos(),
                -d2 * ph.sin() + d1 * ph.cos() * th.cos(),
            )
        }
        // φ (precession), θ (nutation), ψ (spin)
        "zxz" => {
            let (_, th, ps) = (a[0], a[1], a[2]);
            Vector3::new(
                d1 * th.sin() * ps.sin() + d2 * ps.cos(),
                d1 * th.sin() * ps.cos() - d2 * ps.sin(),
                d1 * th.cos() + d3,
            )
        }
        _ => unreachable!(),
    }
}

/// The angle rates giving body rates `omega` (B solved numerically).
fn angle_rates(sequence: &str, a: [f64; 3], omega: Vector3<f64>) -> [f64; 3] {
    let columns: Vec<Vector3<f64>> = (0..3)
        .map(|i| {
            let mut unit = [0.0; 3];
            unit[i] = 1.0;
            body_rates(sequence, a, unit)
        })
        .collect();
    let b = Matrix3::from_columns(&columns);
    let rates = b.lu().solve(&omega).expect("away from gimbal lock");
    [rates[0], rates[1], rates[2]]
}

/// R of an intrinsic sequence from elementary rotations, for the initial conditions.
fn rotation(sequence: &str, a: [f64; 3]) -> Matrix3<f64> {
    let about = |axis: char, angle: f64| {
        let (s, c) = angle.sin_cos();
        match axis {
            'x' => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
            'y' => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
            _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
        }
    };
    let axes: Vec<char> = sequence.chars().collect();
    about(axes[0], a[0]) * about(axes[1], a[1]) * about(axes[2], a[2])
}

/// The state [q, p, m_s] of a body at `angles` turning at body rates `omega` (and moving
/// with `velocity` when it has a position), the momenta from the program itself.
fn start(
    program: &Program,
    sequence: &str,
    position: Option<[f64; 3]>,
    velocity: [f64; 3],
    angles: [f64; 3],
    omega: Vector3<f64>,
    masses: &[f64],
) -> Vec<f64> {
    let rates = angle_rates(sequence, angles, omega);
    let mut q: Vec<f64> = position.map(Vec::from).unwrap_or_default();
    let mut q_dot: Vec<f64> = position.map(|_| Vec::from(velocity)).unwrap_or_default();
    q.extend(angles);
    q_dot.extend(rates);
    let n = q.len();
    let mut velocity_state = q.clone();
    velocity_state.extend(&q_dot);
    velocity_state.extend(masses);
    let mut p = vec![0.0; n];
    program.evaluate(Quantity::Momenta, 0.0, &velocity_state, &mut p);
    let mut state = q;
    state.extend(p);
    state.extend(masses);
    state
}

/// ω in body axes at a state [q, p, m_s], through the program's q̇.
fn omega_at(program: &Program, sequence: &str, state: &[f64], offset: usize) -> Vector3<f64> {
    let n = program.coordinate_count();
    let mut q_dot = vec![0.0; n];
    program.velocities(0.0, state, &mut q_dot).unwrap();
    let angles = [state[offset], state[offset + 1], state[offset + 2]];
    let rates = [q_dot[offset], q_dot[offset + 1], q_dot[offset + 2]];
    body_rates(sequence, angles, rates)
}

/// Integrates the program with DOP853 (through its run-time sized state rate) and calls
/// `visit(t, state)` at every step.
fn integrate<const N: usize, const S: usize>(
    program: Program,
    state: &[f64],
    end: f64,
    tolerance: f64,
    mut visit: impl FnMut(&Program, f64, &[f64]),
) {
    let system = varmass::interpret::TapeSystem::<N, S>::new(program).expect("sizes");
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..AdaptiveControl::default()
    });
    let start = SVector::<f64, S>::from_column_slice(state);
    let mut stepper = Dop853::new(&system, 0.0, start, control).unwrap();
    let solution = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    for (&t, s) in solution.times.iter().zip(&solution.states) {
        visit(system.program(), t, s.as_slice());
    }
}

/// Torque-free, A = B ≠ C. Euler's equations A ω̇1 = (A − C) ω2 ω3, A ω̇2 = (C − A) ω3 ω1,
/// C ω̇3 = 0 give ω3 constant and (ω1 + i ω2)(t) = (ω1 + i ω2)(0) e^{iΩt}, Ω = (C − A)/A ω3;
/// and H = T stays. Returns the worst relative error of ω and of H.
fn torque_free(sequence: &str, angles: [f64; 3]) -> f64 {
    let source = format!(
        "coordinates a1, a2, a3
         mass m = m0
         rigid top: mass m, inertia [A, A, C], position [0, 0, 0], orientation {sequence}(a1, a2, a3)"
    );
    let (a, c) = (1.0, 1.6);
    let parameters = [("m0", 2.0), ("A", a), ("C", c)];
    let program = program(&source, &parameters);
    // Angular momentum along the world z axis: the symmetry axis cones about it at the
    // nutation angle of the start, far from each sequence's gimbal lock.
    let r = rotation(sequence, angles);
    let inertia = Matrix3::from_diagonal(&Vector3::new(a, a, c));
    let omega0 = inertia.try_inverse().unwrap() * r.transpose() * Vector3::new(0.0, 0.0, 4.0);
    let state = start(&program, sequence, None, [0.0; 3], angles, omega0, &[]);
    let spin = (c - a) / a * omega0[2];
    let mut worst = 0.0_f64;
    let mut energy0 = [0.0];
    program
        .evaluate_at_state(Quantity::Energy, 0.0, &state, &mut energy0)
        .unwrap();
    integrate::<3, 6>(program, &state, 100.0, 1e-13, |program, t, s| {
        let mut energy = [0.0];
        program
            .evaluate_at_state(Quantity::Energy, t, s, &mut energy)
            .unwrap();
        // H = T is conserved; measured within the rates' own error.
        worst = worst.max((energy[0] - energy0[0]).abs() / energy0[0]);
        let omega = omega_at(program, sequence, s, 0);
        let (sin, cos) = (spin * t).sin_cos();
        let expected = Vector3::new(
            omega0[0] * cos - omega0[1] * sin,
            omega0[0] * sin + omega0[1] * cos,
            omega0[2],
        );
        worst = worst.max((omega - expected).norm() / omega0.norm());
    });
    worst
}

#[test]
fn torque_free_axisymmetric_body_in_two_sequences() {
    let zyx = torque_free("zyx", [0.3, 0.2, -0.4]);
    let zxz = torque_free("zxz", [0.3, 0.5, -0.4]);
    eprintln!("torque-free: zyx {zyx:e}, zxz {zxz:e}");
    // Measured (ω and H together): 2.9e-12 (zyx), 3.9e-14 (zxz) with DOP853 at 1e-13;
    // bound 1e-10 over 100 s (the issue's).
    assert!(zyx < 1e-10, "zyx: {zyx:e}");
    assert!(zxz < 1e-10, "zxz: {zxz:e}");
}

/// The heavy symmetric top (Goldstein §5.7) about its fixed tip, in zxz(φ, θ, ψ), centre of
/// mass at h on the axis: with A_p = A + m h² about the tip, steady precession at θ0 with
/// φ̇ = Ω needs m g h = Ω (C ω3 − A_p Ω cos θ0), ω3 = ψ̇ + Ω cos θ0. Started there with
/// θ̇ = 0, θ and φ̇ stay.
#[test]
fn heavy_top_stays_on_its_steady_precession() {
    let source = "coordinates ph, th, ps
        mass m = m0
        rigid top: mass m, inertia [A, A, C], position [0, 0, 0], orientation zxz(ph, th, ps), centre [0, 0, h]
        potential m*g*h*cos(th)";
    let (m0, a, c, h, g) = (0.5, 0.002, 0.003, 0.04, 9.81);
    let parameters = [("m0", m0), ("A", a), ("C", c), ("h", h), ("g", g)];
    let program = program(source, &parameters);
    let (theta0, precession): (f64, f64) = (0.6, 2.0);
    let a_tip = a + m0 * h * h;
    let spin = (m0 * g * h / precession + a_tip * precession * theta0.cos()) / c;
    let rates = [precession, 0.0, spin - precession * theta0.cos()];
    let angles = [0.0, theta0, 0.0];
    let omega = body_rates("zxz", angles, rates);
    let state = start(&program, "zxz", None, [0.0; 3], angles, omega, &[]);
    let (mut worst_theta, mut worst_rate) = (0.0_f64, 0.0_f64);
    integrate::<3, 6>(program, &state, 20.0, 1e-13, |program, _, s| {
        let mut q_dot = [0.0; 3];
        program.velocities(0.0, s, &mut q_dot).unwrap();
        worst_theta = worst_theta.max((s[1] - theta0).abs());
        worst_rate = worst_rate.max((q_dot[0] - precession).abs() / precession);
    });
    eprintln!("heavy top: θ {worst_theta:e}, φ̇ {worst_rate:e}");
    // Measured: 3.0e-13 rad (θ), 8.9e-12 (φ̇) over 20 s; bounds 1e-9 rad and 1e-9 relative.
    assert!(worst_theta < 1e-9 && worst_rate < 1e-9);
}

/// A spinning axisymmetric body in free flight, A = m ka², C = m kc² (mass lost uniformly),
/// nozzle on the axis at l behind the centre of mass, exhaust along the axis at u_e
/// (Thomson, *Introduction to Space Dynamics*, §7.8; Eke & Mao, *On the dynamics of
/// variable mass systems*, 2000). About the centre of mass, in body axes, the exhaust
/// carries away μ ρ × (ω × ρ) = μ l² (ω1, ω2, 0) and İ = −μ (ka², ka², kc²), so
///
/// ```text
/// C ω̇3 = μ kc² ω3                                ⇒ ω3 = ω30 m0/m
/// A ẇ = −μ (l² − ka²) w + i (C − A) ω3 w,  w = ω1 + i ω2
///      ⇒ |w| = |w0| (m/m0)^n,  n = (l² − ka²)/ka²
///        arg w = arg w0 + κ ω30 (m0/μ) ln(m0/m),  κ = (kc² − ka²)/ka²
/// ```
///
/// (the axial spin speeds up: a point nozzle on the axis takes no axial angular momentum
/// while C shrinks).
#[test]
fn spinning_body_with_axial_exhaust_matches_the_closed_forms() {
    let source = "coordinates x, y, z, psi, th, phi
        mass m: state, rate -mu
        inertia A = m*ka^2
        inertia C = m*kc^2
        rigid craft: mass m, inertia [A, A, C], position [x, y, z], orientation zyx(psi, th, phi)
        outflow craft: rate mu, at [0, 0, -l], relative_velocity body [0, 0, -u_e]";
    let (mu, u_e, ka, kc, l) = (0.2, 300.0, 0.5, 0.3, 0.9);
    let parameters = [("mu", mu), ("u_e", u_e), ("ka", ka), ("kc", kc), ("l", l)];
    let program = program(source, &parameters);
    let m0 = 10.0;
    let angles = [0.1, 0.1, 0.1];
    let omega0 = Vector3::new(0.2, 0.1, 3.0);
    let velocity = [1.0, -2.0, 0.5];
    let state = start(
        &program,
        "zyx",
        Some([0.0; 3]),
        velocity,
        angles,
        omega0,
        &[m0],
    );
    let (n, kappa) = (
        (l * l - ka * ka) / (ka * ka),
        (kc * kc - ka * ka) / (ka * ka),
    );
    let (w0, phase0) = (omega0[0].hypot(omega0[1]), omega0[1].atan2(omega0[0]));
    let (mut worst_spin, mut worst_size, mut worst_phase) = (0.0_f64, 0.0_f64, 0.0_f64);
    let end = 0.5 * m0 / mu;
    integrate::<6, 13>(program, &state, end, 1e-13, |program, t, s| {
        let omega = omega_at(program, "zyx", s, 3);
        let m = m0 - mu * t;
        let spin = omega0[2] * m0 / m;
        let size = w0 * (m / m0).powf(n);
        let phase = phase0 + kappa * omega0[2] * m0 / mu * (m0 / m).ln();
        worst_spin = worst_spin.max((omega[2] - spin).abs() / spin);
        worst_size = worst_size.max((omega[0].hypot(omega[1]) - size).abs() / size);
        let turned = omega[1].atan2(omega[0]) - phase;
        worst_phase = worst_phase.max(turned.sin().abs());
    });
    eprintln!("axial exhaust: ω3 {worst_spin:e}, |w| {worst_size:e}, arg w {worst_phase:e}");
    // Measured: 1.9e-14 (ω3), 5.3e-13 (|w|), 1.6e-12 (arg w) over half the mass burnt;
    // bound 1e-9.
    assert!(worst_spin < 1e-9, "{worst_spin:e}");
    assert!(worst_size < 1e-9, "{worst_size:e}");
    assert!(worst_phase < 1e-9, "{worst_phase:e}");
}
