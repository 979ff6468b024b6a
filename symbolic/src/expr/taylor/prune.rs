//! Dead-instruction removal over the tapes of one set of stages: an instruction whose
//! results no output reaches is dropped. The compiler leaves such instructions behind when
//! it fuses a product with a reciprocal into a quotient (`Op::Div`): the reciprocal's own
//! series is then computed only if something else still reads it.

use super::{Instr, Op, TaylorTape};

/// The slots `instr` writes (its result and any companion slots).
pub(super) fn writes(instr: &Instr) -> Vec<usize> {
    match instr.op {
        Op::SinCos { cos: other, .. } | Op::SinhCosh { cosh: other, .. } => {
            vec![instr.out, other]
        }
        Op::Tan { v, .. } => vec![instr.out, v],
        Op::Table { h, piece, .. } => {
            let mut slots = vec![instr.out, h];
            slots.extend(piece..piece + 5);
            slots
        }
        _ => vec![instr.out],
    }
}

/// The slots `instr` reads, besides those it writes itself.
fn reads(instr: &Instr, operands: &[usize]) -> Vec<usize> {
    match instr.op {
        Op::Const(_) | Op::Param(_) => vec![],
        Op::Add { start, len } => operands.get(start..start + len).unwrap_or(&[]).to_vec(),
        Op::Scale(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Pow(a, b) => vec![a, b],
        Op::Min(a, b) | Op::Max(a, b) => vec![a, b],
        Op::Quotient { a, d, .. } => vec![a, d],
        Op::Atan2 { y, x, d } => vec![y, x, d],
        Op::Affine { a, .. }
        | Op::Square(a)
        | Op::Recip(a)
        | Op::Sqrt(a)
        | Op::Exp(a)
        | Op::Abs(a)
        | Op::Sign(a)
        | Op::SinCos { a, .. }
        | Op::SinhCosh { a, .. }
        | Op::Tan { a, .. }
        | Op::Table { a, .. } => vec![a],
    }
}

/// Drops from `tapes` every instruction none of whose written slots is read by a kept
/// instruction or is an output of some tape.
pub(super) fn prune(tapes: &mut [TaylorTape]) {
    let slots = tapes.first().map_or(0, |t| t.slots);
    let mut live = vec![false; slots + 1];
    let mark = |live: &mut Vec<bool>, s: usize| {
        if let Some(l) = live.get_mut(s) {
            *l = true;
        }
    };
    for tape in tapes.iter() {
        for s in &tape.outputs {
            mark(&mut live, *s);
        }
    }
    // Every kept instruction's reads are live. Readers come after what they read (later
    // stages after earlier ones, a stage's series instructions after its fixed ones, each
    // list in order), so one pass backwards settles it; the loop only confirms.
    loop {
        let mut changed = false;
        for tape in tapes.iter().rev() {
            for instr in tape.series.iter().rev().chain(tape.fixed.iter().rev()) {
                if writes(instr).iter().any(|s| live.get(*s) == Some(&true)) {
                    for s in reads(instr, &tape.operands) {
                        if live.get(s) == Some(&false) {
                            mark(&mut live, s);
                            changed = true;
                        }
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    let kept = |instr: &Instr| writes(instr).iter().any(|s| live.get(*s) == Some(&true));
    for tape in tapes.iter_mut() {
        tape.fixed.retain(kept);
        tape.series.retain(kept);
    }
}

/// Every slot some instruction of `tape` writes.
pub(super) fn written(tape: &TaylorTape) -> Vec<usize> {
    tape.fixed
        .iter()
        .chain(&tape.series)
        .flat_map(writes)
        .collect()
}

/// Every slot some instruction run at every order writes.
pub(super) fn written_in_series(tape: &TaylorTape) -> Vec<usize> {
    tape.series.iter().flat_map(writes).collect()
}
