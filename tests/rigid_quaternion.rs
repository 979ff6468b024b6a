//! Attitude anywhere (issue 35, item 3): a rigid body turned by a quaternion,
//! `orientation quaternion(e0, e1, e2, e3)` (docs/mechanics.md#quaternions), flies through
//! every attitude, including the singular attitudes of all twelve Euler sequences, where a
//! body turned by Euler angles stops with `SingularMassMatrix`.
//!
//! The references are independent of the derivation: the rotation R and the body rates
//! ω = 2 Im(q* ⊗ q̇)/|q|² come from nalgebra's quaternions; the energy and the angular
//! momentum are computed here from them and the inertia (parallel-axis theorem by hand);
//! Euler's equations I ω̇ + ω × I ω = 0 of a torque-free body are integrated here by RK4;
//! and the rocket of `models/rocket_6dof.vms`, turned by zyx angles, is the same rocket as
//! `models/rocket_6dof_quaternion.vms` (a second formulation, through the frozen-mass
//! rule's flows at points), where zyx is regular.

use varmass::core::nalgebra::{Matrix3, Quaternion, SVector, UnitQuaternion, Vector3};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// A brick (NASA's check-case brick: 8 × 4 × 2.25 in, 2.268 kg) hung by a corner from a
/// fixed pivot: the attitude is the only freedom, and gravity's torque about the pivot
/// makes the tumble chaotic, so the body visits attitudes all over SO(3).
#[variable_mass_system(
    r#"
    coordinates e0, e1, e2, e3
    units e0: 1, e1: 1, e2: 1, e3: 1, m0: kg, A: kg*m^2, B: kg*m^2, C: kg*m^2, a: m, b: m, c: m, g: m/s^2
    mass m = m0
    rigid brick: mass m, inertia [A, B, C], position [0, 0, 0], orientation quaternion(e0, e1, e2, e3), centre [a, b, c]
    force brick: [0, 0, -m*g] at [a, b, c]
"#
)]
#[allow(non_snake_case)] // the model's names
struct HangingBrick {
    m0: f64,
    A: f64,
    B: f64,
    C: f64,
    a: f64,
    b: f64,
    c: f64,
    g: f64,
}

/// The same brick falling freely in uniform gravity, tumbling about its centre.
#[variable_mass_system(
    r#"
    coordinates x, y, z, e0, e1, e2, e3
    units x: m, y: m, z: m, e0: 1, e1: 1, e2: 1, e3: 1, m0: kg, A: kg*m^2, B: kg*m^2, C: kg*m^2, g: m/s^2
    mass m = m0
    rigid brick: mass m, inertia [A, B, C], position [x, y, z], orientation quaternion(e0, e1, e2, e3)
    potential m*g*z
"#
)]
#[allow(non_snake_case)] // the model's names
struct FallingBrick {
    m0: f64,
    A: f64,
    B: f64,
    C: f64,
    g: f64,
}

#[variable_mass_system(file = "models/rocket_6dof.vms")]
#[allow(non_snake_case)] // the model's names: A_d, C_d
struct EulerRocket {
    mu: f64,
    m_d: f64,
    A_d: f64,
    C_d: f64,
    k_a: f64,
    k_c: f64,
    g_c: f64,
    l: f64,
    u_e: f64,
    delta: f64,
    g: f64,
}

#[variable_mass_system(file = "models/rocket_6dof_quaternion.vms")]
#[allow(non_snake_case)] // the model's names: A_d, C_d
struct QuaternionRocket {
    mu: f64,
    m_d: f64,
    A_d: f64,
    C_d: f64,
    k_a: f64,
    k_c: f64,
    g_c: f64,
    l: f64,
    u_e: f64,
    delta: f64,
    g: f64,
}

/// NASA's brick (TM-2015-218675, Table 4, in SI): mass and principal inertias.
const MASS: f64 = 2.267_961_895_856_432_3;
const INERTIA: [f64; 3] = [
    0.002_568_217_474_088_305_3,
    0.008_421_011_037_627_346,
    0.009_754_655_939_231_735,
];
const G: f64 = 9.806_65;

/// R(q/|q|), body → world, by nalgebra.
fn turn(e: &[f64]) -> Matrix3<f64> {
    let q = Quaternion::new(e[0], e[1], e[2], e[3]);
    *UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .matrix()
}

