//! The one explicit Runge–Kutta core: the stages of an embedded explicit pair driven by its
//! Butcher tableau (rows of (j, aⱼ), as data), the combinations h Σⱼ bⱼ kⱼ of its weights and
//! the weighted RMS of its error estimate — written once, generic over what a component is:
//! one `f64` (the scalar steppers, one lane) or [`crate::lanes::Lanes`] (W members side by
//! side, `lanes/dormand_prince.rs`). Each lane computes exactly the scalar operations, in the
//! same order, so a member run in lanes is the scalar run bit for bit
//! (`tests/lanes_dispersion.rs`). Dormand–Prince (`dormand_prince.rs`) and DOP853
//! (`dop853.rs`) take their stages here; their tableaux are `dp_tableau.rs` and
//! `dop853/coefficients.rs`, each with its source and its order conditions tested.
//!
//! The operations, and so the bits: a stage state is accumulated onto y₀ term by term in the
//! row's order, y ← y + kⱼ·(aⱼ h) (one vector operation fewer per stage than summing first);
//! a solution or an error estimate is summed first, (Σⱼ kⱼ bⱼ)·h, in the row's order.

use core::ops::{Add, Div, Mul};

use nalgebra::SVector;

use crate::error::StepError;
use crate::math::sqrt;
use crate::stepper::{state_rate, Statistics};
use crate::system::VariableMassSystem;
use crate::tolerance::Tolerance;

/// A row of a tableau: its non-zero entries (j, aⱼ), j counted from 1.
pub type Row = &'static [(usize, f64)];

/// The stages 2, 3, … of an explicit tableau: each node cᵢ with its row of A.
pub type StageRows = [(f64, Row)];

/// What a component is: one `f64`, or one `f64` in each of W lanes, with the operations the
/// core needs, each lane by lane the `f64` operation (no fused multiply-add).
pub trait Lane:
    Copy
    + Add<Output = Self>
    + Mul<Output = Self>
    + Mul<f64, Output = Self>
    + Div<Output = Self>
    + Div<f64, Output = Self>
{
    /// `value` in every lane.
    fn splat(value: f64) -> Self;
    /// |x|.
    fn abs(self) -> Self;
    /// The greater, as `f64::max`.
    fn max(self, other: Self) -> Self;
    /// √x, correctly rounded.
    fn sqrt(self) -> Self;
    /// 0 in the lanes where `value` is exactly 0, `otherwise` elsewhere: the 0/0 rule of
    /// [`crate::tolerance::weighted_rms`].
    fn zero_where_zero(value: Self, otherwise: Self) -> Self;
}

impl Lane for f64 {
    #[inline(always)]
    fn splat(value: f64) -> Self {
        value
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        sqrt(self)
    }
    #[inline(always)]
    fn zero_where_zero(value: Self, otherwise: Self) -> Self {
        if value == 0.0 {
            0.0
        } else {
            otherwise
        }
    }
}

/// A state of `LEN` components of type `T`: `SVector<f64, S>` for one lane,
/// `crate::lanes::LaneState` for W lanes.
pub trait Vector<T: Lane>: Copy {
    /// The number of components.
    const LEN: usize;
    /// Component `j`.
    fn component(&self, j: usize) -> T;
    /// self + k·s, component by component.
    fn add_scaled(self, k: &Self, s: T) -> Self;
    /// self·a.
    fn scaled(&self, a: f64) -> Self;
    /// self + other.
    fn plus(self, other: &Self) -> Self;
    /// self·h.
    fn times(self, h: T) -> Self;
}

impl<const S: usize> Vector<f64> for SVector<f64, S> {
    const LEN: usize = S;
    #[inline(always)]
    fn component(&self, j: usize) -> f64 {
        self[j]
    }
    #[inline(always)]
    fn add_scaled(self, k: &Self, s: f64) -> Self {
        self + k * s
    }
    #[inline(always)]
    fn scaled(&self, a: f64) -> Self {
        self * a
    }
    #[inline(always)]
    fn plus(self, other: &Self) -> Self {
        self + other
    }
    #[inline(always)]
    fn times(self, h: f64) -> Self {
        self * h
    }
}

/// The state rate the stages evaluate: the system's, counted and checked (one lane), or the
/// generated rate over lanes.
pub trait Rates<T, V> {
    /// Why a rate could not be evaluated.
    type Error;
    /// The rate at `(time, state)`.
    fn rate(&mut self, time: T, state: &V) -> Result<V, Self::Error>;
}

