//! The Taylor coefficients of the run-time tapes (`Program::taylor`, the recurrences of
//! `varmass_symbolic::expr::taylor` staged through the mass laws, q̇ and the state rate)
//! against an independent reference on the examples' systems, to order 20: the series of
//! the solution by Picard iteration, y ← y₀ + ∫ f(y, t) dt, each iteration exact one order
//! further, with f evaluated on truncated power series by `taylor_support/series.rs`
//! (composition with the functions' known series, Gaussian elimination for M q̇ = p − b). The
//! k-th coefficient of a solution's series is its k-th derivative over k!, so this checks
//! y⁽ᵏ⁾/k! for k ≤ 20 of every state component.

#[path = "taylor_support/series.rs"]
mod series;

use std::collections::HashMap;

use series::{add, constant, evaluate, scale, solve, Series, ORDER};
use varmass::interpret::Program;
use varmass::symbolic::expr::{Id, Symbol};
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::{
    derive,
    mechanics::{Derivation, MassKind, Parameters, VelocitySolve},
};

/// A model, its tags, parameter values and an expansion point.
struct Case {
    name: &'static str,
    source: String,
    with: &'static [&'static str],
    parameters: &'static [(&'static str, f64)],
    time: f64,
    state: &'static [f64],
}

fn model(file: &str) -> String {
    std::fs::read_to_string(format!("{}/models/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

fn cases() -> Vec<Case> {
    let pendulum = &[
        ("mu", 0.02),
        ("u_e", 3.0),
        ("k", 40.0),
        ("l0", 1.0),
        ("g", 9.81),
    ];
    vec![
        Case {
            name: "sled (impact)",
            source: model("sled.vms"),
            with: &["impact"],
            parameters: &[("m0", 2.0), ("c", 0.5), ("g", 9.81), ("theta", 0.5), ("f_d", 0.1)],
            time: 0.3,
            state: &[1.2, 5.2],
        },
        Case {
            name: "rocket (drag)",
            source: model("rocket.vms"),
            with: &["drag"],
            parameters: &[("mu", 0.05), ("u_e", 300.0), ("g", 9.81), ("k_d", 0.01)],
            time: 2.0,
            state: &[100.0, 40.0, 0.8],
        },
        Case {
            name: "leaking spring pendulum",
            source: model("leaking_spring_pendulum.vms"),
            with: &[],
            parameters: pendulum,
            time: 0.0,
            state: &[1.1, 0.4, 0.3, 0.2, 0.9],
        },
        Case {
            name: "leaking spring pendulum, Cartesian",
            source: model("leaking_spring_pendulum_cartesian.vms"),
            with: &[],
            parameters: pendulum,
            time: 0.0,
            state: &[0.4, -1.0, 0.2, -0.1, 0.9],
        },
        Case {
            name: "double pendulum",
            source: model("double_pendulum.vms"),
            with: &[],
            parameters: &[("M1", 1.0), ("M2", 0.7), ("l1", 1.0), ("l2", 0.8), ("g", 9.81)],
            time: 0.0,
            state: &[0.5, -0.3, 0.2, 0.1],
        },
        Case {
            name: "swinging tank (numeric q̇)",
            source: model("swinging_tank.vms"),
            with: &[],
            parameters: &[
                ("mu", 0.05),
                ("M0", 3.0),
                ("J0", 0.4),
                ("l", 0.5),
                ("g", 9.81),
                ("K", 50.0),
                ("u_e", 2.0),
            ],
            time: 0.0,
            state: &[0.1, -0.05, 0.3, 0.2, 0.1, -0.05, 1.0],
        },
        Case {
            name: "Kepler",
            source: "coordinates r, th
                     mass m = m1
                     body planet: mass m, position [r*cos(th), r*sin(th)]
                     potential -k*m/r"
                .to_string(),
            with: &[],
            parameters: &[("m1", 1.5), ("k", 1.0)],
            time: 0.0,
            state: &[1.0, 0.3, 0.1, 1.8],
        },
        Case {
            // The planar 3-link chain of accreting bobs (m = m0 + c t: the time is an input).
            name: "3-link chain (numeric q̇, m(t))",
            source: "coordinates a1, a2, a3
                     mass m1 = m0 + c*t
                     mass m2 = m0 + c*t
                     mass m3 = m0 + c*t
                     body bob1: mass m1, position [l*sin(a1), -l*cos(a1)]
                     body bob2: mass m2, position [l*sin(a1) + l*sin(a2), -l*cos(a1) - l*cos(a2)]
                     body bob3: mass m3, position [l*sin(a1) + l*sin(a2) + l*sin(a3), -l*cos(a1) - l*cos(a2) - l*cos(a3)]
                     potential g*(m1*(-l*cos(a1)) + m2*(-l*cos(a1) - l*cos(a2)) + m3*(-l*cos(a1) - l*cos(a2) - l*cos(a3)))
                     inflow bob1: velocity [0, 0]
                     inflow bob2: velocity [0, 0]
                     inflow bob3: velocity [0, 0]"
                .to_string(),
            with: &[],
            parameters: &[("m0", 1.0), ("c", 0.1), ("l", 0.5), ("g", 9.81)],
            time: 0.7,
            state: &[0.3, -0.2, 0.5, 0.1, 0.05, -0.1],
        },
    ]
}

fn derivation(case: &Case) -> Derivation {
    let ast = parse_system(&case.source).unwrap();
    let with: Vec<String> = case.with.iter().map(|s| s.to_string()).collect();
    let ast = select_tags(&ast, &with).unwrap();
    derive(&ast, Parameters::Inferred).unwrap()
}

/// The reference series of every state component by Picard iteration.
fn picard(d: &Derivation, case: &Case) -> Vec<Series> {
    let mut env = vec![f64::NAN; d.pool.symbols().len()];
    for (name, value) in case.parameters {
        let (_, symbol) = d.parameters.iter().find(|(n, _)| n == name).unwrap();
        env[symbol.index()] = *value;
    }
    let n = d.coordinates.len();
    let k = d.state_mass_count();
    let mut y: Vec<Series> = case.state.iter().map(|x| constant(*x)).collect();
    for _ in 0..=ORDER {
        let f = rate(d, &env, case.time, &y, (n, k));
        y = y
            .iter()
            .zip(&f)
            .map(|(y, f)| {
                let mut next = constant(y[0]);
                for j in 1..=ORDER {
                    next[j] = f[j - 1] / j as f64;
                }
                next
            })
            .collect();
    }
    y
}

/// The state rate [q̇, ṗ, ṁ_s] on series.
fn rate(d: &Derivation, env: &[f64], t0: f64, y: &[Series], (n, k): (usize, usize)) -> Vec<Series> {
    let mut inputs: HashMap<Symbol, Series> = HashMap::new();
    let mut time = constant(t0);
    time[1] = 1.0;
    inputs.insert(d.time, time);
    for (a, c) in d.coordinates.iter().enumerate() {
        inputs.insert(c.q, y[a].clone());
        inputs.insert(c.momentum, y[n + a].clone());
    }
    for (i, m) in d.masses.iter().take(k).enumerate() {
        inputs.insert(m.symbol, y[2 * n + i].clone());
    }
    for (m, law) in d.masses.iter().zip(&d.closed_laws) {
        if let (MassKind::Law(_), Some(law)) = (&m.kind, law) {
            let value = evaluate(&d.pool, &[*law], &inputs, env).remove(0);
            inputs.insert(m.symbol, value);
        }
    }
    let velocities = match &d.velocities {
        VelocitySolve::Symbolic(v) => evaluate(&d.pool, v, &inputs, env),
        VelocitySolve::Numeric => {
            let entries: Vec<Id> = d.mass_matrix.iter().flatten().copied().collect();
            let flat = evaluate(&d.pool, &entries, &inputs, env);
            let matrix = flat.chunks(n).map(|row| row.to_vec()).collect();
            let offset = evaluate(&d.pool, &d.momentum_offset, &inputs, env);
            let rhs = (0..n)
                .map(|a| add(&y[n + a], &scale(&offset[a], -1.0)))
                .collect();
            solve(matrix, rhs)
        }
    };
    for (c, v) in d.coordinates.iter().zip(&velocities) {
        inputs.insert(c.velocity, v.clone());
    }
    let mut roots = d.momentum_rate.clone();
    roots.extend(d.mass_rates.iter().take(k));
    let mut out = velocities;
    out.extend(evaluate(&d.pool, &roots, &inputs, env));
    out
}

#[test]
fn coefficients_to_order_20_equal_the_derivatives_over_k_factorial() {
    for case in cases() {
        let d = derivation(&case);
        let reference = picard(&d, &case);
        let program = Program::new(derivation(&case), case.parameters).unwrap();
        let s = program.state_len();
        assert_eq!(s, case.state.len(), "{}", case.name);
        let mut out = vec![f64::NAN; (ORDER + 1) * s];
        program
            .taylor(case.time, case.state, ORDER, &mut out)
            .unwrap();
        for k in 0..=ORDER {
            // Each order against its own size: coefficients shrink like ρ⁻ᵏ.
            let size = (0..s).fold(0.0f64, |m, i| m.max(reference[i][k].abs()));
            for i in 0..s {
                let got = out[k * s + i];
                let expected = reference[i][k];
                let error = (got - expected).abs() / size.max(1e-300);
                // Measured ≤ 2.3e-14 over these models; bound 1e-12.
                assert!(
                    error < 1e-12,
                    "{}: y[{k}][{i}] = {got:e}, reference {expected:e} (relative {error:e})",
                    case.name
                );
            }
        }
    }
}

#[test]
fn order_zero_is_the_state_and_order_one_the_state_rate() {
    for case in cases() {
        let program = Program::new(derivation(&case), case.parameters).unwrap();
        let s = program.state_len();
        let mut out = vec![f64::NAN; 2 * s];
        program.taylor(case.time, case.state, 1, &mut out).unwrap();
        let mut rate = vec![f64::NAN; s];
        program
            .state_rate(case.time, case.state, &mut rate)
            .unwrap();
        assert_eq!(&out[..s], case.state, "{}", case.name);
        for i in 0..s {
            // Order 1 is the state rate through the same formulas evaluated by other code
            // (the value tape): equal to rounding, measured ≤ 1.8e-16.
            let gap = (out[s + i] - rate[i]).abs() / rate[i].abs().max(1.0);
            assert!(gap < 1e-14, "{}: component {i}: {gap:e}", case.name);
        }
    }
}
