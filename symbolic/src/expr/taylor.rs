//! Taylor coefficients by automatic differentiation: the DAG of some roots compiled into a
//! straight-line [`TaylorTape`] whose instructions are the classical recurrences for the
//! normalized derivatives u\[k\] = u⁽ᵏ⁾(t₀)/k! of every subexpression (Jorba & Zou 2005, *A
//! software package for the numerical integration of ODEs by means of high-order Taylor
//! methods*, Exp. Math. 14, §2; Biscani & Izzo 2021, MNRAS 504, §2 and appendix A).
//!
//! The caller owns the order loop. Some symbols are *inputs* whose coefficients the caller
//! supplies (for an ODE y′ = f(y, t): the state and the time); every other symbol is a
//! constant read from the environment (a parameter). Coefficient k of every instruction needs
//! only coefficients 0..=k of its operands, so the caller sets the inputs' coefficient k,
//! calls [`TaylorTape::advance`] for k, reads the outputs' coefficient k and derives the
//! inputs' coefficient k + 1 from them (y\[k+1\] = f\[k\]/(k+1)).
//!
//! Subexpressions that depend on no input are computed once, at order 0
//! ([`TaylorTape::begin`]); their higher coefficients stay zero.
//!
//! The piecewise functions (abs, sign, min, max) are differentiated on the smooth branch
//! chosen by the order-0 values (abs, min, max at a tie: by the first coefficient where the
//! series differ, the branch that holds just after): a step must not straddle their switch,
//! which is located elsewhere (events on the dense output), as for every other stepper.

#[path = "taylor/prune.rs"]
mod prune;
#[path = "taylor/recurrence.rs"]
mod recurrence;

use super::func::Func;
use super::node::{Id, Node};
use super::pool::ExprPool;
use super::rational::Rational;
use super::symbol::Symbol;
use rustc_hash::FxHashMap;
use std::sync::Arc;
use varmass_table::recurrence::Value;
use varmass_table::Table;

/// One recurrence; its result goes to slot `out` of the [`Instr`] holding it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Op {
    /// A number.
    Const(f64),
    /// A parameter: `env[index]`, NaN if missing.
    Param(usize),
    /// Sum of the slots `operands[start..start + len]`.
    Add {
        start: usize,
        len: usize,
    },
    /// A constant slot times a series: w\[k\] = c\[0\] a\[k\].
    Scale(usize, usize),
    /// `offset + scale·a`.
    Affine {
        a: usize,
        scale: f64,
        offset: f64,
    },
    /// The Cauchy product w\[k\] = Σⱼ a\[j\] b\[k−j\].
    Mul(usize, usize),
    /// a², the Cauchy product halved by symmetry.
    Square(usize),
    /// 1/a: w\[k\] = −Σⱼ₌₁ᵏ a\[j\] w\[k−j\] · w\[0\] (w\[0\] = 1/a\[0\]: no division per order).
    Recip(usize),
    /// a/d from w d = a: w\[k\] = (a\[k\] − Σⱼ₌₁ᵏ d\[j\] w\[k−j\]) · (1/d\[0\]), one sum
    /// where 1/d and a product took two.
    Div(usize, usize),
    /// √a: w\[k\] = (a\[k\] − Σⱼ₌₁ᵏ⁻¹ w\[j\] w\[k−j\]) / (2 w\[0\]).
    Sqrt(usize),
    /// a^α for the constant α in the second slot (J&Z eq. 2.6):
    /// w\[k\] = Σⱼ₌₀ᵏ⁻¹ (α(k−j) − j) a\[k−j\] w\[j\] / (k a\[0\]).
    Pow(usize, usize),
    /// eᵃ: w\[k\] = Σⱼ₌₁ᵏ j a\[j\] w\[k−j\] / k.
    Exp(usize),
    /// sin a into `out`, cos a into `cos` (the pair of J&Z eq. 2.9).
    SinCos {
        a: usize,
        cos: usize,
    },
    /// sinh a into `out`, cosh a into `cosh`.
    SinhCosh {
        a: usize,
        cosh: usize,
    },
    /// tan (`sign` +1) or tanh (−1) of a into `out`, v = 1 + sign·w² into `v`:
    /// w′ = v a′.
    Tan {
        a: usize,
        v: usize,
        sign: f64,
        f: Func,
    },
    /// w = f(a) with w′ d = sign·a′ for the slot d: ln (d = a), asin (d = √(1 − a²), +1),
    /// acos (the same, −1), atan (d = 1 + a², +1):
    /// w\[k\] = (sign·a\[k\] − Σⱼ₌₁ᵏ⁻¹ j w\[j\] d\[k−j\] / k) / d\[0\].
    Quotient {
        a: usize,
        d: usize,
        sign: f64,
        f: Func,
    },
    /// atan2(y, x) with d = x² + y²: w′ d = x y′ − y x′.
    Atan2 {
        y: usize,
        x: usize,
        d: usize,
    },
    /// |a| on the branch of a\[0\]'s sign (at 0: of a's first non-zero coefficient).
    Abs(usize),
    /// sign a\[0\], constant over the step.
    Sign(usize),
    /// The series of the argument smaller (larger) at order 0; at a tie, just after.
    Min(usize, usize),
    Max(usize, usize),
    /// Order `order` of table `table` of a (`tables[index]` of the tape): the cubic of the
    /// piece holding a\[0\] composed with a's series by Horner's rule
    /// (`varmass_table::series_coefficient`), its stage h₁ in slot `h` and the piece (knot,
    /// c₀ … c₃) in the slots `piece` … `piece + 4`, written at order 0.
    Table {
        a: usize,
        table: u16,
        order: u8,
        index: usize,
        h: usize,
        piece: usize,
    },
}