/// The rate of one system (one lane), counted in `statistics` and checked
/// (`stepper::state_rate`).
pub(crate) struct Counted<'s, Sys, const N: usize> {
    /// The system.
    pub(crate) system: &'s Sys,
    /// Where the evaluations are counted.
    pub(crate) statistics: &'s mut Statistics,
}

impl<Sys, const N: usize, const S: usize> Rates<f64, SVector<f64, S>> for Counted<'_, Sys, N>
where
    Sys: VariableMassSystem<N, S>,
{
    type Error = StepError<S>;
    #[inline(always)]
    fn rate(
        &mut self,
        time: f64,
        state: &SVector<f64, S>,
    ) -> Result<SVector<f64, S>, StepError<S>> {
        state_rate(self.system, self.statistics, time, state)
    }
}

/// The stages 2 … `rows.len() + 1` of a step of size `h` from `(t0, y0)`: kᵢ = f(t₀ + cᵢ h,
/// yᵢ) with yᵢ = y₀ + Σⱼ kⱼ (aᵢⱼ h) accumulated in the row's order; k₁ is `k[0]` on entry.
/// The stage states yᵢ go to `states` (as many as it holds); the last is returned. One loop
/// with one call of the rate, not one call per stage: the compiler can inline the rate once
/// and hoist what does not vary from stage to stage (the scalar steppers' form).
#[inline(always)]
pub fn stages<T, V, R, const K: usize>(
    rows: &StageRows,
    (t0, y0): (T, &V),
    h: T,
    k: &mut [V; K],
    states: &mut [V],
    rates: &mut R,
) -> Result<V, R::Error>
where
    T: Lane,
    V: Vector<T>,
    R: Rates<T, V>,
{
    let mut last = *y0;
    // Plain loops, no closures: a closure is compiled on its own, without the AVX of the
    // lanes' kernel that inlines this.
    for (stage, &row) in rows.iter().enumerate() {
        one_stage(stage, row, (t0, y0, h), k, states, rates, &mut last)?;
    }
    Ok(last)
}

/// The most stages [`stages_written_out`] writes out; any further ones it loops over.
const WRITTEN_OUT: usize = 8;

/// [`stages`], the same operations in the same order (so the same bits), with each stage
/// written out by the compiler: stage i is a call of [`one_stage`] with i a constant, so
/// where `rows` is a constant (a tableau's `const`) each row's loop is over a known row and
/// unrolls, its coefficients folded into the code and kⱼ read from a known place, as a
/// stage written out by hand. The rate is inlined once per stage: the form of the lanes
/// (`lanes/dormand_prince.rs`), whose state rate is short and whose stages are W members'
/// work each; through the loop of [`stages`] the compiler left each row's loop rolled, its
/// coefficients read from memory and its kⱼ bounds-checked (`docs/bench/explicit_core.md`).
#[inline(always)]
pub fn stages_written_out<T, V, R, const K: usize>(
    rows: &StageRows,
    (t0, y0): (T, &V),
    h: T,
    k: &mut [V; K],
    states: &mut [V],
    rates: &mut R,
) -> Result<V, R::Error>
where
    T: Lane,
    V: Vector<T>,
    R: Rates<T, V>,
{
    let mut last = *y0;
    macro_rules! written_out {
        ($($stage:literal)*) => {$(
            if let Some(&row) = rows.get($stage) {
                one_stage($stage, row, (t0, y0, h), k, states, rates, &mut last)?;
            }
        )*};
    }
    written_out!(0 1 2 3 4 5 6 7);
    for (stage, &row) in rows.iter().enumerate().skip(WRITTEN_OUT) {
        one_stage(stage, row, (t0, y0, h), k, states, rates, &mut last)?;
    }
    Ok(last)
}

/// Stage `stage + 2` of [`stages`], its node c and its row of A: its state y₀ + Σⱼ kⱼ (aⱼ h)
/// in the row's order into `last` (and `states[stage]` if there is one), its rate into
/// `k[stage + 1]`.
#[inline(always)]
fn one_stage<T, V, R, const K: usize>(
    stage: usize,
    (c, row): (f64, Row),
    (t0, y0, h): (T, &V, T),
    k: &mut [V; K],
    states: &mut [V],
    rates: &mut R,
    last: &mut V,
) -> Result<(), R::Error>
where
    T: Lane,
    V: Vector<T>,
    R: Rates<T, V>,
{
    *last = *y0;
    for &(j, a) in row {
        *last = last.add_scaled(&k[j - 1], h * a);
    }
    k[stage + 1] = rates.rate(t0 + h * c, last)?;
    if let Some(state) = states.get_mut(stage) {
        *state = *last;
    }
    Ok(())
}

