//! Forward-mode dual numbers with `W` tangents: a value and its derivatives in `W` directions
//! at once. The generated state rate evaluated over them (`emit = [..., "sensitivities"]`,
//! `VariableMassSystem::state_rate_tangents`) gives f and `W` directional derivatives
//! J_y s + ∂f/∂θ e in one pass, with no Jacobian formed ([`crate::sensitivity`]).
//!
//! The operators take an `f64` or a `Tangent` on either side, so that the state rate's
//! printed text (`2f64 * x`, `1.0 / d`, `x.powi(2)`, `x.sin()`) compiles unchanged over it;
//! comparisons read the value alone (the pivot and mass guards).

use core::cmp::Ordering;
use core::ops::{Add, Div, Mul, Neg, Sub};

use nalgebra::{ComplexField, RealField};

use crate::steppers::taylor::series::{power, Coefficient};
use varmass_table::recurrence::{power_slopes, Value};

/// `slope · x`, 0 where x is 0 whatever the slope (a direction that does not move).
fn times(slope: f64, x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        slope * x
    }
}

/// A value `v` and its derivatives `d` in `W` directions. Equality and order read the value
/// alone, as the generated code's guards do.
#[derive(Clone, Copy, Debug)]
pub struct Tangent<const W: usize> {
    /// The value.
    pub v: f64,
    /// The derivatives.
    pub d: [f64; W],
}

impl<const W: usize> Tangent<W> {
    /// A constant: no derivative.
    pub fn constant(v: f64) -> Self {
        Self { v, d: [0.0; W] }
    }

    /// f(v) with f'(v) = `slope`: the chain rule on every direction. A direction that does
    /// not move the argument does not move the value, even where the slope is infinite
    /// (√ at 0 of a parameter the direction does not seed): 0, not ∞ × 0 = NaN.
    fn chain(self, value: f64, slope: f64) -> Self {
        let d = if slope.is_finite() {
            self.d.map(|x| slope * x)
        } else {
            self.d.map(|x| times(slope, x))
        };
        Self { v: value, d }
    }

