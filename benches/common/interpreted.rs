//! The state rate of a derivation evaluated at run time by the symbolic engine, the
//! alternative to generated code: mass laws, then q̇ from p (closed form, or M q̇ = p − b
//! solved by Cholesky), then ṗ and ṁ_s, each stage either a compiled [`Tape`] or a walk of
//! the expression DAG ([`ExprPool::eval`]).

use std::cell::RefCell;

use varmass::symbolic::expr::{Id, Tape};
use varmass::symbolic::mechanics::{
    derive_source, Derivation, MassKind, Parameters, VelocitySolve,
};

/// How each stage is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// A straight-line [`Tape`] per stage (`ExprPool::compile`).
    Tape,
    /// `ExprPool::eval` on each root: a recursive walk, no compilation.
    Tree,
}

/// One stage: its roots, their tape, and where the values go.
struct Stage {
    roots: Vec<Id>,
    tape: Tape,
}

/// A derivation ready to evaluate its state rate at run time.
pub struct Interpreted {
    d: Derivation,
    mode: Mode,
    /// Env slots of the law masses, in `laws` order.
    law_slots: Vec<usize>,
    laws: Stage,
    /// q̇ in closed form, or the mass-matrix entries (row-major) then the offsets b.
    velocities: Stage,
    numeric: bool,
    /// ṗ then ṁ of the state masses.
    rates: Stage,
    /// The environment (one slot per symbol) and the values of a stage.
    scratch: RefCell<(Vec<f64>, Vec<f64>)>,
}

impl Interpreted {
    /// Derives `source` with the given parameter values.
    pub fn new(source: &str, parameters: &[(&str, f64)], mode: Mode) -> Result<Self, String> {
        let names = parameters.iter().map(|(n, _)| n.to_string()).collect();
        let d = derive_source(source, Parameters::Declared(names)).map_err(|e| format!("{e:?}"))?;
        let mut env = vec![f64::NAN; d.pool.symbols().len()];
        for (name, value) in parameters {
            let symbol = d
                .pool
                .symbols()
                .lookup(name)
                .ok_or_else(|| format!("no parameter {name}"))?;
            if let Some(slot) = env.get_mut(symbol.index()) {
                *slot = *value;
            }
        }
        let mut law_slots = Vec::new();
        let mut law_roots = Vec::new();
        for (mass, law) in d.masses.iter().zip(&d.closed_laws) {
            if let (MassKind::Law(_), Some(law)) = (&mass.kind, law) {
                law_slots.push(mass.symbol.index());
                law_roots.push(*law);
            }
        }
        let (velocity_roots, numeric) = match &d.velocities {
            VelocitySolve::Symbolic(v) => (v.clone(), false),
            VelocitySolve::Numeric => {
                let mut roots: Vec<Id> = d.mass_matrix.iter().flatten().copied().collect();
                roots.extend(&d.momentum_offset);
                (roots, true)
            }
        };
        let mut rate_roots = d.momentum_rate.clone();
        rate_roots.extend(d.mass_rates.iter().take(d.state_mass_count()));
        let stage = |roots: Vec<Id>| Stage {
            tape: d.pool.compile(&roots),
            roots,
        };
        let (laws, velocities, rates) =
            (stage(law_roots), stage(velocity_roots), stage(rate_roots));
        Ok(Self {
            mode,
            law_slots,
            laws,
            velocities,
            numeric,
            rates,
            scratch: RefCell::new((env, Vec::new())),
            d,
        })
    }

    /// Instructions in the three tapes together: the interpreter's work per evaluation.
    pub fn tape_length(&self) -> usize {
        self.laws.tape.len() + self.velocities.tape.len() + self.rates.tape.len()
    }

    /// Instructions of the q̇ stage alone.
    pub fn velocity_tape_length(&self) -> usize {
        self.velocities.tape.len()
    }

