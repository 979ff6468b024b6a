//! The derivation on the paper's examples, checked against hand derivations.

mod mechanics_support;

use std::collections::HashMap;

use mechanics_support::systems::{DOUBLE_PENDULUM, ROCKET, SLED_BODY, SLED_PAPER};
use mechanics_support::*;
use varmass_symbolic::mechanics::{Derivation, VelocitySolve};

/// Sets every named value of `values` in a fresh environment of `d` and settles the masses
/// and momenta.
fn point(d: &Derivation, values: &HashMap<&str, f64>) -> Vec<f64> {
    let mut env = vec![f64::NAN; d.pool.symbols().len()];
    for (name, v) in values {
        if d.pool.symbols().lookup(name).is_some() {
            set(d, name, &mut env, *v);
        }
    }
    settle(d, &mut env);
    env
}

fn sled_values(rng: &mut Rng) -> HashMap<&'static str, f64> {
    HashMap::from([
        ("m0", rng.uniform(1.0, 20.0)),
        ("c", rng.uniform(0.1, 3.0)),
        ("g", 9.81),
        ("theta", rng.uniform(0.1, 1.2)),
        ("f_d", rng.uniform(0.0, 0.3)),
        ("x", rng.uniform(0.0, 50.0)),
        ("x'", rng.uniform(-5.0, 5.0)),
        ("t", rng.uniform(0.0, 3.0)),
    ])
}

#[test]
fn sled_paper_and_body_forms_derive_identical_equations() {
    let paper = derive_ok(SLED_PAPER);
    let body = derive_ok(SLED_BODY);
    let mut rng = Rng(7);
    for _ in 0..50 {
        let values = sled_values(&mut rng);
        let (ep, eb) = (point(&paper, &values), point(&body, &values));
        let pairs = [
            ("L", paper.lagrangian, body.lagrangian),
            ("H", paper.energy, body.energy),
            (
                "H(q,p)",
                paper.hamiltonian.unwrap(),
                body.hamiltonian.unwrap(),
            ),
            ("p", paper.momenta[0], body.momenta[0]),
            ("Q*", paper.active_force[0], body.active_force[0]),
            ("R2", paper.impact_force[0], body.impact_force[0]),
            (
                "d*p/dt",
                paper.frozen_momentum_rate[0],
                body.frozen_momentum_rate[0],
            ),
            (
                "x''",
                paper.accelerations.as_ref().unwrap()[0],
                body.accelerations.as_ref().unwrap()[0],
            ),
        ];
        for (what, a, b) in pairs {
            // Both sides evaluate the same canonical formulas; 1e-12 allows round-off only.
            assert_close(eval(&paper, a, &ep), eval(&body, b, &eb), 1e-12, what);
        }
        let (VelocitySolve::Symbolic(vp), VelocitySolve::Symbolic(vb)) =
            (&paper.velocities, &body.velocities)
        else {
            panic!("a 1-DOF system solves q̇ symbolically");
        };
        assert_close(
            eval(&paper, vp[0], &ep),
            eval(&body, vb[0], &eb),
            1e-12,
            "q̇(q,p)",
        );
    }
}

#[test]
fn sled_matches_the_papers_equations_21_to_24() {
    let d = derive_ok(SLED_BODY);
    let mut rng = Rng(11);
    for _ in 0..50 {
        let env = point(&d, &sled_values(&mut rng));
        let v = |name| value(&d, name, &env);
        let (m, g, th, f, c, xd) = (v("m"), v("g"), v("theta"), v("f_d"), v("c"), v("x'"));
        let x = v("x");
        assert_close(m, v("m0") + c * x, 1e-14, "mass law");
        assert_close(eval(&d, d.momenta[0], &env), m * xd, 1e-13, "p = m ẋ");
        let p = m * xd;
        // eq. 21: H = p²/(2m) − m g x sin θ
        let h = p * p / (2.0 * m) - m * g * x * th.sin();
        assert_close(
            eval(&d, d.hamiltonian.unwrap(), &env),
            h,
            1e-12,
            "H (eq. 21)",
        );
        // eq. 22, 23
        assert_close(
            eval(&d, d.active_force[0], &env),
            -f * m * g * th.cos(),
            1e-13,
            "Q* (eq. 22)",
        );
        assert_close(
            eval(&d, d.impact_force[0], &env),
            -c * xd * xd,
            1e-13,
            "R2 (eq. 23)",
        );
        assert_eq!(
            eval(&d, d.reactive_thrust[0], &env),
            0.0,
            "no outflow, no R1"
        );
        // eq. 24 in Lagrange form: m ẍ = m g sin θ − f_d m g cos θ − c ẋ²
        let xdd = eval(&d, d.accelerations.as_ref().unwrap()[0], &env);
        assert_close(
            m * xdd,
            m * g * th.sin() - f * m * g * th.cos() - c * xd * xd,
            1e-12,
            "eq. 24",
        );
        // The true momentum rate: the snow arrives at rest, so only gravity and friction change p.
        let pdot = eval(&d, d.momentum_rate[0], &env);
        assert_close(pdot, m * g * (th.sin() - f * th.cos()), 1e-12, "true ṗ");
        assert_close(eval(&d, d.mass_rates[0], &env), c * xd, 1e-14, "ṁ = c ẋ");
    }
}