/// An operation and the slot it writes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Instr {
    pub(crate) op: Op,
    pub(crate) out: usize,
}

/// Straight-line Taylor recurrences over some roots (see [`ExprPool::compile_taylor`]).
#[derive(Clone, Debug, Default)]
pub struct TaylorTape {
    /// Run once per expansion point, at order 0: everything that depends on no input.
    fixed: Vec<Instr>,
    /// Run at every order.
    series: Vec<Instr>,
    operands: Vec<usize>,
    inputs: Vec<usize>,
    outputs: Vec<usize>,
    /// Whether each output depends on an input (is a series, not a constant).
    series_outputs: Vec<bool>,
    slots: usize,
    /// The tables the `Op::Table` instructions read, by their `index`.
    tables: Vec<Arc<Table>>,
}

/// The coefficients of every slot of a [`TaylorTape`] up to some order: the caller-owned
/// buffer of an expansion (one per thread; reused without allocation once large enough).
/// Each coefficient is a [`Value`]: `f64`, or a value with derivatives (the interpreter's
/// Taylor sensitivities expand over `varmass_core::tangent::Tangent`).
#[derive(Clone, Debug)]
pub struct TaylorJet<C = f64> {
    coefficients: Vec<C>,
    stride: usize,
}

impl<C> Default for TaylorJet<C> {
    fn default() -> Self {
        Self {
            coefficients: Vec::new(),
            stride: 0,
        }
    }
}

impl<C: Value> TaylorJet<C> {
    /// An empty jet; [`TaylorTape::begin`] sizes it.
    pub fn new() -> TaylorJet<C> {
        TaylorJet::default()
    }

    /// The highest order this jet holds.
    pub fn order(&self) -> usize {
        self.stride.saturating_sub(1)
    }

    fn get(&self, slot: usize, k: usize) -> C {
        match self.coefficients.get(slot * self.stride + k) {
            Some(x) if k < self.stride => *x,
            _ => C::splat(f64::NAN),
        }
    }

