//! A small in-place Cholesky solve for the run-time sized mass matrix (allocation-free, so
//! the state rate of a [`super::Program`] allocates nothing per evaluation).

/// Solves M x = b in place (x into `b`) for a symmetric positive definite row-major `m` of
/// size n × n, overwriting `m` with its Cholesky factor. Returns `false` (and leaves
/// garbage in `b`) when M is not positive definite or a value is not finite.
pub(super) fn cholesky_solve(m: &mut [f64], b: &mut [f64], n: usize) -> bool {
    cholesky_factor(m, n) && cholesky_substitute(m, b, n)
}

/// Overwrites the lower triangle of the row-major `m` (n × n) with its Cholesky factor L
/// (M = L Lᵀ); `false` when M is not positive definite or a value is not finite.
pub(super) fn cholesky_factor(m: &mut [f64], n: usize) -> bool {
    if m.len() < n * n {
        return false;
    }
    for j in 0..n {
        let mut diagonal = m[j * n + j];
        for k in 0..j {
            diagonal -= m[j * n + k] * m[j * n + k];
        }
        if diagonal.is_nan() || diagonal <= 0.0 || diagonal.is_infinite() {
            return false;
        }
        let diagonal = diagonal.sqrt();
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

/// Solves L Lᵀ x = b in place with the factor of [`cholesky_factor`]; `false` when a
/// result is not finite.
pub(super) fn cholesky_substitute(l: &[f64], b: &mut [f64], n: usize) -> bool {
    if l.len() < n * n || b.len() < n {
        return false;
    }
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
}
