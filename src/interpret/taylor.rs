//! The Taylor coefficients of the solution through a state, over the derivation's
//! expressions compiled into [`TaylorTape`]s: the run-time counterpart of the emitted Taylor
//! method, for the Taylor stepper on a model read at run time (`varmass run --method taylor`).
//!
//! The state rate is evaluated in three stages, as [`Program::state_rate`](super::Program)
//! does: the law masses m(q, t), the velocities q̇(q, p, m, t), then ṗ and ṁ of the state
//! masses from (q, q̇, m, t). Each stage is a tape whose inputs are the series of t, q, p, q̇
//! and every mass; coefficient k of one stage feeds coefficient k of the next, and
//! y\[k+1\] = f\[k\]/(k+1) closes the loop (Jorba & Zou 2005, §2). Beyond the closed form,
//! M q̇ = p − b is solved order by order with the factor of M\[0\] (from Σⱼ M\[j\] q̇\[k−j\] =
//! p\[k\] − b\[k\]).

use std::cell::RefCell;

use varmass_core::steppers::taylor::series;
use varmass_core::SystemError;
use varmass_symbolic::expr::{TaylorJet, TaylorTape};
use varmass_symbolic::mechanics::Derivation;

use super::cholesky::{cholesky_factor, cholesky_substitute};

/// The three tapes and where their inputs and outputs go.
#[derive(Debug)]
pub(super) struct TaylorProgram {
    /// Inputs of every tape: t, q, p, q̇, every mass (in mass order).
    n: usize,
    masses: usize,
    state_masses: usize,
    /// Held values of sampled inputs: the state's last entries, constant series.
    held: usize,
    /// Mass index of each law output.
    law_masses: Vec<usize>,
    laws: TaylorTape,
    /// q̇ in closed form, or M (row-major) then b.
    velocities: TaylorTape,
    numeric: bool,
    /// ṗ then ṁ of the state masses, over the velocities' slots (and jet).
    rates: TaylorTape,
    env: Vec<f64>,
    scratch: RefCell<Scratch>,
}

#[derive(Debug, Default)]
struct Scratch {
    laws: TaylorJet,
    /// The jet of q̇ and of the rates, which share their slots.
    velocities: TaylorJet,
    /// Coefficients of every input, input-major: `inputs[i * stride + k]`.
    inputs: Vec<f64>,
    stride: usize,
    /// The factor of M[0] and the right side of the solve.
    factor: Vec<f64>,
    rhs: Vec<f64>,
}

impl TaylorProgram {
    /// Compiles the stages of `d` with the parameter environment `env`.
    pub(super) fn new(d: &Derivation, env: &[f64]) -> Self {
        // The emitted method's stages (`Derivation::taylor_stages`): the same choices.
        let stages = d.taylor_stages();
        Self {
            n: d.coordinates.len(),
            masses: d.masses.len(),
            state_masses: d.state_mass_count(),
            held: d.held().len(),
            law_masses: stages.law_masses,
            velocities: stages.velocities,
            numeric: stages.numeric,
            rates: stages.rates,
            laws: stages.laws,
            env: env.to_vec(),
            scratch: RefCell::new(Scratch::default()),
        }
    }

    /// New parameter values (`env` as [`TaylorProgram::new`] takes it).
    pub(super) fn set_env(&mut self, env: &[f64]) {
        self.env.clear();
        self.env.extend_from_slice(env);
    }

    /// Instructions of the three tapes together.
    pub(super) fn len(&self) -> usize {
        self.laws.len() + self.velocities.len() + self.rates.len()
    }

    /// The coefficients y\[0\] … y\[order\] of the solution through `(t, state)`, each
    /// given to `write(k, i, y[k]ᵢ)`.
    pub(super) fn expand(
        &self,
        t: f64,
        state: &[f64],
        order: usize,
        mut write: impl FnMut(usize, usize, f64),
    ) -> Result<(), SystemError> {
        let scratch = &mut *self.scratch.borrow_mut();
        let s = 2 * self.n + self.state_masses + self.held;
        self.begin(scratch, order);
        for (i, x) in state.iter().take(s).enumerate() {
            let input = self.state_input(i);
            set(scratch, input, 0, *x);
        }
        set(scratch, 0, 0, t);
        set(scratch, 0, 1, 1.0);
        for k in 0..=order {
            self.stage_laws(scratch, k);
            self.stage_velocities(scratch, k)?;
            if k == order {
                break;
            }
            advance(&self.rates, scratch, Stage::Rates, k);
            let next = 1.0 / (k + 1) as f64;
            for a in 0..self.n {
                let v = get(scratch, 1 + 2 * self.n + a, k);
                set(scratch, 1 + a, k + 1, v * next);
            }
            for i in 0..self.n + self.state_masses {
                let rate = self.rates.output(&scratch.velocities, i, k);
                let input = self.state_input(self.n + i);
                set(scratch, input, k + 1, rate * next);
            }
        }
        for k in 0..=order {
            for i in 0..s {
                write(k, i, get(scratch, self.state_input(i), k));
            }
        }
        Ok(())
    }

