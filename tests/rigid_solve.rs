//! q̇ from p in closed form for a lone spatial rigid body (`symbolic/src/mechanics/rigid_solve.rs`:
//! h = E⁻ᵀ p_η, ω = I⁻¹ (h − c × P), ṙ_O = R (P/m − ω × c), η̇ = E⁻¹ ω), on a body that
//! exercises every part of it: a full inertia tensor, a centre off every axis, a symmetric
//! sequence (zxz, whose E is singular where sin θ = 0, not cos θ) and the coordinates listed
//! angles first. Two references: the generated `momenta` (p = M q̇ from L, a forward
//! product) must give p back, and nalgebra's LU solve of the generated `mass_matrix` must
//! give the same q̇; at the sequence's gimbal lock the rate is the typed error.

use varmass::core::nalgebra::{SMatrix, SVector};
use varmass::core::{SystemError, VariableMassSystem};
use varmass::prelude::variable_mass_system;

#[variable_mass_system(
    "coordinates ph, th, ps, x, y, z
mass m = m0
inertia i11 = a11
inertia i22 = a22
inertia i33 = a33
inertia i12 = a12
inertia i13 = a13
inertia i23 = a23
rigid body: mass m, inertia [[i11, i12, i13], [i12, i22, i23], [i13, i23, i33]], position [x, y, z], orientation zxz(ph, th, ps), centre [c1, c2, c3]
potential m*g*z"
)]
struct Tumbler {
    m0: f64,
    a11: f64,
    a22: f64,
    a33: f64,
    a12: f64,
    a13: f64,
    a23: f64,
    c1: f64,
    c2: f64,
    c3: f64,
    g: f64,
}

/// A positive definite tensor (diagonally dominant) and a centre off every axis.
const BODY: Tumbler = Tumbler {
    m0: 7.0,
    a11: 3.0,
    a22: 4.0,
    a33: 2.5,
    a12: 0.4,
    a13: -0.3,
    a23: 0.2,
    c1: 0.3,
    c2: -0.2,
    c3: 0.5,
    g: 9.81,
};

/// A deterministic generator (SplitMix64): uniform in [lo, hi).
struct Draw(u64);

impl Draw {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        lo + (hi - lo) * (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// |a − b|∞ / max(|b|∞, 1).
fn relative(a: &SVector<f64, 6>, b: &SVector<f64, 6>) -> f64 {
    (a - b).amax() / b.amax().max(1.0)
}

#[test]
fn the_closed_form_inverts_the_mass_matrix() {
    let mut draw = Draw(5);
    let (mut backward, mut forward) = (0f64, 0f64);
    for _ in 0..1_000 {
        let mut s = SVector::<f64, 12>::zeros();
        for k in 0..6 {
            s[k] = draw.uniform(-3.0, 3.0);
            s[6 + k] = draw.uniform(-20.0, 20.0);
        }
        // θ (zxz's middle angle) within (10°, 170°): |sin θ| ≥ 0.17.
        s[1] = draw.uniform(10f64.to_radians(), 170f64.to_radians());
        let q_dot = BODY.velocities(0.0, &s).expect("away from gimbal lock");
        let mut velocity_state = s;
        velocity_state.fixed_rows_mut::<6>(6).copy_from(&q_dot);
        let p = BODY.momenta(0.0, &velocity_state);
        backward = backward.max(relative(&p, &s.fixed_rows::<6>(6).into_owned()));
        let m: SMatrix<f64, 6, 6> = BODY.mass_matrix(0.0, &s);
        let by_lu = m
            .lu()
            .solve(&s.fixed_rows::<6>(6).into_owned())
            .expect("regular");
        forward = forward.max(relative(&q_dot, &by_lu));
    }
    eprintln!("backward {backward:e}, against LU {forward:e}");
    // Measured: backward 1.7e-14, against LU 1.1e-14 (M's condition grows as 1/sin²θ);
    // bounds 1e-13 each.
    assert!(backward <= 1e-13, "backward {backward:e}");
    assert!(forward <= 1e-13, "against LU {forward:e}");
}

/// zxz is singular at θ = 0 (sin θ = 0), where E's determinant vanishes: the closed form
/// refuses it with the typed error, not a NaN.
#[test]
fn the_symmetric_sequence_refuses_its_gimbal_lock() {
    let mut s = SVector::<f64, 12>::from_element(0.5);
    s[1] = 0.0;
    assert!(matches!(
        BODY.velocities(0.0, &s),
        Err(SystemError::SingularMassMatrix)
    ));
    assert!(matches!(
        BODY.state_rate(0.0, &s),
        Err(SystemError::SingularMassMatrix)
    ));
    // Just off the floor (sin²θ = 1e-6 > √ε ≈ 1.5e-8) it is a finite rate.
    s[1] = 1e-3;
    let rate = BODY.state_rate(0.0, &s).expect("above the floor");
    assert!(rate.iter().all(|x| x.is_finite()));
}

/// A tensor that is not positive definite (I₁₁ I₂₂ − I₁₂² = 12 − 25 < 0: I's second
/// pivot is negative) and a mass that is not positive are refused with the typed error, as
/// the LDLᵀ of M refuses a pivot that is not positive.
#[test]
fn a_mass_matrix_that_is_not_positive_definite_is_refused() {
    let s = SVector::<f64, 12>::from_element(0.5);
    let skewed = Tumbler { a12: 5.0, ..BODY };
    assert!(matches!(
        skewed.state_rate(0.0, &s),
        Err(SystemError::SingularMassMatrix)
    ));
    let massless = Tumbler { m0: 0.0, ..BODY };
    assert!(matches!(
        massless.state_rate(0.0, &s),
        Err(SystemError::SingularMassMatrix)
    ));
    assert!(BODY.state_rate(0.0, &s).is_ok());
}
