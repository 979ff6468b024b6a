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

use std::any::Any;
use std::cell::RefCell;
use std::fmt;

use varmass_core::table::recurrence::{self as rule, Value};
use varmass_core::tangent::Tangent;
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
    /// The slot in `env` of each parameter, in the derivation's order (the sensitivities'
    /// parameter indices).
    parameter_slots: Vec<usize>,
    scratch: RefCell<Scratch>,
    /// The expansions over tangents' memory, one per width.
    tangents: TangentMemories,
}

/// An expansion over `Tangent<W>`'s memory, kept between expansions (they allocate only
/// when the jets grow): its scratch and its parameters.
struct TangentMemory<const W: usize> {
    scratch: Scratch<Tangent<W>>,
    env: Vec<Tangent<W>>,
}

/// The [`TangentMemory`] of each width expanded so far.
#[derive(Default)]
struct TangentMemories(RefCell<Vec<Box<dyn Any + Send>>>);

impl fmt::Debug for TangentMemories {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "TangentMemories({} widths)", self.0.borrow().len())
    }
}

impl TangentMemories {
    /// `run` with the memory of width W (made on first use).
    fn with<const W: usize, R>(&self, run: impl FnOnce(&mut TangentMemory<W>) -> R) -> R {
        let mut memories = self.0.borrow_mut();
        let mut known = memories.iter_mut();
        if let Some(memory) = known.find_map(|m| m.downcast_mut::<TangentMemory<W>>()) {
            return run(memory);
        }
        let mut memory = TangentMemory::<W> {
            scratch: Scratch::default(),
            env: Vec::new(),
        };
        let result = run(&mut memory);
        memories.push(Box::new(memory));
        result
    }
}

#[derive(Debug)]
struct Scratch<C = f64> {
    laws: TaylorJet<C>,
    /// The jet of q̇ and of the rates, which share their slots.
    velocities: TaylorJet<C>,
    /// Coefficients of every input, input-major: `inputs[i * stride + k]`.
    inputs: Vec<C>,
    stride: usize,
    /// The factor of M[0] and the right side of the solve.
    factor: Vec<f64>,
    rhs: Vec<f64>,
}

impl<C> Default for Scratch<C> {
    fn default() -> Self {
        Self {
            laws: TaylorJet::default(),
            velocities: TaylorJet::default(),
            inputs: Vec::new(),
            stride: 0,
            factor: Vec::new(),
            rhs: Vec::new(),
        }
    }
}

/// A coefficient the tapes expand over: `f64`, which solves M q̇ = p − b order by order where
/// q̇ has no closed form, or a tangent, which does not (such a model has no Taylor
/// sensitivities: [`TaylorProgram::expand_tangents`] refuses it first).
trait TapeCoefficient: Value {
    /// Coefficient k of q̇ from M q̇ = p − b, into the inputs.
    fn solve(
        program: &TaylorProgram,
        scratch: &mut Scratch<Self>,
        k: usize,
    ) -> Result<(), SystemError>;
}

impl TapeCoefficient for f64 {
    fn solve(program: &TaylorProgram, scratch: &mut Scratch, k: usize) -> Result<(), SystemError> {
        program.solve_velocities(scratch, k)
    }
}

