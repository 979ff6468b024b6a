//! Test support: the order conditions of a Runge–Kutta tableau from Butcher's rooted trees
//! (HNW I, II.2, Theorem 2.13). A method (A, b) has order p when Σᵢ bᵢ Φᵢ(t) = 1/γ(t) for
//! every rooted tree t with at most p vertices, where Φᵢ(t) = Πₖ (A Φ(tₖ))ᵢ over the
//! subtrees tₖ hanging from the root and γ(t) = |t| Πₖ γ(tₖ). A continuous extension b(θ)
//! has order p when Σᵢ bᵢ(θ) Φᵢ(t) = θ^|t|/γ(t) (HNW I, II.6).
//!
//! The arithmetic is generic: exact rationals for rational tableaus, f64 for the others.

use core::ops::{Add, Div, Mul, Sub};

use num_rational::BigRational;

/// A field to evaluate the conditions in.
pub(crate) trait Scalar:
    Clone + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// The integer `n`.
    fn integer(n: i64) -> Self;
}

impl Scalar for f64 {
    fn integer(n: i64) -> Self {
        n as f64
    }
}

impl Scalar for BigRational {
    fn integer(n: i64) -> Self {
        BigRational::from_integer(n.into())
    }
}

/// The rational p/q.
pub(crate) fn ratio(p: i64, q: i64) -> BigRational {
    BigRational::new(p.into(), q.into())
}

/// A rooted tree: its number of vertices, its density γ and the indices (into the list
/// built by [`trees`]) of the subtrees hanging from its root, non-decreasing.
#[derive(Clone, Debug)]
pub(crate) struct Tree {
    pub(crate) order: usize,
    pub(crate) density: i64,
    children: Vec<usize>,
}

/// Every rooted tree with at most `max_order` vertices, each once, by increasing order.
pub(crate) fn trees(max_order: usize) -> Vec<Tree> {
    let mut all = vec![Tree {
        order: 1,
        density: 1,
        children: Vec::new(),
    }];
    for order in 2..=max_order {
        let count = all.len();
        let mut forests = Vec::new();
        forests_of(&all[..count], order - 1, 0, &mut Vec::new(), &mut forests);
        for children in forests {
            let density = children
                .iter()
                .map(|&child| all[child].density)
                .product::<i64>()
                * order as i64;
            all.push(Tree {
                order,
                density,
                children,
            });
        }
    }
    all
}

/// Pushes onto `out` every non-decreasing list of indices ≥ `from` of `trees` whose orders
/// sum to `remaining`, after `prefix`.
fn forests_of(
    trees: &[Tree],
    remaining: usize,
    from: usize,
    prefix: &mut Vec<usize>,
    out: &mut Vec<Vec<usize>>,
) {
    if remaining == 0 {
        out.push(prefix.clone());
        return;
    }
    for index in from..trees.len() {
        if trees[index].order <= remaining {
            prefix.push(index);
            forests_of(trees, remaining - trees[index].order, index, prefix, out);
            prefix.pop();
        }
    }
}

/// Φ(t) for every tree of `trees`: one vector over the stages of the tableau `a`.
pub(crate) fn stage_weights<T: Scalar>(a: &[Vec<T>], trees: &[Tree]) -> Vec<Vec<T>> {
    let stages = a.len();
    let mut weights: Vec<Vec<T>> = Vec::with_capacity(trees.len());
    for tree in trees {
        let mut phi = vec![T::integer(1); stages];
        for &child in &tree.children {
            for (i, value) in phi.iter_mut().enumerate() {
                let mut inner = T::integer(0);
                for (j, a_ij) in a[i].iter().enumerate() {
                    inner = inner + a_ij.clone() * weights[child][j].clone();
                }
                *value = value.clone() * inner;
            }
        }
        weights.push(phi);
    }
    weights
}

/// For each tree, Σᵢ bᵢ Φᵢ(t) − θ^|t|/γ(t): zero for every tree up to the order of the
/// weights `b` (θ = 1 for the weights of a step).
pub(crate) fn defects<T: Scalar>(b: &[T], weights: &[Vec<T>], trees: &[Tree], theta: T) -> Vec<T> {
    trees
        .iter()
        .zip(weights)
        .map(|(tree, phi)| {
            let sum = b
                .iter()
                .zip(phi)
                .fold(T::integer(0), |sum, (b, phi)| sum + b.clone() * phi.clone());
            let power = (0..tree.order).fold(T::integer(1), |p, _| p * theta.clone());
            sum - power / T::integer(tree.density)
        })
        .collect()
}

/// The largest |R(iy)| of a stiffly accurate diagonally implicit tableau `a` (f64) over
/// y = 10⁻³…10⁴, 4001 points log-spaced: at most 1 for an A-stable method. R(z) is the last
/// stage value of y′ = λy, z = iy, each stage from (1 − iy aᵢᵢ) Yᵢ = 1 + iy Σ_{j<i} aᵢⱼ Yⱼ
/// in complex arithmetic (an explicit first stage, a₁₁ = 0, gives Y₁ = 1).
pub(crate) fn worst_imaginary_axis_modulus(a: &[Vec<f64>]) -> f64 {
    let modulus = |y: f64| {
        let mut stages = vec![(0.0, 0.0); a.len()];
        for i in 0..a.len() {
            let (mut re, mut im) = (1.0, 0.0);
            for j in 0..i {
                re -= y * a[i][j] * stages[j].1;
                im += y * a[i][j] * stages[j].0;
            }
            let (dr, di) = (1.0, -y * a[i][i]);
            let norm = dr * dr + di * di;
            stages[i] = ((re * dr + im * di) / norm, (im * dr - re * di) / norm);
        }
        let (re, im) = stages[a.len() - 1];
        (re * re + im * im).sqrt()
    };
    (0..=4000)
        .map(|k| modulus(10f64.powf(-3.0 + 7.0 * f64::from(k) / 4000.0)))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The numbers of rooted trees with 1…8 vertices (OEIS A000081) and the densities of
    /// the four trees of order 4 (HNW I, Table II.2.2: 4, 8, 12, 24).
    #[test]
    fn the_tree_count_and_densities_are_butchers() {
        let all = trees(8);
        let counts: Vec<usize> = (1..=8)
            .map(|n| all.iter().filter(|t| t.order == n).count())
            .collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48, 115]);
        let mut order_four: Vec<i64> = all
            .iter()
            .filter(|t| t.order == 4)
            .map(|t| t.density)
            .collect();
        order_four.sort_unstable();
        assert_eq!(order_four, [4, 8, 12, 24]);
    }

    /// The classical RK4 has order 4 exactly: every defect to order 4 is zero, and some
    /// of order 5 is not.
    #[test]
    fn classical_rk4_has_order_four_and_not_five() {
        let zero = || ratio(0, 1);
        let half = || ratio(1, 2);
        let a = vec![
            vec![zero(), zero(), zero(), zero()],
            vec![half(), zero(), zero(), zero()],
            vec![zero(), half(), zero(), zero()],
            vec![zero(), zero(), ratio(1, 1), zero()],
        ];
        let b = [ratio(1, 6), ratio(1, 3), ratio(1, 3), ratio(1, 6)];
        let all = trees(5);
        let defects = defects(&b, &stage_weights(&a, &all), &all, ratio(1, 1));
        for (tree, defect) in all.iter().zip(&defects) {
            if tree.order <= 4 {
                assert_eq!(*defect, zero(), "{tree:?}");
            }
        }
        assert!(defects.iter().any(|d| *d != zero()));
    }
}
