//! The coefficients a diagonally implicit stepper ([`super::Dirk`]) runs on, in the stage
//! increment form of Hairer's `sdirk4.f`, extended to an explicit first stage.
//!
//! The stepper stores one vector Wⱼ per stage: the increment Zⱼ = Yⱼ − y₀ of an implicit
//! stage, and for an explicit first stage (ESDIRK, a₁₁ = 0, so Z₁ = 0) the scaled rate
//! W₁ = h f(t₀, y₀) instead. Stage i then solves
//! Zᵢ = Gᵢ + hγ f(t₀ + cᵢh, y₀ + Zᵢ) with Gᵢ = Σ_{j<i} αᵢⱼ Wⱼ, which is h Σ_{j<i} aᵢⱼ f(Yⱼ)
//! written on the W: with κⱼ = h f(Yⱼ) = Σₗ Tⱼₗ Wₗ (T from the tableau by forward
//! substitution, [`rate_transform`]), α = A·T strictly below the diagonal. Every weight
//! vector v on the κ (the embedded b̂, the dense-output b*(θ)) becomes vᵀT on the W.

/// The coefficients of one diagonally implicit, stiffly accurate method of order 4 with
/// an embedded order-3 solution and M stages; see the module documentation for the
/// stage increment form they are written in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirkTableau<const M: usize> {
    /// γ, the diagonal of the implicit stages.
    pub(crate) gamma: f64,
    /// The nodes cᵢ.
    pub(crate) c: [f64; M],
    /// Whether stage 1 is explicit (a₁₁ = 0): W₁ is then h f(t₀, y₀).
    pub(crate) explicit_first: bool,
    /// αᵢⱼ (j < i): the explicit part of stage i on the W.
    pub(crate) alpha: [[f64; M]; M],
    /// The Newton start of stage i (j < i) on the W; the first implicit stage starts from
    /// the last step's dense output instead when there is one.
    pub(crate) start: [[f64; M]; M],
    /// The embedded solution ŷ₁ = y₀ + Σⱼ eⱼ Wⱼ (while y₁ = y₀ + Z_M).
    pub(crate) embedded: [f64; M],
    /// The dense output y(t₀ + θh) = y₀ + Σₖ θᵏ⁺¹ Σⱼ dₖⱼ Wⱼ.
    pub(crate) dense: [[f64; M]; 4],
}

/// A method the generic stepper [`super::Dirk`] runs: a marker type carrying its tableau.
pub trait DirkMethod<const M: usize>: Clone + Copy + core::fmt::Debug {
    /// The coefficients.
    const TABLEAU: DirkTableau<M>;
}

/// T with κ = T W (κⱼ = h f(Yⱼ)) for the lower-triangular `a`: stage by stage,
/// κⱼ = (Wⱼ − Σ_{l<j} aⱼₗ κₗ)/aⱼⱼ, and κ₁ = W₁ when the first stage is explicit.
pub(crate) const fn rate_transform<const M: usize>(a: &[[f64; M]; M]) -> [[f64; M]; M] {
    let mut t = [[0.0; M]; M];
    let mut j = 0;
    while j < M {
        if a[j][j] == 0.0 {
            // Only an explicit first stage has a zero diagonal: W₁ is its rate.
            t[j][j] = 1.0;
        } else {
            let mut column = 0;
            while column <= j {
                let mut value = if column == j { 1.0 } else { 0.0 };
                let mut l = 0;
                while l < j {
                    value -= a[j][l] * t[l][column];
                    l += 1;
                }
                t[j][column] = value / a[j][j];
                column += 1;
            }
        }
        j += 1;
    }
    t
}

/// vᵀT: weights on the κ turned into weights on the W.
pub(crate) const fn on_increments<const M: usize>(v: &[f64; M], t: &[[f64; M]; M]) -> [f64; M] {
    let mut w = [0.0; M];
    let mut l = 0;
    while l < M {
        let mut j = 0;
        while j < M {
            w[l] += v[j] * t[j][l];
            j += 1;
        }
        l += 1;
    }
    w
}

/// α = A·T strictly below the diagonal: the explicit part of each stage on the W.
pub(crate) const fn explicit_parts<const M: usize>(
    a: &[[f64; M]; M],
    t: &[[f64; M]; M],
) -> [[f64; M]; M] {
    let mut alpha = [[0.0; M]; M];
    let mut i = 0;
    while i < M {
        let mut below = [0.0; M];
        let mut j = 0;
        while j < i {
            below[j] = a[i][j];
            j += 1;
        }
        let row = on_increments(&below, t);
        let mut l = 0;
        while l < i {
            alpha[i][l] = row[l];
            l += 1;
        }
        i += 1;
    }
    alpha
}
