//! A table: an interpolant, what it does outside its data, and the interval it last used.

use core::sync::atomic::{AtomicUsize, Ordering};

use crate::error::LookupError;
use crate::interpolant::Interpolation;
use crate::piecewise::Piecewise;
use crate::points::{InvalidPoints, Points};

/// What a table gives for an argument outside its data.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Outside {
    /// A [`LookupError::Outside`] carrying the argument (the default: data end where they end).
    #[default]
    Error,
    /// Zero (a thrust curve after burnout).
    Zero,
    /// The value at the nearer end, held.
    Hold,
}

/// The interval a caller last looked up, kept by the caller: one per thread or per run, so
/// that lookups need neither the table's own hint nor any sharing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cursor {
    interval: usize,
}

/// A function of one argument given by data: a [`Piecewise`] interpolant and an [`Outside`]
/// rule.
///
/// Lookups remember the interval of the last call, so that an integration, whose arguments
/// move a little from call to call, finds it in one or two comparisons instead of a binary
/// search. The memory is either the caller's [`Cursor`] ([`Table::value_at`]) or the table's
/// own hint ([`Table::value`]), an `AtomicUsize` read and written with `Relaxed` ordering:
/// plain loads and stores on the targets we run on, and the table stays `Sync`, so one table
/// can serve every member of a rayon ensemble. A hint another thread overwrote is only a
/// worse first guess (every guess is checked against the knots), never a wrong value; threads
/// that share a table and want no shared cache line use their own `Cursor`.
#[derive(Debug)]
pub struct Table {
    curve: Piecewise,
    outside: Outside,
    hint: AtomicUsize,
}

impl Clone for Table {
    fn clone(&self) -> Self {
        Self::from_piecewise(self.curve.clone(), self.outside)
    }
}

impl PartialEq for Table {
    /// Tables are equal when they compute the same function (the hint is not compared).
    fn eq(&self, other: &Self) -> bool {
        self.curve == other.curve && self.outside == other.outside
    }
}

impl Table {
    /// The table interpolating `points`.
    pub fn new(points: &Points, interpolation: Interpolation, outside: Outside) -> Self {
        Self::from_piecewise(interpolation.interpolate(points), outside)
    }

    /// [`Table::new`], refused where the interpolant overflows ([`Interpolation::checked`]):
    /// for points that were not read by [`CsvTable::parse_for`](crate::CsvTable::parse_for)
    /// or [`Motor::parse_for`](crate::Motor::parse_for), which check it with the line.
    pub fn checked(
        points: &Points,
        interpolation: Interpolation,
        outside: Outside,
    ) -> Result<Self, InvalidPoints> {
        Ok(Self::from_piecewise(
            interpolation.checked(points)?,
            outside,
        ))
    }

    /// The table of an interpolant already built (e.g. over static arrays the macro emitted).
    pub const fn from_piecewise(curve: Piecewise, outside: Outside) -> Self {
        Self {
            curve,
            outside,
            hint: AtomicUsize::new(0),
        }
    }

    /// The interpolant.
    pub fn curve(&self) -> &Piecewise {
        &self.curve
    }

    /// The rule outside the data.
    pub fn outside(&self) -> Outside {
        self.outside
    }

    /// The first and the last knot: where the data end.
    pub fn domain(&self) -> (f64, f64) {
        self.curve.domain()
    }

    /// The knots: where the table may be non-smooth.
    pub fn knots(&self) -> &[f64] {
        self.curve.knots()
    }

    /// The value at `x`, starting the search from the table's own hint.
    #[inline]
    pub fn value(&self, x: f64) -> Result<f64, LookupError> {
        let hint = self.hint.load(Ordering::Relaxed);
        let mut cursor = Cursor { interval: hint };
        let value = self.value_at(x, &mut cursor);
        // Store only a change: a shared table's cache line stays clean while the interval does.
        if cursor.interval != hint {
            self.hint.store(cursor.interval, Ordering::Relaxed);
        }
        value
    }

    /// The value at `x`, starting the search from `cursor` and leaving it on x's interval.
    #[inline]
    pub fn value_at(&self, x: f64, cursor: &mut Cursor) -> Result<f64, LookupError> {
        let x = self.snap(x);
        match self.place(x, cursor)? {
            Place::Inside(interval) => Ok(self.curve.value_on(interval, x)),
            Place::Outside(end) => self.beyond(x, end),
        }
    }

