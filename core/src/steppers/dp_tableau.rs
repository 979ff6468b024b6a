//! The Dormand–Prince 5(4) tableau (Dormand & Prince 1980; Hairer, Nørsett & Wanner,
//! *Solving ODEs I*, table 5.2) with the dense-output coefficients of `dopri5.f`: one copy
//! for the scalar stepper (`dormand_prince.rs`) and the one over lanes
//! (`core/src/lanes/dormand_prince.rs`), both taking their stages from the explicit core
//! (`explicit.rs`) with [`STAGE_ROWS`], [`WEIGHTS`] and [`ERROR_WEIGHTS`], so that their results
//! agree bit for bit.

use super::explicit::{Row, StageRows};

pub(crate) const C2: f64 = 1.0 / 5.0;
pub(crate) const C3: f64 = 3.0 / 10.0;
pub(crate) const C4: f64 = 4.0 / 5.0;
pub(crate) const C5: f64 = 8.0 / 9.0;
pub(crate) const A21: f64 = 1.0 / 5.0;
pub(crate) const A31: f64 = 3.0 / 40.0;
pub(crate) const A32: f64 = 9.0 / 40.0;
pub(crate) const A41: f64 = 44.0 / 45.0;
pub(crate) const A42: f64 = -56.0 / 15.0;
pub(crate) const A43: f64 = 32.0 / 9.0;
pub(crate) const A51: f64 = 19372.0 / 6561.0;
pub(crate) const A52: f64 = -25360.0 / 2187.0;
pub(crate) const A53: f64 = 64448.0 / 6561.0;
pub(crate) const A54: f64 = -212.0 / 729.0;
pub(crate) const A61: f64 = 9017.0 / 3168.0;
pub(crate) const A62: f64 = -355.0 / 33.0;
pub(crate) const A63: f64 = 46732.0 / 5247.0;
pub(crate) const A64: f64 = 49.0 / 176.0;
pub(crate) const A65: f64 = -5103.0 / 18656.0;
pub(crate) const B1: f64 = 35.0 / 384.0;
pub(crate) const B3: f64 = 500.0 / 1113.0;
pub(crate) const B4: f64 = 125.0 / 192.0;
pub(crate) const B5: f64 = -2187.0 / 6784.0;
pub(crate) const B6: f64 = 11.0 / 84.0;
// e = b − b̂.
pub(crate) const E1: f64 = 71.0 / 57600.0;
pub(crate) const E3: f64 = -71.0 / 16695.0;
pub(crate) const E4: f64 = 71.0 / 1920.0;
pub(crate) const E5: f64 = -17253.0 / 339200.0;
pub(crate) const E6: f64 = 22.0 / 525.0;
pub(crate) const E7: f64 = -1.0 / 40.0;
// Dense output (CONTD5).
pub(crate) const D1: f64 = -12715105075.0 / 11282082432.0;
pub(crate) const D3: f64 = 87487479700.0 / 32700410799.0;
pub(crate) const D4: f64 = -10690763975.0 / 1880347072.0;
pub(crate) const D5: f64 = 701980252875.0 / 199316789632.0;
pub(crate) const D6: f64 = -1453857185.0 / 822651844.0;
pub(crate) const D7: f64 = 69997945.0 / 29380423.0;

/// Stages 2–6 as the explicit core takes them: (cᵢ, row i of A). Stage 7 is at the new
/// state (FSAL: row 7 of A is b).
pub(crate) const STAGE_ROWS: &StageRows = &[
    (C2, &[(1, A21)]),
    (C3, &[(1, A31), (2, A32)]),
    (C4, &[(1, A41), (2, A42), (3, A43)]),
    (C5, &[(1, A51), (2, A52), (3, A53), (4, A54)]),
    (1.0, &[(1, A61), (2, A62), (3, A63), (4, A64), (5, A65)]),
];
/// b, the fifth-order weights (b₂ = b₇ = 0).
pub(crate) const WEIGHTS: Row = &[(1, B1), (3, B3), (4, B4), (5, B5), (6, B6)];
/// e = b − b̂, the error estimate's weights (e₂ = 0).
pub(crate) const ERROR_WEIGHTS: Row = &[(1, E1), (3, E3), (4, E4), (5, E5), (6, E6), (7, E7)];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::steppers::order_conditions::{defects, stage_weights, trees};

    /// The tableau as the core takes it has order 5 with b and order 4 with b̂ = b − e (and
    /// not 5: the pair's estimate measures the fifth-order terms), and its rows sum to their
    /// nodes (cᵢ = Σⱼ aᵢⱼ). In f64: the defects of the rational coefficients are rounding,
    /// measured below 3e-16; the margin is 1e-14, far below the smallest order-6 defect.
    #[test]
    fn the_dormand_prince_rows_have_order_five_and_four() {
        let mut a = vec![vec![0.0; 7]; 7];
        for (i, (c, row)) in STAGE_ROWS.iter().enumerate() {
            for &(j, value) in *row {
                a[i + 1][j - 1] = value;
            }
            let sum: f64 = row.iter().map(|(_, value)| value).sum();
            assert!((sum - c).abs() < 1e-14, "row {}: {sum} vs {c}", i + 2);
        }
        let mut b = [0.0; 7];
        for &(j, value) in WEIGHTS {
            a[6][j - 1] = value;
            b[j - 1] = value;
        }
        let mut embedded = b;
        for &(j, value) in ERROR_WEIGHTS {
            embedded[j - 1] -= value;
        }
        let all = trees(6);
        let weights = stage_weights(&a, &all);
        let order_of = |b: &[f64]| {
            let defects = defects(b, &weights, &all, 1.0);
            let worst = |order: usize| {
                all.iter()
                    .zip(&defects)
                    .filter(|(tree, _)| tree.order == order)
                    .map(|(_, d)| d.abs())
                    .fold(0.0, f64::max)
            };
            (1..=6).take_while(|&order| worst(order) < 1e-14).last()
        };
        assert_eq!(order_of(&b), Some(5));
        assert_eq!(order_of(&embedded), Some(4));
    }
}
