//! Inputs written in Rust (docs/inputs.md): the default partials of the generated
//! `…Inputs` trait, by central differences, and the sample grid of a sampled input.

use crate::error::SystemError;

/// The partials ∂f/∂xⱼ at `x` by central differences,
/// (f(x + hⱼeⱼ) − f(x − hⱼeⱼ)) / (2hⱼ), with hⱼ = ε^(1/3) · max(|xⱼ|, 1).
///
/// Why this step: the truncation error is hⱼ² |f'''|/6 and the rounding error about
/// ε |f| / hⱼ; they balance at hⱼ ∝ ε^(1/3), where both are about ε^(2/3) ≈ 4e-11 relative
/// (for a function scaled to its arguments: |f'''| xⱼ³ ~ |f|). The step is rounded to
/// one representable as (xⱼ + hⱼ) − xⱼ, so that the division uses the step actually taken.
/// These partials only feed the Jacobian of the implicit steppers (their Newton iterations),
/// never the equations, so this accuracy is ample; a trait may give exact ones instead.
pub fn central_partials<const K: usize>(f: impl Fn([f64; K]) -> f64, x: [f64; K]) -> [f64; K] {
    let mut partials = [0.0; K];
    for (j, partial) in partials.iter_mut().enumerate() {
        let h = f64::EPSILON.cbrt() * x[j].abs().max(1.0);
        let (mut up, mut down) = (x, x);
        up[j] = x[j] + h;
        down[j] = x[j] - h;
        let taken = up[j] - down[j];
        *partial = (f(up) - f(down)) / taken;
    }
    partials
}

/// The first sample time k·T of a sampled input of period `period` strictly after `after`
/// (docs/inputs.md#sampled-inputs): the grid starts at t = 0, the usual zero-order-hold
/// convention, so the samples are the same whatever time a run starts at. Each time is
/// computed as `k as f64 * period` (not by adding T to the last), so a run lands on the
/// same times as a loop over k, with no drift. Infinity for a period that is not positive
/// and finite. Where |t|/T reaches 2⁵³ the grid is finer than t's rounding (T is below an
/// ulp of t): every representable time holds a sample, so the next is the next
/// representable time (a run there takes a step per ulp of t and ends on its step limit
/// rather than holding one value for ever).
pub fn next_sample_time(period: f64, after: f64) -> f64 {
    if !(period.is_finite() && period > 0.0) || after.is_nan() {
        return f64::INFINITY;
    }
    let mut k = nalgebra::ComplexField::floor(after / period) + 1.0;
    if k.abs() >= FINER_THAN_T {
        return after.next_up();
    }
    // Rounding in the quotient may give the sample at (or before) `after` itself, or one
    // past the first after it (`after` = 0.35 just below fl(35 · 0.01) = 0.35000000000000003
    // has the quotient 35 exactly, so k = 36 would skip that sample). Below 2⁵³, k ± 1 is
    // exact, so each loop ends within a step or two.
    while (k - 1.0) * period > after {
        k -= 1.0;
    }
    while k * period <= after {
        k += 1.0;
    }
    let time = k * period;
    if time.is_finite() {
        time
    } else {
        f64::INFINITY
    }
}

/// Where k·T stops being a grid: at |k| ≥ 2⁵³, k ± 1 is no longer exact in f64, and T is
/// below an ulp of t = k·T.
const FINER_THAN_T: f64 = 9_007_199_254_740_992.0;

/// Whether `t` is a sample time of a sampled input of period `period`: t = k·T for some
/// integer k, computed as [`next_sample_time`] computes it (`k as f64 * period`, compared
/// exactly), so a run that lands on a sample time finds it on the grid — and, where the
/// grid is finer than t's rounding (|t|/T ≥ 2⁵³), every time. False for a period that is
/// not positive and finite, and for a time that is not finite.
pub fn is_sample_time(period: f64, t: f64) -> bool {
    if !(period.is_finite() && period > 0.0 && t.is_finite()) {
        return false;
    }
    // The nearest k, give or take the rounding of the quotient.
    let k = nalgebra::ComplexField::round(t / period);
    if k.abs() >= FINER_THAN_T {
        return true;
    }
    [k - 1.0, k, k + 1.0].iter().any(|k| k * period == t)
}

/// `value`, the sample of input `input`, if it is a finite number, else the typed
/// [`SystemError::SampledInputNotFinite`] naming the input (the run reports it at the
/// sample's time) instead of a held NaN that the next step would find.
pub fn checked_sample(input: &'static str, value: f64) -> Result<f64, SystemError> {
    match value.is_finite() {
        true => Ok(value),
        false => Err(SystemError::SampledInputNotFinite { input, value }),
    }
}

/// Which held inputs a sample replaces ([`crate::VariableMassSystem::sample`],
/// docs/inputs.md#sampled-inputs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sampling {
    /// Every one: a run's start ([`crate::RunConfig::sample_at_start`]), where the first
    /// held value is u(t₀, …) wherever t₀ falls.
    All,
    /// Those whose grid holds t ([`is_sample_time`]): a landing on a stop time (a sample
    /// time of this input or of another, a knot of a table of t, an output time), or a
    /// continuing start.
    Due,
    /// Those with a sample time in (`after`, t]: a restart past a switch that the crossing
    /// carried a few roundings beyond a sample time (the sample is then taken at the
    /// restart, the time the hook is given).
    Since(f64),
}