    /// The first derivative at `x` (zero outside under `zero` and `hold`); at a knot where the
    /// slope jumps, the slope on the right (see [`Piecewise`]).
    pub fn slope_at(&self, x: f64, cursor: &mut Cursor) -> Result<f64, LookupError> {
        let x = self.snap(x);
        match self.place(x, cursor)? {
            Place::Inside(interval) => Ok(self.curve.slope_on(interval, x)),
            // A held or zero value has zero slope; an error stays an error.
            Place::Outside(end) => self.beyond(x, end).map(|_| 0.0),
        }
    }

    /// The derivative table: the interpolant's derivative (a piecewise polynomial on the same
    /// knots, one degree lower), zero outside the data unless this table errs there (a held
    /// or zero value has zero slope). Differentiate again for higher derivatives.
    pub fn derivative(&self) -> Self {
        let outside = match self.outside {
            Outside::Error => Outside::Error,
            Outside::Zero | Outside::Hold => Outside::Zero,
        };
        Self::from_piecewise(self.curve.derivative(), outside)
    }

    /// The table scaled by `value_scale` and stretched by `argument_scale`, k·F(x/s), with
    /// the same rule outside (see [`Piecewise::transformed`]; `None` for a scale it
    /// refuses).
    pub fn transformed(&self, value_scale: f64, argument_scale: f64) -> Option<Self> {
        let curve = self.curve.transformed(value_scale, argument_scale)?;
        Some(Self::from_piecewise(curve, self.outside))
    }

    /// The value at `x` beyond `end`, by the table's rule.
    fn beyond(&self, x: f64, end: End) -> Result<f64, LookupError> {
        match self.outside {
            Outside::Zero => Ok(0.0),
            // The end piece at its knot: the value the curve reaches there.
            Outside::Hold => Ok(self.curve.value_on(end.interval, end.knot)),
            Outside::Error => {
                let (first, last) = self.curve.domain();
                Err(LookupError::Outside {
                    argument: x,
                    first,
                    last,
                })
            }
        }
    }

    /// `x`, or the end of the data it lies within rounding beyond: a step landed on a knot
    /// by a stop time evaluates its last stage at t + h (or an argument a·t + b there), which
    /// can round to an ulp or two *of t* past the knot, and must see the end's value there,
    /// not the rule for outside the data (nor the end piece extrapolated, which past a thrust
    /// curve's final zero is a negative thrust). The table does not know t: the slack is
    /// [`END_SLACK`] of the data's span, which covers the roundings of any t up to about
    /// 10⁵ spans (a motor of 3.9 s ignited up to ~10 days into a run), besides
    /// [`ROUNDING_ULPS`] roundings of the largest knot — except at an end where the table
    /// *jumps* (`outside zero` after a value that is not zero): there a run restarts just
    /// past the knot and must read the value after the jump, so only the roundings of the
    /// knot are taken back (`Table::jumps_at`).
    #[inline]
    fn snap(&self, x: f64) -> f64 {
        let (first, last) = self.curve.domain();
        if first <= x && x <= last {
            return x;
        }
        let end = if x > last { last } else { first };
        if (x - end).abs() <= self.band(end) {
            end
        } else {
            x
        }
    }

    /// How far beyond `end` (its first or last knot) an argument is snapped onto it.
    #[inline]
    fn band(&self, end: f64) -> f64 {
        let (first, last) = self.curve.domain();
        let ulps = ROUNDING_ULPS * f64::EPSILON * first.abs().max(last.abs());
        match self.jumps_at(end) {
            true => ulps,
            false => ulps.max(END_SLACK * (last - first)),
        }
    }

    /// Whether the table's value jumps at `end` (its first or last knot): `outside zero`
    /// where the data's value there is not zero — beyond the rounding of the end piece's
    /// evaluation, 10⁻¹⁰ of the piece's larger end value (a thrust curve's final zero
    /// evaluates to ~10⁻¹³ of its thrust). (`hold` is continuous; `error` has no value
    /// beyond.) False for any other argument.
    pub fn jumps_at(&self, end: f64) -> bool {
        let (first, last) = self.curve.domain();
        let knots = self.curve.knots();
        let (interval, other) = match end {
            _ if end == first => (0, knots[1]),
            _ if end == last => (self.curve.intervals() - 1, knots[knots.len() - 2]),
            _ => return false,
        };
        let near = self.curve.value_on(interval, end).abs();
        let far = self.curve.value_on(interval, other).abs();
        self.outside == Outside::Zero && near > 1e-10 * near.max(far)
    }