/// (Σⱼ kⱼ bⱼ)·h over a row of weights (a solution's increment or an error estimate), summed
/// in the row's order.
#[inline(always)]
pub fn combination<T, V, const K: usize>(row: Row, k: &[V; K], h: T) -> V
where
    T: Lane,
    V: Vector<T>,
{
    weighted_sum(row, k).times(h)
}

/// Σⱼ kⱼ bⱼ over a row of weights, in the row's order.
#[inline(always)]
pub fn weighted_sum<T, V, const K: usize>(row: Row, k: &[V; K]) -> V
where
    T: Lane,
    V: Vector<T>,
{
    let (&(first, b), rest) = row.split_first().expect("a row of weights is not empty");
    let mut sum = k[first - 1].scaled(b);
    for &(j, b) in rest {
        sum = sum.plus(&k[j - 1].scaled(b));
    }
    sum
}

/// The new state y₀ + (Σⱼ kⱼ bⱼ)·h of the weights `b`.
#[inline(always)]
pub fn solution<T, V, const K: usize>(b: Row, y0: &V, k: &[V; K], h: T) -> V
where
    T: Lane,
    V: Vector<T>,
{
    y0.plus(&combination(b, k, h))
}

/// The scaled error of an estimate: the weighted RMS [`Tolerance::norm`] with weights
/// atol + rtol·max(|y₀ᵢ|, |y₁ᵢ|), an exact zero counting 0, the squares summed in
/// component order — lane by lane, to the bit.
#[inline(always)]
pub fn error_norm<T, V>(tolerance: &Tolerance, estimate: &V, (y0, y1): (&V, &V)) -> T
where
    T: Lane,
    V: Vector<T>,
{
    let absolute = T::splat(tolerance.absolute());
    let relative = T::splat(tolerance.relative());
    let mut sum = T::splat(0.0);
    let entries = tolerance.entries(V::LEN);
    for j in 0..entries {
        let value = estimate.component(j);
        let magnitude = y0.component(j).abs().max(y1.component(j).abs());
        // `Tolerance::weight`: atol + rtol·m.
        let scaled = value / (absolute + relative * magnitude);
        sum = sum + T::zero_where_zero(value, scaled * scaled);
    }
    (sum / entries as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::{lane, LaneState, Lanes};

    /// The core's norm is [`Tolerance::norm`] to the bit: on an estimate with an exact zero,
    /// a component over a zero weight's neighbour and magnitudes from either end.
    #[test]
    fn the_error_norm_is_the_tolerances() {
        let tolerance = Tolerance::new(1e-6, 1e-9).unwrap();
        let estimate = SVector::<f64, 4>::new(3e-7, 0.0, -2.5e-10, 1.0e-3);
        let y0 = SVector::<f64, 4>::new(1.0, 0.0, -4.0, 1e5);
        let y1 = SVector::<f64, 4>::new(-2.0, 0.0, 3.0, 0.5);
        let expected = tolerance.norm(&estimate, |i| y0[i].abs().max(y1[i].abs()));
        let got: f64 = error_norm(&tolerance, &estimate, (&y0, &y1));
        assert_eq!(got.to_bits(), expected.to_bits());
    }

    /// The stages written out are the loop's to the bit: over ten rows (so two run in the
    /// loop that follows the eight written out), a rate that is not linear, every k and
    /// every stage state compared, in one lane and in four.
    #[test]
    fn stages_written_out_are_the_loops() {
        const ROWS: &StageRows = &[
            (0.1, &[(1, 0.1)]),
            (0.3, &[(1, 0.075), (2, 0.225)]),
            (0.8, &[(1, 0.97), (2, -3.7), (3, 3.5)]),
            (0.9, &[(2, 0.4), (4, 0.5)]),
            (1.0, &[(1, 0.3), (3, 0.2), (5, 0.5)]),
            (0.5, &[(6, 0.5)]),
            (0.7, &[(1, 0.1), (7, 0.6)]),
            (0.2, &[(8, 0.2)]),
            (0.6, &[(2, -0.4), (9, 1.0)]),
            (1.0, &[(1, 0.25), (5, 0.25), (10, 0.5)]),
        ];
        struct Bent;
        impl Rates<f64, SVector<f64, 2>> for Bent {
            type Error = ();
            fn rate(&mut self, t: f64, y: &SVector<f64, 2>) -> Result<SVector<f64, 2>, ()> {
                Ok(SVector::<f64, 2>::new(
                    y[1] * y[0] + t,
                    1.0 / (1.0 + y[0] * y[0]),
                ))
            }
        }
        impl Rates<Lanes<4>, LaneState<2, 4>> for Bent {
            type Error = ();
            fn rate(&mut self, t: Lanes<4>, y: &LaneState<2, 4>) -> Result<LaneState<2, 4>, ()> {
                Ok([y[1] * y[0] + t, Lanes::splat(1.0) / (y[0] * y[0] + 1.0)])
            }
        }
        let y0 = SVector::<f64, 2>::new(0.7, -1.3);
        let mut k = [y0 * 0.5; 11];
        let (mut k_out, mut states, mut states_out) = (k, [y0; 10], [y0; 10]);
        let last = stages(ROWS, (0.25, &y0), 0.1, &mut k, &mut states, &mut Bent).unwrap();
        let out = stages_written_out(
            ROWS,
            (0.25, &y0),
            0.1,
            &mut k_out,
            &mut states_out,
            &mut Bent,
        );
        assert_eq!(out.unwrap().map(f64::to_bits), last.map(f64::to_bits));
        for (a, b) in k.iter().chain(&states).zip(k_out.iter().chain(&states_out)) {
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
        }
        // Four lanes, lane 2 the one-lane run above: the written-out stages over lanes give
        // its bits.
        let spread = |v: &SVector<f64, 2>| -> LaneState<2, 4> {
            core::array::from_fn(|j| Lanes([v[j] * 3.0, -v[j], v[j], v[j] + 1.0]))
        };
        let mut k_lanes = [spread(&(y0 * 0.5)); 11];
        let mut states_lanes = [spread(&y0); 10];
        let (t0, h) = (Lanes::splat(0.25), Lanes([0.2, 0.05, 0.1, 0.1]));
        let y0_lanes = spread(&y0);
        let lanes = (&mut k_lanes, &mut states_lanes[..]);
        stages_written_out(ROWS, (t0, &y0_lanes), h, lanes.0, lanes.1, &mut Bent).unwrap();
        for (a, b) in k
            .iter()
            .chain(&states)
            .zip(k_lanes.iter().chain(&states_lanes))
        {
            assert_eq!(a.map(f64::to_bits), lane(b, 2).map(f64::to_bits));
        }
    }

    /// A stage state accumulates y + kⱼ·(aⱼ h) in the row's order, a combination sums
    /// first: on 1-vectors whose rounding tells the two apart.
    #[test]
    fn stages_accumulate_and_combinations_sum_first() {
        struct Doubling;
        impl Rates<f64, SVector<f64, 1>> for Doubling {
            type Error = ();
            fn rate(&mut self, _: f64, y: &SVector<f64, 1>) -> Result<SVector<f64, 1>, ()> {
                Ok(y * 2.0)
            }
        }
        const ROWS: &StageRows = &[(0.5, &[(1, 0.1)]), (1.0, &[(1, 0.3), (2, 0.7)])];
        let (y0, h) = (SVector::<f64, 1>::new(1.0), 0.1);
        let mut k = [y0 * 2.0; 3];
        let mut states = [y0; 2];
        stages(ROWS, (0.0, &y0), h, &mut k, &mut states, &mut Doubling).unwrap();
        let y2 = 1.0 + 2.0 * (0.1 * h);
        assert_eq!(states[0][0].to_bits(), y2.to_bits());
        let y3 = (1.0 + 2.0 * (0.3 * h)) + (2.0 * y2) * (0.7 * h);
        assert_eq!(states[1][0].to_bits(), y3.to_bits());
        let b: Row = &[(1, 0.25), (3, 0.75)];
        let y1: SVector<f64, 1> = solution(b, &y0, &k, h);
        let expected = 1.0 + (2.0 * 0.25 + (2.0 * y3) * 0.75) * h;
        assert_eq!(y1[0].to_bits(), expected.to_bits());
    }
}
