//! One coefficient of one instruction: for k ≥ 1 the rule of `varmass_table::recurrence`
//! (Jorba & Zou 2005, §2; Biscani & Izzo 2021, appendix A), the function generated code
//! calls too, so a rule lives in one place. At order 0 every instruction is the function
//! itself, with the numeric semantics of the value tape (`powi`, `sqrt`), so order 0 equals
//! a [`Tape`](crate::expr::Tape) evaluation.

use super::super::func::{max, min, sign};
use super::super::tape::power;
use super::{Instr, Op, TaylorJet};
use std::sync::Arc;
use varmass_table::recurrence as rule;
use varmass_table::{series_coefficient, Local, Table};

/// Coefficient `k` of the slots `instr` writes (k = 0: the value).
pub(super) fn run(
    instr: &Instr,
    (operands, tables): (&[usize], &[Arc<Table>]),
    env: &[f64],
    jet: &mut TaylorJet,
    k: usize,
) {
    let out = instr.out;
    let value = match instr.op {
        Op::Table {
            a, index, h, piece, ..
        } => return table(jet, tables.get(index), (out, h, piece), a, k),
        Op::SinCos { a, cos } => return pair(jet, (out, cos), a, k, -1.0),
        Op::SinhCosh { a, cosh } => return pair(jet, (out, cosh), a, k, 1.0),
        Op::Tan { a, v, sign, f } => return tan(jet, (out, v), a, k, (sign, f)),
        op if k == 0 => value(op, operands, env, jet),
        op => coefficient(op, operands, jet, out, k),
    };
    jet.set(out, k, value);
}

/// The value (order 0) of a single-output operation.
fn value(op: Op, operands: &[usize], env: &[f64], jet: &TaylorJet) -> f64 {
    let at = |slot: usize| jet.get(slot, 0);
    match op {
        Op::Const(c) => c,
        Op::Param(i) => env.get(i).copied().unwrap_or(f64::NAN),
        Op::Add { start, len } => rule::add(terms(operands, start, len).map(|s| at(*s))),
        Op::Scale(c, a) | Op::Mul(c, a) => at(c) * at(a),
        Op::Affine { a, scale, offset } => rule::affine(|_| at(a), 0, (scale, offset)),
        Op::Square(a) => at(a) * at(a),
        Op::Recip(a) => 1.0 / at(a),
        Op::Div(a, d) => at(a) * (1.0 / at(d)),
        Op::Sqrt(a) => at(a).sqrt(),
        Op::Pow(a, e) => power(at(a), at(e)),
        Op::Exp(a) => at(a).exp(),
        Op::Quotient { a, f, .. } => f.apply(&[at(a)]),
        Op::Atan2 { y, x, .. } => at(y).atan2(at(x)),
        Op::Abs(a) => at(a).abs(),
        Op::Sign(a) => sign(at(a)),
        Op::Min(a, b) => min(at(a), at(b)),
        Op::Max(a, b) => max(at(a), at(b)),
        Op::SinCos { .. } | Op::SinhCosh { .. } | Op::Tan { .. } | Op::Table { .. } => f64::NAN,
    }
}

/// The slots an `Op::Add` sums (none if the range is out of the operands).
fn terms(operands: &[usize], start: usize, len: usize) -> std::slice::Iter<'_, usize> {
    operands.get(start..start + len).unwrap_or(&[]).iter()
}