    fn set(&mut self, slot: usize, k: usize, value: C) {
        if k < self.stride {
            if let Some(x) = self.coefficients.get_mut(slot * self.stride + k) {
                *x = value;
            }
        }
    }
}

/// What the compiler knows of a slot: whether it depends on an input.
struct Compiler<'p> {
    pool: &'p ExprPool,
    fixed: Vec<Instr>,
    series: Vec<Instr>,
    operands: Vec<usize>,
    is_series: Vec<bool>,
    /// The slot of each node compiled.
    slot: FxHashMap<Id, usize>,
    /// The denominator d of each slot holding a reciprocal 1/d.
    reciprocal_of: FxHashMap<usize, usize>,
    /// Pair slots already made for an argument slot: (sin, cos) and (sinh, cosh).
    sin_cos: FxHashMap<usize, (usize, usize)>,
    sinh_cosh: FxHashMap<usize, (usize, usize)>,
    /// The slot of each product, square, scaling, quotient and reciprocal already made
    /// ([`Compiler::emit`]).
    made: FxHashMap<(u8, usize, usize), usize>,
    /// Symbols compiled through an expression in place of their input slot.
    substitutions: &'p [(Symbol, Id)],
    /// The tables `Op::Table` reads (every tape of the stages gets them all).
    tables: Vec<Arc<Table>>,
}

impl ExprPool {
    /// Compiles the Taylor recurrences of `roots`, with `inputs[i]` the symbol whose
    /// coefficients the caller sets as input `i`. Defined symbols are compiled through their
    /// values; any other symbol is a constant read from the environment.
    pub fn compile_taylor(&self, roots: &[Id], inputs: &[Symbol]) -> TaylorTape {
        self.compile_taylor_substituting(roots, inputs, &[])
    }

    /// [`compile_taylor`](Self::compile_taylor) with each symbol of `substitutions` compiled
    /// through its expression instead of as an input: for an input known to be a constant
    /// (a mass whose law depends on no input), so that the products with it are scalings
    /// and its reciprocal is computed once, not as series of zeros at every order.
    pub fn compile_taylor_substituting(
        &self,
        roots: &[Id],
        inputs: &[Symbol],
        substitutions: &[(Symbol, Id)],
    ) -> TaylorTape {
        let tapes = self.compile_taylor_stages(&[roots], inputs, substitutions);
        tapes.into_iter().next().unwrap_or_default()
    }

    /// The tapes of the state rate's three stages (`mechanics::RateStages`): the laws
    /// `laws` of the masses `law_symbols`, then `[q̇, rates]` over one set of slots
    /// ([`compile_taylor_stages`](Self::compile_taylor_stages)), in which a mass whose law
    /// depends on no input is compiled as the constant it is. The emitted Taylor method
    /// and the interpreter's Taylor program both compile here, so they make the same
    /// choices and stay bit-identical. Returns `[laws, velocities, rates]`.
    pub fn compile_taylor_rate(
        &self,
        inputs: &[Symbol],
        (laws, law_symbols): (&[Id], &[Symbol]),
        later: [&[Id]; 2],
    ) -> [TaylorTape; 3] {
        let law_tape = self.compile_taylor(laws, inputs);
        let constants: Vec<(Symbol, Id)> = (0..laws.len().min(law_symbols.len()))
            .filter(|i| law_tape.output_is_constant(*i))
            .map(|i| (law_symbols[i], laws[i]))
            .collect();
        let mut tapes = self
            .compile_taylor_stages(&later, inputs, &constants)
            .into_iter();
        let velocities = tapes.next().unwrap_or_default();
        [law_tape, velocities, tapes.next().unwrap_or_default()]
    }