/// ω in body axes: 2 Im(q* ⊗ q̇)/|q|², by nalgebra's quaternion product.
fn body_rates(e: &[f64], de: &[f64]) -> Vector3<f64> {
    let q = Quaternion::new(e[0], e[1], e[2], e[3]);
    let dq = Quaternion::new(de[0], de[1], de[2], de[3]);
    (q.conjugate() * dq).imag() * 2.0 / q.norm_squared()
}

/// q̇ = ½ q ⊗ (0, ω) for a unit q: the start of a body turning at ω (body axes).
fn quaternion_rates(e: &UnitQuaternion<f64>, omega: Vector3<f64>) -> [f64; 4] {
    let dq = e.quaternion() * Quaternion::from_imag(omega) * 0.5;
    [dq.w, dq.i, dq.j, dq.k]
}

fn dop853_control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-13,
        ..AdaptiveControl::default()
    })
}

/// For each world axis i and body axis j, the smallest angle between them (or between one
/// and the other's opposite) over the run: the singular attitude of an Euler sequence
/// a1 a2 a3 is body axis a3 along world axis a1 (Tait–Bryan, |R[a1][a3]| = |sin φ2| = 1)
/// or body a1 along world a1 (proper, |R[a1][a1]| = |cos φ2| = 1), so the nine angles are
/// the distances to the singular attitudes of the twelve sequences.
fn closer(closest: &mut [[f64; 3]; 3], r: &Matrix3<f64>) {
    for (i, row) in closest.iter_mut().enumerate() {
        for (j, angle) in row.iter_mut().enumerate() {
            *angle = angle.min(r[(i, j)].abs().min(1.0).acos());
        }
    }
}

/// The brick hung by its corner a = half its sides (the centre of mass at a from the pivot),
/// from a generic attitude and spin, 60 s.
///
/// By hand: about the fixed pivot, T = ½ ωᵀ I_p ω with I_p = I + m(|a|² 1 − a aᵀ) (parallel
/// axes), V = m g (R a)_z, so E = T + V is constant, and gravity's torque (R a) × (−m g e_z)
/// has no vertical component, so L_z = (R I_p ω)_z is constant too.
#[test]
fn a_brick_hung_by_a_corner_passes_the_singular_attitudes_of_every_euler_sequence() {
    let corner = Vector3::new(0.1016, 0.0508, 0.028_575);
    let system = HangingBrick {
        m0: MASS,
        A: INERTIA[0],
        B: INERTIA[1],
        C: INERTIA[2],
        a: corner.x,
        b: corner.y,
        c: corner.z,
        g: G,
    };
    let pivot_inertia = Matrix3::from_diagonal(&Vector3::from(INERTIA))
        + (Matrix3::identity() * corner.norm_squared() - corner * corner.transpose()) * MASS;
    let start = UnitQuaternion::from_quaternion(Quaternion::new(-0.335, -0.895, -0.294, 0.009));
    let rates = quaternion_rates(&start, Vector3::new(-1.45, 1.8, 0.12));
    let s = start.quaternion();
    let velocity_state = SVector::<f64, 8>::from_column_slice(&[
        s.w, s.i, s.j, s.k, rates[0], rates[1], rates[2], rates[3],
    ]);
    let initial = system.momentum_state(0.0, &velocity_state);
    let mut stepper = Dop853::new(&system, 0.0, initial, dop853_control()).expect("stepper");
    let solution = run(&mut stepper, &RunConfig::until(60.0), &[]).expect("no singular attitude");
    assert_eq!(solution.last().map(|(t, _)| t), Some(60.0));
    assert_eq!(
        solution.closest_singular_attitude, None,
        "no Euler sequence"
    );

    let invariants = |state: &SVector<f64, 8>| {
        let de = system.velocities(0.0, state).expect("q̇");
        let (r, omega) = (
            turn(state.as_slice()),
            body_rates(state.as_slice(), de.as_slice()),
        );
        let energy = 0.5 * omega.dot(&(pivot_inertia * omega)) + MASS * G * (r * corner).z;
        let vertical_spin = (r * pivot_inertia * omega).z;
        (
            energy,
            vertical_spin,
            state.fixed_rows::<4>(0).norm_squared(),
        )
    };
    let (energy0, spin0, _) = invariants(&initial);
    let (mut energy_drift, mut spin_drift, mut norm_drift) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut closest = [[f64::INFINITY; 3]; 3];
    for state in &solution.states {
        let (energy, spin, norm) = invariants(state);
        // E is about m g |a| = 2.6 J in size; L_z's scale is |L(0)| = 0.03 kg m²/s.
        energy_drift = energy_drift.max((energy - energy0).abs() / (MASS * G * corner.norm()));
        spin_drift = spin_drift.max((spin - spin0).abs());
        norm_drift = norm_drift.max((norm - 1.0).abs());
        closer(&mut closest, &turn(state.as_slice()));
    }
    let degrees = closest.map(|row| row.map(f64::to_degrees));
    eprintln!(
        "hanging brick, {} steps: energy drift {energy_drift:.2e} (of m g |a|), L_z drift \
         {spin_drift:.2e} kg m²/s, | |q|² − 1 | ≤ {norm_drift:.2e}; closest to each world \
         axis i (rows) of body axis j (columns), deg: {degrees:.2?}",
        solution.states.len()
    );
    // Measured: energy 7.5e-12, L_z 5.1e-14 (bounds: 13×, 20×). |q|² is no invariant of
    // the numbers: the radial rate's equation keeps u = q·q̇/|q|² constant, so |q|² follows
    // e^{2ut} with u the steps' rounding (docs/mechanics.md#quaternions); measured 2.3e-9 in
    // 60 s, harmless (R and ω depend on q/|q| only); bound 1e-8.
    assert!(energy_drift <= 1e-10, "{energy_drift:e}");
    assert!(spin_drift <= 1e-12, "{spin_drift:e}");
    assert!(norm_drift <= 1e-8, "{norm_drift:e}");
    // Measured: every body axis within 1.6° of every world axis at some step (the steps are
    // ~9 ms, a few degrees of turn apart); bound 3°.
    for row in degrees {
        for angle in row {
            assert!(angle <= 3.0, "{degrees:?}");
        }
    }
}

