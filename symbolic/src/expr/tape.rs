//! The evaluator: the DAG of some roots compiled into straight-line code over numbered
//! slots, each shared subexpression computed once. Reusable, and allocation-free per
//! evaluation after the first; [`ExprPool::eval`] runs a one-root tape, so there is one
//! numeric semantics (`sqrt` for `^(1/2)`, `powi` for integer exponents).

use super::func::Func;
use super::node::{Id, Node};
use super::pool::ExprPool;
use super::rational::Rational;
use rustc_hash::FxHashMap;
use std::cell::{Cell, RefCell};
use std::sync::Arc;
use varmass_table::Table;

/// `b^e`, by `powi` for integer exponents (it keeps `(-2)^3 = -8` and is more accurate),
/// `cbrt` for ⅓ (the real cube root, as the printed state rate's `.cbrt()`: `powf` is NaN
/// below 0), `powf` otherwise: a power whose exponent is not a constant.
pub(crate) fn power(b: f64, e: f64) -> f64 {
    if e.fract() == 0.0 && e.abs() <= f64::from(i32::MAX) {
        b.powi(e as i32)
    } else if e == 1.0 / 3.0 {
        b.cbrt()
    } else {
        b.powf(e)
    }
}

/// `slots[k]`, NaN past the end (a missing value, never a panic).
fn slot(slots: &[f64], k: usize) -> f64 {
    match slots.get(k) {
        Some(x) => *x,
        None => f64::NAN,
    }
}

/// One instruction; its result goes to the slot with its own index.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Instr {
    Const(f64),
    /// `env[index]`, NaN if missing.
    Var(usize),
    /// The value of an earlier slot (a defined symbol's value).
    Copy(usize),
    /// Sum of `operands[start..start + len]`.
    Add {
        start: usize,
        len: usize,
    },
    /// Product of `operands[start..start + len]`.
    Mul {
        start: usize,
        len: usize,
    },
    /// `a^n` for an integer exponent: `powi`, exact for small `n` and sign-correct.
    PowI(usize, i32),
    Sqrt(usize),
    Pow(usize, usize),
    Call1(Func, usize),
    Call2(Func, usize, usize),
    /// `tables[table]` at the slot's value.
    Table {
        table: usize,
        argument: usize,
    },
}

/// A table a tape calls: the interpolant (or its derivative) and the model's name.
#[derive(Clone, Debug)]
struct TapeTable {
    table: Arc<Table>,
    name: String,
}

/// Straight-line code evaluating several expressions at once (see
/// [`ExprPool::compile`]). Defined symbols are compiled through their values.
#[derive(Debug)]
pub struct Tape {
    code: Vec<Instr>,
    operands: Vec<usize>,
    outputs: Vec<usize>,
    scratch: RefCell<Vec<f64>>,
    tables: Vec<TapeTable>,
    /// Whether tables extrapolate their end pieces (the derivation's numeric checks test
    /// algebra at random points, not data) instead of applying their `Outside` rule.
    extrapolate: bool,
    /// The first lookup the last evaluation could not make: (table, argument).
    outside: Cell<Option<(usize, f64)>>,
}

impl Clone for Tape {
    fn clone(&self) -> Tape {
        Tape {
            code: self.code.clone(),
            operands: self.operands.clone(),
            outputs: self.outputs.clone(),
            scratch: RefCell::new(Vec::new()),
            tables: self.tables.clone(),
            extrapolate: self.extrapolate,
            outside: Cell::new(None),
        }
    }
}

/// Appends the slots of `ids` (by `slot`) to `operands`: where they start and how many.
fn push_operands(
    operands: &mut Vec<usize>,
    ids: &[Id],
    slot: impl Fn(&Id) -> usize,
) -> (usize, usize) {
    let start = operands.len();
    operands.extend(ids.iter().map(slot));
    (start, ids.len())
}