    /// The tapes of stages run one after the other over one set of slots (one
    /// [`TaylorJet`] serves them all): a subexpression of a later stage's roots that an
    /// earlier stage computed is read from its slot, not recomputed (q̇'s 1/r² or
    /// cos(a₁ − a₂) again in ṗ). Each tape holds the instructions its stage added; every
    /// tape has the slot count of all of them. Stage i's instructions at order k may read
    /// what stages before i wrote at order k, so the caller runs the stages in order at
    /// each k, starting them with [`begin`](TaylorTape::begin) for the first and
    /// [`begin_more`](TaylorTape::begin_more) for the rest. Always at least one tape.
    pub fn compile_taylor_stages(
        &self,
        stages: &[&[Id]],
        inputs: &[Symbol],
        substitutions: &[(Symbol, Id)],
    ) -> Vec<TaylorTape> {
        let mut c = Compiler {
            pool: self,
            fixed: Vec::new(),
            series: Vec::new(),
            operands: Vec::new(),
            is_series: Vec::new(),
            slot: FxHashMap::default(),
            reciprocal_of: FxHashMap::default(),
            sin_cos: FxHashMap::default(),
            sinh_cosh: FxHashMap::default(),
            made: FxHashMap::default(),
            substitutions,
            tables: Vec::new(),
        };
        let input_slots: Vec<usize> = inputs.iter().map(|_| c.new_slot(true)).collect();
        let mut tapes = Vec::new();
        for roots in stages
            .iter()
            .copied()
            .chain(stages.is_empty().then_some(&[][..]))
        {
            c.compile_all(roots, inputs, &input_slots);
            let outputs: Vec<usize> = roots.iter().map(|r| c.of(*r)).collect();
            tapes.push(TaylorTape {
                series_outputs: outputs.iter().map(|s| c.series(*s)).collect(),
                slots: 0,
                fixed: std::mem::take(&mut c.fixed),
                series: std::mem::take(&mut c.series),
                operands: c.operands.clone(),
                inputs: input_slots.clone(),
                outputs,
                tables: Vec::new(),
            });
        }
        for tape in &mut tapes {
            tape.slots = c.is_series.len();
            tape.tables.clone_from(&c.tables);
        }
        prune::prune(&mut tapes);
        tapes
    }
}

