//! The coefficients of ESDIRK4(3)6L\[2\]SA, the implicit half of Kennedy & Carpenter's
//! ARK4(3)6L\[2\]SA (Appl. Numer. Math. 44 (2003) 139–181, with its dense-output
//! coefficients b*ᵢⱼ): six stages, the first explicit, γ = 1/4,
//! c = (0, 1/2, 83/250, 31/50, 17/20, 1), order 4, stiffly accurate and L-stable, stage
//! order 2, an embedded third-order solution and a third-order dense output.
//!
//! The rationals are those of SUNDIALS ARKODE's `ARKODE_ARK436L2SA_DIRK_6_3_4`
//! (<https://github.com/LLNL/sundials/blob/86245688d1547b5fc600d592d8167e201e88f3cb/src/arkode/arkode_butcher_dirk.def>,
//! loaded by `arkode_butcher_dirk.c`)
//! and OrdinaryDiffEq's `KenCarp4Tableau`; the dense-output coefficients, which ARKODE does
//! not carry, are PETSc's `binterpt` of `TSARKIMEX4`
//! (<https://github.com/petsc/petsc/blob/9ace16cde02cabf8d09861e743518d008f430653/src/ts/impls/arkimex/arkimex.c>),
//! Kennedy & Carpenter's b*ᵢⱼ: bᵢ(θ) = Σⱼ b*ᵢⱼ θʲ. Unlike A, b and b̂ they are rational
//! approximations of real numbers (Σⱼ b*ᵢⱼ = bᵢ to 2e-26).
//!
//! Everything is kept as published, as (numerator, denominator) pairs; the stage
//! increment form the stepper runs on ([`super::super::dirk::DirkTableau`]) is computed
//! from them at compile time.

/// A rational p/q as written in the sources above.
pub(crate) type Ratio = (i64, i64);

/// A of the method, row by row (the first row is zero: stage 1 is explicit).
pub(crate) const A: [[Ratio; 6]; 6] = [
    [(0, 1), (0, 1), (0, 1), (0, 1), (0, 1), (0, 1)],
    [(1, 4), (1, 4), (0, 1), (0, 1), (0, 1), (0, 1)],
    [
        (8611, 62500),
        (-1743, 31250),
        (1, 4),
        (0, 1),
        (0, 1),
        (0, 1),
    ],
    [
        (5012029, 34652500),
        (-654441, 2922500),
        (174375, 388108),
        (1, 4),
        (0, 1),
        (0, 1),
    ],
    [
        (15267082809, 155376265600),
        (-71443401, 120774400),
        (730878875, 902184768),
        (2285395, 8070912),
        (1, 4),
        (0, 1),
    ],
    [
        (82889, 524892),
        (0, 1),
        (15625, 83664),
        (69875, 102672),
        (-2260, 8211),
        (1, 4),
    ],
];

/// b̂, the embedded third-order weights (b is the last row of A).
pub(crate) const EMBEDDED: [Ratio; 6] = [
    (4586570599, 29645900160),
    (0, 1),
    (178811875, 945068544),
    (814220225, 1159782912),
    (-3700637, 11593932),
    (61727, 225920),
];

/// b*ᵢⱼ, j = 1…3: the dense-output weights bᵢ(θ) = Σⱼ b*ᵢⱼ θʲ.
pub(crate) const DENSE: [[Ratio; 3]; 6] = [
    [
        (6943876665148, 7220017795957),
        (-54480133, 30881146),
        (6818779379841, 7100303317025),
    ],
    [(0, 1), (0, 1), (0, 1)],
    [
        (7640104374378, 9702883013639),
        (-11436875, 14766696),
        (2173542590792, 12501825683035),
    ],
    [
        (-20649996744609, 7521556579894),
        (174696575, 18121608),
        (-31592104683404, 5083833661969),
    ],
    [
        (8854892464581, 2390941311638),
        (-12120380, 966161),
        (61146701046299, 7138195549469),
    ],
    [
        (-11397109935349, 6675773540249),
        (3843, 706),
        (-17219254887155, 4939391667607),
    ],
];

/// p/q in f64 (p and q are exact in f64: below 2⁵³).
pub(crate) const fn value((p, q): Ratio) -> f64 {
    p as f64 / q as f64
}

/// A in f64.
pub(crate) const fn a() -> [[f64; 6]; 6] {
    let mut a = [[0.0; 6]; 6];
    let mut i = 0;
    while i < 6 {
        let mut j = 0;
        while j < 6 {
            a[i][j] = value(A[i][j]);
            j += 1;
        }
        i += 1;
    }
    a
}

/// A row of rationals in f64.
pub(crate) const fn row(r: &[Ratio; 6]) -> [f64; 6] {
    let mut v = [0.0; 6];
    let mut i = 0;
    while i < 6 {
        v[i] = value(r[i]);
        i += 1;
    }
    v
}

/// The weights of θ^(k+1) in the dense output, k = 0…2, on the stage rates.
pub(crate) const fn dense_weights(k: usize) -> [f64; 6] {
    let mut v = [0.0; 6];
    let mut i = 0;
    while i < 6 {
        v[i] = value(DENSE[i][k]);
        i += 1;
    }
    v
}