    fn run(&self, stage: &Stage, env: &[f64], values: &mut Vec<f64>) {
        values.clear();
        values.resize(stage.roots.len(), f64::NAN);
        match self.mode {
            Mode::Tape => stage.tape.eval(env, values),
            Mode::Tree => {
                for (value, root) in values.iter_mut().zip(&stage.roots) {
                    *value = self.d.pool.eval(*root, env);
                }
            }
        }
    }

    /// The state rate [q̇, ṗ, ṁ_s] at `(t, state)` into `out` (NaN where it cannot be had).
    pub fn state_rate(&self, t: f64, state: &[f64], out: &mut [f64]) {
        let mut scratch = self.scratch.borrow_mut();
        let (env, values) = &mut *scratch;
        let n = self.d.coordinates.len();
        let set = |env: &mut Vec<f64>, slot: usize, value: f64| {
            if let Some(s) = env.get_mut(slot) {
                *s = value;
            }
        };
        set(env, self.d.time.index(), t);
        for (a, c) in self.d.coordinates.iter().enumerate() {
            set(env, c.q.index(), state.get(a).copied().unwrap_or(f64::NAN));
            set(
                env,
                c.momentum.index(),
                state.get(n + a).copied().unwrap_or(f64::NAN),
            );
        }
        for (k, m) in self
            .d
            .masses
            .iter()
            .take(self.d.state_mass_count())
            .enumerate()
        {
            set(
                env,
                m.symbol.index(),
                state.get(2 * n + k).copied().unwrap_or(f64::NAN),
            );
        }
        self.run(&self.laws, env, values);
        for (slot, value) in self.law_slots.iter().zip(values.iter()) {
            set(env, *slot, *value);
        }
        self.run(&self.velocities, env, values);
        if self.numeric {
            let (matrix, offset) = values.split_at_mut(n * n);
            for (a, b) in offset.iter_mut().enumerate() {
                *b = env
                    .get(self.d.coordinates[a].momentum.index())
                    .copied()
                    .unwrap_or(f64::NAN)
                    - *b;
            }
            cholesky_solve(matrix, offset, n);
            for (c, v) in self.d.coordinates.iter().zip(offset.iter()) {
                set(env, c.velocity.index(), *v);
            }
        } else {
            for (c, v) in self.d.coordinates.iter().zip(values.iter()) {
                set(env, c.velocity.index(), *v);
            }
        }
        for (o, c) in out.iter_mut().zip(&self.d.coordinates) {
            *o = env.get(c.velocity.index()).copied().unwrap_or(f64::NAN);
        }
        self.run(&self.rates, env, values);
        for (o, v) in out.iter_mut().skip(n).zip(values.iter()) {
            *o = *v;
        }
    }
}

/// Solves M x = b in place (x into `b`) for a symmetric positive definite row-major `m` of
/// size n × n, overwriting `m` with its Cholesky factor; NaN if M is not positive definite.
fn cholesky_solve(m: &mut [f64], b: &mut [f64], n: usize) {
    for j in 0..n {
        let mut diagonal = m[j * n + j];
        for k in 0..j {
            diagonal -= m[j * n + k] * m[j * n + k];
        }
        let diagonal = if diagonal > 0.0 {
            diagonal.sqrt()
        } else {
            f64::NAN
        };
        m[j * n + j] = diagonal;
        for i in j + 1..n {
            let mut entry = m[i * n + j];
            for k in 0..j {
                entry -= m[i * n + k] * m[j * n + k];
            }
            m[i * n + j] = entry / diagonal;
        }
    }
    for i in 0..n {
        let mut value = b[i];
        for k in 0..i {
            value -= m[i * n + k] * b[k];
        }
        b[i] = value / m[i * n + i];
    }
    for i in (0..n).rev() {
        let mut value = b[i];
        for k in i + 1..n {
            value -= m[k * n + i] * b[k];
        }
        b[i] = value / m[i * n + i];
    }
}
