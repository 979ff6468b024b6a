//! Rotations of rigid bodies (docs/mechanics.md#rigid-bodies): the matrix R that takes
//! body-frame components to world components, and the body-frame angular velocity ω as a
//! function of the angles and their rates, in the plane, for the twelve intrinsic Euler
//! sequences and for a quaternion (docs/mechanics.md#quaternions).

use super::linear::Matrix;
use crate::expr::{ExprPool, Func, Id};

/// R(θ) = [[cos θ, −sin θ], [sin θ, cos θ]]: body → world in the plane.
pub(crate) fn planar(pool: &mut ExprPool, angle: Id) -> Matrix {
    let (c, s) = (
        pool.call(Func::Cos, &[angle]),
        pool.call(Func::Sin, &[angle]),
    );
    let minus_s = pool.neg(s);
    vec![vec![c, minus_s], vec![s, c]]
}

/// The elementary rotation by `angle` about body axis `axis` (0 = x, 1 = y, 2 = z).
fn elementary(pool: &mut ExprPool, axis: usize, angle: Id) -> Matrix {
    let (c, s) = (
        pool.call(Func::Cos, &[angle]),
        pool.call(Func::Sin, &[angle]),
    );
    let minus_s = pool.neg(s);
    let (zero, one) = (pool.int(0), pool.int(1));
    let mut m = vec![vec![zero; 3]; 3];
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    m[axis][axis] = one;
    m[i][i] = c;
    m[j][j] = c;
    m[i][j] = minus_s;
    m[j][i] = s;
    m
}

/// The axes of an intrinsic sequence written `zyx` (already checked by the parser).
pub(crate) fn sequence_axes(sequence: &str) -> Option<[usize; 3]> {
    let mut axes = [0; 3];
    let letters: Vec<char> = sequence.chars().collect();
    if letters.len() != 3 {
        return None;
    }
    for (axis, letter) in axes.iter_mut().zip(letters) {
        *axis = match letter {
            'x' => 0,
            'y' => 1,
            'z' => 2,
            _ => return None,
        };
    }
    Some(axes)
}

/// R = R_a1(φ1) R_a2(φ2) R_a3(φ3) for the intrinsic sequence a1 a2 a3: each rotation about
/// an axis of the frame the previous ones produced.
pub(crate) fn spatial(pool: &mut ExprPool, axes: [usize; 3], angles: &[Id; 3]) -> Matrix {
    let first = elementary(pool, axes[0], angles[0]);
    let second = elementary(pool, axes[1], angles[1]);
    let third = elementary(pool, axes[2], angles[2]);
    let partial = product(pool, &first, &second);
    product(pool, &partial, &third)
}

/// ω in body axes from the rates: ω_b = R3ᵀ R2ᵀ e_a1 φ̇1 + R3ᵀ e_a2 φ̇2 + e_a3 φ̇3, each rate
/// seen from the final (body) frame.
pub(crate) fn body_rates(
    pool: &mut ExprPool,
    axes: [usize; 3],
    angles: &[Id; 3],
    rates: &[Id; 3],
) -> Vec<Id> {
    let second = elementary(pool, axes[1], angles[1]);
    let third = elementary(pool, axes[2], angles[2]);
    let third_t = transpose(&third);
    let second_t = transpose(&second);
    let zero = pool.int(0);
    let along = |pool: &mut ExprPool, axis: usize, rate: Id| -> Vec<Id> {
        let mut v = vec![pool.int(0); 3];
        v[axis] = rate;
        v
    };
    let e1 = along(pool, axes[0], rates[0]);
    let e1 = super::linear::mat_vec(pool, &second_t, &e1);
    let e1 = super::linear::mat_vec(pool, &third_t, &e1);
    let e2 = along(pool, axes[1], rates[1]);
    let e2 = super::linear::mat_vec(pool, &third_t, &e2);
    let e3 = along(pool, axes[2], rates[2]);
    (0..3)
        .map(|i| {
            let sum = pool.add(&[e1[i], e2[i], e3[i], zero]);
            pool.reduce_trig(sum)
        })
        .collect()
}

/// n = e0² + e1² + e2² + e3², the squared norm of a quaternion.
pub(crate) fn quaternion_norm(pool: &mut ExprPool, e: &[Id; 4]) -> Id {
    let two = pool.int(2);
    let squares: Vec<Id> = e.iter().map(|c| pool.pow(*c, two)).collect();
    pool.add(&squares)
}