/// Euler's equations I ω̇ = −ω × I ω of a torque-free body, by RK4 at a fixed step.
fn euler_equations(omega: Vector3<f64>, step: f64, steps: usize) -> Vec<Vector3<f64>> {
    let inertia = Vector3::from(INERTIA);
    let rate = |w: &Vector3<f64>| -w.cross(&inertia.component_mul(w)).component_div(&inertia);
    let mut path = vec![omega];
    let mut w = omega;
    for _ in 0..steps {
        let k1 = rate(&w);
        let k2 = rate(&(w + k1 * (step / 2.0)));
        let k3 = rate(&(w + k2 * (step / 2.0)));
        let k4 = rate(&(w + k3 * step));
        w += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (step / 6.0);
        path.push(w);
    }
    path
}

/// The number of sign changes of ω about the intermediate axis.
fn flips(rates: impl Iterator<Item = f64>) -> usize {
    let signs: Vec<bool> = rates.map(|w| w > 0.0).collect();
    signs.windows(2).filter(|pair| pair[0] != pair[1]).count()
}

/// The brick dropped spinning at 3 rad/s about its intermediate axis (y) with a small
/// perturbation: the spin is unstable (the tennis-racket theorem), and the brick flips
/// end over end, ω_y changing sign, while it falls for 60 s.
///
/// By hand: gravity acts at the centre, so about the centre the motion is torque-free:
/// H = T + m g z and the spin h = R I ω (world axes) are constant, and ω(t) obeys Euler's
/// equations, integrated here independently (RK4, 1e-4 s: within 5.4e-9 rad/s of a step
/// of 5e-5 s over the 60 s).
#[test]
fn a_brick_spun_about_its_intermediate_axis_flips_as_it_falls() {
    let system = FallingBrick {
        m0: MASS,
        A: INERTIA[0],
        B: INERTIA[1],
        C: INERTIA[2],
        g: G,
    };
    let omega0 = Vector3::new(0.1, 3.0, 0.1);
    let start = UnitQuaternion::identity();
    let rates = quaternion_rates(&start, omega0);
    let velocity_state = SVector::<f64, 14>::from_column_slice(&[
        0.0, 0.0, 9144.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, rates[0], rates[1], rates[2], rates[3],
    ]);
    let initial = system.momentum_state(0.0, &velocity_state);
    let (step, steps) = (1e-4, 600_000);
    let reference = euler_equations(omega0, step, steps);
    let mut stepper = Dop853::new(&system, 0.0, initial, dop853_control()).expect("stepper");
    // Landing on every 0.1 s (a time of the reference's grid).
    let (mut times, mut states) = (Vec::new(), Vec::new());
    for k in 1..=600 {
        let t = f64::from(k) * 0.1;
        let solution = run(&mut stepper, &RunConfig::until(t).continuing(), &[])
            .expect("no singular attitude");
        let (end, state) = solution.last().expect("a point");
        assert_eq!(end, t);
        times.push(t);
        states.push(*state);
    }
    let inertia = Matrix3::from_diagonal(&Vector3::from(INERTIA));
    let observe = |t: f64, state: &SVector<f64, 14>| {
        let de = system.velocities(t, state).expect("q̇");
        let e = &state.as_slice()[3..7];
        let omega = body_rates(e, &de.as_slice()[3..7]);
        (
            omega,
            turn(e) * inertia * omega,
            system.hamiltonian(t, state).expect("H"),
        )
    };
    let (_, spin0, energy0) = observe(0.0, &initial);
    let (mut rate_gap, mut spin_drift, mut energy_drift) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut ours = Vec::new();
    for (&t, state) in times.iter().zip(&states) {
        let (omega, spin, energy) = observe(t, state);
        let theirs = reference[(t / step).round() as usize];
        rate_gap = rate_gap.max((omega - theirs).norm());
        spin_drift = spin_drift.max((spin - spin0).norm() / spin0.norm());
        energy_drift = energy_drift.max(((energy - energy0) / energy0).abs());
        ours.push(omega.y);
    }
    let (ours_flips, their_flips) = (
        flips(ours.into_iter()),
        flips(reference.iter().step_by(1000).map(|w| w.y)),
    );
    eprintln!(
        "falling brick: {ours_flips} flips (Euler's equations: {their_flips}); |ω − ω_Euler| ≤ \
         {rate_gap:.2e} rad/s, spin drift {spin_drift:.2e}, energy drift {energy_drift:.2e}"
    );
    // Measured: 9 flips each.
    assert_eq!(ours_flips, their_flips);
    assert!(ours_flips >= 6, "{ours_flips}");
    // Measured: 1.7e-7 rad/s (of 3 rad/s), growing with the flips from 2.6e-9 at 10 s: the
    // phase error of DOP853 at 1e-13, which each passage near the unstable spin amplifies —
    // at 1e-11 it is 6.2e-5, following the tolerance, so it is the integration's, not the
    // equations'. Bound 1e-6.
    assert!(rate_gap <= 1e-6, "{rate_gap:e}");
    // Measured: spin 1.7e-13, energy 3.0e-15 (bounds 600×, 3e4×: the issue's 1e-10).
    assert!(spin_drift <= 1e-10, "{spin_drift:e}");
    assert!(energy_drift <= 1e-10, "{energy_drift:e}");
}

