//! The closed-form inverse the derivation stops using past `SYMBOLIC_INVERSE_MAX_DOF`
//! coordinates, for three, so the threshold can be measured from both sides.

// `varmass_symbolic` by its own name: build.rs includes this file too.
use varmass_symbolic::expr::{ExprPool, Id};
use varmass_symbolic::mechanics::Derivation;

/// q̇ = adj(M)(p − b)/det M for a 3 × 3 mass matrix.
pub fn closed_velocities(d: &mut Derivation) -> Vec<Id> {
    let m = d.mass_matrix.clone();
    assert_eq!(m.len(), 3, "the closed variant is for three links");
    let pool = &mut d.pool;
    let cofactor = |pool: &mut ExprPool, row: usize, column: usize| -> Id {
        let rows: Vec<usize> = (0..3).filter(|r| *r != row).collect();
        let columns: Vec<usize> = (0..3).filter(|c| *c != column).collect();
        let ad = pool.mul(&[m[rows[0]][columns[0]], m[rows[1]][columns[1]]]);
        let bc = pool.mul(&[m[rows[0]][columns[1]], m[rows[1]][columns[0]]]);
        let minor = pool.sub(ad, bc);
        if (row + column).is_multiple_of(2) {
            minor
        } else {
            pool.neg(minor)
        }
    };
    let first_row: Vec<Id> = (0..3)
        .map(|j| {
            let c = cofactor(pool, 0, j);
            pool.mul(&[m[0][j], c])
        })
        .collect();
    let determinant = pool.add(&first_row);
    let minus_one = pool.int(-1);
    let inverse_determinant = pool.pow(determinant, minus_one);
    let excess: Vec<Id> = (0..3)
        .map(|a| {
            let momentum = pool.sym(d.coordinates[a].momentum);
            pool.sub(momentum, d.momentum_offset[a])
        })
        .collect();
    (0..3)
        .map(|i| {
            // adj(M)[i][j] = cofactor(M)[j][i]
            let terms: Vec<Id> = (0..3)
                .map(|j| {
                    let c = cofactor(pool, j, i);
                    pool.mul(&[c, excess[j]])
                })
                .collect();
            let sum = pool.add(&terms);
            pool.mul(&[sum, inverse_determinant])
        })
        .collect()
}
