//! A lone spatial rigid body turned by a quaternion takes the closed forms of a lone rigid
//! body (docs/mechanics.md#quaternions, "q̇ from p" and "ṗ in body axes"), not the LDLᵀ of
//! its 7×7 M and eq. 14's world-frame rows. Both are held here to the derivation's own
//! equations at random states off the motions the integrator follows: |q| ≠ 1 and
//! q·q̇ ≠ 0, where the gauge term T_g = ½ λ (q·q̇)²/n² and its part of ṗ are not zero.
//!
//! The forms, by hand: with n = qᵀq and G(q) = [[−e1, e0, e3, −e2], [−e2, −e3, e0, e1],
//! [−e3, e2, −e1, e0]] (ω = (2/n) G q̇, G q = 0, G Gᵀ = n I₃), p_q = (2/n) Gᵀ h + λ (q·q̇) q/n²
//! with h = I ω + c × P, so h = ½ G p_q, q·q̇ = n qᵀp_q/λ and
//! q̇ = ½ Gᵀ ω + (qᵀp_q/λ) q. The body-axes ṗ rows of `rigid_rates.rs` hold for any
//! attitude coordinates with Rᵀ ∂R/∂e_k = [∂ω/∂ė_k]× (true of q since Ṙ = R [ω]× for every
//! path), plus T_g's own part ∂T_g/∂e_k (+ Σ φ̇ ∂(∂T_g/∂ė_k)/∂φ without flows).

use varmass_symbolic::expr::SymbolKind;
use varmass_symbolic::{derive_source, mechanics::Parameters};

/// (1) A tumbling brick: full tensor, centre off every axis, a body force at a point, a
/// torque, gravity; the coordinates declared out of order. (2) The 6-dof rocket with its
/// outflow (models/rocket_6dof_quaternion.vms). (3) A body without flows whose mass,
/// inertia and centre follow a law in t.
const BRICK: &str = "coordinates q3, x, q1, y, q0, z, q2
    mass m = m0
    rigid b: mass m, inertia [[a11, a12, a13], [a12, a22, a23], [a13, a23, a33]], position [x, y, z], orientation quaternion(q0, q1, q2, q3), centre [c1, c2, c3]
    potential m*g*z
    force b: body [F1, F2, F3] at [h1, h2, h3]
    torque b: body [T1, T2, T3]";

const CHANGING: &str = "coordinates x, y, z, q0, q1, q2, q3
    mass m = m0 - mu*t
    inertia i11 = a11 + k1*m
    inertia i22 = a22 + k2*m
    inertia i33 = a33 + k3*m
    inertia i12 = a12*m
    rigid b: mass m, inertia [[i11, i12, 0], [i12, i22, 0], [0, 0, i33]], position [x, y, z], orientation quaternion(q0, q1, q2, q3), centre [e1*m, e2, e3*m]
    potential m*g*z
    torque b: [T1, T2, T3]";

/// Parameters held positive and of order one, the products of inertia small, so that I is
/// positive definite and M well conditioned (q̇ from p loses cond(M) of p's rounding).
const POSITIVE: [(&str, f64); 19] = [
    ("e1", 0.1),
    ("e3", -0.08),
    ("k1", 0.5),
    ("k2", 0.4),
    ("k3", 0.3),
    ("a12", 0.3),
    ("a13", -0.2),
    ("a23", 0.25),
    ("m", 3.0),
    ("m0", 9.0),
    ("a11", 3.0),
    ("a22", 4.0),
    ("a33", 2.5),
    ("m_d", 5.0),
    ("m_p", 2.0),
    ("A_d", 3.0),
    ("C_d", 1.0),
    ("k_a", 0.5),
    ("k_c", 0.3),
];

fn sources() -> Vec<(&'static str, String)> {
    let path = format!(
        "{}/../models/rocket_6dof_quaternion.vms",
        env!("CARGO_MANIFEST_DIR")
    );
    let rocket = std::fs::read_to_string(path).expect("the model file");
    vec![
        ("brick", BRICK.to_string()),
        ("rocket", rocket),
        ("changing", CHANGING.to_string()),
    ]
}