/// The rocket of `models/rocket_6dof.vms` (a burning grain below the dry centre, a gimballed
/// nozzle, jet damping from the outflow at its point) in both attitudes.
fn rockets() -> (EulerRocket, QuaternionRocket) {
    let euler = EulerRocket {
        mu: 2.0,
        m_d: 60.0,
        A_d: 20.0,
        C_d: 2.0,
        k_a: 0.8,
        k_c: 0.2,
        g_c: 1.0,
        l: 1.5,
        u_e: 2000.0,
        delta: 0.05,
        g: 9.81,
    };
    let quaternion = QuaternionRocket {
        mu: euler.mu,
        m_d: euler.m_d,
        A_d: euler.A_d,
        C_d: euler.C_d,
        k_a: euler.k_a,
        k_c: euler.k_c,
        g_c: euler.g_c,
        l: euler.l,
        u_e: euler.u_e,
        delta: euler.delta,
        g: euler.g,
    };
    (euler, quaternion)
}

/// R = R_z(ψ) R_y(θ) R_x(φ) and ω in body axes of zyx angles and their rates (by hand:
/// ω = R_x(φ)ᵀ R_y(θ)ᵀ e_z ψ̇ + R_x(φ)ᵀ e_y θ̇ + e_x φ̇).
fn zyx(angles: &[f64], rates: &[f64]) -> (Matrix3<f64>, Vector3<f64>) {
    let (psi, th, phi) = (angles[0], angles[1], angles[2]);
    let (dpsi, dth, dphi) = (rates[0], rates[1], rates[2]);
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), psi)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), th)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), phi);
    let omega = Vector3::new(
        dphi - dpsi * th.sin(),
        dth * phi.cos() + dpsi * th.cos() * phi.sin(),
        -dth * phi.sin() + dpsi * th.cos() * phi.cos(),
    );
    (*turn.to_rotation_matrix().matrix(), omega)
}

