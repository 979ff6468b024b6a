//! SIMD lanes: W members of an ensemble integrated side by side, each in its own lane.
//!
//! [`Lanes<W>`] is W `f64`s with the arithmetic and the real functions generated code uses,
//! applied lane by lane: each lane sees exactly the operation the scalar code performs on
//! its `f64` (no fused multiply-add, the same function for `ln`, `sin`, …), so a lane's
//! values are bit-identical to the scalar path's. The arithmetic is written as plain loops
//! over `[f64; W]`, which the compiler turns into packed instructions of whatever width the
//! code is compiled for (SSE2's two lanes in a default x86-64 build; [`run_lanes`] also
//! compiles its kernel for AVX's four and takes it where the CPU has AVX); the
//! transcendental functions stay one call per lane.
//!
//! [`LaneSystem`] is what `emit = [..., "lanes"]` adds to a system: its parameters as
//! lanes and its state rate over lanes (and, with `"taylor"`, its Taylor recurrences over
//! lanes). [`run_lanes`] integrates with it: Dormand–Prince ([`dormand_prince`]) or
//! Taylor's method (`taylor.rs`), by the control it is given.

#[cfg(feature = "run")]
pub mod dormand_prince;
#[cfg(feature = "run")]
mod events;
#[cfg(feature = "run")]
mod member;
#[cfg(feature = "run")]
mod taylor;

use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub};

use nalgebra::{ComplexField, RealField, SVector};

use crate::error::SystemError;
use crate::scratch::Scratch;
use crate::steppers::explicit::{Lane, Vector};
use crate::steppers::taylor::series::Coefficient;
use crate::system::VariableMassSystem;
use varmass_table::recurrence::Scalar;

#[cfg(feature = "run")]
pub use dormand_prince::{run_lanes, run_lanes_with, LaneEnd, LaneJob, LaneKernel, LaneMethod};

/// W `f64`s, one per lane, with arithmetic and functions applied lane by lane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const W: usize>(pub [f64; W]);

impl<const W: usize> Default for Lanes<W> {
    fn default() -> Self {
        Self([0.0; W])
    }
}

impl<const W: usize> From<f64> for Lanes<W> {
    fn from(value: f64) -> Self {
        Self::splat(value)
    }
}

impl<const W: usize> Lanes<W> {
    /// `value` in every lane.
    #[inline(always)]
    pub fn splat(value: f64) -> Self {
        Self([value; W])
    }

    /// Lane `i` is `f(i)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        let mut out = [0.0; W];
        for (i, x) in out.iter_mut().enumerate() {
            *x = f(i);
        }
        Self(out)
    }

    /// `f` applied to each lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut out = self.0;
        for x in &mut out {
            *x = f(*x);
        }
        Self(out)
    }

    /// `f` applied to each lane of `self` and `other`.
    #[inline(always)]
    pub fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut out = self.0;
        for (x, y) in out.iter_mut().zip(other.0) {
            *x = f(*x, y);
        }
        Self(out)
    }

    /// Lane by lane: `if_true` where `mask` is set, `if_false` elsewhere (the branches of a
    /// switch, both evaluated).
    #[inline(always)]
    pub fn select(mask: [bool; W], if_true: Self, if_false: Self) -> Self {
        let mut out = if_false.0;
        for ((x, t), m) in out.iter_mut().zip(if_true.0).zip(mask) {
            if m {
                *x = t;
            }
        }
        Self(out)
    }

    /// √x (correctly rounded, as `f64::sqrt`).
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        self.map(<f64 as ComplexField>::sqrt)
    }

    /// ∛x.
    #[inline(always)]
    pub fn cbrt(self) -> Self {
        self.map(<f64 as ComplexField>::cbrt)
    }

    /// xⁿ.
    #[inline(always)]
    pub fn powi(self, n: i32) -> Self {
        self.map(|x| <f64 as ComplexField>::powi(x, n))
    }

    /// xʸ, y a lane value or an `f64` for all lanes.
    #[inline(always)]
    pub fn powf(self, y: impl Into<Self>) -> Self {
        self.zip(y.into(), <f64 as ComplexField>::powf)
    }

    /// eˣ.
    #[inline(always)]
    pub fn exp(self) -> Self {
        self.map(<f64 as ComplexField>::exp)
    }

    /// ln x.
    #[inline(always)]
    pub fn ln(self) -> Self {
        self.map(<f64 as ComplexField>::ln)
    }

    /// sin x.
    #[inline(always)]
    pub fn sin(self) -> Self {
        self.map(<f64 as ComplexField>::sin)
    }

    /// cos x.
    #[inline(always)]
    pub fn cos(self) -> Self {
        self.map(<f64 as ComplexField>::cos)
    }

    /// tan x.
    #[inline(always)]
    pub fn tan(self) -> Self {
        self.map(<f64 as ComplexField>::tan)
    }

    /// sinh x.
    #[inline(always)]
    pub fn sinh(self) -> Self {
        self.map(<f64 as ComplexField>::sinh)
    }

    /// cosh x.
    #[inline(always)]
    pub fn cosh(self) -> Self {
        self.map(<f64 as ComplexField>::cosh)
    }

    /// tanh x.
    #[inline(always)]
    pub fn tanh(self) -> Self {
        self.map(<f64 as ComplexField>::tanh)
    }

    /// asin x.
    #[inline(always)]
    pub fn asin(self) -> Self {
        self.map(<f64 as ComplexField>::asin)
    }

    /// acos x.
    #[inline(always)]
    pub fn acos(self) -> Self {
        self.map(<f64 as ComplexField>::acos)
    }

    /// atan x.
    #[inline(always)]
    pub fn atan(self) -> Self {
        self.map(<f64 as ComplexField>::atan)
    }

    /// atan2(self, x).
    #[inline(always)]
    pub fn atan2(self, x: impl Into<Self>) -> Self {
        self.zip(x.into(), <f64 as RealField>::atan2)
    }

    /// |x|.
    #[inline(always)]
    pub fn abs(self) -> Self {
        self.map(f64::abs)
    }

    /// The lesser, as `f64::min` (a NaN loses).
    #[inline(always)]
    pub fn min(self, other: impl Into<Self>) -> Self {
        self.zip(other.into(), f64::min)
    }

    /// The greater, as `f64::max` (a NaN loses).
    #[inline(always)]
    pub fn max(self, other: impl Into<Self>) -> Self {
        self.zip(other.into(), f64::max)
    }
}

