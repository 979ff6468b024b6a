//! The Cholesky factorisation M = L Lᵀ of a small symmetric positive definite matrix, row
//! major, in place and without allocating, and the solve with its factor. The interpreter's
//! mass-matrix solve (`varmass::interpret`) and the Taylor stepper's series of q̇
//! (`steppers/taylor/series.rs`) call it. Here too the rule every solve of M shares (the
//! trait's default, generated code, the interpreter): which pivot is regular.

use crate::math::sqrt;

/// The smallest pivot of a factorisation of M, relative to its diagonal entry, that is not
/// reported as a singular mass matrix: √ε = 2⁻²⁶.
///
/// Rounding in the pivot d_j = m_jj − Σₖ l_jk² leaves an absolute error of about n ε m_jj
/// (each term is at most m_jj when M is positive definite), so d_j, and every rate divided
/// by it, carries a relative error of about n ε m_jj / d_j. Below √ε m_jj that error passes
/// √ε ≈ 1.5e-8: half the digits are gone, more than the tolerance of any run can absorb, and
/// an adaptive stepper would only shrink its steps towards the singularity. The typical
/// case is a rigid body's attitude near the gimbal lock of its Euler sequence, where a pivot
/// falls as cos²θ of the middle angle: the floor is met at |cos θ| ≈ ε^(1/4) ≈ 1.2e-4
/// (0.007° from the lock), and the run ends there with `SystemError::SingularMassMatrix`
/// at its time instead of stepping on with meaningless angle rates. Well-posed mass matrices
/// stay far above it (a pivot is the part of a coordinate's inertia that the earlier
/// coordinates cannot take up, e.g. 1 − m₂cos²/(m₁+m₂) of a double pendulum's second arm).
pub const RELATIVE_PIVOT_FLOOR: f64 = 1.490_116_119_384_765_6e-8;

/// Whether a pivot of M's factorisation is usable: above [`RELATIVE_PIVOT_FLOOR`] times its
/// diagonal entry (false for a NaN, a pivot ≤ 0, or a diagonal entry ≤ 0).
pub fn regular_pivot(pivot: f64, diagonal: f64) -> bool {
    pivot > RELATIVE_PIVOT_FLOOR * diagonal && diagonal > 0.0
}

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
        // it divides have lost half their digits (gimbal lock, see there).
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