    /// Input index of state component i: q, p, then the state masses, then the held
    /// inputs (after every mass among the inputs; their higher coefficients stay 0).
    fn state_input(&self, i: usize) -> usize {
        if i < 2 * self.n {
            1 + i
        } else if i < 2 * self.n + self.state_masses {
            1 + 3 * self.n + (i - 2 * self.n)
        } else {
            1 + 3 * self.n + self.masses + (i - 2 * self.n - self.state_masses)
        }
    }

    fn begin(&self, scratch: &mut Scratch, order: usize) {
        let stride = order + 1;
        let inputs = 1 + 3 * self.n + self.masses + self.held;
        scratch.stride = stride;
        scratch.inputs.clear();
        scratch.inputs.resize(inputs * stride, 0.0);
        self.laws.begin(&mut scratch.laws, order, &self.env);
        self.velocities
            .begin(&mut scratch.velocities, order, &self.env);
        self.rates.begin_more(&mut scratch.velocities, &self.env);
    }

    /// Coefficient k of the law masses, into the inputs.
    fn stage_laws(&self, scratch: &mut Scratch, k: usize) {
        advance(&self.laws, scratch, Stage::Laws, k);
        for (i, mass) in self.law_masses.iter().enumerate() {
            let value = self.laws.output(&scratch.laws, i, k);
            set(scratch, 1 + 3 * self.n + mass, k, value);
        }
    }

    /// Coefficient k of q̇, into the inputs: read off the closed form, or solved.
    fn stage_velocities(&self, scratch: &mut Scratch, k: usize) -> Result<(), SystemError> {
        advance(&self.velocities, scratch, Stage::Velocities, k);
        let n = self.n;
        let first_velocity = 1 + 2 * n;
        if !self.numeric {
            for a in 0..n {
                let v = self.velocities.output(&scratch.velocities, a, k);
                if k == 0 && !v.is_finite() && scratch.inputs.iter().all(|x| x.is_finite()) {
                    return Err(SystemError::SingularMassMatrix);
                }
                set(scratch, first_velocity + a, k, v);
            }
            return Ok(());
        }
        let jet = &scratch.velocities;
        let entry = |a: usize, b: usize, j: usize| self.velocities.output(jet, a * n + b, j);
        if k == 0 {
            scratch.factor.clear();
            scratch
                .factor
                .extend((0..n * n).map(|e| entry(e / n, e % n, 0)));
            if !cholesky_factor(&mut scratch.factor, n) {
                return Err(SystemError::SingularMassMatrix);
            }
        }
        // M[0] q̇[k] = p[k] − b[k] − Σⱼ₌₁ᵏ M[j] q̇[k−j].
        scratch.rhs.clear();
        // The sum over j in four chains, as the generated code's `series::solve_velocities`.
        for a in 0..n {
            let coupling = series::sum(1, k + 1, |j| {
                (0..n).fold(-0.0, |total, b| {
                    total + entry(a, b, j) * get(scratch, first_velocity + b, k - j)
                })
            });
            let r = get(scratch, 1 + n + a, k) - self.velocities.output(jet, n * n + a, k);
            scratch.rhs.push(r - coupling);
        }
        if !cholesky_substitute(&scratch.factor, &mut scratch.rhs, n) {
            return Err(SystemError::SingularMassMatrix);
        }
        for a in 0..n {
            let v = scratch.rhs[a];
            set(scratch, first_velocity + a, k, v);
        }
        Ok(())
    }
}

#[derive(Clone, Copy)]
enum Stage {
    Laws,
    Velocities,
    Rates,
}

/// Copies coefficient k of every input into the stage's jet and advances it to order k.
fn advance(tape: &TaylorTape, scratch: &mut Scratch, stage: Stage, k: usize) {
    let Scratch {
        laws,
        velocities,
        inputs,
        stride,
        ..
    } = scratch;
    let jet = match stage {
        Stage::Laws => laws,
        Stage::Velocities | Stage::Rates => velocities,
    };
    for i in 0..tape.inputs() {
        let value = inputs.get(i * *stride + k).copied().unwrap_or(f64::NAN);
        tape.set_input(jet, i, k, value);
    }
    tape.advance(jet, k);
}

fn get(scratch: &Scratch, input: usize, k: usize) -> f64 {
    scratch
        .inputs
        .get(input * scratch.stride + k)
        .copied()
        .unwrap_or(f64::NAN)
}

fn set(scratch: &mut Scratch, input: usize, k: usize, value: f64) {
    if k < scratch.stride {
        if let Some(x) = scratch.inputs.get_mut(input * scratch.stride + k) {
            *x = value;
        }
    }
}