impl Compiler<'_> {
    /// Compiles every node `roots` reach that is not compiled yet, children first.
    fn compile_all(&mut self, roots: &[Id], inputs: &[Symbol], input_slots: &[usize]) {
        for id in self.pool.reachable(roots, true) {
            if !self.slot.contains_key(&id) {
                let slot = self.node(id, inputs, input_slots);
                self.slot.insert(id, slot);
            }
        }
    }

    /// The slot of a substituted symbol's expression, compiled without substitutions (an
    /// expression naming its own symbol reads the input instead of recursing).
    fn substitute(&mut self, value: Id, inputs: &[Symbol], input_slots: &[usize]) -> usize {
        let substitutions = std::mem::take(&mut self.substitutions);
        self.compile_all(&[value], inputs, input_slots);
        self.substitutions = substitutions;
        self.of(value)
    }

    fn new_slot(&mut self, series: bool) -> usize {
        self.is_series.push(series);
        self.is_series.len() - 1
    }

    /// The slot of a compiled node; a constant NaN for a node not compiled (never happens
    /// for children, which come first).
    fn of(&mut self, id: Id) -> usize {
        match self.slot.get(&id) {
            Some(s) => *s,
            None => self.emit(Op::Const(f64::NAN), &[]),
        }
    }

    fn series(&self, slot: usize) -> bool {
        self.is_series.get(slot).copied().unwrap_or(false)
    }

    /// Appends `op` writing a new slot, a series slot when any of `reads` is one; an
    /// operation on slots alone that was made before is not made again. The pool shares
    /// equal nodes, but not the parts of products it keeps apart: the 3-link pendulum's ṗ
    /// holds q̇₁ q̇₂ sin(a₁ − a₂) times four different constants (m₁l², m₂l², …), four
    /// chains of the same two Cauchy products, ten of its sixteen products.
    fn emit(&mut self, op: Op, reads: &[usize]) -> usize {
        let key = match op {
            Op::Mul(a, b) => Some((0, a, b)),
            Op::Scale(c, a) => Some((1, c, a)),
            Op::Div(a, d) => Some((2, a, d)),
            Op::Square(a) => Some((3, a, a)),
            Op::Recip(a) => Some((4, a, a)),
            _ => None,
        };
        if let Some(made) = key.and_then(|key| self.made.get(&key)) {
            return *made;
        }
        let series = reads.iter().any(|s| self.series(*s));
        let out = self.new_slot(series);
        if let Some(key) = key {
            self.made.insert(key, out);
        }
        let list = if series {
            &mut self.series
        } else {
            &mut self.fixed
        };
        list.push(Instr { op, out });
        out
    }

    fn node(&mut self, id: Id, inputs: &[Symbol], input_slots: &[usize]) -> usize {
        let pool = self.pool;
        match pool.node(id) {
            Node::Num(r) => self.emit(Op::Const(r.to_f64()), &[]),
            Node::Float(bits) => self.emit(Op::Const(f64::from_bits(*bits)), &[]),
            Node::Sym(sym) => match pool.definition(*sym) {
                Some(value) => self.of(value),
                None => match self.substitutions.iter().find(|(s, _)| s == sym) {
                    Some(&(_, value)) => self.substitute(value, inputs, input_slots),
                    None => match inputs.iter().position(|s| s == sym) {
                        Some(i) => input_slots[i],
                        None => self.emit(Op::Param(sym.index()), &[]),
                    },
                },
            },
            Node::Add(terms) => {
                let slots: Vec<usize> = terms.iter().map(|t| self.of(*t)).collect();
                let start = self.operands.len();
                self.operands.extend(&slots);
                let len = slots.len();
                self.emit(Op::Add { start, len }, &slots)
            }
            Node::Mul(factors) => {
                let slots: Vec<usize> = factors.iter().map(|f| self.of(*f)).collect();
                self.product(&slots)
            }
            Node::Pow(b, e) => {
                let (b, exponent) = (self.of(*b), pool.as_rational(*e));
                let e = self.of(*e);
                self.power(b, e, exponent)
            }
            // An input is the user's function: no recurrence exists for it, so NaN
            // coefficients end a Taylor step in the typed NonFiniteState error
            // (docs/inputs.md#steppers), never a silently wrong series.
            Node::Call(Func::Input { .. }, _) => self.emit(Op::Const(f64::NAN), &[]),
            Node::Call(f, args) => {
                let slots: Vec<usize> = args.iter().map(|a| self.of(*a)).collect();
                match slots.as_slice() {
                    [a] => self.call1(*f, *a),
                    [a, b] => self.call2(*f, *a, *b),
                    _ => self.emit(Op::Const(f64::NAN), &[]),
                }
            }
        }
    }

    /// A product: the constant factors multiplied once, the series factors chained by
    /// Cauchy products, then scaled.
    fn product(&mut self, factors: &[usize]) -> usize {
        let (series, constant): (Vec<usize>, Vec<usize>) =
            factors.iter().partition(|s| self.series(**s));
        let constant = constant
            .into_iter()
            .reduce(|a, b| self.emit(Op::Mul(a, b), &[a, b]));
        // A series factor 1/d divides the others' product (`Op::Div`): one recurrence where
        // the reciprocal's and a product's took two (the reciprocal is pruned if unread).
        let (denominators, numerators): (Vec<usize>, Vec<usize>) = series
            .iter()
            .partition(|s| self.reciprocal_of.contains_key(s));
        let mut series = numerators
            .into_iter()
            .reduce(|a, b| self.emit(Op::Mul(a, b), &[a, b]));
        for r in denominators {
            series = Some(match series {
                Some(a) => {
                    let d = self.reciprocal_of[&r];
                    self.emit(Op::Div(a, d), &[a, d])
                }
                None => r,
            });
        }
        match (constant, series) {
            (Some(c), Some(s)) => self.emit(Op::Scale(c, s), &[s]),
            (Some(c), None) => c,
            (None, Some(s)) => s,
            (None, None) => self.emit(Op::Const(1.0), &[]),
        }
    }

    /// `b^e`: positive integer powers by squaring (exact, and defined where b\[0\] = 0),
    /// negative ones as their reciprocal, ½ as √, another constant exponent by the general
    /// power recurrence, a varying exponent as exp(e ln b).
    fn power(&mut self, b: usize, e: usize, exponent: Option<Rational>) -> usize {
        if !self.series(b) && !self.series(e) {
            return self.emit(Op::Pow(b, e), &[]);
        }
        if self.series(e) {
            let ln = self.call1(Func::Ln, b);
            let product = self.product(&[e, ln]);
            return self.call1(Func::Exp, product);
        }
        let integer = exponent
            .and_then(|r| r.as_integer())
            .filter(|n| (1..=64).contains(&n.unsigned_abs()));
        match (integer, exponent) {
            (Some(n), _) if n > 0 => self.integer_power(b, n.unsigned_abs()),
            (Some(n), _) => {
                let positive = self.integer_power(b, n.unsigned_abs());
                let reciprocal = self.emit(Op::Recip(positive), &[positive]);
                self.reciprocal_of.insert(reciprocal, positive);
                reciprocal
            }
            (None, Some(Rational::HALF)) => self.emit(Op::Sqrt(b), &[b]),
            _ => self.emit(Op::Pow(b, e), &[b]),
        }
    }

    /// bⁿ for 1 ≤ n ≤ 64 by binary powering.
    fn integer_power(&mut self, b: usize, n: u128) -> usize {
        let mut result: Option<usize> = None;
        let mut square = b;
        let mut n = n;
        loop {
            if n & 1 == 1 {
                result = Some(match result {
                    Some(r) => self.emit(Op::Mul(r, square), &[r, square]),
                    None => square,
                });
            }
            n >>= 1;
            if n == 0 {
                return result.unwrap_or(b);
            }
            square = self.emit(Op::Square(square), &[square]);
        }
    }

    fn call1(&mut self, f: Func, a: usize) -> usize {
        if let Func::Table { table, order } = f {
            return self.table(a, table, order);
        }
        if !self.series(a) {
            // Constant: the pair and companion slots are not needed.
            return self.emit(constant_call(f, a), &[]);
        }
        match f {
            Func::Sin | Func::Cos | Func::Sinh | Func::Cosh => {
                // One pair of recurrences gives both functions (sin with cos, sinh with cosh).
                let hyperbolic = matches!(f, Func::Sinh | Func::Cosh);
                let (odd, even) = self.pair(a, hyperbolic);
                if matches!(f, Func::Sin | Func::Sinh) {
                    odd
                } else {
                    even
                }
            }
            Func::Tan | Func::Tanh => {
                let v = self.new_slot(true);
                let sign = if f == Func::Tan { 1.0 } else { -1.0 };
                self.emit(Op::Tan { a, v, sign, f }, &[a])
            }
            Func::Exp => self.emit(Op::Exp(a), &[a]),
            Func::Ln => self.emit(
                Op::Quotient {
                    a,
                    d: a,
                    sign: 1.0,
                    f,
                },
                &[a],
            ),
            Func::Asin | Func::Acos => {
                let square = self.emit(Op::Square(a), &[a]);
                let affine = Op::Affine {
                    a: square,
                    scale: -1.0,
                    offset: 1.0,
                };
                let one_minus = self.emit(affine, &[square]);
                let d = self.emit(Op::Sqrt(one_minus), &[one_minus]);
                let sign = if f == Func::Asin { 1.0 } else { -1.0 };
                self.emit(Op::Quotient { a, d, sign, f }, &[a])
            }
            Func::Atan => {
                let square = self.emit(Op::Square(a), &[a]);
                let affine = Op::Affine {
                    a: square,
                    scale: 1.0,
                    offset: 1.0,
                };
                let d = self.emit(affine, &[square]);
                self.emit(Op::Quotient { a, d, sign: 1.0, f }, &[a])
            }
            Func::Abs => self.emit(Op::Abs(a), &[a]),
            Func::Sign => self.emit(Op::Sign(a), &[a]),
            Func::Atan2 | Func::Min | Func::Max | Func::Table { .. } | Func::Input { .. } => {
                self.emit(Op::Const(f64::NAN), &[])
            }
        }
    }

    /// Order `order` of table `table` of the slot `a` (docs/tables.md#taylor-series): a
    /// polynomial of the piece holding a\[0\], valid while the step stays in it (knots are
    /// stop times or switching functions). An unknown table is NaN.
    fn table(&mut self, a: usize, table: u16, order: u8) -> usize {
        let Some(t) = self.pool.table(table, order) else {
            return self.emit(Op::Const(f64::NAN), &[]);
        };
        let index = self.tables.len();
        self.tables.push(Arc::clone(t));
        let series = self.series(a);
        let h = self.new_slot(series);
        let piece = self.new_slot(series);
        for _ in 1..5 {
            self.new_slot(series);
        }
        let op = Op::Table {
            a,
            table,
            order,
            index,
            h,
            piece,
        };
        self.emit(op, &[a])
    }

    /// The slots of (sin a, cos a), or (sinh a, cosh a), made once per argument.
    fn pair(&mut self, a: usize, hyperbolic: bool) -> (usize, usize) {
        let known = if hyperbolic {
            self.sinh_cosh.get(&a)
        } else {
            self.sin_cos.get(&a)
        };
        if let Some(pair) = known {
            return *pair;
        }
        let second = self.new_slot(true);
        let op = if hyperbolic {
            Op::SinhCosh { a, cosh: second }
        } else {
            Op::SinCos { a, cos: second }
        };
        let first = self.emit(op, &[a]);
        let map = if hyperbolic {
            &mut self.sinh_cosh
        } else {
            &mut self.sin_cos
        };
        map.insert(a, (first, second));
        (first, second)
    }

    fn call2(&mut self, f: Func, a: usize, b: usize) -> usize {
        match f {
            Func::Atan2 if self.series(a) || self.series(b) => {
                let ya = self.emit(Op::Square(a), &[a]);
                let xb = self.emit(Op::Square(b), &[b]);
                let start = self.operands.len();
                self.operands.extend([ya, xb]);
                let d = self.emit(Op::Add { start, len: 2 }, &[ya, xb]);
                self.emit(Op::Atan2 { y: a, x: b, d }, &[a, b])
            }
            Func::Atan2 => self.emit(
                Op::Atan2 {
                    y: a,
                    x: b,
                    d: usize::MAX,
                },
                &[],
            ),
            Func::Min => self.emit(Op::Min(a, b), &[a, b]),
            Func::Max => self.emit(Op::Max(a, b), &[a, b]),
            _ => self.emit(Op::Const(f64::NAN), &[]),
        }
    }
}