impl Sampling {
    /// Whether an input of period `period` is sampled at `t`.
    pub fn takes(self, period: f64, t: f64) -> bool {
        match self {
            Sampling::All => true,
            Sampling::Due => is_sample_time(period, t),
            Sampling::Since(after) => next_sample_time(period, after) <= t,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{central_partials, is_sample_time, next_sample_time, Sampling};

    /// f = sin(a) e^b + a b²: ∂f/∂a = cos(a) e^b + b², ∂f/∂b = sin(a) e^b + 2ab.
    /// Measured relative errors 6.6e-12 and 3.1e-12 at (0.7, 1.3); bound 1e-9 (the ε^(2/3)
    /// ≈ 4e-11 estimate times |f'''| ~ 4, with a margin of 6).
    #[test]
    fn central_partials_match_the_closed_form() {
        let f = |x: [f64; 2]| x[0].sin() * x[1].exp() + x[0] * x[1] * x[1];
        let (a, b) = (0.7_f64, 1.3_f64);
        let got = central_partials(f, [a, b]);
        let exact = [a.cos() * b.exp() + b * b, a.sin() * b.exp() + 2.0 * a * b];
        for (g, e) in got.iter().zip(exact) {
            assert!((g - e).abs() <= 1e-9 * e.abs(), "{g} vs {e}");
        }
    }

    #[test]
    fn the_next_sample_is_the_next_multiple_of_the_period() {
        assert_eq!(next_sample_time(0.01, 0.0), 0.01);
        // On a sample, the next one; the times are k·T as a loop over k computes them.
        for k in 0..2000 {
            let t = f64::from(k) * 0.01;
            assert_eq!(
                next_sample_time(0.01, t),
                f64::from(k + 1) * 0.01,
                "k = {k}"
            );
        }
        assert_eq!(next_sample_time(0.01, 0.005), 0.01);
        assert_eq!(next_sample_time(0.25, -0.3), -0.25);
        assert_eq!(next_sample_time(0.0, 1.0), f64::INFINITY);
        assert_eq!(next_sample_time(-1.0, 1.0), f64::INFINITY);
        assert_eq!(next_sample_time(0.01, f64::NAN), f64::INFINITY);
    }

    /// Just below a sample time, the next sample is that one: none of the grid is skipped
    /// when a run restarts a few roundings before a sample (after a switch, at a knot of a
    /// table of t at 0.35 while fl(35 · 0.01) = 0.35000000000000003). Before the fix, 93 834
    /// of the 1.4 million cases below were skipped (0.35 gave 0.36).
    #[test]
    fn just_below_a_sample_time_the_next_sample_is_that_one() {
        assert_eq!(next_sample_time(0.01, 0.35), 35.0 * 0.01);
        for period in [0.01, 0.03, 0.1, 0.001, 0.25, 1.0 / 3.0, 0.07] {
            for k in 1..200_000 {
                let t = f64::from(k) * period;
                let below = f64::from_bits(t.to_bits() - 1);
                assert_eq!(next_sample_time(period, below), t, "k = {k}, T = {period}");
            }
        }
    }

    /// The sample times are exactly the times next_sample_time gives, and nothing between.
    #[test]
    fn a_sample_time_is_one_of_the_grid() {
        for period in [0.01, 0.03, 1.0 / 3.0] {
            let mut t = 0.0;
            for _ in 0..3000 {
                let next = next_sample_time(period, t);
                assert!(is_sample_time(period, next), "{next} for T = {period}");
                let between = f64::from_bits(next.to_bits() - 1);
                assert!(
                    between <= t || !is_sample_time(period, between),
                    "{between}"
                );
                t = next;
            }
        }
        assert!(is_sample_time(0.01, 0.0));
        assert!(is_sample_time(0.25, -0.25));
        assert!(is_sample_time(0.01, 0.35000000000000003));
        assert!(!is_sample_time(0.01, 0.35));
        assert!(!is_sample_time(0.01, 0.015));
        assert!(!is_sample_time(0.03, 0.01));
        assert!(!is_sample_time(0.0, 0.0));
        assert!(!is_sample_time(0.01, f64::NAN));
        assert!(!is_sample_time(0.01, f64::INFINITY));
    }

    /// Past 2⁵³ periods (t = 10¹⁵ with T = 0.01: an ulp of t is 0.125) every representable
    /// time holds a sample: the next is the next representable time, on either side of 0,
    /// and each is a sample time. Before, the loops correcting k could not move it (k ± 1 = k
    /// there) and the call never returned.
    #[test]
    fn a_grid_finer_than_t_samples_at_every_representable_time() {
        for t in [1e15, -1e15, 1e17, 2f64.powi(53) * 0.01] {
            let next = next_sample_time(0.01, t);
            assert_eq!(next, t.next_up(), "{t}");
            assert!(is_sample_time(0.01, next), "{next}");
        }
        // Just below the limit the grid is still one: 2⁵³ − 2 periods of 1.
        let below = 2f64.powi(53) - 2.0;
        assert_eq!(next_sample_time(1.0, below), below + 1.0);
        assert!(!is_sample_time(2.0, below + 1.0));
    }

    #[test]
    fn sampling_takes_all_the_due_or_those_since() {
        assert!(Sampling::All.takes(0.03, 0.015));
        assert!(Sampling::Due.takes(0.03, 0.03));
        assert!(!Sampling::Due.takes(0.03, 0.01));
        // A restart a few roundings past 0.01 from a step that began before it.
        let restart = 0.010_000_000_000_000_788;
        assert!(Sampling::Since(0.005).takes(0.01, restart));
        assert!(!Sampling::Since(0.01).takes(0.01, restart));
        assert!(!Sampling::Since(0.005).takes(0.03, restart));
    }
}