    /// sin.
    pub fn sin(self) -> Self {
        self.chain(ComplexField::sin(self.v), ComplexField::cos(self.v))
    }
    /// cos.
    pub fn cos(self) -> Self {
        self.chain(ComplexField::cos(self.v), -ComplexField::sin(self.v))
    }
    /// tan.
    pub fn tan(self) -> Self {
        let t = ComplexField::tan(self.v);
        self.chain(t, 1.0 + t * t)
    }
    /// exp.
    pub fn exp(self) -> Self {
        let e = ComplexField::exp(self.v);
        self.chain(e, e)
    }
    /// ln.
    pub fn ln(self) -> Self {
        self.chain(ComplexField::ln(self.v), 1.0 / self.v)
    }
    /// sqrt.
    pub fn sqrt(self) -> Self {
        let r = ComplexField::sqrt(self.v);
        self.chain(r, 0.5 / r)
    }
    /// cbrt.
    pub fn cbrt(self) -> Self {
        let r = ComplexField::cbrt(self.v);
        self.chain(r, 1.0 / (3.0 * r * r))
    }
    /// x^n.
    pub fn powi(self, n: i32) -> Self {
        let slope = match n {
            0 => 0.0,
            _ => f64::from(n) * ComplexField::powi(self.v, n - 1),
        };
        self.chain(ComplexField::powi(self.v, n), slope)
    }
    /// x^y. Along y the slope x^y ln x exists for x > 0 only: NaN elsewhere where the
    /// direction moves y (as the symbolic derivative gives), nothing where it does not.
    pub fn powf(self, y: impl Into<Tangent<W>>) -> Self {
        let y = y.into();
        let value = ComplexField::powf(self.v, y.v);
        let along_x = y.v * ComplexField::powf(self.v, y.v - 1.0);
        let along_y = if self.v > 0.0 {
            value * ComplexField::ln(self.v)
        } else {
            f64::NAN
        };
        let mut d = [0.0; W];
        for (k, slot) in d.iter_mut().enumerate() {
            *slot = times(along_x, self.d[k]) + times(along_y, y.d[k]);
        }
        Self { v: value, d }
    }
    /// tanh.
    pub fn tanh(self) -> Self {
        let t = ComplexField::tanh(self.v);
        self.chain(t, 1.0 - t * t)
    }
    /// sinh.
    pub fn sinh(self) -> Self {
        self.chain(ComplexField::sinh(self.v), ComplexField::cosh(self.v))
    }
    /// cosh.
    pub fn cosh(self) -> Self {
        self.chain(ComplexField::cosh(self.v), ComplexField::sinh(self.v))
    }
    /// asin.
    pub fn asin(self) -> Self {
        self.chain(
            ComplexField::asin(self.v),
            1.0 / ComplexField::sqrt(1.0 - self.v * self.v),
        )
    }
    /// acos.
    pub fn acos(self) -> Self {
        self.chain(
            ComplexField::acos(self.v),
            -1.0 / ComplexField::sqrt(1.0 - self.v * self.v),
        )
    }
    /// atan.
    pub fn atan(self) -> Self {
        self.chain(ComplexField::atan(self.v), 1.0 / (1.0 + self.v * self.v))
    }
    /// atan2(self, x).
    pub fn atan2(self, x: impl Into<Tangent<W>>) -> Self {
        let x = x.into();
        let r2 = self.v * self.v + x.v * x.v;
        let mut d = [0.0; W];
        for (k, slot) in d.iter_mut().enumerate() {
            *slot = (x.v * self.d[k] - self.v * x.d[k]) / r2;
        }
        Self {
            v: RealField::atan2(self.v, x.v),
            d,
        }
    }
}

impl<const W: usize> From<f64> for Tangent<W> {
    fn from(v: f64) -> Self {
        Self::constant(v)
    }
}

impl<const W: usize> PartialEq for Tangent<W> {
    fn eq(&self, other: &Self) -> bool {
        self.v == other.v
    }
}

impl<const W: usize> PartialEq<f64> for Tangent<W> {
    fn eq(&self, other: &f64) -> bool {
        self.v == *other
    }
}

impl<const W: usize> PartialOrd for Tangent<W> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.v.partial_cmp(&other.v)
    }
}

impl<const W: usize> PartialOrd<f64> for Tangent<W> {
    fn partial_cmp(&self, other: &f64) -> Option<Ordering> {
        self.v.partial_cmp(other)
    }
}

impl<const W: usize> Neg for Tangent<W> {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            v: -self.v,
            d: self.d.map(|x| -x),
        }
    }
}

impl<const W: usize> Add for Tangent<W> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        for (a, b) in d.iter_mut().zip(o.d) {
            *a += b;
        }
        Self { v: self.v + o.v, d }
    }
}

impl<const W: usize> Sub for Tangent<W> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        let mut d = self.d;
        for (a, b) in d.iter_mut().zip(o.d) {
            *a -= b;
        }
        Self { v: self.v - o.v, d }
    }
}

impl<const W: usize> Mul for Tangent<W> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; W];
        for (k, slot) in d.iter_mut().enumerate() {
            *slot = self.d[k] * o.v + self.v * o.d[k];
        }
        Self { v: self.v * o.v, d }
    }
}

impl<const W: usize> Div for Tangent<W> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let v = self.v / o.v;
        let inverse = 1.0 / o.v;
        let mut d = [0.0; W];
        for (k, slot) in d.iter_mut().enumerate() {
            *slot = (self.d[k] - v * o.d[k]) * inverse;
        }
        Self { v, d }
    }
}

