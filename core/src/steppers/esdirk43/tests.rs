//! The tableau of ESDIRK4(3)6L\[2\]SA against its order conditions (exact rationals for
//! A, b, b̂; f64 for the dense output, whose published coefficients are rational
//! approximations), its L-stability, and the stage increment form the stepper runs on.

use num_rational::BigRational;

use super::coefficients::{Ratio, A, DENSE, EMBEDDED};
use super::Esdirk43Method;
use crate::steppers::dirk::DirkMethod;
use crate::steppers::order_conditions::{
    defects, stage_weights, trees, worst_imaginary_axis_modulus,
};

fn exact((p, q): Ratio) -> BigRational {
    BigRational::new(p.into(), q.into())
}

fn zero() -> BigRational {
    exact((0, 1))
}

fn tableau() -> Vec<Vec<BigRational>> {
    A.iter()
        .map(|row| row.iter().map(|&r| exact(r)).collect())
        .collect()
}

fn f64_tableau() -> Vec<Vec<f64>> {
    A.iter()
        .map(|row| row.iter().map(|&(p, q)| p as f64 / q as f64).collect())
        .collect()
}

/// The weights of θ^(k+1) on the stage rates in f64.
fn dense_weights(theta: f64) -> Vec<f64> {
    DENSE
        .iter()
        .map(|row| {
            row.iter()
                .enumerate()
                .map(|(k, &(p, q))| p as f64 / q as f64 * theta.powi(k as i32 + 1))
                .sum()
        })
        .collect()
}

/// b (the last row: stiffly accurate) meets every condition to order 4 and not all of
/// order 5; b̂ every one to order 3 and not all of order 4. Exact.
#[test]
fn the_method_has_order_four_and_the_embedded_one_order_three() {
    let a = tableau();
    let c: Vec<BigRational> = a.iter().map(|row| row.iter().sum()).collect();
    let nodes = [(0, 1), (1, 2), (83, 250), (31, 50), (17, 20), (1, 1)].map(exact);
    assert_eq!(c, nodes);
    let all = trees(5);
    let weights = stage_weights(&a, &all);
    let step = defects(&a[5], &weights, &all, exact((1, 1)));
    let embedded: Vec<BigRational> = EMBEDDED.iter().map(|&r| exact(r)).collect();
    let estimate = defects(&embedded, &weights, &all, exact((1, 1)));
    for (tree, (d, e)) in all.iter().zip(step.iter().zip(&estimate)) {
        if tree.order <= 4 {
            assert_eq!(*d, zero(), "b: {tree:?}");
        }
        if tree.order <= 3 {
            assert_eq!(*e, zero(), "b̂: {tree:?}");
        }
    }
    let nonzero_of = |defects: &[BigRational], order| {
        all.iter()
            .zip(defects)
            .any(|(t, d)| t.order == order && *d != zero())
    };
    assert!(nonzero_of(&step, 5));
    assert!(nonzero_of(&estimate, 4));
}

/// Stage order 2: A𝟙 = c and A c = c²/2 on every implicit stage (Kennedy & Carpenter's
/// "[2]"), exactly.
#[test]
fn the_stage_order_is_two() {
    let a = tableau();
    let c: Vec<BigRational> = a.iter().map(|row| row.iter().sum()).collect();
    for (i, row) in a.iter().enumerate().skip(1) {
        let ac: BigRational = row.iter().zip(&c).map(|(a, c)| a * c).sum();
        assert_eq!(ac, &c[i] * &c[i] / exact((2, 1)), "stage {}", i + 1);
    }
}

/// L-stability. The stages of y′ = λy with z = hλ are Y₁ = 1,
/// Yᵢ = (1 + z Σ_{j<i} aᵢⱼYⱼ)/(1 − zγ), and R(z) = Y₆ (stiffly accurate). As z → ∞,
/// Yᵢ → −Σ_{j<i} aᵢⱼYⱼ/γ: exactly 0 for i = 6. And |R(iy)| ≤ 1 on the imaginary axis
/// (A-stability: the only pole is 1/γ > 0), sampled densely in f64.
#[test]
fn the_method_is_l_stable() {
    let a = tableau();
    let mut at_infinity = vec![exact((1, 1))];
    for (i, row) in a.iter().enumerate().skip(1) {
        let sum: BigRational = (0..i).map(|j| &row[j] * &at_infinity[j]).sum();
        at_infinity.push(-sum / &row[i]);
    }
    assert_eq!(at_infinity[5], zero(), "{at_infinity:?}");
    let a = f64_tableau();
    let worst = worst_imaginary_axis_modulus(&a);
    eprintln!("max |R(iy)| = {worst}");
    assert!(worst <= 1.0 + 1e-12, "{worst}");
}

