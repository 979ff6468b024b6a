//! The six-degree-of-freedom rocket of `models/rocket_6dof.vms`, its state rate written by
//! hand: the reference for "the generated state rate within 1.05× of a hand-written one"
//! (issue 22, `benches/costs.rs`), and an independent check of the derivation
//! (`tests/rigid_6dof_hand.rs` holds the two equal at 1 000 random states).
//!
//! # The model
//!
//! q = [x, y, z, ψ, θ, φ]: r_O = [x, y, z] the dry centre of mass (z up), R = R_z(ψ) R_y(θ)
//! R_x(φ) turning body components into world ones; a grain m_p (state, ṁ_p = −μ) g_c below
//! r_O on the axis, so m = m_d + m_p, the centre of mass at c = [0, 0, c_z] (body),
//! c_z = −g_c m_p / m, I = diag(A, A, C) about it with A = A_d + m_p k_a² + m_d m_p g_c²/m,
//! C = C_d + m_p k_c²; V = m g (r_c)_z = m g z − g g_c m_p cos θ cos φ; an outflow μ at the
//! nozzle a = [0, 0, −l] (body) at v = [u_e sin δ, 0, −u_e cos δ] (body) relative to it.
//!
//! # Kinematics
//!
//! Intrinsic zyx: ω = E(θ, φ) η̇ (body axes, η = [ψ, θ, φ]) with
//!
//! ```text
//!     ⎡ −sθ     0    1 ⎤        ω1 = φ̇ − ψ̇ sθ
//! E = ⎢ cθ sφ   cφ   0 ⎥        ω2 = θ̇ cφ + ψ̇ cθ sφ
//!     ⎣ cθ cφ  −sφ   0 ⎦        ω3 = ψ̇ cθ cφ − θ̇ sφ
//! ```
//!
//! and ∂R/∂η_k = R [E_k]× (E_k the k-th column: a change of η_k turns the body by E_k δη_k).
//! In body axes the velocity of O is V = Rᵀ ṙ_O and that of the centre w = V + ω × c, so
//!
//! ```text
//! T = ½ m |w|² + ½ ωᵀ I ω
//! ```
//!
//! # Momenta, and q̇ from them (no 6×6 solve)
//!
//! p_r = ∂T/∂ṙ_O = m R w = m ṙ_c (world), and with P = Rᵀ p_r = m w,
//! p_η = Eᵀ ∂T/∂ω = Eᵀ h, h = I ω + m c × w = I ω + c × P (the angular momentum about O).
//! Backwards: P = Rᵀ p_r; h from Eᵀ h = p_η, whose last row is h1 = p_φ, the middle
//! cφ h2 − sφ h3 = p_θ, the first sφ h2 + cφ h3 = (p_ψ + sθ p_φ)/cθ =: s, so
//! h2 = cφ p_θ + sφ s, h3 = cφ s − sφ p_θ; then ω = I⁻¹ (h − c × P) (I diagonal),
//! ṙ_O = R (P/m − ω × c) and η̇ = E⁻¹ ω: ψ̇ = (sφ ω2 + cφ ω3)/cθ, θ̇ = cφ ω2 − sφ ω3,
//! φ̇ = ω1 + sθ ψ̇. The only division that can fail is by cθ (zyx's gimbal lock at
//! θ = ±90°, where M's pivot falls as cθ²): below the core's relative pivot floor the rate
//! is the typed singular-mass-matrix error, as the generated code's.
//!
//! # Momentum rates (docs/mechanics.md, "Flows at points", F1)
//!
//! ṗ_α = ∂*L/∂q_α − μ u · ∂r_P/∂q_α + ṙ_c · (∂R/∂q_α) I_f, with every mass, inertia and the
//! centre held fixed in ∂*, u = ṙ_P + R v the exhaust's absolute velocity (body axes:
//! u_b = V + ω × a + v) and I_f = d(m c)/dt + μ a = [0, 0, μ (g_c − l)] (m c_z = −g_c m_p).
//!
//! Translation: T does not contain r_O and ∂R/∂r_O = 0, so ṗ_r = −m g e_z − μ R u_b.
//!
//! Rotation, at fixed q̇: ∂T/∂η_k = m w · (∂Rᵀ/∂η_k ṙ_O + ∂ω/∂η_k × c) + Iω · ∂ω/∂η_k
//! with ∂Rᵀ/∂η_k ṙ_O = −E_k × V, so ∂T/∂η_k = ∂ω/∂η_k · h − E_k · (V × P). The potential,
//! V = m g e_z · r_c, gives ∂V/∂η_k = m g e_z · R (E_k × c) = E_k · (c × m g γ), γ = Rᵀ e_z
//! = [−sθ, cθ sφ, cθ cφ]. The flow: u · ∂r_P/∂η_k = u_b · (E_k × a) = E_k · (a × u_b); the
//! coupling: ṙ_c · R (E_k × I_f) = E_k · (I_f × w). Gathering the terms of the form E_k · G:
//!
//! ```text
//! ṗ_η = Eᵀ G + [∂ω/∂ψ · h, ∂ω/∂θ · h, ∂ω/∂φ · h]
//! G   = −V × P − m g c × γ − μ a × u_b + I_f × P/m
//! ∂ω/∂ψ = 0,   ∂ω/∂θ = −ψ̇ [cθ, sθ sφ, sθ cφ],   ∂ω/∂φ = [0, ω3, −ω2]
//! ```
//!
//! (−μ a × u_b is the thrust torque and, through ω × a in u_b, the exhaust's share of the
//! jet damping; the inertia's own loss is in the true rate through p = Eᵀ h with the new I.)
//! Finally ṁ_p = −μ. c = [0, 0, c_z] and a = [0, 0, −l] lie on the axis, which the cross
//! products below use.