/// The same rocket turned by zyx angles and by a quaternion, from the same tilted, turning
/// start, burning half its grain in 10 s: the two derivations (the frozen-mass rule's flows
/// at points through each parametrization) give the same motion. By hand, the zyx angle
/// rates of ω: θ̇ = ω₂ cos φ − ω₃ sin φ, ψ̇ = (ω₂ sin φ + ω₃ cos φ)/cos θ, φ̇ = ω₁ + ψ̇ sin θ.
#[test]
fn the_rocket_turned_by_a_quaternion_flies_as_the_rocket_turned_by_zyx_angles() {
    let (euler, quaternion) = rockets();
    let (angles, omega): ([f64; 3], _) = ([0.3, 0.4, -0.2], Vector3::new(0.2, -0.1, 0.3));
    let (th, phi) = (angles[1], angles[2]);
    let dth = omega.y * phi.cos() - omega.z * phi.sin();
    let dpsi = (omega.y * phi.sin() + omega.z * phi.cos()) / th.cos();
    let dphi = omega.x + dpsi * th.sin();
    let (r0, check) = zyx(&angles, &[dpsi, dth, dphi]);
    assert!((check - omega).norm() < 1e-15);
    let e = UnitQuaternion::from_rotation_matrix(
        &varmass::core::nalgebra::Rotation3::from_matrix_unchecked(r0),
    );
    let de = quaternion_rates(&e, omega);
    let (velocity, grain) = ([1.0, -2.0, 30.0], 40.0);
    let euler_start = SVector::<f64, 13>::from_column_slice(&[
        0.0,
        0.0,
        0.0,
        angles[0],
        angles[1],
        angles[2],
        velocity[0],
        velocity[1],
        velocity[2],
        dpsi,
        dth,
        dphi,
        grain,
    ]);
    let q = e.quaternion();
    let quaternion_start = SVector::<f64, 15>::from_column_slice(&[
        0.0,
        0.0,
        0.0,
        q.w,
        q.i,
        q.j,
        q.k,
        velocity[0],
        velocity[1],
        velocity[2],
        de[0],
        de[1],
        de[2],
        de[3],
        grain,
    ]);
    let mut worst = [0.0_f64; 4];
    let mut a = Dop853::new(
        &euler,
        0.0,
        euler.momentum_state(0.0, &euler_start),
        dop853_control(),
    )
    .expect("stepper");
    let mut b = Dop853::new(
        &quaternion,
        0.0,
        quaternion.momentum_state(0.0, &quaternion_start),
        dop853_control(),
    )
    .expect("stepper");
    for k in 1..=20 {
        let t = f64::from(k) * 0.5;
        let config = RunConfig::until(t).continuing();
        let first = run(&mut a, &config, &[]).expect("zyx is regular here");
        let second = run(&mut b, &config, &[]).expect("the quaternion run");
        let (sa, sb) = (
            first.last().expect("a point").1,
            second.last().expect("a point").1,
        );
        let (da, db) = (
            euler.velocities(t, sa).expect("q̇"),
            quaternion.velocities(t, sb).expect("q̇"),
        );
        let (ra, wa) = zyx(&sa.as_slice()[3..6], &da.as_slice()[3..6]);
        let (rb, wb) = (
            turn(&sb.as_slice()[3..7]),
            body_rates(&sb.as_slice()[3..7], &db.as_slice()[3..7]),
        );
        let (pa, pb) = (sa.fixed_rows::<3>(0), sb.fixed_rows::<3>(0));
        worst[0] = worst[0].max((pa - pb).norm() / pa.norm());
        worst[1] = worst[1].max((ra - rb).norm());
        worst[2] = worst[2].max((wa - wb).norm() / wa.norm());
        worst[3] = worst[3].max((sa[12] - sb[14]).abs() / sa[12]);
    }
    eprintln!(
        "zyx against quaternion over 10 s: position {:.2e}, R {:.2e}, ω {:.2e}, grain {:.2e} (relative)",
        worst[0], worst[1], worst[2], worst[3]
    );
    // Measured: 6.3e-12, 1.25e-8 rad, 6.9e-10, 5.5e-15. Every gap but the grain's (a law
    // of t) follows the tolerance ten to one (1.3e-7 rad at 1e-12, 1.4e-6 at 1e-11,
    // 1.25e-5 at 1e-10): the steppers' error, not the equations'. Bounds ~10×.
    let bounds = [1e-10, 1e-7, 1e-8, 1e-13];
    for (gap, bound) in worst.iter().zip(bounds) {
        assert!(*gap <= bound, "{worst:?}");
    }
}