/// A one-argument call of a constant: only its value at order 0 is needed, which every
/// recurrence gives from `f` itself (the companion slots are not read at order 0).
fn constant_call(f: Func, a: usize) -> Op {
    match f {
        Func::Exp => Op::Exp(a),
        Func::Abs => Op::Abs(a),
        Func::Sign => Op::Sign(a),
        _ => Op::Quotient {
            a,
            d: a,
            sign: 1.0,
            f,
        },
    }
}

impl TaylorTape {
    /// The slot of each input.
    pub(crate) fn input_slots(&self) -> &[usize] {
        &self.inputs
    }

    /// The slot of each output.
    pub(crate) fn output_slots(&self) -> &[usize] {
        &self.outputs
    }

    /// Whether output `i` depends on no input: a constant, its higher coefficients zero.
    pub fn output_is_constant(&self, i: usize) -> bool {
        !self.series_outputs.get(i).copied().unwrap_or(true)
    }

    /// Every slot an instruction of this tape writes.
    pub(crate) fn written_slots(&self) -> Vec<usize> {
        prune::written(self)
    }

    /// Every slot the instructions run at every order write: the others (the inputs aside)
    /// hold constants, whose higher coefficients are 0.
    pub(crate) fn series_written_slots(&self) -> Vec<usize> {
        prune::written_in_series(self)
    }

