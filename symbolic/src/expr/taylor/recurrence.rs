//! One coefficient of one instruction: for k ≥ 1 the rule of `varmass_table::recurrence`
//! (Jorba & Zou 2005, §2; Biscani & Izzo 2021, appendix A), the function generated code
//! calls too, so a rule lives in one place. At order 0 every instruction is the function
//! itself, with the numeric semantics of the value tape (`powi`, `sqrt`), so order 0 equals
//! a [`Tape`](crate::expr::Tape) evaluation.

use super::super::func::{max, min, sign};
use super::super::tape::power;
use super::{Func, Instr, Op, TaylorJet};
use std::sync::Arc;
use varmass_table::recurrence::{self as rule, Value};
use varmass_table::{series_coefficient, Local, Table};

/// Coefficient `k` of the slots `instr` writes (k = 0: the value).
pub(super) fn run<C: Value>(
    instr: &Instr,
    (operands, tables): (&[usize], &[Arc<Table>]),
    env: &[C],
    jet: &mut TaylorJet<C>,
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

/// The value (order 0) of a single-output operation; over values with derivatives, by the
/// chain rule (a function's slope beside it).
fn value<C: Value>(op: Op, operands: &[usize], env: &[C], jet: &TaylorJet<C>) -> C {
    let at = |slot: usize| jet.get(slot, 0);
    let one = C::splat(1.0);
    match op {
        Op::Const(c) => C::splat(c),
        Op::Param(i) => env.get(i).copied().unwrap_or(C::splat(f64::NAN)),
        Op::Add { start, len } => rule::add(terms(operands, start, len).map(|s| at(*s))),
        Op::Scale(c, a) | Op::Mul(c, a) => at(c) * at(a),
        Op::Affine { a, scale, offset } => rule::affine(|_| at(a), 0, (scale, offset)),
        Op::Square(a) => at(a) * at(a),
        Op::Recip(a) => one / at(a),
        Op::Div(a, d) => at(a) * (one / at(d)),
        Op::Sqrt(a) => at(a).map(f64::sqrt, |_, w| 0.5 / w),
        Op::Pow(a, e) => at(a).map2(at(e), power, |x, e, w| {
            rule::power_slopes((x, e, w), power, f64::ln)
        }),
        Op::Exp(a) => at(a).map(f64::exp, |x, w| Func::Exp.slope(x, w)),
        Op::Quotient { a, f, .. } => at(a).map(|x| f.apply(&[x]), |x, w| f.slope(x, w)),
        Op::Atan2 { y, x, .. } => at(y).map2(at(x), f64::atan2, |y, x, _| {
            let r2 = y * y + x * x;
            (x / r2, -y / r2)
        }),
        Op::Abs(a) => at(a).map(f64::abs, |x, w| Func::Abs.slope(x, w)),
        Op::Sign(a) => at(a).map(sign, |x, w| Func::Sign.slope(x, w)),
        Op::Min(a, b) => at(a).pick(at(b), min),
        Op::Max(a, b) => at(a).pick(at(b), max),
        Op::SinCos { .. } | Op::SinhCosh { .. } | Op::Tan { .. } | Op::Table { .. } => {
            C::splat(f64::NAN)
        }
    }
}

/// The slots an `Op::Add` sums (none if the range is out of the operands).
fn terms(operands: &[usize], start: usize, len: usize) -> std::slice::Iter<'_, usize> {
    operands.get(start..start + len).unwrap_or(&[]).iter()
}