#[test]
fn sled_impact_force_is_derived_exactly_from_the_inflow() {
    let mut d = derive_ok(SLED_BODY);
    let pool = &mut d.pool;
    let c = pool.symbols().lookup("c").unwrap();
    let xd = pool.symbols().lookup("x'").unwrap();
    let (c, xd) = (pool.sym(c), pool.sym(xd));
    let two = pool.int(2);
    let square = pool.pow(xd, two);
    let product = pool.mul(&[c, square]);
    let expected = pool.neg(product);
    // Canonical form, not just numbers: R2 is the node −c·ẋ².
    assert_eq!(
        d.impact_force[0],
        expected,
        "R2 = {}",
        d.pool.display(d.impact_force[0])
    );
}

#[test]
fn rocket_thrust_and_momentum_rates() {
    let d = derive_ok(ROCKET);
    assert_eq!(d.state_mass_count(), 1);
    let mut rng = Rng(3);
    for _ in 0..50 {
        let values = HashMap::from([
            ("m", rng.uniform(1.0, 100.0)),
            ("mu", rng.uniform(0.1, 5.0)),
            ("u_e", rng.uniform(100.0, 3000.0)),
            ("g", 9.81),
            ("y", rng.uniform(0.0, 1e3)),
            ("y'", rng.uniform(-50.0, 300.0)),
        ]);
        let env = point(&d, &values);
        let (m, mu, u, g, yd) = (
            values["m"],
            values["mu"],
            values["u_e"],
            values["g"],
            values["y'"],
        );
        assert_close(
            eval(&d, d.reactive_thrust[0], &env),
            -mu * u,
            1e-13,
            "R1 = −μ u_e",
        );
        assert_close(
            eval(&d, d.frozen_momentum_rate[0], &env),
            -m * g + mu * u,
            1e-13,
            "d*p/dt",
        );
        // The true rate also loses the momentum the exhaust carries away at the rocket's speed:
        // d(m ẏ)/dt = ṁ ẏ + m ÿ = −μ ẏ − m g + μ u_e.
        assert_close(
            eval(&d, d.momentum_rate[0], &env),
            -m * g + mu * u - mu * yd,
            1e-13,
            "true ṗ",
        );
        assert_close(eval(&d, d.mass_rates[0], &env), -mu, 1e-14, "ṁ");
        let ydd = eval(&d, d.accelerations.as_ref().unwrap()[0], &env);
        assert_close(ydd, -g + mu * u / m, 1e-13, "ÿ = −g + μ u_e / m");
    }
}

#[test]
fn constant_mass_double_pendulum_gives_the_textbook_equations() {
    let d = derive_ok(DOUBLE_PENDULUM);
    let mut rng = Rng(5);
    for i in 0..100 {
        let values = HashMap::from([
            ("M1", rng.uniform(0.5, 3.0)),
            ("M2", rng.uniform(0.5, 3.0)),
            ("l1", rng.uniform(0.5, 2.0)),
            ("l2", rng.uniform(0.5, 2.0)),
            ("g", 9.81),
            ("a", rng.uniform(-3.0, 3.0)),
            ("b", rng.uniform(-3.0, 3.0)),
            ("a'", rng.uniform(-4.0, 4.0)),
            ("b'", rng.uniform(-4.0, 4.0)),
        ]);
        let env = point(&d, &values);
        let acc = accelerations(&d, &env);
        let (m1, m2, l1, l2, g) = (
            values["M1"],
            values["M2"],
            values["l1"],
            values["l2"],
            values["g"],
        );
        let (a, b, ad, bd) = (values["a"], values["b"], values["a'"], values["b'"]);
        let (add, bdd) = (acc[0], acc[1]);
        // Hand derivation (e.g. Goldstein): with δ = a − b,
        // (m1+m2) l1 ä + m2 l2 b̈ cos δ + m2 l2 ḃ² sin δ + (m1+m2) g sin a = 0
        // l2 b̈ + l1 ä cos δ − l1 ȧ² sin δ + g sin b = 0
        let delta = a - b;
        let first = (m1 + m2) * l1 * add
            + m2 * l2 * bdd * delta.cos()
            + m2 * l2 * bd * bd * delta.sin()
            + (m1 + m2) * g * a.sin();
        let second = l2 * bdd + l1 * add * delta.cos() - l1 * ad * ad * delta.sin() + g * b.sin();
        // The terms are O(100); 1e-11 absolute is round-off.
        assert!(
            first.abs() < 1e-11 && second.abs() < 1e-11,
            "point {i}: residuals {first:e}, {second:e}"
        );
        // No mass change: no reactive, impact or mass-flux force, and d*p/dt is the true ṗ.
        for k in 0..2 {
            assert_eq!(eval(&d, d.reactive_thrust[k], &env), 0.0);
            assert_eq!(eval(&d, d.impact_force[k], &env), 0.0);
            assert_eq!(eval(&d, d.mass_flux_force[k], &env), 0.0);
        }
    }
    assert!(
        d.mass_flux_force.iter().all(|e| d.pool.is_zero(*e)),
        "constant masses: flux term identically zero"
    );
}

#[test]
fn every_check_of_the_sled_is_decided() {
    let d = derive_ok(SLED_BODY);
    assert_eq!(d.checks.len(), 4);
    let text = {
        let mut d = d;
        d.to_text()
    };
    for needle in ["p_x =", "H(q, p, t) =", "R2_x =", "x'' =", "dH/dt ="] {
        assert!(text.contains(needle), "report lacks {needle}:\n{text}");
    }
}
