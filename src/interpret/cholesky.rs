//! A small in-place Cholesky solve for the run-time sized mass matrix (allocation-free, so
//! the state rate of a [`super::Program`] allocates nothing per evaluation): the core's
//! [`varmass_core::cholesky`], with the lengths and the results checked.

use varmass_core::cholesky;

/// Solves M x = b in place (x into `b`) for a symmetric positive definite row-major `m` of
/// size n × n, overwriting `m` with its Cholesky factor. Returns `false` (and leaves
/// garbage in `b`) when M is not positive definite or a value is not finite.
pub(super) fn cholesky_solve(m: &mut [f64], b: &mut [f64], n: usize) -> bool {
    cholesky_factor(m, n) && cholesky_substitute(m, b, n)
}

/// Overwrites the lower triangle of the row-major `m` (n × n) with its Cholesky factor L
/// (M = L Lᵀ, [`cholesky::factor`]); `false` when `m` is too short, M is not positive
/// definite or a value is not finite.
pub(super) fn cholesky_factor(m: &mut [f64], n: usize) -> bool {
    m.len() >= n * n && cholesky::factor(m, n)
}

/// Solves L Lᵀ x = b in place with the factor of [`cholesky_factor`]
/// ([`cholesky::substitute`]); `false` when a slice is too short or a result is not finite.
pub(super) fn cholesky_substitute(l: &[f64], b: &mut [f64], n: usize) -> bool {
    if l.len() < n * n || b.len() < n {
        return false;
    }
    cholesky::substitute(l, b, n);
    b.iter().take(n).all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::cholesky_solve;

    #[test]
    fn solves_a_known_system_and_rejects_an_indefinite_one() {
        // M = [[4, 2], [2, 3]], x = [1, -2] → b = [0, -4].
        let mut m = [4.0, 2.0, 2.0, 3.0];
        let mut b = [0.0, -4.0];
        assert!(cholesky_solve(&mut m, &mut b, 2));
        assert!((b[0] - 1.0).abs() < 1e-15 && (b[1] + 2.0).abs() < 1e-15);
        let mut m = [1.0, 2.0, 2.0, 1.0];
        let mut b = [1.0, 1.0];
        assert!(!cholesky_solve(&mut m, &mut b, 2));
    }

    #[test]
    fn a_pivot_under_the_relative_floor_is_singular() {
        // M = [[1, s], [s, 1]]: the second pivot is 1 − s², the floor √ε ≈ 1.49e-8 of
        // m_11 = 1. s² = 1 − 1e-7 passes (x = [1, 1] solved from b = [1 + s, 1 + s]);
        // s² = 1 − 1e-9 (positive definite, but half the digits gone) is singular.
        let s = (1.0_f64 - 1e-7).sqrt();
        let mut m = [1.0, s, s, 1.0];
        let mut b = [1.0 + s, 1.0 + s];
        assert!(cholesky_solve(&mut m, &mut b, 2));
        // κ(M) ≈ 4e7, so x is good to about ε κ ≈ 1e-8; bound 1e-7.
        assert!(
            (b[0] - 1.0).abs() < 1e-7 && (b[1] - 1.0).abs() < 1e-7,
            "{b:?}"
        );
        let s = (1.0_f64 - 1e-9).sqrt();
        let mut m = [1.0, s, s, 1.0];
        let mut b = [1.0 + s, 1.0 + s];
        assert!(!cholesky_solve(&mut m, &mut b, 2));
    }
}
