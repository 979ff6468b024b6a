//! The apogee located between the recorded rows: the zero of the vertical speed in the
//! interval whose ends bracket it (v > 0, then v ≤ 0), on the cubic Hermite interpolant of
//! (altitude, vertical speed) at those two rows, with an estimate of its error.
//!
//! On an interval of length Δ the cubic Hermite interpolant H of h (values and first
//! derivatives at both ends) errs by at most ‖h⁗‖ Δ⁴/384 and its derivative by at most
//! √3 ‖h⁗‖ Δ³/216 (Birkhoff & Priver 1967, "Hermite interpolation errors for derivatives",
//! J. Math. Phys. 46, 440–447; both are reached by h = s²(s − Δ)²: its value at the middle,
//! its slope at s = Δ/2 ± Δ/√12). So the highest value of H on the interval is within
//! ‖h⁗‖Δ⁴/384 of the highest of h, and the zero t* of H′ within √3‖h⁗‖Δ³/(216 |h″(t*)|) of
//! the zero of v (to first order). ‖h⁗‖ is estimated from the rows: H‴ is constant on each
//! interval (6 a₃), and the difference of the neighbouring intervals' H‴ over the distance
//! of their midpoints approximates h⁗ between them; twice the larger of the two such
//! estimates around the interval is taken for ‖h⁗‖ on it (the margin covers h⁗ varying
//! across the three intervals: measured on an exponential coast, the time error reaches
//! 0.97 of the bound without the factor). A drag-free coast (h⁗ = 0) is located to
//! rounding.
//! The bounds do not include the integration's own error in the rows.

use serde::{Deserialize, Serialize};

/// The located apogee.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Apogee {
    /// Its time.
    pub time: f64,
    /// Its altitude.
    pub altitude: f64,
    /// The estimated bound of the time's interpolation error (`None`: too few rows around
    /// it to estimate h⁗).
    pub time_error: Option<f64>,
    /// The estimated bound of the altitude's interpolation error.
    pub altitude_error: Option<f64>,
    /// The times of the two rows that bracket it.
    pub between: (f64, f64),
}

/// The cubic Hermite interpolant of (h, v) on one interval, in s = t − t₀:
/// H(s) = h₀ + v₀ s + a₂ s² + a₃ s³.
#[derive(Clone, Copy, Debug)]
struct Cubic {
    t0: f64,
    length: f64,
    h0: f64,
    v0: f64,
    a2: f64,
    a3: f64,
}

impl Cubic {
    /// The interpolant between rows `i` and `i + 1` (`None` for an interval of length zero,
    /// the two rows of a change of phase).
    fn between(t: &[f64], h: &[f64], v: &[f64], i: usize) -> Option<Self> {
        let length = t[i + 1] - t[i];
        if length.is_nan() || length <= 0.0 {
            return None;
        }
        let slope = (h[i + 1] - h[i]) / length;
        Some(Self {
            t0: t[i],
            length,
            h0: h[i],
            v0: v[i],
            a2: (3.0 * slope - 2.0 * v[i] - v[i + 1]) / length,
            a3: (v[i] + v[i + 1] - 2.0 * slope) / (length * length),
        })
    }

    fn value(&self, s: f64) -> f64 {
        self.h0 + s * (self.v0 + s * (self.a2 + s * self.a3))
    }

    fn rate(&self, s: f64) -> f64 {
        self.v0 + s * (2.0 * self.a2 + 3.0 * self.a3 * s)
    }

    fn second(&self, s: f64) -> f64 {
        2.0 * self.a2 + 6.0 * self.a3 * s
    }

    /// H‴, constant on the interval.
    fn third(&self) -> f64 {
        6.0 * self.a3
    }

    /// The zero of H′ in [0, Δ] where it falls from H′(0) > 0 to H′(Δ) ≤ 0, by bisection
    /// (H′ is a quadratic; its sign change is guaranteed, so this cannot miss it).
    fn top(&self) -> f64 {
        let (mut lo, mut hi) = (0.0, self.length);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.rate(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        // The end where |H′| is smaller.
        match self.rate(lo).abs() <= self.rate(hi).abs() {
            true => lo,
            false => hi,
        }
    }
}

/// The apogee of the rows (`t`, altitude `h`, vertical speed `v`): the highest of the
/// located tops of the intervals where v falls from > 0 to ≤ 0 (a change of phase at the
/// top, two rows at one time, is its own row). `None` if v never falls through zero.
pub fn locate_apogee(t: &[f64], h: &[f64], v: &[f64]) -> Option<Apogee> {
    let n = t.len().min(h.len()).min(v.len());
    let mut best: Option<Apogee> = None;
    for i in 0..n.saturating_sub(1) {
        if !(v[i] > 0.0 && v[i + 1] <= 0.0) {
            continue;
        }
        let found = match Cubic::between(t, h, v, i) {
            None => Apogee {
                time: t[i],
                altitude: h[i].max(h[i + 1]),
                time_error: Some(0.0),
                altitude_error: Some(0.0),
                between: (t[i], t[i + 1]),
            },
            Some(cubic) => located(&cubic, (t, h, v), i),
        };
        if best.as_ref().is_none_or(|b| found.altitude > b.altitude) {
            best = Some(found);
        }
    }
    best
}

/// The top of `cubic` (rows `i`, `i + 1` of `rows`) with its error bounds.
fn located(cubic: &Cubic, rows: (&[f64], &[f64], &[f64]), i: usize) -> Apogee {
    let s = cubic.top();
    let length = cubic.length;
    let fourth = fourth_derivative(rows, i);
    let curvature = cubic.second(s).abs();
    let altitude = cubic.value(s);
    // Rounding: the interpolant's few operations on numbers of the altitude's size.
    let (_, h, v) = rows;
    let size = h[i].abs() + h[i + 1].abs() + length * (v[i].abs() + v[i + 1].abs());
    let rounding = 16.0 * f64::EPSILON * size;
    let time_rounding = 16.0 * f64::EPSILON * (cubic.t0.abs() + length);
    Apogee {
        time: cubic.t0 + s,
        altitude,
        altitude_error: fourth.map(|m| m * length.powi(4) / 384.0 + rounding),
        time_error: fourth.map(|m| {
            let slope_error = 3f64.sqrt() * m * length.powi(3) / 216.0;
            // A slope error ε moves the zero of v by ε/|h″| (first order), and rounding in
            // v moves it by its own size over |h″|.
            let rate_rounding = 16.0 * f64::EPSILON * (v[i].abs() + v[i + 1].abs());
            (slope_error + rate_rounding) / curvature + time_rounding
        }),
        between: (cubic.t0, cubic.t0 + length),
    }
}

/// ‖h⁗‖ on interval `i`, estimated as twice the largest jump of H‴ between it and its
/// neighbours (those of positive length sharing a row with it) over the distance of their
/// midpoints; `None` without a neighbour.
fn fourth_derivative((t, h, v): (&[f64], &[f64], &[f64]), i: usize) -> Option<f64> {
    let at = |j: usize| Cubic::between(t, h, v, j);
    let here = at(i)?;
    let before = i.checked_sub(1).and_then(at);
    let after = (i + 2 < t.len()).then(|| at(i + 1)).flatten();
    let jump = |a: &Cubic, b: &Cubic| (b.third() - a.third()).abs() / (0.5 * (a.length + b.length));
    let estimates = [
        before.map(|b| jump(&b, &here)),
        after.map(|a| jump(&here, &a)),
    ];
    estimates
        .into_iter()
        .flatten()
        .reduce(f64::max)
        .map(|m| 2.0 * m)
}