/// `Tangent ∘ f64` and `f64 ∘ Tangent`: the constant's derivatives are zero, so each
/// operator skips their terms (generated code is full of constants). For finite values the
/// same as through [`Tangent::constant`] but for the sign of a zero; where a value is
/// infinite or NaN the derivatives are no longer poisoned by it (∞ · 0 = NaN): `∞ * 2` moves
/// with d·2, as its limit does.
impl<const W: usize> Add<f64> for Tangent<W> {
    type Output = Tangent<W>;
    fn add(self, o: f64) -> Tangent<W> {
        Self {
            v: self.v + o,
            d: self.d,
        }
    }
}

impl<const W: usize> Add<Tangent<W>> for f64 {
    type Output = Tangent<W>;
    fn add(self, o: Tangent<W>) -> Tangent<W> {
        Tangent {
            v: self + o.v,
            d: o.d,
        }
    }
}

impl<const W: usize> Sub<f64> for Tangent<W> {
    type Output = Tangent<W>;
    fn sub(self, o: f64) -> Tangent<W> {
        Self {
            v: self.v - o,
            d: self.d,
        }
    }
}

impl<const W: usize> Sub<Tangent<W>> for f64 {
    type Output = Tangent<W>;
    fn sub(self, o: Tangent<W>) -> Tangent<W> {
        Tangent {
            v: self - o.v,
            d: o.d.map(|x| -x),
        }
    }
}

impl<const W: usize> Mul<f64> for Tangent<W> {
    type Output = Tangent<W>;
    fn mul(self, o: f64) -> Tangent<W> {
        Self {
            v: self.v * o,
            d: self.d.map(|x| x * o),
        }
    }
}

impl<const W: usize> Mul<Tangent<W>> for f64 {
    type Output = Tangent<W>;
    fn mul(self, o: Tangent<W>) -> Tangent<W> {
        Tangent {
            v: self * o.v,
            d: o.d.map(|x| self * x),
        }
    }
}

impl<const W: usize> Div<f64> for Tangent<W> {
    type Output = Tangent<W>;
    fn div(self, o: f64) -> Tangent<W> {
        let inverse = 1.0 / o;
        Self {
            v: self.v / o,
            d: self.d.map(|x| x * inverse),
        }
    }
}

impl<const W: usize> Div<Tangent<W>> for f64 {
    type Output = Tangent<W>;
    fn div(self, o: Tangent<W>) -> Tangent<W> {
        let v = self / o.v;
        let inverse = 1.0 / o.v;
        Tangent {
            v,
            d: o.d.map(|x| -(v * x) * inverse),
        }
    }
}

/// A tangent as a Taylor coefficient: the Taylor stepper's recurrences over tangents
/// (`VariableMassSystem::taylor_coefficients_tangents`) expand the solution and, in the
/// tangents' directions, its derivatives with respect to the columns (Taylor sensitivities,
/// [`crate::sensitivity`]). Its "lanes", for the scratch's key of constants, are the value
/// and the derivatives; a function's value at order 0 follows the chain rule.
impl<const W: usize> varmass_table::recurrence::Scalar for Tangent<W> {
    const NEG_ZERO: Self = Self {
        v: -0.0,
        d: [-0.0; W],
    };
    fn splat(x: f64) -> Self {
        Self::constant(x)
    }
}

/// A tangent as a run-time tape's coefficient (`varmass_symbolic::expr::TaylorTape`, the
/// interpreter's Taylor sensitivities): selections branch on the value, functions follow the
/// chain rule as in [`Coefficient::map`].
impl<const W: usize> Value for Tangent<W> {
    fn lead(self) -> f64 {
        self.v
    }
    fn map(self, f: impl Fn(f64) -> f64, slope: impl Fn(f64, f64) -> f64) -> Self {
        Coefficient::map(self, f, slope)
    }
    fn map2(
        self,
        x: Self,
        f: impl Fn(f64, f64) -> f64,
        slopes: impl Fn(f64, f64, f64) -> (f64, f64),
    ) -> Self {
        let v = f(self.v, x.v);
        let (along_self, along_x) = slopes(self.v, x.v, v);
        let d = core::array::from_fn(|k| times(along_self, self.d[k]) + times(along_x, x.d[k]));
        Self { v, d }
    }
    fn pick(self, other: Self, choose: impl Fn(f64, f64) -> f64) -> Self {
        let v = choose(self.v, other.v);
        match v.is_nan() {
            true => Self::constant(v),
            false if v == self.v || v != other.v => self,
            false => other,
        }
    }
}

