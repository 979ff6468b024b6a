//! The coefficients of SDIRK4 with γ = 1/4, copied from Hairer & Wanner's `sdirk4.f`
//! (subroutine `SDICOR`, `METH = 1`; "version of June 22, 1995"), as distributed at
//! <http://www.unige.ch/~hairer/software.html> and mirrored in
//! <https://github.com/cpmech/hwode/blob/784b80fe5ed02670bd9f17a73489de42652c38b3/sdirk4.f>
//! (lines 533–577). The method is HNW II, IV.6, Table 6.5: five stages, order 4, stiffly
//! accurate and L-stable, with an embedded third-order solution.
//!
//! The code works, as `sdirk4.f` does, with the stage increments Zᵢ = Yᵢ − y₀ = h Σⱼ aᵢⱼ f(Yⱼ)
//! instead of the stage rates, so its coefficients are those of the tableau transformed:
//!
//! * `ALPHᵢⱼ`: the explicit part of stage i, h Σ_{j<i} aᵢⱼ f(Yⱼ) = Σ_{j<i} αᵢⱼ Zⱼ, so that
//!   Zᵢ = Σ_{j<i} αᵢⱼ Zⱼ + hγ f(t₀ + cᵢh, y₀ + Zᵢ) (α = I − γA⁻¹ below the diagonal);
//! * `Eⱼ`: the embedded solution ŷ₁ = y₀ + Σⱼ eⱼ Zⱼ (e = b̂ᵀA⁻¹), while y₁ = y₀ + Z₅;
//! * `Dₖⱼ`: the dense output y(t₀ + θh) = y₀ + Σₖ θᵏ Σⱼ dₖⱼ Zⱼ.
//!
//! The unit tests recover the Butcher tableau of Table 6.5 from these and check its order
//! conditions in exact rational arithmetic.

/// γ, the diagonal of A.
pub(crate) const GAMMA: f64 = 0.25;
/// The nodes c₂…c₄ (c₁ = γ, c₅ = 1).
pub(crate) const C2: f64 = 0.75;
pub(crate) const C3: f64 = 11.0 / 20.0;
pub(crate) const C4: f64 = 0.5;
pub(crate) const ALPH21: f64 = 2.0;
pub(crate) const ALPH31: f64 = 42.0 / 25.0;
pub(crate) const ALPH32: f64 = -4.0 / 25.0;
pub(crate) const ALPH41: f64 = 89.0 / 68.0;
pub(crate) const ALPH42: f64 = -25.0 / 136.0;
pub(crate) const ALPH43: f64 = 15.0 / 136.0;
pub(crate) const ALPH51: f64 = -37.0 / 12.0;
pub(crate) const ALPH52: f64 = -103.0 / 24.0;
pub(crate) const ALPH53: f64 = 275.0 / 8.0;
pub(crate) const ALPH54: f64 = -85.0 / 3.0;
pub(crate) const E1: f64 = -23.0 / 6.0;
pub(crate) const E2: f64 = -17.0 / 12.0;
pub(crate) const E3: f64 = 125.0 / 4.0;
pub(crate) const E4: f64 = -85.0 / 3.0;
pub(crate) const D11: f64 = 61.0 / 27.0;
pub(crate) const D12: f64 = -185.0 / 54.0;
pub(crate) const D13: f64 = 2525.0 / 18.0;
pub(crate) const D14: f64 = -3740.0 / 27.0;
pub(crate) const D15: f64 = -44.0 / 9.0;
pub(crate) const D21: f64 = 2315.0 / 81.0;
pub(crate) const D22: f64 = 1049.0 / 162.0;
pub(crate) const D23: f64 = -27725.0 / 54.0;
pub(crate) const D24: f64 = 40460.0 / 81.0;
pub(crate) const D25: f64 = 557.0 / 27.0;
pub(crate) const D31: f64 = -6178.0 / 81.0;
pub(crate) const D32: f64 = -1607.0 / 81.0;
pub(crate) const D33: f64 = 20075.0 / 27.0;
pub(crate) const D34: f64 = -56440.0 / 81.0;
pub(crate) const D35: f64 = -718.0 / 27.0;
pub(crate) const D41: f64 = 3680.0 / 81.0;
pub(crate) const D42: f64 = 1360.0 / 81.0;
pub(crate) const D43: f64 = -10000.0 / 27.0;
pub(crate) const D44: f64 = 27200.0 / 81.0;
pub(crate) const D45: f64 = 320.0 / 27.0;
/// The starting values of the Newton iteration of stages 2–4 (`ETA1`, `ANU1`, `ANU2`,
/// `AMU1`, `AMU3`): Z₂ ≈ η₁Z₁, Z₃ ≈ ν₁Z₁ + ν₂Z₂, Z₄ ≈ μ₁Z₁ + μ₃Z₃.
pub(crate) const ETA1: f64 = 3.0;
pub(crate) const ANU1: f64 = 0.88;
pub(crate) const ANU2: f64 = 0.44;
pub(crate) const AMU1: f64 = 3.0 / 17.0;
pub(crate) const AMU3: f64 = 155.0 / 187.0;