/// `impl Op<Lanes> for Lanes`, `Op<f64> for Lanes` and `Op<Lanes> for f64`, lane by lane.
/// (Plain loops over the arrays, not `core::array::from_fn`, whose guarded iteration the
/// compiler left unvectorized: a tenth of the lanes' time went there.)
macro_rules! lane_operator {
    ($Op:ident, $op:ident, $symbol:tt) => {
        impl<const W: usize> $Op for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            fn $op(self, other: Self) -> Self {
                self.zip(other, |x, y| x $symbol y)
            }
        }
        impl<const W: usize> $Op<f64> for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            fn $op(self, other: f64) -> Self {
                self.map(|x| x $symbol other)
            }
        }
        impl<const W: usize> $Op<Lanes<W>> for f64 {
            type Output = Lanes<W>;
            #[inline(always)]
            fn $op(self, other: Lanes<W>) -> Lanes<W> {
                other.map(|y| self $symbol y)
            }
        }
    };
}

lane_operator!(Add, add, +);
lane_operator!(Sub, sub, -);
lane_operator!(Mul, mul, *);
lane_operator!(Div, div, /);

impl<const W: usize> Neg for Lanes<W> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|x| -x)
    }
}

impl<const W: usize> AddAssign for Lanes<W> {
    #[inline(always)]
    fn add_assign(&mut self, other: Self) {
        *self = *self + other;
    }
}

impl<const W: usize> MulAssign<f64> for Lanes<W> {
    #[inline(always)]
    fn mul_assign(&mut self, other: f64) {
        *self = *self * other;
    }
}

/// A component of the explicit core (`steppers/explicit.rs`) over W lanes.
impl<const W: usize> Lane for Lanes<W> {
    #[inline(always)]
    fn splat(value: f64) -> Self {
        Self::splat(value)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Self::abs(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Self::max(self, other)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self::sqrt(self)
    }
    #[inline(always)]
    fn zero_where_zero(value: Self, otherwise: Self) -> Self {
        Self::select(value.0.map(|v| v == 0.0), Self::splat(0.0), otherwise)
    }
}

/// A number of the Taylor recurrences (`varmass_table::recurrence`) over W lanes: each
/// operation the `f64` one, lane by lane.
impl<const W: usize> Scalar for Lanes<W> {
    const NEG_ZERO: Self = Self([-0.0; W]);
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self::splat(x)
    }
}

/// A Taylor coefficient of W members (`steppers::taylor::series`, `emit = [..., "taylor",
/// "lanes"]`).
impl<const W: usize> Coefficient for Lanes<W> {
    const WIDTH: usize = W;
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.0[i]
    }
    #[inline(always)]
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self {
        Self::from_fn(f)
    }
    #[inline(always)]
    fn set_lane(&mut self, i: usize, x: f64) {
        self.0[i] = x;
    }
    #[inline(always)]
    fn singular(_: Self, _: &[Self]) -> bool {
        false
    }
}

/// A state of the explicit core over W lanes: each operation component by component, lane
/// by lane (plain loops, which the compiler vectorizes).
impl<const S: usize, const W: usize> Vector<Lanes<W>> for LaneState<S, W> {
    const LEN: usize = S;
    #[inline(always)]
    fn component(&self, j: usize) -> Lanes<W> {
        self[j]
    }
    #[inline(always)]
    fn add_scaled(mut self, k: &Self, s: Lanes<W>) -> Self {
        for (y, k) in self.iter_mut().zip(k) {
            *y += *k * s;
        }
        self
    }
    #[inline(always)]
    fn scaled(&self, a: f64) -> Self {
        let mut out = *self;
        for y in &mut out {
            *y *= a;
        }
        out
    }
    #[inline(always)]
    fn plus(mut self, other: &Self) -> Self {
        for (y, x) in self.iter_mut().zip(other) {
            *y += *x;
        }
        self
    }
    #[inline(always)]
    fn times(mut self, h: Lanes<W>) -> Self {
        for y in &mut self {
            *y = *y * h;
        }
        self
    }
}

