//! One coefficient of one instruction: the recurrences of Jorba & Zou (2005, §2) and
//! Biscani & Izzo (2021, appendix A), each derived from a first-order identity between the
//! result w and its argument a (named beside each case), written for normalized
//! coefficients u\[k\] = u⁽ᵏ⁾/k!. At order 0 every instruction is the function itself, with
//! the numeric semantics of the value tape (`powi`, `sqrt`), so order 0 equals a
//! [`Tape`](crate::expr::Tape) evaluation.

use super::super::func::{max, min, sign};
use super::super::tape::power;
use super::{Instr, Op, TaylorJet};
use std::sync::Arc;
use varmass_table::{series_coefficient, sum, Local, Table};

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
        Op::Add { start, len } => operands
            .get(start..start + len)
            .unwrap_or(&[])
            .iter()
            .fold(-0.0, |total, s| total + at(*s)),
        Op::Scale(c, a) | Op::Mul(c, a) => at(c) * at(a),
        Op::Affine { a, scale, offset } => offset + scale * at(a),
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

/// Coefficient k ≥ 1 of a single-output operation.
fn coefficient(op: Op, operands: &[usize], jet: &TaylorJet, out: usize, k: usize) -> f64 {
    let at = |slot: usize, j: usize| jet.get(slot, j);
    let kf = k as f64;
    match op {
        Op::Const(_) | Op::Param(_) | Op::Sign(_) => 0.0,
        Op::Add { start, len } => operands
            .get(start..start + len)
            .unwrap_or(&[])
            .iter()
            .fold(-0.0, |total, s| total + at(*s, k)),
        Op::Scale(c, a) => at(c, 0) * at(a, k),
        Op::Affine { a, scale, .. } => scale * at(a, k),
        // w = a b.
        Op::Mul(a, b) => sum(0, k + 1, |j| at(a, j) * at(b, k - j)),
        // w = a²: the Cauchy product, each cross term once and doubled.
        Op::Square(a) => {
            let cross = sum(0, k.div_ceil(2), |j| at(a, j) * at(a, k - j));
            let middle = if k.is_multiple_of(2) {
                at(a, k / 2).powi(2)
            } else {
                -0.0
            };
            2.0 * cross + middle
        }
        // w a = 1, times w[0] = 1/a[0] (a product, not a division, on the chain of orders).
        Op::Recip(a) => -sum(1, k + 1, |j| at(a, j) * at(out, k - j)) * at(out, 0),
        // w d = a, times 1/d[0] (see Recip).
        Op::Div(a, d) => {
            (at(a, k) - sum(1, k + 1, |j| at(d, j) * at(out, k - j))) * (1.0 / at(d, 0))
        }
        // w² = a.
        Op::Sqrt(a) => {
            let cross = sum(1, k, |j| at(out, j) * at(out, k - j));
            (at(a, k) - cross) / (2.0 * at(out, 0))
        }
        // a w′ = α a′ w.
        Op::Pow(a, e) => {
            let alpha = at(e, 0);
            let total = sum(0, k, |j| {
                (alpha * (k - j) as f64 - j as f64) * at(a, k - j) * at(out, j)
            });
            total / (kf * at(a, 0))
        }
        // w′ = a′ w.
        Op::Exp(a) => sum(1, k + 1, |j| j as f64 * at(a, j) * at(out, k - j)) * (1.0 / kf),
        // w′ d = sign·a′.
        Op::Quotient { a, d, sign, .. } => {
            let total = sum(1, k, |j| j as f64 * at(out, j) * at(d, k - j));
            (sign * at(a, k) - total / kf) / at(d, 0)
        }
        // w′ d = x y′ − y x′ with d = x² + y².
        Op::Atan2 { y, x, d } => {
            let cross = sum(0, k, |j| {
                (k - j) as f64 * (at(x, j) * at(y, k - j) - at(y, j) * at(x, k - j))
            });
            let total = sum(1, k, |j| j as f64 * at(out, j) * at(d, k - j));
            (cross - total) / (kf * at(d, 0))
        }
        // The branch of a[0]'s sign (the kink itself is located by events).
        Op::Abs(a) => {
            if at(a, 0) < 0.0 {
                -at(a, k)
            } else {
                at(a, k)
            }
        }
        Op::Min(a, b) => at(if at(a, 0) <= at(b, 0) { a } else { b }, k),
        Op::Max(a, b) => at(if at(a, 0) >= at(b, 0) { a } else { b }, k),
        Op::SinCos { .. } | Op::SinhCosh { .. } | Op::Tan { .. } | Op::Table { .. } => f64::NAN,
    }
}

/// (sin a, cos a) for `sign` −1: s′ = a′ c, c′ = −a′ s; (sinh a, cosh a) for +1: both +.
fn pair(jet: &mut TaylorJet, (s, c): (usize, usize), a: usize, k: usize, sign: f64) {
    let (first, second) = if k == 0 {
        let a0 = jet.get(a, 0);
        if sign < 0.0 {
            a0.sin_cos()
        } else {
            (a0.sinh(), a0.cosh())
        }
    } else {
        let first = sum(1, k + 1, |j| j as f64 * jet.get(a, j) * jet.get(c, k - j));
        let second = sum(1, k + 1, |j| j as f64 * jet.get(a, j) * jet.get(s, k - j));
        let inverse = 1.0 / k as f64;
        (first * inverse, sign * second * inverse)
    };
    jet.set(s, k, first);
    jet.set(c, k, second);
}

/// tan (`sign` +1) or tanh (−1): w′ = v a′ with v = 1 + sign·w².
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
        sum(1, k + 1, |j| j as f64 * jet.get(a, j) * jet.get(v, k - j)) * (1.0 / k as f64)
    };
    jet.set(w, k, wk);
    let square = sum(0, k + 1, |j| jet.get(w, j) * jet.get(w, k - j));
    let one = if k == 0 { 1.0 } else { 0.0 };
    jet.set(v, k, one + sign * square);
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
