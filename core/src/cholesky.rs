//! The Cholesky factorisation M = L Lᵀ of a small symmetric positive definite matrix, row
//! major, in place and without allocating, and the solve with its factor. The interpreter's
//! mass-matrix solve (`varmass::interpret`) and the Taylor stepper's series of q̇
//! (`steppers/taylor/series.rs`) call it.

use crate::math::sqrt;
use crate::system::regular_pivot;

/// Overwrites the lower triangle of the row-major `m` (n × n, `m.len() ≥ n²`) with its
/// Cholesky factor L (M = L Lᵀ); `false` when M is not positive definite (a pivot not
/// [`regular_pivot`]) or a value is infinite.
pub fn factor(m: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut diagonal = m[j * n + j];
        for k in 0..j {
            diagonal -= m[j * n + k] * m[j * n + k];
        }
        // A pivot below RELATIVE_PIVOT_FLOOR of its diagonal entry is singular: the rates
        // it divides have lost half their digits (gimbal lock, core::system).
        if !regular_pivot(diagonal, m[j * n + j]) || diagonal.is_infinite() {
            return false;
        }
        let diagonal = sqrt(diagonal);
        m[j * n + j] = diagonal;
        for i in j + 1..n {
            let mut entry = m[i * n + j];
            for k in 0..j {
                entry -= m[i * n + k] * m[j * n + k];
            }
            m[i * n + j] = entry / diagonal;
        }
    }
    true
}

/// Solves L Lᵀ x = b in place (x into `b`, `b.len() ≥ n`) with the factor L of [`factor`]:
/// forward, then backward substitution.
pub fn substitute(l: &[f64], b: &mut [f64], n: usize) {
    for i in 0..n {
        let mut value = b[i];
        for k in 0..i {
            value -= l[i * n + k] * b[k];
        }
        b[i] = value / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut value = b[i];
        for k in i + 1..n {
            value -= l[k * n + i] * b[k];
        }
        b[i] = value / l[i * n + i];
    }
}