/// A state of S components over W lanes: component-major, `state[j].0[i]` is component j of
/// lane i.
pub type LaneState<const S: usize, const W: usize> = [Lanes<W>; S];

/// Lane `lane` of a lane state, as the scalar code's vector.
#[inline]
pub fn lane<const S: usize, const W: usize>(
    state: &LaneState<S, W>,
    lane: usize,
) -> SVector<f64, S> {
    SVector::from_fn(|j, _| state[j].0[lane])
}

/// Writes `value` into lane `lane` of a lane state.
#[inline]
pub fn set_lane<const S: usize, const W: usize>(
    state: &mut LaneState<S, W>,
    lane: usize,
    value: &SVector<f64, S>,
) {
    for (component, v) in state.iter_mut().zip(value.iter()) {
        component.0[lane] = *v;
    }
}

/// A system whose state rate can be evaluated for W members at once: what
/// `emit = [..., "lanes"]` generates (for a model without tables, inputs, `sign` or a
/// numeric velocity solve). Lane i of [`LaneSystem::state_rate_lanes`] is bit-identical to
/// [`VariableMassSystem::state_rate`] of the system in lane i.
///
/// Its [`VariableMassSystem::mass`] of a state mass k returns the state's component 2N + k
/// as it is (as generated code does): the lanes locate a state mass's event on that one
/// component of the interpolant, and rely on it to give the scalar path's bits.
pub trait LaneSystem<const N: usize, const S: usize, const W: usize>:
    VariableMassSystem<N, S>
{
    /// The parameters (the struct's fields) of W systems, each field a [`Lanes<W>`].
    type Parameters: Copy;

    /// Every lane holding `system`'s parameters.
    fn splat(system: &Self) -> Self::Parameters;

    /// Puts `system`'s parameters in lane `lane`.
    fn set_lane(parameters: &mut Self::Parameters, lane: usize, system: &Self);

    /// The state rate [q̇, ṗ, ṁ_s] in every lane: the generated scalar state rate's
    /// operations, lane by lane. Nothing is checked here: the caller checks each lane's
    /// input is finite (as the scalar stepper does) before trusting its rate.
    fn state_rate_lanes(
        parameters: &Self::Parameters,
        t: Lanes<W>,
        state: &LaneState<S, W>,
    ) -> LaneState<S, W>;

    /// The Taylor coefficients of W members at once (`coefficients[k]` is y\[k\] in every
    /// lane, k up to `coefficients.len() − 1`): the generated scalar
    /// `taylor_coefficients`' recurrences, instantiated over lanes, so that lane i is that
    /// method's expansion of the system in lane i, bit for bit, to whatever order it is
    /// truncated. `None` unless generated (`emit = [..., "taylor", "lanes"]`). Nothing is
    /// checked: a lane whose coefficients are not finite is expanded again alone by the
    /// caller for the scalar error.
    fn taylor_coefficients_lanes(
        parameters: &Self::Parameters,
        t: Lanes<W>,
        state: &LaneState<S, W>,
        coefficients: &mut [LaneState<S, W>],
        scratch: &mut Scratch<Lanes<W>>,
    ) -> Option<Result<(), SystemError>> {
        let _ = (parameters, t, state, coefficients, scratch);
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each lane gets exactly the scalar operation: mixed lane/scalar operands, a function,
    /// a min with a NaN (which loses, as `f64::min`), the ln of a negative (NaN).
    #[test]
    fn lanes_compute_what_the_scalar_code_computes() {
        let x = Lanes::<4>([0.1, -2.5, 3.0e10, f64::NAN]);
        let y = Lanes::<4>([7.0, 0.3, -1.0e-3, 2.0]);
        let lanes = (2.0 * x - y / 3.0) * (x + 1.5).abs().sqrt() + x.min(y).ln();
        for i in 0..4 {
            let (a, b) = (x.0[i], y.0[i]);
            let scalar = (2.0 * a - b / 3.0) * (a + 1.5).abs().sqrt() + a.min(b).ln();
            // Rust leaves a NaN's sign and payload unspecified (the scalar expression, folded
            // at compile time, gives +NaN where glibc's `log` of a negative gives −NaN): a
            // NaN lane matches a NaN, every other lane the scalar bits.
            if scalar.is_nan() {
                assert!(lanes.0[i].is_nan(), "lane {i}: {}", lanes.0[i]);
            } else {
                assert_eq!(lanes.0[i].to_bits(), scalar.to_bits(), "lane {i}");
            }
        }
    }
}