/// The generated `velocities` of the quaternion rocket (a lone body turned by a quaternion:
/// the closed form q̇ = ½ Gᵀ ω + (qᵀ p_q/λ) q with ω = I⁻¹(½ G p_q − c × P),
/// docs/mechanics.md#quaternions, in place of the trait's LDLᵀ of M) against the q̇ whose
/// momenta p = M q̇ (`momenta`) it is given, and against nalgebra's Cholesky solve of the
/// generated M, at 200 random states off |q| = 1 and q·q̇ = 0, where the gauge term's
/// momentum is not zero. Measured: 6.7e-13 and 8.6e-13 normwise relative (both p's rounding
/// times cond(M): the rates of x, y, z are a hundred times the others); bound 1e-11 (a
/// wrong term gives order one).
#[test]
fn the_quaternion_rockets_velocities_solve_its_momenta() {
    let (_, rocket) = rockets();
    let mut seed: u64 = 0x5eed;
    let mut uniform = |lo: f64, hi: f64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut to_truth, mut to_cholesky) = (0f64, 0f64);
    for _ in 0..200 {
        let mut velocity_state = SVector::<f64, 15>::zeros();
        for i in 0..14 {
            velocity_state[i] = uniform(-1.2, 1.2);
        }
        for i in 7..10 {
            velocity_state[i] *= 100.0;
        }
        velocity_state[14] = uniform(5.0, 40.0);
        let t = uniform(0.0, 5.0);
        let momenta = rocket.momenta(t, &velocity_state);
        let mut state = velocity_state;
        state.fixed_rows_mut::<7>(7).copy_from(&momenta);
        let closed = rocket.velocities(t, &state).expect("a regular state");
        let truth = velocity_state.fixed_rows::<7>(7).into_owned();
        let solved = rocket
            .mass_matrix(t, &state)
            .cholesky()
            .expect("M positive definite")
            .solve(&momenta);
        for range in [0..3, 3..7] {
            let rows = |v: &SVector<f64, 7>| -> Vec<f64> { range.clone().map(|i| v[i]).collect() };
            let (c, r, s) = (rows(&closed), rows(&truth), rows(&solved));
            let size = r.iter().fold(0f64, |a, x| a.max(x.abs()));
            let gap = |x: &[f64]| {
                x.iter()
                    .zip(&r)
                    .fold(0f64, |a, (x, y)| a.max((x - y).abs()))
            };
            to_truth = to_truth.max(gap(&c) / size);
            to_cholesky = to_cholesky.max(gap(&s) / size);
        }
    }
    eprintln!("closed form {to_truth:e}, Cholesky {to_cholesky:e}");
    assert!(to_truth <= 1e-11, "closed form {to_truth:e}");
    assert!(to_cholesky <= 1e-11, "Cholesky {to_cholesky:e}");
}