    /// The first and the last argument a lookup reads the data at: the ends, widened by
    /// the band of arguments within rounding beyond them that are snapped onto them (see
    /// [`END_SLACK`]; only the knot's roundings where the table jumps). Where the table
    /// jumps at an end, this is where its value jumps: a switch at that knot is placed on
    /// the edge, so that it says which side a lookup reads.
    pub fn data_edges(&self) -> (f64, f64) {
        let (first, last) = self.curve.domain();
        (self.data_edge(first), self.data_edge(last))
    }

    /// The farthest argument beyond `end` (the first or the last knot) that a lookup snaps
    /// onto it ([`Table::data_edges`]); `end` itself for any other argument.
    pub fn data_edge(&self, end: f64) -> f64 {
        let (first, last) = self.curve.domain();
        let step: [fn(f64) -> f64; 2] = match end {
            _ if end == first => [f64::next_down, f64::next_up],
            _ if end == last => [f64::next_up, f64::next_down],
            _ => return end,
        };
        let [outward, inward] = step;
        let on_data = |x: f64| {
            let x = self.snap(x);
            first <= x && x <= last
        };
        // The band's edge end ± band, rounded, then moved by ulps onto the last argument
        // on the data (x − end is exact this close to the end: a step or two at most).
        let band = self.band(end);
        let mut x = if end == first { end - band } else { end + band };
        for _ in 0..4 {
            if !on_data(x) {
                x = inward(x);
            } else if on_data(outward(x)) {
                x = outward(x);
            }
        }
        x
    }

    /// A cursor on the table's own hint.
    pub(crate) fn hint_cursor(&self) -> Cursor {
        Cursor {
            interval: self.hint.load(Ordering::Relaxed),
        }
    }

    /// Stores `cursor` as the table's hint, if it moved.
    pub(crate) fn store_hint(&self, cursor: Cursor) {
        if cursor.interval != self.hint.load(Ordering::Relaxed) {
            self.hint.store(cursor.interval, Ordering::Relaxed);
        }
    }

    /// The argument a lookup at `x` uses: `x`, or the end it lies within rounding beyond
    /// (see [`END_SLACK`]; only the knot's roundings where the table jumps there).
    pub fn snapped(&self, x: f64) -> f64 {
        self.snap(x)
    }

    /// The interval a cursor is on.
    pub(crate) fn cursor_interval(&self, cursor: &Cursor) -> usize {
        cursor.interval.min(self.curve.intervals() - 1)
    }

    /// Where `x` lies: an interval (the cursor moved to it) or beyond an end.
    #[inline]
    fn place(&self, x: f64, cursor: &mut Cursor) -> Result<Place, LookupError> {
        let (first, last) = self.curve.domain();
        if first <= x && x <= last {
            cursor.interval = self.curve.interval(x, cursor.interval);
            return Ok(Place::Inside(cursor.interval));
        }
        if x.is_nan() {
            return Err(LookupError::NotANumber);
        }
        Ok(Place::Outside(if x < first {
            End {
                interval: 0,
                knot: first,
            }
        } else {
            End {
                interval: self.curve.intervals() - 1,
                knot: last,
            }
        }))
    }
}

/// How many roundings of the data's largest |knot| an argument may lie beyond an end and
/// still be on the end piece: a stage time t + c·h of a step landed on a knot rounds to at
/// most an ulp or two of t past it (docs/tables.md#outside-the-data).
const ROUNDING_ULPS: f64 = 4.0;

/// The part of the data's span an argument may lie beyond an end and still be on the end
/// piece: the roundings of a stage time t + c·h scale with t, not with the knots, so an
/// ignition at t = 100 s puts the argument of a 3.9 s curve 5.8e-15 past its end, more
/// than 4 ε·3.9 = 3.5e-15. 10⁻¹⁰ of the span is far below any measured data's resolution
/// and covers t up to 10⁻¹⁰/(2 ε) ≈ 2·10⁵ spans.
pub const END_SLACK: f64 = 1e-10;

/// Where an argument lies relative to the data.
enum Place {
    /// In this interval.
    Inside(usize),
    /// Beyond this end.
    Outside(End),
}

/// An end of the data: its knot and the interval that ends there.
struct End {
    interval: usize,
    knot: f64,
}