impl<const W: usize> TapeCoefficient for Tangent<W> {
    /// Not reached: `expand_tangents` refuses a model without a closed-form q̇ first.
    fn solve(_: &TaylorProgram, _: &mut Scratch<Self>, _: usize) -> Result<(), SystemError> {
        Err(SystemError::SingularMassMatrix)
    }
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
            parameter_slots: d.parameters.iter().map(|(_, s)| s.index()).collect(),
            tangents: TangentMemories::default(),
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
        write: impl FnMut(usize, usize, f64),
    ) -> Result<(), SystemError> {
        let scratch = &mut *self.scratch.borrow_mut();
        self.expand_over(scratch, &self.env, (t, state), order, write)
    }

    /// Whether [`TaylorProgram::expand_tangents`] expands this model (q̇ in closed form).
    pub(super) fn has_tangents(&self) -> bool {
        !self.numeric
    }

    /// [`TaylorProgram::expand`] over tangents: the state's entries as given (their
    /// derivatives the sensitivities' columns) and parameter `j` moved by 1 in direction c
    /// where `seeds[c] = Some(j)`; the derivatives of y\[k\] are the Taylor coefficients of
    /// the sensitivities. `None` where q̇ has no closed form (a tangent M q̇ = p − b is not
    /// solved; generated code refuses the same).
    pub(super) fn expand_tangents<const W: usize>(
        &self,
        t: f64,
        state: &[Tangent<W>],
        seeds: &[Option<usize>; W],
        order: usize,
        write: impl FnMut(usize, usize, Tangent<W>),
    ) -> Option<Result<(), SystemError>> {
        if !self.has_tangents() {
            return None;
        }
        let expanded = self.tangents.with(|memory: &mut TangentMemory<W>| {
            let TangentMemory { scratch, env } = memory;
            env.clear();
            env.extend(self.env.iter().map(|x| Tangent::constant(*x)));
            for (c, seed) in seeds.iter().enumerate() {
                let slot = seed.and_then(|j| self.parameter_slots.get(j));
                if let Some(x) = slot.and_then(|slot| env.get_mut(*slot)) {
                    x.d[c] = 1.0;
                }
            }
            self.expand_over(scratch, env, (t, state), order, write)
        });
        Some(expanded)
    }

    /// The expansion itself, over the coefficient `C` and its parameters `env`.
    fn expand_over<C: TapeCoefficient>(
        &self,
        scratch: &mut Scratch<C>,
        env: &[C],
        (t, state): (f64, &[C]),
        order: usize,
        mut write: impl FnMut(usize, usize, C),
    ) -> Result<(), SystemError> {
        let l = self.layout;
        self.begin(scratch, env, order);
        for (i, x) in state.iter().take(l.state_len()).enumerate() {
            set(scratch, l.state(i), 0, *x);
        }
        set(scratch, TaylorLayout::TIME, 0, C::splat(t));
        set(scratch, TaylorLayout::TIME, 1, C::splat(1.0));
        for k in 0..=order {
            self.stage_laws(scratch, k);
            self.stage_velocities(scratch, k)?;
            if k == order {
                break;
            }
            advance(&self.rates, scratch, Stage::Rates, k);
            let next = C::splat(1.0 / (k + 1) as f64);
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

    fn begin<C: TapeCoefficient>(&self, scratch: &mut Scratch<C>, env: &[C], order: usize) {
        let stride = order + 1;
        scratch.stride = stride;
        scratch.inputs.clear();
        scratch
            .inputs
            .resize(self.layout.len() * stride, C::splat(0.0));
        self.laws.begin(&mut scratch.laws, order, env);
        self.velocities.begin(&mut scratch.velocities, order, env);
        self.rates.begin_more(&mut scratch.velocities, env);
    }

    /// Coefficient k of the law masses, into the inputs.
    fn stage_laws<C: TapeCoefficient>(&self, scratch: &mut Scratch<C>, k: usize) {
        advance(&self.laws, scratch, Stage::Laws, k);
        for (i, mass) in self.law_masses.iter().enumerate() {
            let value = self.laws.output(&scratch.laws, i, k);
            set(scratch, self.layout.mass(*mass), k, value);
        }
    }

    /// Coefficient k of q̇, into the inputs: read off the closed form, or solved.
    fn stage_velocities<C: TapeCoefficient>(
        &self,
        scratch: &mut Scratch<C>,
        k: usize,
    ) -> Result<(), SystemError> {
        advance(&self.velocities, scratch, Stage::Velocities, k);
        if self.numeric {
            return C::solve(self, scratch, k);
        }
        let l = self.layout;
        for a in 0..l.n {
            let v = self.velocities.output(&scratch.velocities, a, k);
            let finite = |x: &C| x.lead().is_finite();
            if k == 0 && !finite(&v) && scratch.inputs.iter().all(finite) {
                return Err(SystemError::SingularMassMatrix);
            }
            set(scratch, l.velocity(a), k, v);
        }
        Ok(())
    }

    /// Coefficient k of q̇ from M q̇ = p − b, with the factor of M\[0\] (made at k = 0).
    fn solve_velocities(&self, scratch: &mut Scratch, k: usize) -> Result<(), SystemError> {
        let (l, n) = (self.layout, self.layout.n);
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
fn advance<C: Value>(tape: &TaylorTape, scratch: &mut Scratch<C>, stage: Stage, k: usize) {
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
        let value = inputs.get(i * *stride + k).copied();
        tape.set_input(jet, i, k, value.unwrap_or(C::splat(f64::NAN)));
    }
    tape.advance(jet, k);
}

fn get<C: Value>(scratch: &Scratch<C>, input: usize, k: usize) -> C {
    scratch
        .inputs
        .get(input * scratch.stride + k)
        .copied()
        .unwrap_or(C::splat(f64::NAN))
}

fn set<C: Value>(scratch: &mut Scratch<C>, input: usize, k: usize, value: C) {
    if k < scratch.stride {
        if let Some(x) = scratch.inputs.get_mut(input * scratch.stride + k) {
            *x = value;
        }
    }
}