/// The generated `accelerations` of the quaternion rocket (q̈ as the total derivative of
/// its closed-form q̇ = F(q, p, t, m): Σ ∂F/∂q_j q̇_j + F(q, ṗ) + ∂F/∂t + Σ ∂F/∂m_k ṁ_k,
/// docs/mechanics.md#quaternions) against two others:
/// - the interpreter's, eq. 6 as derived: M q̈ = d*p/dt − (d*p/dt at q̈ = 0) solved by
///   Cholesky, none of it shared with the closed form;
/// - the time derivative of q̇ along the motion, which the state rate and `velocities` give:
///   the derivative of q̇(t + h, y + h ẏ) at h = 0 (the line's tangent is the motion's), by
///   central differences at h and 2h combined by Richardson, so the truncation is O(h⁴)
///   (h = 1e-4; the plain central difference is 4.1e-5 off there, falling as h²: 4.1e-3 at
///   1e-3).
///
/// At 200 random states off |q| = 1 and q·q̇ = 0 (the gauge term's momentum not zero),
/// normwise relative, translation and attitude blocks apart. Measured: against eq. 6
/// 3.0e-13 (p's rounding times cond(M), as for `velocities` above); against the differences
/// 3.7e-10, their rounding (1.2e-9 at h = 3e-5, 4.5e-9 at 1e-5). Bounds 1e-11 and 3e-9 (a
/// wrong term gives order one).
#[test]
fn the_quaternion_rockets_accelerations_are_the_rate_of_its_velocities() {
    let (_, rocket) = rockets();
    let derivation =
        derive_source(QuaternionRocket::SOURCE, Parameters::Inferred).expect("derives");
    let r = &rocket;
    let parameters = [
        ("mu", r.mu),
        ("m_d", r.m_d),
        ("A_d", r.A_d),
        ("C_d", r.C_d),
        ("k_a", r.k_a),
        ("k_c", r.k_c),
        ("g_c", r.g_c),
        ("l", r.l),
        ("u_e", r.u_e),
        ("delta", r.delta),
        ("g", r.g),
    ];
    let tape: TapeSystem<7, 15> =
        TapeSystem::new(Program::new(derivation, &parameters).expect("parameters fit"))
            .expect("sizes fit");
    let mut seed: u64 = 0xacce1;
    let mut uniform = |lo: f64, hi: f64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let h = 1e-4;
    let (mut to_eq6, mut to_differences) = (0f64, 0f64);
    let gap = |a: &SVector<f64, 7>, b: &SVector<f64, 7>| {
        [0..3, 3..7].into_iter().fold(0f64, |worst, range| {
            let size = range.clone().fold(0f64, |m, i| m.max(b[i].abs()));
            let gap = range.fold(0f64, |m, i| m.max((a[i] - b[i]).abs()));
            worst.max(gap / size)
        })
    };
    for _ in 0..200 {
        let mut velocity_state = SVector::<f64, 15>::zeros();
        for i in 0..14 {
            velocity_state[i] = uniform(-1.2, 1.2);
        }
        for i in 7..10 {
            velocity_state[i] *= 100.0;
        }
        velocity_state[14] = uniform(5.0, 40.0);
        let t = uniform(0.0, 3.5);
        let mut state = velocity_state;
        state
            .fixed_rows_mut::<7>(7)
            .copy_from(&rocket.momenta(t, &velocity_state));
        let rate = rocket.state_rate(t, &state).expect("a regular state");
        let central = |h: f64| {
            let ahead = rocket.velocities(t + h, &(state + rate * h)).expect("q̇");
            let behind = rocket.velocities(t - h, &(state - rate * h)).expect("q̇");
            (ahead - behind) / (2.0 * h)
        };
        let difference = (central(h) * 4.0 - central(2.0 * h)) / 3.0;
        let closed = rocket.accelerations(t, &velocity_state).expect("q̈");
        let eq6 = tape.accelerations(t, &velocity_state).expect("q̈");
        to_eq6 = to_eq6.max(gap(&closed, &eq6));
        to_differences = to_differences.max(gap(&closed, &difference));
    }
    // A quaternion too short to turn by, |q| = 1e-100 (n = 1e-200; q̈'s 1/n³ overflows),
    // is refused as a singular mass matrix by both methods, not answered with NaN (the
    // review of session 38); |q| = 1e-3 (n = 1e-6, above the floor √ε) is a state.
    for (size, refused) in [(1e-100, true), (1e-3, false)] {
        let mut state = SVector::<f64, 15>::zeros();
        state[3] = size;
        state[14] = 10.0;
        let velocities = rocket.velocities(1.0, &state);
        let accelerations = rocket.accelerations(1.0, &state);
        if refused {
            assert_eq!(velocities.err(), Some(SystemError::SingularMassMatrix));
            assert_eq!(accelerations.err(), Some(SystemError::SingularMassMatrix));
        } else {
            let finite = |v: &SVector<f64, 7>| v.iter().all(|x| x.is_finite());
            assert!(finite(&velocities.expect("a state")));
            assert!(finite(&accelerations.expect("a state")));
        }
    }
    eprintln!("accelerations against eq. 6 {to_eq6:e}, against d/dt q̇ {to_differences:e}");
    assert!(to_eq6 <= 1e-11, "{to_eq6:e}");
    assert!(to_differences <= 3e-9, "{to_differences:e}");
}