    /// The instructions run once at order 0.
    pub(crate) fn fixed_instructions(&self) -> &[Instr] {
        &self.fixed
    }

    /// The instructions run at every order.
    pub(crate) fn series_instructions(&self) -> &[Instr] {
        &self.series
    }

    /// The slots an `Add` sums.
    pub(crate) fn operand_slots(&self, start: usize, len: usize) -> &[usize] {
        self.operands.get(start..start + len).unwrap_or(&[])
    }

    /// Number of instructions (order-0 ones and recurrences).
    pub fn len(&self) -> usize {
        self.fixed.len() + self.series.len()
    }

    /// Whether the tape computes nothing.
    pub fn is_empty(&self) -> bool {
        self.fixed.is_empty() && self.series.is_empty()
    }

    /// Number of inputs.
    pub fn inputs(&self) -> usize {
        self.inputs.len()
    }

    /// Number of outputs (the roots it was compiled from).
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Starts an expansion to `order`: sizes `jet` (allocating only when it grows), zeroes
    /// it and computes every subexpression that depends on no input, with symbol `s` worth
    /// `env[s.index()]`.
    pub fn begin<C: Value>(&self, jet: &mut TaylorJet<C>, order: usize, env: &[C]) {
        jet.stride = order + 1;
        jet.coefficients.clear();
        jet.coefficients
            .resize(self.slots * jet.stride, C::splat(0.0));
        for instr in &self.fixed {
            recurrence::run(instr, (&self.operands, &self.tables), env, jet, 0);
        }
    }