/// Coefficient k ≥ 1 of a single-output operation: the rule of `varmass_table::recurrence`
/// that generated code calls too (`varmass_core::steppers::taylor::series`), over this jet.
fn coefficient(op: Op, operands: &[usize], jet: &TaylorJet, out: usize, k: usize) -> f64 {
    let at = |slot: usize| move |j: usize| jet.get(slot, j);
    match op {
        Op::Const(_) | Op::Param(_) | Op::Sign(_) => 0.0,
        Op::Add { start, len } => rule::add(terms(operands, start, len).map(|s| at(*s)(k))),
        Op::Scale(c, a) => rule::scale(at(c), at(a), k),
        Op::Affine { a, scale, offset } => rule::affine(at(a), k, (scale, offset)),
        Op::Mul(a, b) => rule::mul(at(a), at(b), k),
        Op::Square(a) => rule::square(at(a), k),
        Op::Recip(a) => rule::recip(at(a), at(out), k),
        Op::Div(a, d) => rule::div(at(a), at(d), at(out), k, 1.0 / at(d)(0)),
        Op::Sqrt(a) => rule::sqrt(at(a), at(out), k),
        Op::Pow(a, e) => rule::pow(at(a), at(e)(0), at(out), k),
        Op::Exp(a) => rule::exp(at(a), at(out), k),
        Op::Quotient { a, d, sign, .. } => rule::quotient(at(a), at(d), at(out), k, sign),
        Op::Atan2 { y, x, d } => rule::atan2((at(y), at(x)), at(d), at(out), k),
        Op::Abs(a) => rule::abs(at(a), k),
        Op::Min(a, b) => rule::min_max(at(a), at(b), k, false),
        Op::Max(a, b) => rule::min_max(at(a), at(b), k, true),
        Op::SinCos { .. } | Op::SinhCosh { .. } | Op::Tan { .. } | Op::Table { .. } => f64::NAN,
    }
}

/// (sin a, cos a) for `sign` −1, (sinh a, cosh a) for +1 ([`rule::sin_cos`] for k ≥ 1).
fn pair(jet: &mut TaylorJet, (s, c): (usize, usize), a: usize, k: usize, sign: f64) {
    let (first, second) = if k == 0 {
        let a0 = jet.get(a, 0);
        if sign < 0.0 {
            a0.sin_cos()
        } else {
            (a0.sinh(), a0.cosh())
        }
    } else {
        let jet = &*jet;
        let at = |slot: usize| move |j: usize| jet.get(slot, j);
        rule::sin_cos(at(a), (at(s), at(c)), k, sign)
    };
    jet.set(s, k, first);
    jet.set(c, k, second);
}

/// tan (`sign` +1) or tanh (−1): w′ = v a′ with v = 1 + sign·w² ([`rule::tan`]).
fn tan(
    jet: &mut TaylorJet,
    (w, v): (usize, usize),
    a: usize,
    k: usize,
    (sign, f): (f64, super::Func),
) {
    let wk = if k == 0 {
        f.apply(&[jet.get(a, 0)])
    } else {
        rule::tan(|j| jet.get(a, j), |j| jet.get(v, j), k)
    };
    jet.set(w, k, wk);
    let vk = rule::tan_companion(|j| jet.get(w, j), k, sign);
    jet.set(v, k, vk);
}

/// w = F(a) for a table F: at order 0 the piece holding a\[0\] (NaN if the lookup fails)
/// into the slots `piece` … `piece + 4`; then `varmass_table::series_coefficient`, which
/// generated code calls too.
fn table(
    jet: &mut TaylorJet,
    table: Option<&Arc<Table>>,
    (w, h, piece): (usize, usize, usize),
    a: usize,
    k: usize,
) {
    let local = if k == 0 {
        let x = jet.get(a, 0);
        let local = table.map_or(Local::NAN, |t| t.local(x).unwrap_or(Local::NAN));
        jet.set(piece, 0, local.knot);
        for (j, c) in local.coefficients.iter().enumerate() {
            jet.set(piece + 1 + j, 0, *c);
        }
        local
    } else {
        let c = |j: usize| jet.get(piece + 1 + j, 0);
        Local {
            knot: jet.get(piece, 0),
            coefficients: [c(0), c(1), c(2), c(3)],
            value: f64::NAN,
        }
    };
    let (hk, wk) = series_coefficient(&local, |j| jet.get(a, j), |j| jet.get(h, j), k);
    jet.set(h, k, hk);
    jet.set(w, k, wk);
}
