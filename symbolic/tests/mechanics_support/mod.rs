//! Helpers shared by the mechanics tests: evaluating a derivation at a point.
#![allow(dead_code, clippy::needless_range_loop)]

pub mod systems;

use varmass_symbolic::expr::{Id, SymbolKind};
use varmass_symbolic::{
    derive_source,
    mechanics::{Derivation, MassKind, Parameters, VelocitySolve},
};

/// Derives `source`, panicking with the rendered diagnostics if it fails.
pub fn derive_ok(source: &str) -> Derivation {
    match derive_source(source, Parameters::Inferred) {
        Ok(d) => d,
        Err(errors) => panic!(
            "derivation failed:\n{}",
            errors
                .iter()
                .map(|e| e.render(source))
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}

/// A deterministic generator of numbers in [lo, hi).
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// An environment indexed by symbol: every parameter, coordinate, velocity, time and state
/// mass random, law masses computed from their closed laws, momenta from p(q, q̇).
pub fn random_point(d: &Derivation, rng: &mut Rng) -> Vec<f64> {
    let symbols = d.pool.symbols();
    let mut env = vec![f64::NAN; symbols.len()];
    for s in symbols.iter() {
        env[s.index()] = match symbols.kind(s) {
            SymbolKind::Parameter | SymbolKind::Frozen => rng.uniform(0.5, 2.0),
            SymbolKind::Coordinate | SymbolKind::Time => rng.uniform(0.1, 1.2),
            SymbolKind::Velocity { .. } => rng.uniform(-1.5, 1.5),
            _ => f64::NAN,
        };
    }
    settle(d, &mut env);
    env
}

/// Recomputes the law masses and momenta of `env` from its q, q̇, t, parameters and state masses.
pub fn settle(d: &Derivation, env: &mut [f64]) {
    for (m, law) in d.masses.iter().zip(&d.closed_laws) {
        if let (MassKind::Law(_), Some(law)) = (&m.kind, law) {
            env[m.symbol.index()] = d.pool.eval(*law, env);
        }
    }
    for (c, p) in d.coordinates.iter().zip(&d.momenta) {
        env[c.momentum.index()] = d.pool.eval(*p, env);
    }
}

pub fn eval(d: &Derivation, e: Id, env: &[f64]) -> f64 {
    d.pool.eval(e, env)
}

pub fn eval_all(d: &Derivation, es: &[Id], env: &[f64]) -> Vec<f64> {
    es.iter().map(|e| d.pool.eval(*e, env)).collect()
}

pub fn value(d: &Derivation, name: &str, env: &[f64]) -> f64 {
    let s = d
        .pool
        .symbols()
        .lookup(name)
        .unwrap_or_else(|| panic!("no symbol {name}"));
    env[s.index()]
}

pub fn set(d: &Derivation, name: &str, env: &mut [f64], v: f64) {
    let s = d
        .pool
        .symbols()
        .lookup(name)
        .unwrap_or_else(|| panic!("no symbol {name}"));
    env[s.index()] = v;
}

/// q̇ from p by the derivation's velocity solve (symbolic, or a dense solve of M q̇ = p − b).
pub fn velocities_from_momenta(d: &Derivation, env: &[f64]) -> Vec<f64> {
    match &d.velocities {
        VelocitySolve::Symbolic(v) => eval_all(d, v, env),
        VelocitySolve::Numeric => {
            let m: Vec<Vec<f64>> = d.mass_matrix.iter().map(|r| eval_all(d, r, env)).collect();
            let b = eval_all(d, &d.momentum_offset, env);
            let rhs: Vec<f64> = d
                .coordinates
                .iter()
                .zip(&b)
                .map(|(c, b)| env[c.momentum.index()] - b)
                .collect();
            solve(m, rhs)
        }
    }
}

/// Dense Gaussian elimination with partial pivoting (test reference, small n).
pub fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..n {
            let f = a[row][col] / a[col][col];
            for k in col..n {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let s: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    x
}

/// q̈ from the derivation: symbolic if available, else M⁻¹ · rhs.
pub fn accelerations(d: &Derivation, env: &[f64]) -> Vec<f64> {
    match &d.accelerations {
        Some(a) => eval_all(d, a, env),
        None => {
            let m: Vec<Vec<f64>> = d.mass_matrix.iter().map(|r| eval_all(d, r, env)).collect();
            solve(m, eval_all(d, &d.acceleration_rhs, env))
        }
    }
}

/// |a − b| ≤ tol·(1 + |a| + |b|).
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * (1.0 + a.abs() + b.abs()),
        "{what}: {a} vs {b} (difference {:e})",
        (a - b).abs()
    );
}
