//! Tables of data in generated code (docs/tables.md): the macro embeds each table a system
//! calls as a `static` [`Table`] over its coefficients, and calls it through [`lookup`] in
//! the methods that return a `Result` (a lookup outside the data is
//! [`SystemError::TableOutside`]) and [`lookup_or_nan`] in the others, which the run only
//! calls where the state rate succeeded at the same state.

pub use varmass_table::*;

use crate::system::SystemError;

/// The value of `table` (called `name` in the model) at `x`, or the typed error naming
/// both when `x` is outside its data under `outside error` (or is NaN).
#[inline]
pub fn lookup(table: &Table, name: &'static str, x: f64) -> Result<f64, SystemError> {
    table.value(x).map_err(|_| SystemError::TableOutside {
        table: name,
        argument: x,
    })
}

/// [`lookup`] where no error can be returned: NaN on failure, which the steppers'
/// non-finite check stops at.
#[inline]
pub fn lookup_or_nan(table: &Table, x: f64) -> f64 {
    table.value(x).unwrap_or(f64::NAN)
}

/// The piece of `table` holding `x` for a Taylor series (`series_coefficient`), or
/// [`Local::NAN`] where the lookup fails (outside the data under `outside error`, a NaN):
/// the series is NaN and the Taylor step ends in a typed non-finite error.
#[inline]
pub fn local_or_nan(table: &Table, x: f64) -> Local {
    table.local(x).unwrap_or(Local::NAN)
}

/// The first time after `after` at which the argument `slope·t + offset` of `table` crosses
/// one of its knots, t = (knot − offset)/slope; infinity if none does (or the slope is 0
/// or not finite). What generated systems' `next_stop_time` asks of each table of t, by a
/// binary search on the knots.
///
/// The time is moved up by ulps until the argument has reached the knot in its direction of
/// travel, so that the run restarting there reads the piece the argument enters (its slope,
/// for a derivative table in the state rate; the Taylor series' piece,
/// `Table::local_at`), not the one it leaves: a rising argument on or past the knot
/// (computed as (knot − offset)/slope, a quarter of the M1670's knots at ignition times up
/// to 3 s landed an ulp short), a falling one strictly below it. At an end where the table
/// jumps ([`Table::jumps_at`]) the argument is moved beyond the lookups' rounding slack, so
/// that the restart reads the value after the jump. A knot counts as crossed only once the
/// argument has reached it so: a run *starting* with a falling argument on a knot gets a
/// stop time a few roundings later, where it lies below (a Taylor series there would read
/// the piece above for its whole first step).
pub fn next_knot_time(table: &Table, slope: f64, offset: f64, after: f64) -> f64 {
    if !(slope.is_finite() && offset.is_finite()) || slope == 0.0 {
        return f64::INFINITY;
    }
    let knots = table.knots();
    let argument = |t: f64| slope * t + offset;
    let reached = |knot: f64, t: f64| {
        // The end the argument leaves the data by, if the table jumps there.
        let leaving = match slope > 0.0 {
            true => knots.last() == Some(&knot),
            false => knots.first() == Some(&knot),
        };
        let jumps = leaving && table.jumps_at(knot);
        let x = if jumps {
            table.snapped(argument(t))
        } else {
            argument(t)
        };
        match (slope > 0.0, jumps) {
            (true, false) => x >= knot,
            (true, true) => x > knot,
            (false, _) => x < knot,
        }
    };
    // The first knot along the argument's travel it has not reached at `after` (one it
    // sits on counts as not reached when falling: it still reads the piece above).
    let found = if slope > 0.0 {
        knots.get(knots.partition_point(|&k| reached(k, after)))
    } else {
        knots
            .partition_point(|&k| !reached(k, after))
            .checked_sub(1)
            .and_then(|k| knots.get(k))
    };
    found.map_or(f64::INFINITY, |&knot| {
        // An ulp of the argument, in time: how far t must move for it to change.
        let scale = f64::EPSILON * knot.abs().max(offset.abs()) / slope.abs();
        let start = ((knot - offset) / slope).max(after);
        let time = moved_until(start, scale, |t| reached(knot, t));
        if time > after {
            time
        } else {
            after.next_up()
        }
    })
}

/// `t`, or the first time after it (up by ulps, then by steps doubling from `scale`: at most
/// ~70 tries) at which `reached` holds; `t` if none is found.
fn moved_until(t: f64, scale: f64, reached: impl Fn(f64) -> bool) -> f64 {
    if reached(t) {
        return t;
    }
    let mut moved = t;
    for _ in 0..8 {
        moved = moved.next_up();
        if reached(moved) {
            return moved;
        }
    }
    let mut step = (moved - t).max(scale);
    for _ in 0..60 {
        if reached(t + step) {
            return t + step;
        }
        step *= 2.0;
    }
    t
}

/// The knot bracket of `x` in `table`, as the anchor of a switch at the table's knots
/// ([`VariableMassSystem::switch_anchors`](crate::VariableMassSystem::switch_anchors)):
/// j when kⱼ ≤ x < kⱼ₊₁ for the knots k₀ < … < kₙ₋₁, −1 below the first knot, n − 1 from
/// the last on (NaN for a NaN `x`). One binary search; exact as an `f64` below 2⁵³ knots.
pub fn knot_bracket(table: &Table, x: f64) -> f64 {
    if x.is_nan() {
        return f64::NAN;
    }
    let above = table.knots().partition_point(|&k| k <= x);
    above as f64 - 1.0
}

/// The switching function of the knots of a table of the state, anchored at bracket
/// `bracket` ([`knot_bracket`] at the run's last accepted point): the distance from `x`
/// to the nearer end of the bracket, min(x − kⱼ, kⱼ₊₁ − x), with kⱼ = −∞ below the first
/// knot and kⱼ₊₁ = +∞ from the last on. Positive inside the bracket, zero at its knots,
/// negative anywhere outside: however many knots a step passes, the sign changes, and the
/// first zero along the step is the first knot crossed. Two knots read, no search, so a
/// table of 1 000 knots costs what one of 2 does.
pub fn knot_gap(table: &Table, x: f64, bracket: f64) -> f64 {
    // A NaN argument or anchor must not read as "far inside" (+∞), which would silence the
    // switch: NaN reaches the run's non-finite checks instead.
    if x.is_nan() || bracket.is_nan() {
        return f64::NAN;
    }
    let knots = table.knots();
    let index = |offset: f64| {
        let at = bracket + offset;
        (at >= 0.0 && at < knots.len() as f64).then(|| knots[at as usize])
    };
    let below = index(0.0).map_or(f64::INFINITY, |k| x - k);
    let above = index(1.0).map_or(f64::INFINITY, |k| k - x);
    below.min(above)
}
