//! Rotations of rigid bodies (docs/mechanics.md#rigid-bodies): the matrix R that takes
//! body-frame components to world components, and the body-frame angular velocity ω as a
//! function of the angles and their rates, in the plane and for the twelve intrinsic Euler
//! sequences.

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
