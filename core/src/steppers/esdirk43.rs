//! ESDIRK4(3)6L\[2\]SA: Kennedy & Carpenter's L-stable, stiffly accurate explicit-first-stage
//! singly diagonally implicit Runge–Kutta pair of orders 4 and 3 (the implicit half of
//! ARK4(3)6L\[2\]SA; SUNDIALS' `ARK436L2SA_DIRK_6_3_4`, OrdinaryDiffEq's `KenCarp4`), with
//! its published third-order dense output. Coefficients and sources:
//! `esdirk43/coefficients.rs`.
//!
//! Six stages, γ = 1/4. Stage 1 is explicit and costs nothing after the first step: its
//! rate is the last stage's rate of the step before (the method is stiffly accurate, so
//! that stage is y₁). Stage 2 starts its Newton iteration from the last step's dense
//! output; each later stage from the polynomial Z(θ) = θ W₁ + aθ² + bθ³ (θ in steps, so
//! Z′(0) = h f(y₀) = W₁) through the two stages before it (stage 3: the quadratic through
//! stage 2). Newton, the Jacobian reuse, the error estimate filtered through
//! (I − hγJ)⁻¹ and the step-size control are those of SDIRK4: both are the one stepper
//! [`Dirk`].
//!
//! Its embedded third-order solution is accurate by design, so the error estimate is less
//! conservative than SDIRK4's: at the same tolerance it takes longer steps and ends with a
//! larger error (Kepler orbit at 1e-9: 75× the tolerance against SDIRK4's 2.7×; stiff
//! pendulum: about 120×, proportional to the tolerance). Ask for about two orders below
//! the error you need.

mod coefficients;

use self::coefficients::{a, dense_weights, row, value, EMBEDDED};
use super::dirk::{explicit_parts, on_increments, rate_transform};
use super::dirk::{Dirk, DirkMethod, DirkTableau};

/// The ESDIRK4(3)6L\[2\]SA stepper on the state `[q, p, m_s]`: [`Dirk`] with the tableau
/// of [`Esdirk43Method`]. Use [`super::AdaptiveControl::sdirk4`] for its step-size
/// control.
pub type Esdirk43<'a, Sys, const N: usize, const S: usize> = Dirk<'a, Sys, Esdirk43Method, N, S, 6>;

/// The tableau of [`Esdirk43`].
#[derive(Clone, Copy, Debug)]
pub struct Esdirk43Method;

/// The nodes cᵢ (the row sums of A).
const fn nodes(a: &[[f64; 6]; 6]) -> [f64; 6] {
    let mut c = [0.0; 6];
    let mut i = 0;
    while i < 6 {
        let mut j = 0;
        while j < 6 {
            c[i] += a[i][j];
            j += 1;
        }
        i += 1;
    }
    c
}

/// The Newton start of each implicit stage after the second, on the W: the value at cᵢ
/// of Z(θ) = θW₁ + aθ² + bθ³ through the stages p = i − 2 and q = i − 1 (stage 3: the
/// quadratic, b = 0, through stage 2). Stage 2 has the Euler start c₂W₁ (used only
/// when there is no previous step to extrapolate).
const fn starts(c: &[f64; 6]) -> [[f64; 6]; 6] {
    let mut start = [[0.0; 6]; 6];
    start[1][0] = c[1];
    let (q, t) = (c[1], c[2]);
    start[2][1] = t * t / (q * q);
    start[2][0] = t - t * t / q;
    let mut i = 3;
    while i < 6 {
        let (p, q, t) = (c[i - 2], c[i - 1], c[i]);
        let det = p * p * q * q * (q - p);
        // a = (Rₚ q³ − R_q p³)/det, b = (p² R_q − q² Rₚ)/det with Rⱼ = Zⱼ − cⱼW₁.
        let on_p = (q * q * q * t * t - q * q * t * t * t) / det;
        let on_q = (p * p * t * t * t - p * p * p * t * t) / det;
        start[i][i - 2] = on_p;
        start[i][i - 1] = on_q;
        start[i][0] = t - p * on_p - q * on_q;
        i += 1;
    }
    start
}

/// The coefficients of the dense output on the W (θ⁴ has none: the output is cubic).
const fn dense(t: &[[f64; 6]; 6]) -> [[f64; 6]; 4] {
    [
        on_increments(&dense_weights(0), t),
        on_increments(&dense_weights(1), t),
        on_increments(&dense_weights(2), t),
        [0.0; 6],
    ]
}

impl DirkMethod<6> for Esdirk43Method {
    const TABLEAU: DirkTableau<6> = {
        let a = a();
        let t = rate_transform(&a);
        let c = nodes(&a);
        DirkTableau {
            gamma: value(coefficients::A[1][1]),
            c,
            explicit_first: true,
            alpha: explicit_parts(&a, &t),
            start: starts(&c),
            embedded: on_increments(&row(&EMBEDDED), &t),
            dense: dense(&t),
        }
    };
}

#[cfg(test)]
mod tests;