use varmass::core::nalgebra::SVector;
use varmass::core::system::RELATIVE_PIVOT_FLOOR;
use varmass::core::SystemError;

/// The rocket's parameters, named as in the model file.
#[allow(non_snake_case)] // the model's names: A_d, C_d
#[derive(Clone, Copy, Debug)]
pub struct HandRocket6 {
    /// Burn rate μ, kg/s.
    pub mu: f64,
    /// Dry mass, kg.
    pub m_d: f64,
    /// Dry transverse inertia about the dry centre, kg·m².
    pub A_d: f64,
    /// Dry axial inertia, kg·m².
    pub C_d: f64,
    /// The grain's transverse radius of gyration, m.
    pub k_a: f64,
    /// The grain's axial radius of gyration, m.
    pub k_c: f64,
    /// The grain's centre below the dry centre, m.
    pub g_c: f64,
    /// The nozzle below the dry centre, m.
    pub l: f64,
    /// Exhaust speed relative to the nozzle, m/s.
    pub u_e: f64,
    /// Gimbal angle in the body x-z plane, rad.
    pub delta: f64,
    /// Gravity, m/s².
    pub g: f64,
}

/// a × b.
#[inline(always)]
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl HandRocket6 {
    /// The state rate [q̇, ṗ, ṁ_p] at the state [x, y, z, ψ, θ, φ, p…, m_p] (the generated
    /// code's layout); `t` is unused (nothing in the model depends on time).
    #[inline]
    pub fn state_rate(
        &self,
        _t: f64,
        s: &SVector<f64, 13>,
    ) -> Result<SVector<f64, 13>, SystemError> {
        let (m_p, g_c, l, mu) = (s[12], self.g_c, self.l, self.mu);
        let m = self.m_d + m_p;
        let inv_m = 1.0 / m;
        let c_z = -g_c * m_p * inv_m;
        let a_in = self.A_d + m_p * self.k_a * self.k_a + self.m_d * m_p * g_c * g_c * inv_m;
        let c_in = self.C_d + m_p * self.k_c * self.k_c;

        let (s_psi, c_psi) = s[3].sin_cos();
        let (s_th, c_th) = s[4].sin_cos();
        let (s_phi, c_phi) = s[5].sin_cos();
        if c_th * c_th <= RELATIVE_PIVOT_FLOOR {
            return Err(SystemError::SingularMassMatrix);
        }
        // R = R_z(ψ) R_y(θ) R_x(φ), by rows.
        let r = [
            [
                c_psi * c_th,
                c_psi * s_th * s_phi - s_psi * c_phi,
                c_psi * s_th * c_phi + s_psi * s_phi,
            ],
            [
                s_psi * c_th,
                s_psi * s_th * s_phi + c_psi * c_phi,
                s_psi * s_th * c_phi - c_psi * s_phi,
            ],
            [-s_th, c_th * s_phi, c_th * c_phi],
        ];
        let to_body =
            |v: [f64; 3]| [0, 1, 2].map(|j| r[0][j] * v[0] + r[1][j] * v[1] + r[2][j] * v[2]);

        // Momenta → P (body), h, ω, w, V, q̇.
        let big_p = to_body([s[6], s[7], s[8]]);
        let (p_psi, p_th, p_phi) = (s[9], s[10], s[11]);
        let inv_c_th = 1.0 / c_th;
        let sum = (p_psi + s_th * p_phi) * inv_c_th;
        let h = [
            p_phi,
            c_phi * p_th + s_phi * sum,
            c_phi * sum - s_phi * p_th,
        ];
        // c × P with c = c_z e3: c_z [−P2, P1, 0].
        let inv_a = 1.0 / a_in;
        let omega = [
            (h[0] + c_z * big_p[1]) * inv_a,
            (h[1] - c_z * big_p[0]) * inv_a,
            h[2] / c_in,
        ];
        let w = big_p.map(|x| x * inv_m);
        // V = w − ω × c, ω × c = c_z [ω2, −ω1, 0].
        let vel = [w[0] - c_z * omega[1], w[1] + c_z * omega[0], w[2]];
        let psi_dot = (s_phi * omega[1] + c_phi * omega[2]) * inv_c_th;
        let th_dot = c_phi * omega[1] - s_phi * omega[2];
        let phi_dot = omega[0] + s_th * psi_dot;
        let r_dot = [0, 1, 2].map(|i| r[i][0] * vel[0] + r[i][1] * vel[1] + r[i][2] * vel[2]);

        // The exhaust's velocity, body axes: u_b = V + ω × a + v, ω × a = −l [ω2, −ω1, 0].
        let (s_d, c_d) = self.delta.sin_cos();
        let u_b = [
            vel[0] - l * omega[1] + self.u_e * s_d,
            vel[1] + l * omega[0],
            vel[2] - self.u_e * c_d,
        ];
        // G = −V × P − m g c × γ − μ a × u_b + I_f × P/m, with c, a, I_f along e3
        // (e3 × x = [−x2, x1, 0]).
        // −V × P = (ω × c) × P: w is along P, so V × P = −(ω × c) × P exactly, written so
        // (|V × P| cancels down from |V||P| when the rocket flies fast and turns slowly).
        let v_x_p = cross(big_p, [c_z * omega[1], -c_z * omega[0], 0.0]);
        let gamma = [-s_th, c_th * s_phi, c_th * c_phi];
        let along = m * self.g * c_z; // coefficient of e3 × γ
        let flow = mu * l; // −μ a × u_b = μ l e3 × u_b
        let coupling = mu * (g_c - l); // I_f × w = I_f,z e3 × w
        let big_g = [
            -v_x_p[0] + along * gamma[1] - flow * u_b[1] - coupling * w[1],
            -v_x_p[1] - along * gamma[0] + flow * u_b[0] + coupling * w[0],
            -v_x_p[2],
        ];
        // ṗ_η = Eᵀ G + [0, ∂ω/∂θ · h, ∂ω/∂φ · h].
        let dth = -psi_dot * (c_th * h[0] + s_th * (s_phi * h[1] + c_phi * h[2]));
        let dphi = omega[2] * h[1] - omega[1] * h[2];
        let g_psi = -s_th * big_g[0] + c_th * (s_phi * big_g[1] + c_phi * big_g[2]);
        let g_th = c_phi * big_g[1] - s_phi * big_g[2];
        let g_phi = big_g[0];

        // ṗ_r = −m g e_z − μ R u_b.
        let u = [0, 1, 2].map(|i| r[i][0] * u_b[0] + r[i][1] * u_b[1] + r[i][2] * u_b[2]);
        Ok(SVector::<f64, 13>::from_column_slice(&[
            r_dot[0],
            r_dot[1],
            r_dot[2],
            psi_dot,
            th_dot,
            phi_dot,
            -mu * u[0],
            -mu * u[1],
            -m * self.g - mu * u[2],
            g_psi,
            g_th + dth,
            g_phi + dphi,
            -mu,
        ]))
    }
}

