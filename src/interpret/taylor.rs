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

use varmass_core::table::recurrence as rule;
use varmass_core::SystemError;
use varmass_symbolic::expr::{TaylorJet, TaylorTape};
use varmass_symbolic::mechanics::{Derivation, TaylorLayout};

use super::cholesky::{cholesky_factor, cholesky_substitute};

/// The three tapes and where their inputs and outputs go.
#[derive(Debug)]
pub(super) struct TaylorProgram {
    /// Where t, q, p, q̇, the masses and the held inputs sit among every tape's inputs.
    layout: TaylorLayout,
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
            layout: stages.layout,
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
        let l = self.layout;
        self.begin(scratch, order);
        for (i, x) in state.iter().take(l.state_len()).enumerate() {
            set(scratch, l.state(i), 0, *x);
        }
        set(scratch, TaylorLayout::TIME, 0, t);
        set(scratch, TaylorLayout::TIME, 1, 1.0);
        for k in 0..=order {
            self.stage_laws(scratch, k);
            self.stage_velocities(scratch, k)?;
            if k == order {
                break;
            }
            advance(&self.rates, scratch, Stage::Rates, k);
            let next = 1.0 / (k + 1) as f64;
            for a in 0..l.n {
                let v = get(scratch, l.velocity(a), k);
                set(scratch, l.q(a), k + 1, v * next);
            }
            for i in 0..l.n + l.state_masses {
                let rate = self.rates.output(&scratch.velocities, i, k);
                set(scratch, l.state(l.n + i), k + 1, rate * next);
            }
        }
        for k in 0..=order {
            for i in 0..l.state_len() {
                write(k, i, get(scratch, l.state(i), k));
            }
        }
        Ok(())
    }

    fn begin(&self, scratch: &mut Scratch, order: usize) {
        let stride = order + 1;
        scratch.stride = stride;
        scratch.inputs.clear();
        scratch.inputs.resize(self.layout.len() * stride, 0.0);
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
            set(scratch, self.layout.mass(*mass), k, value);
        }
    }

    /// Coefficient k of q̇, into the inputs: read off the closed form, or solved.
    fn stage_velocities(&self, scratch: &mut Scratch, k: usize) -> Result<(), SystemError> {
        advance(&self.velocities, scratch, Stage::Velocities, k);
        let (l, n) = (self.layout, self.layout.n);
        if !self.numeric {
            for a in 0..n {
                let v = self.velocities.output(&scratch.velocities, a, k);
                if k == 0 && !v.is_finite() && scratch.inputs.iter().all(|x| x.is_finite()) {
                    return Err(SystemError::SingularMassMatrix);
                }
                set(scratch, l.velocity(a), k, v);
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
        // M[0] q̇[k] = p[k] − b[k] − Σⱼ₌₁ᵏ M[j] q̇[k−j], by the rule generated code calls.
        scratch.rhs.clear();
        for a in 0..n {
            let r = rule::velocity_right_side(
                (n, a, k),
                entry,
                |b, j| get(scratch, l.velocity(b), j),
                (
                    get(scratch, l.momentum(a), k),
                    self.velocities.output(jet, n * n + a, k),
                ),
            );
            scratch.rhs.push(r);
        }
        if !cholesky_substitute(&scratch.factor, &mut scratch.rhs, n) {
            return Err(SystemError::SingularMassMatrix);
        }
        for a in 0..n {
            let v = scratch.rhs[a];
            set(scratch, l.velocity(a), k, v);
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