/// R(q) = R(q/|q|) for q = (e0, e1, e2, e3), scalar first (Hamilton's convention, body →
/// world): the rotation of the unit quaternion, written with n = |q|² so that every q ≠ 0
/// is an attitude and the radial direction of q moves nothing:
///
/// ```text
///       1 ⎡ e0²+e1²−e2²−e3²   2(e1e2 − e0e3)    2(e1e3 + e0e2)  ⎤
/// R  =  ─ ⎢ 2(e1e2 + e0e3)    e0²−e1²+e2²−e3²   2(e2e3 − e0e1)  ⎥
///       n ⎣ 2(e1e3 − e0e2)    2(e2e3 + e0e1)    e0²−e1²−e2²+e3² ⎦
/// ```
pub(crate) fn quaternion_rotation(pool: &mut ExprPool, e: &[Id; 4]) -> Matrix {
    let n = quaternion_norm(pool, e);
    let two = pool.int(2);
    let square = |pool: &mut ExprPool, i: usize| pool.pow(e[i], two);
    let diagonal = |pool: &mut ExprPool, k: usize| {
        // e0² + e_k² − the other two.
        let terms: Vec<Id> = (1..4)
            .map(|i| {
                let s = square(pool, i);
                if i == k {
                    s
                } else {
                    pool.neg(s)
                }
            })
            .collect();
        let e0 = square(pool, 0);
        pool.add(&[&[e0], terms.as_slice()].concat())
    };
    // 2(e_i e_j ± e0 e_k): the off-diagonal entry (row i, column j) for {i, j, k} = {1, 2, 3}.
    let off = |pool: &mut ExprPool, i: usize, j: usize, k: usize, plus: bool| {
        let (a, b) = (pool.mul(&[two, e[i], e[j]]), pool.mul(&[two, e[0], e[k]]));
        let b = if plus { b } else { pool.neg(b) };
        pool.add(&[a, b])
    };
    let entries = [
        [
            diagonal(pool, 1),
            off(pool, 1, 2, 3, false),
            off(pool, 1, 3, 2, true),
        ],
        [
            off(pool, 1, 2, 3, true),
            diagonal(pool, 2),
            off(pool, 2, 3, 1, false),
        ],
        [
            off(pool, 1, 3, 2, false),
            off(pool, 2, 3, 1, true),
            diagonal(pool, 3),
        ],
    ];
    entries
        .iter()
        .map(|row| row.iter().map(|x| pool.div(*x, n)).collect())
        .collect()
}

/// ω in body axes from a quaternion and its rates: the vector part of 2 q* ⊗ q̇ / n,
///
/// ```text
/// ω = 2 (e0 ė − ė0 e − e × ė) / n,    e = (e1, e2, e3),
/// ```
///
/// which q̇ along q leaves unchanged (so ω is that of q/|q|; `Rᵀ Ṙ = [ω]×` with R above).
pub(crate) fn quaternion_rates(pool: &mut ExprPool, e: &[Id; 4], rates: &[Id; 4]) -> Vec<Id> {
    let n = quaternion_norm(pool, e);
    let (two, minus) = (pool.int(2), pool.int(-1));
    (1..4)
        .map(|i| {
            let (j, k) = (i % 3 + 1, (i + 1) % 3 + 1);
            // (e × ė)_i = e_j ė_k − e_k ė_j for (i, j, k) cyclic in 1..3.
            let terms = [
                pool.mul(&[e[0], rates[i]]),
                pool.mul(&[minus, rates[0], e[i]]),
                pool.mul(&[minus, e[j], rates[k]]),
                pool.mul(&[e[k], rates[j]]),
            ];
            let sum = pool.add(&terms);
            let twice = pool.mul(&[two, sum]);
            pool.div(twice, n)
        })
        .collect()
}

/// The transpose (the inverse of a rotation).
pub(crate) fn transpose(m: &Matrix) -> Matrix {
    (0..m.first().map_or(0, Vec::len))
        .map(|j| m.iter().map(|row| row[j]).collect())
        .collect()
}

/// A B, entry by entry.
pub(crate) fn product(pool: &mut ExprPool, a: &Matrix, b: &Matrix) -> Matrix {
    a.iter()
        .map(|row| {
            (0..b.first().map_or(0, Vec::len))
                .map(|j| {
                    let terms: Vec<Id> = row
                        .iter()
                        .zip(b)
                        .map(|(x, b_row)| pool.mul(&[*x, b_row[j]]))
                        .collect();
                    pool.add(&terms)
                })
                .collect()
        })
        .collect()
}