impl HandRocket6 {
    /// The rocket `cli/tests/rigid.rs` flies: 60 kg dry, a 40 kg grain burning at 2 kg/s,
    /// exhaust at 2 km/s through a nozzle 2 m below the dry centre, gimballed 2 mrad.
    pub fn standard() -> Self {
        Self {
            mu: 2.0,
            m_d: 60.0,
            A_d: 30.0,
            C_d: 2.0,
            k_a: 0.8,
            k_c: 0.2,
            g_c: 1.0,
            l: 2.0,
            u_e: 2000.0,
            delta: 0.002,
            g: 9.81,
        }
    }
}

/// `n` states [q, p, m_p] of the standard rocket in flight, drawn by a fixed generator:
/// attitude within 30° of vertical in pitch and roll, any heading, speeds to 300 m/s,
/// angle rates to 1 rad/s (as momenta of their size), the grain anywhere in its burn.
pub fn flight_states(n: usize) -> Vec<SVector<f64, 13>> {
    let mut seed: u64 = 0x6d0f;
    let mut uniform = |lo: f64, hi: f64| {
        // Knuth's MMIX LCG, top 53 bits.
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let tilt = 30f64.to_radians();
    (0..n)
        .map(|_| {
            let mut s = SVector::<f64, 13>::zeros();
            for k in 0..3 {
                s[k] = uniform(-2e3, 2e3);
                s[6 + k] = uniform(-3e4, 3e4);
                s[9 + k] = uniform(-40.0, 40.0);
            }
            s[2] = uniform(0.0, 1e4);
            s[3] = uniform(-std::f64::consts::PI, std::f64::consts::PI);
            s[4] = uniform(-tilt, tilt);
            s[5] = uniform(-tilt, tilt);
            s[12] = uniform(0.0, 40.0);
            s
        })
        .collect()
}