    /// Continues an expansion that an earlier stage's tape (of the same
    /// [`ExprPool::compile_taylor_stages`]) began in `jet`: computes this stage's
    /// subexpressions that depend on no input, leaving the rest of the jet as it is.
    pub fn begin_more<C: Value>(&self, jet: &mut TaylorJet<C>, env: &[C]) {
        for instr in &self.fixed {
            recurrence::run(instr, (&self.operands, &self.tables), env, jet, 0);
        }
    }

    /// Sets coefficient `k` of input `i` (to be done before [`advance`](Self::advance)`(k)`).
    pub fn set_input<C: Value>(&self, jet: &mut TaylorJet<C>, i: usize, k: usize, value: C) {
        if let Some(slot) = self.inputs.get(i) {
            jet.set(*slot, k, value);
        }
    }

    /// Computes coefficient `k` of every subexpression, from coefficients 0..=k of the
    /// inputs and 0..k of the rest.
    pub fn advance<C: Value>(&self, jet: &mut TaylorJet<C>, k: usize) {
        if k >= jet.stride {
            return;
        }
        for instr in &self.series {
            recurrence::run(instr, (&self.operands, &self.tables), &[], jet, k);
        }
    }

    /// Coefficient `k` of output `i` (NaN if not computed).
    pub fn output<C: Value>(&self, jet: &TaylorJet<C>, i: usize, k: usize) -> C {
        match self.outputs.get(i) {
            Some(slot) => jet.get(*slot, k),
            None => C::splat(f64::NAN),
        }
    }
}

#[cfg(test)]
#[path = "taylor/tests.rs"]
mod tests;