impl ExprPool {
    /// Compiles `roots` into one [`Tape`]; `out[i]` of [`Tape::eval`] is the value of
    /// `roots[i]`.
    pub fn compile(&self, roots: &[Id]) -> Tape {
        let mut tables: Vec<TapeTable> = Vec::new();
        let mut slot: FxHashMap<Id, usize> = FxHashMap::default();
        let mut code = Vec::new();
        let mut operands = Vec::new();
        for id in self.reachable(roots, true) {
            let s = |c: &Id| slot.get(c).copied().unwrap_or(usize::MAX);
            let instr = match self.node(id) {
                Node::Num(r) => Instr::Const(r.to_f64()),
                Node::Float(bits) => Instr::Const(f64::from_bits(*bits)),
                Node::Sym(sym) => match self.definition(*sym) {
                    Some(value) => Instr::Copy(s(&value)),
                    None => Instr::Var(sym.index()),
                },
                Node::Add(terms) => {
                    let (start, len) = push_operands(&mut operands, terms, s);
                    Instr::Add { start, len }
                }
                Node::Mul(factors) => {
                    let (start, len) = push_operands(&mut operands, factors, s);
                    Instr::Mul { start, len }
                }
                Node::Pow(b, x) => {
                    let exponent = self.as_rational(*x);
                    let small = exponent
                        .and_then(|r| r.as_integer())
                        .and_then(|n| i32::try_from(n).ok());
                    match small {
                        Some(n) => Instr::PowI(s(b), n),
                        None if exponent == Some(Rational::HALF) => Instr::Sqrt(s(b)),
                        None => Instr::Pow(s(b), s(x)),
                    }
                }
                Node::Call(Func::Table { table, order }, args) => {
                    match (self.table(*table, *order), args.as_ref()) {
                        (Some(t), [a]) => {
                            tables.push(TapeTable {
                                table: Arc::clone(t),
                                name: self.table_call_name(*table, *order),
                            });
                            Instr::Table {
                                table: tables.len() - 1,
                                argument: s(a),
                            }
                        }
                        _ => Instr::Const(f64::NAN),
                    }
                }
                // The user's function is not known to the tape (the `check`s see NaN, the
                // interpreter substitutes an expression for each input before deriving).
                Node::Call(Func::Input { .. }, _) => Instr::Const(f64::NAN),
                Node::Call(f, args) => match args.as_ref() {
                    [a] => Instr::Call1(*f, s(a)),
                    [a, b] => Instr::Call2(*f, s(a), s(b)),
                    _ => Instr::Const(f64::NAN),
                },
            };
            slot.insert(id, code.len());
            code.push(instr);
        }
        let outputs = roots
            .iter()
            .map(|r| slot.get(r).copied().unwrap_or(usize::MAX))
            .collect();
        Tape {
            code,
            operands,
            outputs,
            scratch: RefCell::new(Vec::new()),
            tables,
            extrapolate: false,
            outside: Cell::new(None),
        }
    }
}

impl Tape {
    /// Number of instructions (one per distinct subexpression).
    pub fn len(&self) -> usize {
        self.code.len()
    }