/// The worst differences of (i) the closed-form q̇ against the q̇ whose momenta p = M q̇ it
/// is given (M's exact solution) and (ii) ṗ as derived against eq. 14 as derived
/// (d*p/dt + Σ φ̇ ∂*p/∂φ), normwise relative over the origin's and the quaternion's blocks,
/// at 1 000 random states of each model. Measured: q̇ 4.2e-13 (brick), 6.1e-15 (rocket),
/// 1.2e-13 (changing), p's rounding times cond(M); ṗ 2.7e-14, 4.4e-15, 9.1e-15. Bound 1e-12
/// (issue 22's tolerance for equivalences): a wrong sign or factor in any term gives order
/// one (leaving out the gauge's frozen-rate part: 0.27 for the changing body). ṗ is also
/// held to take under a tenth of eq. 14's operations as derived (744, 702, 667 against
/// 44 463, 21 987, 51 214): the body form, which the derivation keeps.
#[test]
fn quaternion_closed_forms_equal_the_derivation() {
    for (name, source) in sources() {
        let (velocity, rate) = differences(&source);
        eprintln!("{name}: q̇ {velocity:e}, ṗ {rate:e}");
        assert!(velocity <= 1e-12, "{name}: q̇ differs by {velocity:e}");
        assert!(rate <= 1e-12, "{name}: ṗ differs by {rate:e}");
    }
}

fn differences(source: &str) -> (f64, f64) {
    let mut d = derive_source(source, Parameters::Inferred).expect("derives");
    let closed = d.rigid_velocities.clone().expect("the closed-form q̇");
    let count = d.coordinates.len();
    assert_eq!(count, 7);
    let eq14: Vec<_> = (0..count)
        .map(|k| {
            d.pool
                .add(&[d.frozen_momentum_rate[k], d.mass_flux_force[k]])
        })
        .collect();
    let (body, derived) = (
        d.pool.operation_count(&d.momentum_rate),
        d.pool.operation_count(&eq14),
    );
    eprintln!("ṗ {body} operations, eq. 14 as derived {derived}");
    // Under a tenth: the body form, not eq. 14 reduced (the rocket's takes 21 761,
    // `mechanics_rigid.rs`), which would make the comparison below an identity.
    assert!(10 * body < derived, "{body} against {derived} operations");
    let n = d.pool.symbols().len();
    let mut seed: u64 = 0x5eed;
    let mut uniform = |lo: f64, hi: f64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    // q̇(q, p): no velocity in it, so the comparison below is not the identity.
    for v in &closed.velocities {
        let velocity = (d.pool.free_symbols(*v).into_iter())
            .find(|s| matches!(d.pool.symbols().kind(*s), SymbolKind::Velocity { .. }));
        assert!(velocity.is_none(), "q̇ names {velocity:?}");
    }
    // The origin's coordinates and the quaternion's, by name.
    let is_origin = |name: &str| ["x", "y", "z"].contains(&name);
    let names: Vec<String> = (d.coordinates.iter())
        .map(|c| d.pool.symbols().name(c.q).to_string())
        .collect();
    let (mut worst_velocity, mut worst_rate) = (0f64, 0f64);
    for _ in 0..1_000 {
        // Every symbol of order one with either sign (the velocities, so q·q̇ ≠ 0); the
        // quaternion's components too, so |q| ≠ 1; masses and inertias positive.
        let mut env: Vec<f64> = (0..n).map(|_| uniform(-2.0, 2.0)).collect();
        for (name, value) in POSITIVE {
            if let Some(s) = d.pool.symbols().lookup(name) {
                env[s.index()] = value * uniform(0.8, 1.2);
            }
        }
        for _ in 0..2 {
            for (m, law) in d.masses.iter().zip(&d.closed_laws) {
                if let Some(law) = law {
                    env[m.symbol.index()] = d.pool.eval(*law, &env);
                }
            }
        }
        for k in 0..count {
            let p = d.pool.eval(d.momenta[k], &env);
            env[d.coordinates[k].momentum.index()] = p;
        }
        for origin in [true, false] {
            let block: Vec<usize> = (0..count)
                .filter(|k| is_origin(&names[*k]) == origin)
                .collect();
            let (mut error, mut size) = (0f64, 0f64);
            for &k in &block {
                let truth = env[d.coordinates[k].velocity.index()];
                error = error.max((d.pool.eval(closed.velocities[k], &env) - truth).abs());
                size = size.max(truth.abs());
            }
            worst_velocity = worst_velocity.max(error / size);
            let (mut error, mut size) = (0f64, 0f64);
            for &k in &block {
                let reference = d.pool.eval(eq14[k], &env);
                error = error.max((d.pool.eval(d.momentum_rate[k], &env) - reference).abs());
                size = size.max(reference.abs());
            }
            worst_rate = worst_rate.max(error / size);
        }
    }
    (worst_velocity, worst_rate)
}
