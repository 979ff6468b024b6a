//! SDIRK4: Hairer & Wanner's L-stable singly diagonally implicit Runge–Kutta method of
//! order 4 with an embedded third-order solution (HNW II, IV.6, Table 6.5, γ = 1/4; the
//! coefficients and the step logic follow `sdirk4.f`, see `sdirk4/coefficients.rs`).
//!
//! All five stages are implicit; the first starts its Newton iteration from the last
//! step's dense output, the later ones from `sdirk4.f`'s extrapolations of the earlier
//! stages, the last from the embedded solution. The dense output is the
//! cubic-in-increments polynomial of `sdirk4.f` (order 3). The stepper itself is the one
//! diagonally implicit stepper [`Dirk`] (see `dirk.rs` for Newton, the Jacobian reuse, the
//! filtered error estimate and the step-size control).

mod coefficients;

use self::coefficients::*;
use super::dirk::{Dirk, DirkMethod, DirkNewton, DirkTableau};

/// The Newton settings of [`Sdirk4`] (defaults of `sdirk4.f`).
pub type Sdirk4Newton = DirkNewton;

/// The SDIRK4 stepper on the state `[q, p, m_s]`: [`Dirk`] with the tableau of
/// [`Sdirk4Method`].
pub type Sdirk4<'a, Sys, const N: usize, const S: usize> = Dirk<'a, Sys, Sdirk4Method, N, S, 5>;

/// The tableau of [`Sdirk4`].
#[derive(Clone, Copy, Debug)]
pub struct Sdirk4Method;

impl DirkMethod<5> for Sdirk4Method {
    const TABLEAU: DirkTableau<5> = DirkTableau {
        gamma: GAMMA,
        c: [GAMMA, C2, C3, C4, 1.0],
        explicit_first: false,
        alpha: [
            [0.0; 5],
            [ALPH21, 0.0, 0.0, 0.0, 0.0],
            [ALPH31, ALPH32, 0.0, 0.0, 0.0],
            [ALPH41, ALPH42, ALPH43, 0.0, 0.0],
            [ALPH51, ALPH52, ALPH53, ALPH54, 0.0],
        ],
        // Z₂ ≈ η₁Z₁, Z₃ ≈ ν₁Z₁ + ν₂Z₂, Z₄ ≈ μ₁Z₁ + μ₃Z₃, Z₅ ≈ the embedded solution.
        start: [
            [0.0; 5],
            [ETA1, 0.0, 0.0, 0.0, 0.0],
            [ANU1, ANU2, 0.0, 0.0, 0.0],
            [AMU1, 0.0, AMU3, 0.0, 0.0],
            [E1, E2, E3, E4, 0.0],
        ],
        embedded: [E1, E2, E3, E4, 0.0],
        dense: [
            [D11, D12, D13, D14, D15],
            [D21, D22, D23, D24, D25],
            [D31, D32, D33, D34, D35],
            [D41, D42, D43, D44, D45],
        ],
    };
}