impl<const W: usize> Coefficient for Tangent<W> {
    const WIDTH: usize = 1 + W;
    fn lane(self, i: usize) -> f64 {
        match i {
            0 => self.v,
            i => self.d[i - 1],
        }
    }
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        Self {
            v: f(0),
            d: core::array::from_fn(|i| f(i + 1)),
        }
    }
    fn set_lane(&mut self, i: usize, x: f64) {
        match i {
            0 => self.v = x,
            i => self.d[i - 1] = x,
        }
    }
    fn singular(velocity: Self, state: &[Self]) -> bool {
        !velocity.v.is_finite() && state.iter().all(|x| x.v.is_finite())
    }
    fn map(self, f: impl Fn(f64) -> f64, slope: impl Fn(f64, f64) -> f64) -> Self {
        let value = f(self.v);
        self.chain(value, slope(self.v, value))
    }
    fn map_atan2(y: Self, x: Self) -> Self {
        y.atan2(x)
    }
    fn map_power(self, alpha: Self) -> Self {
        let slopes = |x, e, w| power_slopes((x, e, w), power, ComplexField::ln);
        Value::map2(self, alpha, power, slopes)
    }
    fn map_sin_cos(self, hyperbolic: bool) -> (Self, Self) {
        let (sine, cosine) = match hyperbolic {
            true => (ComplexField::sinh(self.v), ComplexField::cosh(self.v)),
            false => ComplexField::sin_cos(self.v),
        };
        let sign = if hyperbolic { 1.0 } else { -1.0 };
        (self.chain(sine, cosine), self.chain(cosine, sign * sine))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rule over tangents beside its f64 function.
    type Rule = (fn(Tangent<1>) -> Tangent<1>, fn(f64) -> f64);

    /// Each rule against a central difference of its f64 function at a point.
    #[test]
    fn each_rule_meets_a_central_difference() {
        let x = 0.37;
        let h = 1e-6;
        let seed = Tangent::<1> { v: x, d: [1.0] };
        let rules: [Rule; 12] = [
            (|t| t.sin(), f64::sin),
            (|t| t.cos(), f64::cos),
            (|t| t.tan(), f64::tan),
            (|t| t.exp(), f64::exp),
            (|t| t.ln(), f64::ln),
            (|t| t.sqrt(), f64::sqrt),
            (|t| t.cbrt(), f64::cbrt),
            (|t| t.powi(3), |x| x.powi(3)),
            (|t| t.powf(2.5), |x| x.powf(2.5)),
            (|t| t.atan2(0.8), |x| x.atan2(0.8)),
            (
                |t| 2.0 / (t * t - 1.5) + 3.0 * t,
                |x| 2.0 / (x * x - 1.5) + 3.0 * x,
            ),
            (
                |t| t.asin() + t.acos() * t.atan() + t.tanh(),
                |x| x.asin() + x.acos() * x.atan() + x.tanh(),
            ),
        ];
        for (k, (tangent, plain)) in rules.iter().enumerate() {
            let ours = tangent(seed);
            let difference = (plain(x + h) - plain(x - h)) / (2.0 * h);
            assert_eq!(ours.v, plain(x), "rule {k}");
            assert!(
                (ours.d[0] - difference).abs() <= 1e-8 * difference.abs().max(1.0),
                "rule {k}"
            );
        }
    }
}