#[cfg(test)]
mod tests {
    //! The transformed coefficients against the Butcher tableau of HNW II, Table 6.5, in
    //! exact rationals (the f64 constants above are the same fractions, each rounded once).
    use num_rational::BigRational;

    use crate::steppers::order_conditions::{
        defects, ratio, stage_weights, trees, worst_imaginary_axis_modulus,
    };

    fn q(p: i64, q: i64) -> BigRational {
        ratio(p, q)
    }

    fn zero() -> BigRational {
        q(0, 1)
    }

    /// A of Table 6.5 (γ = 1/4).
    fn tableau() -> Vec<Vec<BigRational>> {
        let rows: [&[(i64, i64)]; 5] = [
            &[(1, 4)],
            &[(1, 2), (1, 4)],
            &[(17, 50), (-1, 25), (1, 4)],
            &[(371, 1360), (-137, 2720), (15, 544), (1, 4)],
            &[(25, 24), (-49, 48), (125, 16), (-85, 12), (1, 4)],
        ];
        rows.iter()
            .map(|row| {
                let mut full = vec![zero(); 5];
                for (j, &(p, d)) in row.iter().enumerate() {
                    full[j] = q(p, d);
                }
                full
            })
            .collect()
    }

    /// The inverse of the lower-triangular A by forward substitution.
    fn inverse(a: &[Vec<BigRational>]) -> Vec<Vec<BigRational>> {
        let n = a.len();
        let mut inverse = vec![vec![zero(); n]; n];
        for column in 0..n {
            for i in 0..n {
                let mut value = if i == column { q(1, 1) } else { zero() };
                for (j, row) in inverse.iter().enumerate().take(i) {
                    value -= a[i][j].clone() * row[column].clone();
                }
                inverse[i][column] = value / a[i][i].clone();
            }
        }
        inverse
    }

    /// The fractions as written in `sdirk4.f` (the f64 constants are these rounded).
    fn alpha() -> Vec<Vec<BigRational>> {
        let mut alpha = vec![vec![zero(); 5]; 5];
        let entries = [
            (2, 1, q(2, 1)),
            (3, 1, q(42, 25)),
            (3, 2, q(-4, 25)),
            (4, 1, q(89, 68)),
            (4, 2, q(-25, 136)),
            (4, 3, q(15, 136)),
            (5, 1, q(-37, 12)),
            (5, 2, q(-103, 24)),
            (5, 3, q(275, 8)),
            (5, 4, q(-85, 3)),
        ];
        for (i, j, value) in entries {
            alpha[i - 1][j - 1] = value;
        }
        alpha
    }

    fn embedded() -> Vec<BigRational> {
        vec![q(-23, 6), q(-17, 12), q(125, 4), q(-85, 3), zero()]
    }

    fn dense() -> [Vec<BigRational>; 4] {
        [
            vec![q(61, 27), q(-185, 54), q(2525, 18), q(-3740, 27), q(-44, 9)],
            vec![
                q(2315, 81),
                q(1049, 162),
                q(-27725, 54),
                q(40460, 81),
                q(557, 27),
            ],
            vec![
                q(-6178, 81),
                q(-1607, 81),
                q(20075, 27),
                q(-56440, 81),
                q(-718, 27),
            ],
            vec![
                q(3680, 81),
                q(1360, 81),
                q(-10000, 27),
                q(27200, 81),
                q(320, 27),
            ],
        ]
    }

    /// vᵀA: weights on the stage rates from weights on the increments Z = A (h f).
    fn times_a(v: &[BigRational], a: &[Vec<BigRational>]) -> Vec<BigRational> {
        (0..5)
            .map(|j| (0..5).fold(zero(), |s, i| s + v[i].clone() * a[i][j].clone()))
            .collect()
    }

    #[test]
    fn the_constants_are_the_fractions() {
        use super::*;
        let to_f64 = |r: &BigRational| {
            let (n, d) = (r.numer().to_string(), r.denom().to_string());
            n.parse::<f64>().unwrap() / d.parse::<f64>().unwrap()
        };
        let alpha = alpha();
        let constants = [
            (ALPH21, &alpha[1][0]),
            (ALPH31, &alpha[2][0]),
            (ALPH32, &alpha[2][1]),
            (ALPH41, &alpha[3][0]),
            (ALPH42, &alpha[3][1]),
            (ALPH43, &alpha[3][2]),
            (ALPH51, &alpha[4][0]),
            (ALPH52, &alpha[4][1]),
            (ALPH53, &alpha[4][2]),
            (ALPH54, &alpha[4][3]),
        ];
        for (constant, fraction) in constants {
            assert_eq!(constant, to_f64(fraction));
        }
        let e = embedded();
        assert_eq!([E1, E2, E3, E4], [0, 1, 2, 3].map(|j| to_f64(&e[j])));
        let d = dense();
        let rows = [
            [D11, D12, D13, D14, D15],
            [D21, D22, D23, D24, D25],
            [D31, D32, D33, D34, D35],
            [D41, D42, D43, D44, D45],
        ];
        for (row, fractions) in rows.iter().zip(&d) {
            assert_eq!(*row, [0, 1, 2, 3, 4].map(|j| to_f64(&fractions[j])));
        }
        let a = tableau();
        assert_eq!(GAMMA, to_f64(&a[0][0]));
        let c: Vec<f64> = a
            .iter()
            .map(|row| to_f64(&row.iter().fold(zero(), |s, x| s + x.clone())))
            .collect();
        assert_eq!(c, [GAMMA, C2, C3, C4, 1.0]);
    }