    /// Whether the tape computes nothing.
    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }

    /// Number of outputs (the roots it was compiled from).
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Evaluates every root with symbol `s` worth `env[s.index()]` (NaN if missing) and
    /// writes root `i` to `out[i]` (as many as fit). Uses an internal scratch buffer,
    /// allocated on the first call only.
    pub fn eval(&self, env: &[f64], out: &mut [f64]) {
        match self.scratch.try_borrow_mut() {
            Ok(mut scratch) => self.eval_with(env, &mut scratch, out),
            // Only reachable through re-entrancy, which `eval` never does; stay correct.
            Err(_) => self.eval_with(env, &mut Vec::new(), out),
        }
    }

    /// [`eval`](Self::eval) with a caller-owned scratch buffer (for sharing a tape between
    /// threads: one buffer per thread).
    pub fn eval_with(&self, env: &[f64], scratch: &mut Vec<f64>, out: &mut [f64]) {
        self.outside.set(None);
        scratch.clear();
        scratch.resize(self.code.len(), 0.0);
        for (i, instr) in self.code.iter().enumerate() {
            let value = self.value(instr, env, scratch);
            if let Some(slot) = scratch.get_mut(i) {
                *slot = value;
            }
        }
        for (o, k) in out.iter_mut().zip(&self.outputs) {
            *o = slot(scratch, *k);
        }
    }

    /// The value of one instruction, from the slots computed so far.
    fn value(&self, instr: &Instr, env: &[f64], slots: &[f64]) -> f64 {
        match *instr {
            Instr::Const(c) => c,
            Instr::Var(k) => slot(env, k),
            Instr::Copy(k) => slot(slots, k),
            Instr::Add { start, len } => self.sum(start, len, slots),
            Instr::Mul { start, len } => self.product(start, len, slots),
            Instr::PowI(a, n) => slot(slots, a).powi(n),
            Instr::Sqrt(a) => slot(slots, a).sqrt(),
            Instr::Pow(a, b) => power(slot(slots, a), slot(slots, b)),
            Instr::Call1(f, a) => f.apply(&[slot(slots, a)]),
            Instr::Call2(f, a, b) => f.apply(&[slot(slots, a), slot(slots, b)]),
            Instr::Table { table, argument } => self.lookup(table, slot(slots, argument)),
        }
    }

    /// A table's value at `x`: under the table's `Outside` rule, a failed lookup NaN and
    /// remembered for [`outside`](Self::outside); extrapolated for the checks.
    fn lookup(&self, table: usize, x: f64) -> f64 {
        let Some(t) = self.tables.get(table) else {
            return f64::NAN;
        };
        if self.extrapolate {
            return t.table.curve().value(x);
        }
        match t.table.value(x) {
            Ok(value) => value,
            Err(_) => {
                if self.outside.get().is_none() {
                    self.outside.set(Some((table, x)));
                }
                f64::NAN
            }
        }
    }

    /// The first table lookup of the last evaluation that fell outside the table's data
    /// under `outside error` (or had a NaN argument): the table's name (`F`, or `F'` for
    /// its derivative) and the argument. Its outputs that depend on it are NaN.
    pub fn outside(&self) -> Option<(&str, f64)> {
        let (table, x) = self.outside.get()?;
        self.tables.get(table).map(|t| (t.name.as_str(), x))
    }

    /// The same tape with tables extrapolating their end pieces instead of applying
    /// their `Outside` rule: the derivation's numeric checks test algebra at random
    /// points, not data (docs/tables.md).
    pub fn extrapolating(mut self) -> Tape {
        self.extrapolate = true;
        self
    }

    /// The slots an `Add` or `Mul` reads.
    fn operands(&self, start: usize, len: usize) -> &[usize] {
        self.operands.get(start..start + len).unwrap_or(&[])
    }

    /// The sum of the operands' slots, in order from -0.0 as `Iterator::sum` does. (A plain
    /// loop: iterator adapters cost calls per element in unoptimized builds, and the
    /// numerical identity check evaluates a tape at least 32 times.)
    fn sum(&self, start: usize, len: usize, slots: &[f64]) -> f64 {
        let mut total = -0.0;
        for &k in self.operands(start, len) {
            total += slot(slots, k);
        }
        total
    }

    /// The product of the operands' slots, in order from 1 as `Iterator::product` does.
    fn product(&self, start: usize, len: usize, slots: &[f64]) -> f64 {
        let mut total = 1.0;
        for &k in self.operands(start, len) {
            total *= slot(slots, k);
        }
        total
    }

    /// Like [`eval_with`](Self::eval_with), and also the *magnitude* of each root: the same
    /// expression with every sum replaced by the sum of absolute values. It bounds the
    /// rounding error of the evaluation (≈ ops × ε × magnitude), which a value that cancels
    /// to nearly zero cannot.
    pub(crate) fn eval_with_magnitude(
        &self,
        env: &[f64],
        scratch: &mut Vec<f64>,
        magnitudes: &mut Vec<f64>,
        out: &mut [f64],
        out_magnitude: &mut [f64],
    ) {
        self.eval_with(env, scratch, out);
        magnitudes.clear();
        magnitudes.resize(self.code.len(), 0.0);
        for (i, instr) in self.code.iter().enumerate() {
            let value = slot(scratch, i).abs();
            let magnitude = match *instr {
                Instr::Copy(k) => slot(magnitudes, k),
                Instr::Add { start, len } => self.sum(start, len, magnitudes),
                Instr::Mul { start, len } => self.product(start, len, magnitudes),
                Instr::PowI(a, n) if n > 0 => slot(magnitudes, a).powi(n),
                // Nonlinear: the value's size is the best cheap scale.
                _ => value,
            };
            if let Some(slot) = magnitudes.get_mut(i) {
                *slot = magnitude.max(value);
            }
        }
        for (o, k) in out_magnitude.iter_mut().zip(&self.outputs) {
            *o = slot(magnitudes, *k);
        }
    }
}