/// The dense output b(θ) = Σⱼ b*ᵢⱼθʲ ends on b (θ = 1) and meets the conditions to
/// order 3 for every θ, not all of order 4. In f64: the published b*ᵢⱼ are rational
/// approximations (measured defects below 4e-16; bound 1e-14).
#[test]
fn the_dense_output_has_order_three() {
    let a = f64_tableau();
    let all = trees(4);
    let weights = stage_weights(&a, &all);
    for (at_one, b) in dense_weights(1.0).iter().zip(&a[5]) {
        assert!((at_one - b).abs() < 1e-15, "{at_one} against {b}");
    }
    for theta in [0.25, 0.5, 0.8] {
        let defects = defects(&dense_weights(theta), &weights, &all, theta);
        let mut worst: f64 = 0.0;
        for (tree, defect) in all.iter().zip(&defects) {
            if tree.order <= 3 {
                worst = worst.max(defect.abs());
            }
        }
        eprintln!("θ = {theta}: worst defect to order 3 {worst:e}");
        assert!(worst < 1e-14, "θ = {theta}: {worst:e}");
        assert!(defects.iter().any(|d| d.abs() > 1e-6), "θ = {theta}");
    }
}

/// The stage increment form against the rate form on arbitrary stage rates κ (scalars):
/// with Zᵢ = Σⱼ aᵢⱼκⱼ, W₁ = κ₁ and Wᵢ = Zᵢ, the explicit parts Σ_{j<i} αᵢⱼWⱼ are
/// Σ_{j<i} aᵢⱼκⱼ, the embedded and dense combinations are b̂ᵀκ and b(θ)ᵀκ, and the nodes
/// and γ are the tableau's. Measured agreement 1.6e-14 (α has cancellations of terms near 10); bound 1e-13.
#[test]
fn the_increment_form_is_the_rate_form() {
    let tableau = Esdirk43Method::TABLEAU;
    let a = f64_tableau();
    assert!(tableau.explicit_first);
    assert_eq!(tableau.gamma, 0.25);
    let nodes = [0.0, 0.5, 0.332, 0.62, 0.85, 1.0];
    for (c, expected) in tableau.c.iter().zip(nodes) {
        assert!((c - expected).abs() < 1e-15, "{c}");
    }
    let kappa = [0.7, -1.3, 2.1, 0.4, -0.9, 1.6];
    let z: Vec<f64> = a
        .iter()
        .map(|row| row.iter().zip(&kappa).map(|(a, k)| a * k).sum())
        .collect();
    let mut w = z.clone();
    w[0] = kappa[0];
    let on_w =
        |coefficients: &[f64; 6]| -> f64 { coefficients.iter().zip(&w).map(|(c, w)| c * w).sum() };
    let on_kappa =
        |weights: &[f64]| -> f64 { weights.iter().zip(&kappa).map(|(b, k)| b * k).sum() };
    let mut worst: f64 = 0.0;
    for i in 1..6 {
        worst = worst.max((on_w(&tableau.alpha[i]) - on_kappa(&a[i][..i])).abs());
        assert!(tableau.alpha[i][i..].iter().all(|x| *x == 0.0));
    }
    let embedded: Vec<f64> = EMBEDDED.iter().map(|&(p, q)| p as f64 / q as f64).collect();
    worst = worst.max((on_w(&tableau.embedded) - on_kappa(&embedded)).abs());
    for theta in [0.3, 1.0] {
        let [d1, d2, d3, d4] = &tableau.dense;
        let dense = theta * (on_w(d1) + theta * (on_w(d2) + theta * (on_w(d3) + theta * on_w(d4))));
        worst = worst.max((dense - on_kappa(&dense_weights(theta))).abs());
    }
    eprintln!("worst disagreement {worst:e}");
    assert!(worst < 1e-13, "{worst:e}");
}

/// The Newton start of stages 3–6 is exact on increments Z(θ) = θw + aθ² + bθ³ (stage 3
/// on quadratics), θ in steps and W₁ = Z′(0) = w. Measured 4e-16; bound 1e-13.
#[test]
fn the_newton_starts_extrapolate_cubics() {
    let tableau = Esdirk43Method::TABLEAU;
    let c = tableau.c;
    for (w, a, b) in [(1.0, 0.0, 0.0), (0.3, -2.0, 0.0), (-0.5, 1.5, 3.0)] {
        let increment = |theta: f64| w * theta + a * theta * theta + b * theta.powi(3);
        let mut stages: Vec<f64> = c.iter().map(|&theta| increment(theta)).collect();
        stages[0] = w;
        for (i, &node) in c.iter().enumerate().skip(2) {
            if i == 2 && b != 0.0 {
                continue;
            }
            let start: f64 = (0..i).map(|j| tableau.start[i][j] * stages[j]).sum();
            let error = (start - increment(node)).abs();
            assert!(error < 1e-13, "stage {}: {error:e}", i + 1);
        }
    }
    assert_eq!(tableau.start[1][0], 0.5);
}
