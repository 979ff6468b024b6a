//! Small symbolic linear algebra: the inverse of a mass matrix of up to 3 coordinates by the
//! adjugate, and matrix–vector products.

use crate::expr::{ExprPool, Id};

/// A matrix of expressions, row-major (a list of rows of equal length). Square for the
/// mass matrix and its inverse; the Jacobian blocks are (N + K) × N, (N + K) × K, N × N or
/// N × K (see [`JacobianParts`](super::JacobianParts)).
pub type Matrix = Vec<Vec<Id>>;

/// The symbolic inverse adj(M)/det(M) for n ≤ 3, `None` beyond.
pub fn inverse(pool: &mut ExprPool, m: &Matrix) -> Option<Matrix> {
    let n = m.len();
    let det = determinant(pool, m)?;
    let inv_det = {
        let minus_one = pool.int(-1);
        pool.pow(det, minus_one)
    };
    let mut out = vec![vec![inv_det; n]; n];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            // adj(M)[i][j] = cofactor(M)[j][i]
            let cofactor = cofactor(pool, m, j, i)?;
            *entry = pool.mul(&[cofactor, inv_det]);
        }
    }
    Some(out)
}

/// det(M) for n ≤ 3.
pub fn determinant(pool: &mut ExprPool, m: &Matrix) -> Option<Id> {
    match m.len() {
        1 => Some(m[0][0]),
        2 => {
            let ad = pool.mul(&[m[0][0], m[1][1]]);
            let bc = pool.mul(&[m[0][1], m[1][0]]);
            Some(pool.sub(ad, bc))
        }
        3 => {
            let mut terms = Vec::with_capacity(3);
            for j in 0..3 {
                let c = cofactor(pool, m, 0, j)?;
                terms.push(pool.mul(&[m[0][j], c]));
            }
            Some(pool.add(&terms))
        }
        _ => None,
    }
}

/// The cofactor (−1)^(i+j) · minor(i, j), for n ≤ 3.
pub(crate) fn cofactor(pool: &mut ExprPool, m: &Matrix, i: usize, j: usize) -> Option<Id> {
    let n = m.len();
    if n == 1 {
        return Some(pool.int(1));
    }
    let minor: Matrix = (0..n)
        .filter(|&r| r != i)
        .map(|r| (0..n).filter(|&c| c != j).map(|c| m[r][c]).collect())
        .collect();
    let det = determinant(pool, &minor)?;
    Some(if (i + j).is_multiple_of(2) {
        det
    } else {
        pool.neg(det)
    })
}

/// M·v.
pub fn mat_vec(pool: &mut ExprPool, m: &Matrix, v: &[Id]) -> Vec<Id> {
    m.iter()
        .map(|row| {
            let terms: Vec<Id> = row
                .iter()
                .zip(v)
                .map(|(a, b)| pool.mul(&[*a, *b]))
                .collect();
            pool.add(&terms)
        })
        .collect()
}

/// a·b.
pub fn dot(pool: &mut ExprPool, a: &[Id], b: &[Id]) -> Id {
    let terms: Vec<Id> = a.iter().zip(b).map(|(x, y)| pool.mul(&[*x, *y])).collect();
    pool.add(&terms)
}