/// Coefficient k ≥ 1 of a single-output operation: the rule of `varmass_table::recurrence`
/// that generated code calls too (`varmass_core::steppers::taylor::series`), over this jet.
fn coefficient<C: Value>(
    op: Op,
    operands: &[usize],
    jet: &TaylorJet<C>,
    out: usize,
    k: usize,
) -> C {
    let at = |slot: usize| move |j: usize| jet.get(slot, j);
    match op {
        Op::Const(_) | Op::Param(_) | Op::Sign(_) => C::splat(0.0),
        Op::Add { start, len } => rule::add(terms(operands, start, len).map(|s| at(*s)(k))),
        Op::Scale(c, a) => rule::scale(at(c), at(a), k),
        Op::Affine { a, scale, offset } => rule::affine(at(a), k, (scale, offset)),
        Op::Mul(a, b) => rule::mul(at(a), at(b), k),
        Op::Square(a) => rule::square(at(a), k),
        Op::Recip(a) => rule::recip(at(a), at(out), k),
        Op::Div(a, d) => rule::div(at(a), at(d), at(out), k, C::splat(1.0) / at(d)(0)),
        Op::Sqrt(a) => rule::sqrt(at(a), at(out), k),
        Op::Pow(a, e) => rule::pow(at(a), at(e)(0), at(out), k),
        Op::Exp(a) => rule::exp(at(a), at(out), k),
        Op::Quotient { a, d, sign, .. } => rule::quotient(at(a), at(d), at(out), k, sign),
        Op::Atan2 { y, x, d } => rule::atan2((at(y), at(x)), at(d), at(out), k),
        Op::Abs(a) => rule::abs(at(a), k),
        Op::Min(a, b) => rule::min_max(at(a), at(b), k, false),
        Op::Max(a, b) => rule::min_max(at(a), at(b), k, true),
        Op::SinCos { .. } | Op::SinhCosh { .. } | Op::Tan { .. } | Op::Table { .. } => {
            C::splat(f64::NAN)
        }
    }
}

/// (sin a, cos a) for `sign` −1, (sinh a, cosh a) for +1 ([`rule::sin_cos`] for k ≥ 1).
fn pair<C: Value>(jet: &mut TaylorJet<C>, (s, c): (usize, usize), a: usize, k: usize, sign: f64) {
    let (first, second) = if k == 0 {
        let a0 = jet.get(a, 0);
        if sign < 0.0 {
            (
                a0.map(f64::sin, |x, w| Func::Sin.slope(x, w)),
                a0.map(f64::cos, |x, w| Func::Cos.slope(x, w)),
            )
        } else {
            (
                a0.map(f64::sinh, |x, w| Func::Sinh.slope(x, w)),
                a0.map(f64::cosh, |x, w| Func::Cosh.slope(x, w)),
            )
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
fn tan<C: Value>(
    jet: &mut TaylorJet<C>,
    (w, v): (usize, usize),
    a: usize,
    k: usize,
    (sign, f): (f64, super::Func),
) {
    let wk = if k == 0 {
        jet.get(a, 0).map(|x| f.apply(&[x]), |x, w| f.slope(x, w))
    } else {
        rule::tan(|j| jet.get(a, j), |j| jet.get(v, j), k)
    };
    jet.set(w, k, wk);
    let vk = rule::tan_companion(|j| jet.get(w, j), k, sign);
    jet.set(v, k, vk);
}

/// w = F(a) for a table F: at order 0 the piece holding a\[0\] (NaN if the lookup fails)
/// into the slots `piece` … `piece + 4`, and F(a\[0\]) with the cubic's slope there; then
/// `varmass_table::series_coefficient`, which generated code calls too.
fn table<C: Value>(
    jet: &mut TaylorJet<C>,
    table: Option<&Arc<Table>>,
    (w, h, piece): (usize, usize, usize),
    a: usize,
    k: usize,
) {
    let local = if k == 0 {
        let x = jet.get(a, 0).lead();
        let local = table.map_or(Local::NAN, |t| t.local(x).unwrap_or(Local::NAN));
        jet.set(piece, 0, C::splat(local.knot));
        for (j, c) in local.coefficients.iter().enumerate() {
            jet.set(piece + 1 + j, 0, C::splat(*c));
        }
        local
    } else {
        let c = |j: usize| jet.get(piece + 1 + j, 0).lead();
        Local {
            knot: jet.get(piece, 0).lead(),
            coefficients: [c(0), c(1), c(2), c(3)],
            value: f64::NAN,
        }
    };
    let (hk, wk) = series_coefficient(&local, |j| jet.get(a, j), |j| jet.get(h, j), k);
    let wk = match k {
        0 => jet
            .get(a, 0)
            .map(|_| wk.lead(), |x, _| cubic_slope(&local, x)),
        _ => wk,
    };
    jet.set(h, k, hk);
    jet.set(w, k, wk);
}

/// The slope of the piece's cubic c₀ + c₁s + c₂s² + c₃s³ at x (s = x − knot).
fn cubic_slope(local: &Local, x: f64) -> f64 {
    let [_, c1, c2, c3] = local.coefficients;
    let s = x - local.knot;
    c1 + s * (2.0 * c2 + s * (3.0 * c3))
}
