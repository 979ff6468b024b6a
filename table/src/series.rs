//! Taylor coefficients of a table call F(a(t)) (docs/tables.md#taylor-series): between two
//! knots an interpolant is one polynomial of degree ≤ 3 in s = a − xᵢ, so the series of
//! F(a) is that cubic composed with a's series, by Horner's rule over series:
//!
//! h₂ = c₃ s + c₂,  h₁ = h₂ s + c₁,  w = h₁ s + c₀,
//!
//! each product a Cauchy product, coefficient by coefficient (w\[k\] needs a\[0..=k\] and
//! h₁\[0..k\]). The piece is the one holding a\[0\], chosen at order 0; the series is valid
//! while the argument stays in it, so a step must not straddle a knot (the knots of a table
//! of t are stop times, of a table of the state switching functions: every stepper, the
//! Taylor stepper included, ends its step there). One function serves the run-time tapes and
//! generated code, so the two are bit-identical.

use crate::error::LookupError;
use crate::recurrence::Scalar;
use crate::table::{Cursor, Outside, Table};

/// The piece of a table holding an argument, as a cubic in s = x − `knot`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Local {
    /// The knot the piece starts at (the end of the data outside them).
    pub knot: f64,
    /// c₀ … c₃ of Σ cⱼ sʲ, zero past the piece's degree; outside the data under `zero` or
    /// `hold`, the constant value and zeros. NaN for a piece of degree above 3 (not an
    /// interpolant of this crate).
    pub coefficients: [f64; 4],
    /// The table's value at the argument ([`Table::value_at`], to the bit).
    pub value: f64,
}

impl Local {
    /// No piece: every coefficient NaN (a lookup that failed), so the series is NaN and a
    /// Taylor step ends in a typed non-finite error, never a silently wrong series.
    pub const NAN: Local = Local {
        knot: f64::NAN,
        coefficients: [f64::NAN; 4],
        value: f64::NAN,
    };
}

impl Table {
    /// [`Table::local_at`] from the table's own hint (as [`Table::value`]).
    pub fn local(&self, x: f64) -> Result<Local, LookupError> {
        let mut cursor = self.hint_cursor();
        let local = self.local_at(x, &mut cursor);
        self.store_hint(cursor);
        local
    }

    /// The piece holding `x`, starting the search from `cursor`, for a series that looks
    /// forward from `x` with the argument rising (or at rest); the outside rule as for a value
    /// (an error under `outside error`).
    ///
    /// The piece is chosen from `x` itself, not from `x` snapped onto an end as a value is
    /// ([`Table::value_at`]): from the last knot on, the piece is the constant the table is
    /// worth after its data (zero or the held value; under `outside error` a
    /// [`LookupError::Outside`]), and that constant is also the series' value at order 0 —
    /// where `outside zero` meets a last value that is not zero, the table jumps at its last
    /// knot, and the series of a step leaving it is the value after the jump (a step
    /// arriving there ended at the knot: it is a stop time). Below the first knot, likewise
    /// the constant before the data. Except where the table jumps at an end: within the
    /// lookups' rounding band beyond it, the value is the data's ([`Table::data_edges`]),
    /// and so is the series (the end piece's), since a switch on the state lets a run
    /// entering the data restart there; a run on a table of t leaving the data stands there
    /// only for the tiny step between a jump's two stop times (`next_knot_time`). On an
    /// interior knot, the piece starting there.
    ///
    /// A falling argument needs the piece *below* a knot: the stop times of a falling
    /// argument are moved until it lies strictly below the knot
    /// (`varmass_core::table::next_knot_time`), and a table of the
    /// state is restarted past a knot it crosses, so an argument falls exactly on a knot only
    /// when a run *starts* there (docs/tables.md#taylor-series). Under `outside error` the
    /// last knot itself belongs to the last piece: there is no constant after it, and a
    /// run starting there with a falling argument (the only way on into the data) must not
    /// fail.
    pub fn local_at(&self, x: f64, cursor: &mut Cursor) -> Result<Local, LookupError> {
        let value = self.value_at(x, cursor)?;
        let (first, last) = self.curve().domain();
        // Under `outside error` nothing lies after the last knot: a run standing on it
        // reads the last piece, so that an argument falling from it into the data has its
        // series (a rising one is stopped past it, `next_knot_time`, where this errs).
        // Where the table jumps at an end, the lookups read the data within their rounding
        // band beyond it, and a switch on the state restarts a run entering the data at
        // the band's edge (`varmass_core::table::knot_bracket_read`): the series must read what
        // the lookups read there.
        let in_band = |end: f64| self.jumps_at(end) && (first..=last).contains(&self.snapped(x));
        let from_first = first <= x || in_band(first);
        let to_last = x < last || x == last && self.outside() == Outside::Error || in_band(last);
        let on_data = from_first && to_last;
        if !on_data {
            let constant = match self.outside() {
                Outside::Zero => 0.0,
                // The end's value: the value at `x`, on or beyond the end.
                Outside::Hold => value,
                Outside::Error => {
                    return Err(LookupError::Outside {
                        argument: x,
                        first,
                        last,
                    })
                }
            };
            return Ok(Local {
                knot: 0.0,
                coefficients: [constant, 0.0, 0.0, 0.0],
                value: constant,
            });
        }
        let curve = self.curve();
        let interval = self.cursor_interval(cursor);
        let width = curve.degree() + 1;
        let piece = &curve.coefficients()[interval * width..(interval + 1) * width];
        let mut coefficients = [0.0; 4];
        if width > 4 {
            coefficients = [f64::NAN; 4];
        } else {
            coefficients[..width].copy_from_slice(piece);
        }
        Ok(Local {
            knot: curve.knots()[interval],
            coefficients,
            value,
        })
    }
}

/// Coefficient `k` of w = F(a(t)) on the piece `local` (looked up at a\[0\] at order 0),
/// with `a(j)` the argument's coefficient j ≤ k and `h(j)` the stored coefficients j < k of
/// the Horner stage h₁; returns (h₁\[k\], w\[k\]), the caller storing h₁\[k\]. At order 0,
/// w\[0\] is `local.value`: the table's own value (as the state rate's lookup gives it), or
/// on and beyond an end the constant after it, a constant over any [`Scalar`] (a caller
/// whose coefficients carry derivatives gives w\[0\] its slope itself).
#[inline]
pub fn series_coefficient<S: Scalar>(
    local: &Local,
    a: impl Fn(usize) -> S,
    h: impl Fn(usize) -> S,
    k: usize,
) -> (S, S) {
    let [_, c1, c2, c3] = local.coefficients.map(S::splat);
    let s = |i: usize| {
        if i == 0 {
            a(0) - S::splat(local.knot)
        } else {
            a(i)
        }
    };
    let h2 = |i: usize| {
        if i == 0 {
            c3 * s(0) + c2
        } else {
            c3 * s(i)
        }
    };
    let mut h1 = if k == 0 { c1 } else { S::splat(0.0) };
    for i in 0..=k {
        h1 = h1 + h2(i) * s(k - i);
    }
    if k == 0 {
        return (h1, S::splat(local.value));
    }
    let mut w = h1 * s(0);
    for i in 0..k {
        w = w + h(i) * s(k - i);
    }
    (h1, w)
}
