//! For every test system: the Hamilton and Lagrange forms agree, the Jacobian agrees with
//! finite differences, and the energy-budget power is the rate of H along the motion.

mod mechanics_support;

use mechanics_support::systems::ALL;
use mechanics_support::*;
use varmass_symbolic::mechanics::{Derivation, MassKind, VelocitySolve};

/// The bound of the checks that hold exactly in exact arithmetic (q̇ from p, H, ∂*H/∂p,
/// −∂*H/∂q), relative to the scale 1 + |a| + |b|: the largest residual measured over every
/// system is 9.3e-16 (double pendulum, H); bound ~10× that.
const EXACT: f64 = 1e-14;

/// The finite-difference checks compared, per system: (M q̈ vs the true ṗ, the Jacobian,
/// dH/dt), each relative to the scale. Every bound is ~10× (between 9× and 14×) the largest
/// residual measured over the test's seeded sample points, which is written after it.
const FD_BOUNDS: &[(&str, [f64; 3])] = &[
    ("sled (paper form)", [2e-10, 2e-9, 1e-9]), // 2.2e-11, 1.5e-10, 8.6e-11
    ("sled (body form)", [2e-10, 2e-9, 1e-9]),  // 2.2e-11, 1.5e-10, 8.6e-11
    ("rocket", [1e-10, 1e-9, 3e-9]),            // 7.3e-12, 8.3e-11, 3.1e-10
    ("double pendulum", [3e-9, 2e-9, 2e-8]),    // 3.0e-10, 2.0e-10, 1.9e-9
    ("leaking spring pendulum", [6e-9, 3e-9, 2e-8]), // 5.9e-10, 2.9e-10, 1.8e-9
    ("accreting bead", [6e-9, 2e-9, 3e-9]),     // 6.1e-10, 1.8e-10, 2.8e-10
    ("three dof", [2e-9, 3e-9, 1e-9]),          // 1.8e-10, 2.9e-10, 8.9e-11
];

/// The finite-difference bounds of the system called `name`.
fn fd_bounds(name: &str) -> [f64; 3] {
    FD_BOUNDS
        .iter()
        .find(|(system, _)| *system == name)
        .map(|(_, bounds)| *bounds)
        .unwrap_or_else(|| panic!("no finite-difference bounds for {name}: measure them"))
}

/// The state [q, p, m_s] of an environment.
fn state_of(d: &Derivation, env: &[f64]) -> Vec<f64> {
    let mut s: Vec<f64> = d.coordinates.iter().map(|c| env[c.q.index()]).collect();
    s.extend(d.coordinates.iter().map(|c| env[c.momentum.index()]));
    s.extend(
        d.masses
            .iter()
            .take(d.state_mass_count())
            .map(|m| env[m.symbol.index()]),
    );
    s
}

/// Writes a state [q, p, m_s] (and time) into `env`, then recovers the law masses and q̇.
fn load_state(d: &Derivation, env: &mut [f64], state: &[f64], t: f64) {
    let n = d.coordinates.len();
    env[d.time.index()] = t;
    for (a, c) in d.coordinates.iter().enumerate() {
        env[c.q.index()] = state[a];
        env[c.momentum.index()] = state[n + a];
    }
    for (k, m) in d.masses.iter().take(d.state_mass_count()).enumerate() {
        env[m.symbol.index()] = state[2 * n + k];
    }
    for (m, law) in d.masses.iter().zip(&d.closed_laws) {
        if let (MassKind::Law(_), Some(law)) = (&m.kind, law) {
            env[m.symbol.index()] = d.pool.eval(*law, env);
        }
    }
    let v = velocities_from_momenta(d, env);
    for (c, v) in d.coordinates.iter().zip(v) {
        env[c.velocity.index()] = v;
    }
}

/// The state rate [q̇, ṗ, ṁ_s] at `env`.
fn state_rate(d: &Derivation, env: &[f64]) -> Vec<f64> {
    let mut f: Vec<f64> = d
        .coordinates
        .iter()
        .map(|c| env[c.velocity.index()])
        .collect();
    f.extend(eval_all(d, &d.momentum_rate, env));
    f.extend(
        d.mass_rates
            .iter()
            .take(d.state_mass_count())
            .map(|r| eval(d, *r, env)),
    );
    f
}

fn matrix(d: &Derivation, m: &[Vec<varmass_symbolic::expr::Id>], env: &[f64]) -> Vec<Vec<f64>> {
    m.iter().map(|row| eval_all(d, row, env)).collect()
}

#[test]
fn hamilton_form_recovers_the_velocities_and_h() {
    for (name, source) in ALL {
        let mut d = derive_ok(source);
        let mut rng = Rng(17);
        for _ in 0..30 {
            let env = random_point(&d, &mut rng);
            let v = velocities_from_momenta(&d, &env);
            for (c, v) in d.coordinates.iter().zip(&v) {
                assert_close(
                    *v,
                    env[c.velocity.index()],
                    EXACT,
                    &format!("{name}: q̇(q, p)"),
                );
            }
            if let Some(h) = d.hamiltonian {
                assert_close(
                    eval(&d, h, &env),
                    eval(&d, d.energy, &env),
                    EXACT,
                    &format!("{name}: H"),
                );
                // eq. 13–14: ∂*H/∂p = q̇ and −∂*H/∂q = ∂*L/∂q.
                for (a, c) in d.coordinates.clone().iter().enumerate() {
                    let dh_dp = d.pool.diff(h, c.momentum);
                    let dh_dq = d.pool.diff(h, c.q);
                    assert_close(
                        eval(&d, dh_dp, &env),
                        env[c.velocity.index()],
                        EXACT,
                        &format!("{name}: ∂H/∂p"),
                    );
                    assert_close(
                        -eval(&d, dh_dq, &env),
                        eval(&d, d.lagrangian_gradient[a], &env),
                        EXACT,
                        &format!("{name}: −∂H/∂q"),
                    );
                }
            } else {
                assert!(matches!(d.velocities, VelocitySolve::Numeric));
            }
        }
    }
}