    #[test]
    fn alpha_is_the_explicit_part_of_the_tableau() {
        let a = tableau();
        let inverse = inverse(&a);
        let alpha = alpha();
        for i in 0..5 {
            for j in 0..i {
                // α = I − γA⁻¹ below the diagonal.
                let expected = -(q(1, 4) * inverse[i][j].clone());
                assert_eq!(alpha[i][j], expected, "α{}{}", i + 1, j + 1);
            }
        }
    }

    #[test]
    fn the_method_has_order_four_and_the_embedded_one_order_three() {
        let a = tableau();
        let all = trees(5);
        let weights = stage_weights(&a, &all);
        let b = a[4].clone(); // stiffly accurate: b is the last row
        let step = defects(&b, &weights, &all, q(1, 1));
        let embedded = times_a(&embedded(), &a);
        assert_eq!(embedded[4], zero());
        let estimate = defects(&embedded, &weights, &all, q(1, 1));
        for (tree, (d, e)) in all.iter().zip(step.iter().zip(&estimate)) {
            if tree.order <= 4 {
                assert_eq!(*d, zero(), "{tree:?}");
            }
            if tree.order <= 3 {
                assert_eq!(*e, zero(), "{tree:?}");
            }
        }
        assert!(all
            .iter()
            .zip(&step)
            .any(|(t, d)| t.order == 5 && *d != zero()));
        assert!(all
            .iter()
            .zip(&estimate)
            .any(|(t, e)| t.order == 4 && *e != zero()));
    }

    /// The dense output is exact at θ = 1 (it ends on y₁ = y₀ + Z₅) and has order 3 for
    /// every θ: the θ-weights Σₖ θᵏ dₖᵀA meet the conditions to order 3, not all of order 4.
    #[test]
    fn the_dense_output_has_order_three() {
        let a = tableau();
        let all = trees(4);
        let weights = stage_weights(&a, &all);
        let d = dense();
        let at = |theta: &BigRational| -> Vec<BigRational> {
            let mut on_z = vec![zero(); 5];
            let mut power = q(1, 1);
            for row in &d {
                power *= theta.clone();
                for j in 0..5 {
                    on_z[j] = on_z[j].clone() + power.clone() * row[j].clone();
                }
            }
            on_z
        };
        let at_one = at(&q(1, 1));
        assert_eq!(at_one, vec![zero(), zero(), zero(), zero(), q(1, 1)]);
        for theta in [q(1, 3), q(1, 2), q(4, 5)] {
            let b = times_a(&at(&theta), &a);
            let defects = defects(&b, &weights, &all, theta.clone());
            for (tree, defect) in all.iter().zip(&defects) {
                if tree.order <= 3 {
                    assert_eq!(*defect, zero(), "θ = {theta}: {tree:?}");
                }
            }
            assert!(defects.iter().any(|d| *d != zero()));
        }
    }

    /// L-stability: R(z) = 1 + z bᵀ(I − zA)⁻¹𝟙 has R(∞) = 1 − bᵀA⁻¹𝟙 = 0 exactly, and
    /// |R(iy)| ≤ 1 on the imaginary axis (A-stability; all poles 1/γ lie in the right
    /// half-plane), sampled densely in f64.
    #[test]
    fn the_method_is_l_stable() {
        let a = tableau();
        let inverse = inverse(&a);
        let b = &a[4];
        let at_infinity = (0..5).fold(q(1, 1), |s, i| {
            s - (0..5).fold(zero(), |t, j| t + b[i].clone() * inverse[i][j].clone())
        });
        assert_eq!(at_infinity, zero());
        let a: Vec<Vec<f64>> = a
            .iter()
            .map(|row| {
                row.iter()
                    .map(|x| {
                        x.numer().to_string().parse::<f64>().unwrap()
                            / x.denom().to_string().parse::<f64>().unwrap()
                    })
                    .collect()
            })
            .collect();
        let worst = worst_imaginary_axis_modulus(&a);
        eprintln!("max |R(iy)| = {worst}");
        assert!(worst <= 1.0 + 1e-12, "{worst}");
    }
}
