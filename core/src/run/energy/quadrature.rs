//! Adaptive Gauss–Kronrod quadrature of a function smooth over an interval: the power over
//! one step of a run, read along the step's interpolant.
//!
//! The 15-point Kronrod rule holds the 7-point Gauss rule's nodes, so one set of 15 values
//! gives both; |K15 − G7| bounds the error of G7 and, generously, of K15 (QUADPACK's
//! `qk15`, Piessens, de Doncker-Kapenga, Überhuber & Kahaner, *QUADPACK*, Springer 1983,
//! §2.2). K15 integrates polynomials of degree 22 exactly, so on the polynomial pieces of a
//! dense output it is near exact; where the estimate is too large the interval is halved,
//! a bounded number of times. Gauss–Legendre at a fixed order would need no estimate but
//! could not tell when Taylor's long steps outgrow it; Simpson's rule (the former one) is
//! exact to degree 3 only.

/// The nodes of the 15-point Kronrod rule on [−1, 1], ≥ 0 (the rule is symmetric), from
/// QUADPACK's `qk15`; entries 1, 3 and 5 (and 7, the centre) are the 7-point Gauss nodes.
const NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];

/// The weights of the 15-point Kronrod rule at [`NODES`].
const KRONROD: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];

/// The weights of the 7-point Gauss rule at [`NODES`] 1, 3, 5 and 7.
const GAUSS: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// The accuracy asked of the integral over a step, relative to ∫|f| there: near rounding,
/// so that the quadrature adds nothing the state's own error would not hide.
const TOLERANCE: f64 = 1e-14;

/// How many times an interval may be halved: 2¹⁰ pieces at most, reached only where f is
/// not smooth (which a run's steps never straddle); the estimate then stands.
const MAX_DEPTH: u32 = 10;

/// ∫ f from `a` to `b` by adaptive Gauss–Kronrod quadrature; NaN where f is NaN.
pub(super) fn integral(mut f: impl FnMut(f64) -> f64, a: f64, b: f64) -> f64 {
    if a == b {
        return 0.0;
    }
    let whole = kronrod(&mut f, a, b);
    let tolerance = TOLERANCE * whole.magnitude;
    refine(&mut f, (a, b), whole, tolerance / (b - a).abs(), 0)
}

/// K15 over an interval, with its error estimate |K15 − G7| and K15 of |f|.
#[derive(Clone, Copy, Debug)]
struct Estimate {
    value: f64,
    error: f64,
    magnitude: f64,
}

/// `estimate` over `(a, b)` if its error is within `density` times the width (the
/// tolerance shared out by width), else the sum over its halves, each refined in turn.
fn refine(
    f: &mut impl FnMut(f64) -> f64,
    (a, b): (f64, f64),
    estimate: Estimate,
    density: f64,
    depth: u32,
) -> f64 {
    // Not `error <= …`: a NaN estimate stands (halving would not help), and the caller
    // reports it.
    let within = estimate.error <= density * (b - a).abs() || estimate.error.is_nan();
    if within || depth >= MAX_DEPTH {
        return estimate.value;
    }
    let middle = 0.5 * (a + b);
    let left = kronrod(f, a, middle);
    let right = kronrod(f, middle, b);
    refine(f, (a, middle), left, density, depth + 1)
        + refine(f, (middle, b), right, density, depth + 1)
}

/// The 15-point Kronrod and 7-point Gauss sums over `(a, b)`.
fn kronrod(f: &mut impl FnMut(f64) -> f64, a: f64, b: f64) -> Estimate {
    let (centre, half) = (0.5 * (a + b), 0.5 * (b - a));
    let (mut kronrod, mut gauss, mut magnitude) = (0.0, 0.0, 0.0);
    for (k, (&node, &weight)) in NODES.iter().zip(&KRONROD).enumerate() {
        let values = if node == 0.0 {
            let value = f(centre);
            [value, 0.0]
        } else {
            [f(centre - half * node), f(centre + half * node)]
        };
        let sum = values[0] + values[1];
        kronrod += weight * sum;
        magnitude += weight * (values[0].abs() + values[1].abs());
        if k % 2 == 1 {
            gauss += GAUSS[k / 2] * sum;
        }
    }
    Estimate {
        value: kronrod * half,
        error: ((kronrod - gauss) * half).abs(),
        magnitude: magnitude * half.abs(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rules_integrate_their_polynomials_exactly() {
        // K15 is exact to degree 22 and G7 to degree 13: ∫₋₁¹ x^k dx = 2/(k+1) for even k.
        for k in (0..=22).step_by(2) {
            let exact = 2.0 / f64::from(k + 1);
            let estimate = kronrod(&mut |x: f64| x.powi(k), -1.0, 1.0);
            assert!((estimate.value - exact).abs() < 1e-15, "K15, x^{k}");
            if k <= 12 {
                assert!(estimate.error < 1e-15, "G7, x^{k}: {}", estimate.error);
            }
        }
    }

    #[test]
    fn a_long_interval_is_refined_to_rounding() {
        // ∫₀²⁰ e^(sin t) cos t dt = e^(sin 20) − 1: too wiggly for one K15 over 20 (about
        // three periods), so the estimate asks for halvings.
        let exact = 20f64.sin().exp() - 1.0;
        let mut calls = 0;
        let value = integral(
            |t: f64| {
                calls += 1;
                t.sin().exp() * t.cos()
            },
            0.0,
            20.0,
        );
        assert!((value - exact).abs() < 1e-14, "{:e}", value - exact);
        assert!(calls > 15, "{calls}");
    }
}