#[test]
fn lagrange_form_accelerations_reproduce_the_true_momentum_rate() {
    // d/dt p(q, q̇, t, m) along (q̇, q̈, ṁ) by central differences must equal the derived
    // true ṗ. h = 1e-5: truncation O(h²) ≈ 1e-10, round-off ≈ 1e-16/h ≈ 1e-11 (relative).
    for (name, source) in ALL {
        let d = derive_ok(source);
        let mut rng = Rng(23);
        for _ in 0..30 {
            let env = random_point(&d, &mut rng);
            let acc = accelerations(&d, &env);
            let shifted = |h: f64| {
                let mut e = env.clone();
                e[d.time.index()] += h;
                for (a, c) in d.coordinates.iter().enumerate() {
                    e[c.q.index()] += h * env[c.velocity.index()];
                    e[c.velocity.index()] += h * acc[a];
                }
                for (m, rate) in d
                    .masses
                    .iter()
                    .zip(&d.mass_rates)
                    .take(d.state_mass_count())
                {
                    e[m.symbol.index()] += h * eval(&d, *rate, &env);
                }
                settle(&d, &mut e);
                eval_all(&d, &d.momenta, &e)
            };
            let h = 1e-5;
            let (plus, minus) = (shifted(h), shifted(-h));
            let pdot = eval_all(&d, &d.momentum_rate, &env);
            for a in 0..d.coordinates.len() {
                assert_close(
                    (plus[a] - minus[a]) / (2.0 * h),
                    pdot[a],
                    fd_bounds(name)[0],
                    &format!("{name}: M q̈ vs ṗ"),
                );
            }
        }
    }
}

#[test]
fn jacobian_agrees_with_finite_differences() {
    for (name, source) in ALL {
        let d = derive_ok(source);
        let n = d.coordinates.len();
        let k = d.state_mass_count();
        let mut rng = Rng(29);
        for _ in 0..10 {
            let env = random_point(&d, &mut rng);
            let t = env[d.time.index()];
            let state = state_of(&d, &env);
            // From the parts: J_q = F_q − F_v M⁻¹ P_q, J_p = F_v M⁻¹, J_m = F_m − F_v M⁻¹ P_m.
            let j = d
                .jacobian
                .as_ref()
                .expect("derive derives the Jacobian by default");
            let (fq, fv, fm) = (
                matrix(&d, &j.rate_wrt_q, &env),
                matrix(&d, &j.rate_wrt_velocity, &env),
                matrix(&d, &j.rate_wrt_state_mass, &env),
            );
            let (pq, pm) = (
                matrix(&d, &j.momentum_wrt_q, &env),
                matrix(&d, &j.momentum_wrt_state_mass, &env),
            );
            let mass = matrix(&d, &d.mass_matrix, &env);
            let minv_col = |b: Vec<f64>| solve(mass.clone(), b);
            let mut fd_env = env.clone();
            for col in 0..2 * n + k {
                let h = 1e-6 * state[col].abs().max(1.0);
                let mut rate = |delta: f64| {
                    let mut s = state.clone();
                    s[col] += delta;
                    load_state(&d, &mut fd_env, &s, t);
                    state_rate(&d, &fd_env)
                };
                let (plus, minus) = (rate(h), rate(-h));
                // ∂v/∂(column), then the rows of ṗ and ṁ_s.
                let dv: Vec<f64> = if col < n {
                    minv_col(pq.iter().map(|r| -r[col]).collect())
                } else if col < 2 * n {
                    minv_col(
                        (0..n)
                            .map(|r| if r == col - n { 1.0 } else { 0.0 })
                            .collect(),
                    )
                } else {
                    minv_col(pm.iter().map(|r| -r[col - 2 * n]).collect())
                };
                for row in 0..2 * n + k {
                    let fd = (plus[row] - minus[row]) / (2.0 * h);
                    let analytic = if row < n {
                        dv[row]
                    } else {
                        let r = row - n;
                        let direct = if col < n {
                            fq[r][col]
                        } else if col < 2 * n {
                            0.0
                        } else {
                            fm[r][col - 2 * n]
                        };
                        direct + (0..n).map(|b| fv[r][b] * dv[b]).sum::<f64>()
                    };
                    // Central differences with h = 1e-6: truncation ~1e-12, round-off
                    // ~1e-16/h = 1e-10 relative to the scale.
                    let bound = fd_bounds(name)[1];
                    assert_close(analytic, fd, bound, &format!("{name}: J[{row}][{col}]"));
                }
            }
        }
    }
}

#[test]
fn power_is_the_rate_of_h_along_the_motion() {
    for (name, source) in ALL {
        let d = derive_ok(source);
        let mut rng = Rng(31);
        for _ in 0..20 {
            let env = random_point(&d, &mut rng);
            let t = env[d.time.index()];
            let state = state_of(&d, &env);
            let f = state_rate(&d, &env);
            let mut e = env.clone();
            let mut energy_at = |h: f64| {
                let s: Vec<f64> = state.iter().zip(&f).map(|(s, f)| s + h * f).collect();
                load_state(&d, &mut e, &s, t + h);
                eval(&d, d.energy, &e)
            };
            let h = 1e-5;
            let fd = (energy_at(h) - energy_at(-h)) / (2.0 * h);
            let bound = fd_bounds(name)[2];
            assert_close(
                eval(&d, d.power, &env),
                fd,
                bound,
                &format!("{name}: dH/dt"),
            );
        }
    }
}
