//! Tables of data in generated code (docs/tables.md): the macro embeds each table a system
//! calls as a `static` [`Table`] over its coefficients, and calls it through [`lookup`] in
//! the methods that return a `Result` (a lookup outside the data is
//! [`SystemError::TableOutside`]) and [`lookup_or_nan`] in the others, which the run only
//! calls where the state rate succeeded at the same state.

pub use varmass_table::*;

use core::borrow::Borrow;

use crate::error::SystemError;

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
/// to 3 s landed an ulp short), a falling one strictly below it. A knot counts as crossed
/// only once the argument has reached it so: a run *starting* with a falling argument on a
/// knot gets a stop time a few roundings later, where it lies below (a Taylor series there
/// would read the piece above for its whole first step).
///
/// **Where the table jumps at an end** ([`Table::jumps_at`]) the knot has two stop times
/// (docs/tables.md#outside-the-data): T₁, a few roundings of t before the last time at which
/// the lookup (its argument snapped, [`Table::snapped`]) still reads the side the argument
/// comes from, and T₂, the first at which the run restarting reads the side it enters (the
/// value after the jump; entering the data, the raw argument on the data, for a Taylor
/// series' piece). `after` before T₁ gives T₁: the step arriving there reads the old side
/// at every stage, its last (t + h, rounded) included; from T₁ on it gives T₂, and the
/// tiny step between them errs by (T₂ − T₁)·jump, a few roundings. Before (review of
/// 2026-11-26) only T₂ was a stop, and the arriving step's last stage read the value after
/// the jump: a unit mass pushed by 1 on [1, 2] ended 0.1/6 short by RK4 at step 0.3.
pub fn next_knot_time(table: &Table, slope: f64, offset: f64, after: f64) -> f64 {
    next_knot_time_read(&[table], slope, offset, after)
}

/// [`next_knot_time`] for a table of which the equations read the derivative orders
/// `orders[0]` (the table), `orders[1]` (its derivative table), … up to the highest order
/// read: a knot where one of them jumps — an interior knot of a linear table whose slope
/// is read, of a pchip whose second derivative is read, under `outside hold` the last knot
/// of a table whose slope is read and not zero there — has two stop times T₁ and T₂ as a
/// jumping end has (docs/tables.md#knots-are-switches), on the first order that jumps
/// there: the step arriving at T₁ reads the piece it comes from at every stage, the run
/// restarting at T₂ the piece it enters (before, the step arriving at a knot read the next
/// piece's slope at its last stage, and a mass law M(t) under `outside hold` integrated
/// the last slope for a whole step past the data: Taylor 52 % off). Where none jumps (a
/// table read only at order 0 at an interior knot) the knot has the one stop time T₂, on
/// which every order reads the same value from either side.
pub fn next_knot_time_read(orders: &[&Table], slope: f64, offset: f64, after: f64) -> f64 {
    let Some(&table) = orders.first() else {
        return f64::INFINITY;
    };
    if !(slope.is_finite() && offset.is_finite()) || slope == 0.0 {
        return f64::INFINITY;
    }
    let knots = table.knots();
    let crossing = |knot: f64| Crossing::new(orders, knot, slope);
    let argument = |t: f64| slope * t + offset;
    // The first knot along the argument's travel it has not reached at `after` (one it
    // sits on counts as not reached when falling: it still reads the piece above).
    let reached_at_after = |&k: &f64| crossing(k).entered(argument(after));
    let found = if slope > 0.0 {
        knots.get(knots.partition_point(reached_at_after))
    } else {
        knots
            .partition_point(|k| !reached_at_after(k))
            .checked_sub(1)
            .and_then(|k| knots.get(k))
    };
    let Some(&knot) = found else {
        return f64::INFINITY;
    };
    let crossing = crossing(knot);
    // An ulp of the argument, in time: how far t must move for it to change; at least an
    // ulp of `after`, the step's start, whose roundings the stage times carry (a knot at
    // t = 0, knot = offset = 0, reached from t < 0 had a scale and a margin of 0: no T₁ at
    // a first knot under `hold`, T₁ = −5e-324 at an interior one, RK4 first order).
    let scale = f64::EPSILON * (knot.abs().max(offset.abs()) / slope.abs()).max(after.abs());
    let start = ((knot - offset) / slope).max(after);
    let entered = moved_until(start, scale, |t| crossing.entered(argument(t)));
    let entered = if entered > after {
        entered
    } else {
        after.next_up()
    };
    if crossing.jumps {
        let left = |t: f64| crossing.left(argument(t));
        let left = last_holding(moved_down_until(entered, scale, left), entered, left);
        // Stage times t + c·h of a step landed here round by an ulp or two of t, and the
        // argument by an ulp or two of itself: a margin of four of the larger.
        let margin = 4.0 * (f64::EPSILON * left.abs()).max(scale);
        let arrival = left - margin;
        if crossing.left(argument(left)) && arrival > after {
            return arrival;
        }
    }
    entered
}

/// A knot of a table of t as the argument travels through it, judged on `table`: the first
/// derivative order read that jumps there, else the table itself.
#[derive(Clone, Copy)]
struct Crossing<'a> {
    table: &'a Table,
    knot: f64,
    rising: bool,
    /// An order read jumps at the knot (an end under `outside zero`, [`Table::jumps_at`];
    /// a slope or higher derivative at an interior knot or under `outside hold`).
    jumps: bool,
    /// The argument leaves the data there (the last knot rising, the first falling).
    leaving: bool,
}

impl<'a> Crossing<'a> {
    fn new(orders: &[&'a Table], knot: f64, slope: f64) -> Self {
        let knots = orders[0].knots();
        let rising = slope > 0.0;
        let leaving = match rising {
            true => knots.last() == Some(&knot),
            false => knots.first() == Some(&knot),
        };
        let jumping = orders
            .iter()
            .copied()
            .find(|table| jumps_across(table, knot));
        Self {
            table: jumping.unwrap_or(orders[0]),
            knot,
            rising,
            jumps: jumping.is_some(),
            leaving,
        }
    }

    /// Whether a run restarting at argument `x` reads the side of the knot the argument
    /// enters: a rising argument on or past the knot, a falling one strictly below (the
    /// piece below, for a Taylor series); leaving the data where it jumps, the argument
    /// beyond the lookups' rounding band, so that the value after the jump is read.
    ///
    /// Under `outside error` a rising argument leaves the last knot only once strictly past
    /// it: a run standing on it reads the last piece (`Table::local_at`), and one going on
    /// must fail where it leaves the data, not a Taylor step later.
    fn entered(&self, x: f64) -> bool {
        let table = self.table;
        let x = match self.leaving && self.jumps {
            true => table.snapped(x),
            false => x,
        };
        let strictly = self.leaving && (self.jumps || table.outside() == Outside::Error);
        match (self.rising, strictly) {
            (true, false) => x >= self.knot,
            (true, true) => x > self.knot,
            (false, _) => x < self.knot,
        }
    }

    /// Whether a lookup at argument `x` still reads the side of a jumping knot the argument
    /// comes from: at an end, the data's value leaving them (within the rounding band
    /// beyond the end included), the value outside entering them (beyond the band); at an
    /// interior knot, the piece it comes from (below the knot rising, on or above it
    /// falling).
    fn left(&self, x: f64) -> bool {
        let table = self.table;
        let (first, last) = table.domain();
        if self.knot != first && self.knot != last {
            return !self.entered(x);
        }
        let snapped = table.snapped(x);
        let on_data = first <= snapped && snapped <= last;
        on_data == self.leaving
    }
}

/// Whether `table` jumps at its knot `knot`: at an end, as [`Table::jumps_at`] says (or,
/// under `outside hold`, [`Outside::Zero`] for a derivative table: a held value has zero
/// slope, so a slope that is not zero there jumps); at an interior knot, where the pieces
/// on either side differ there by more than 10⁻¹⁰ of the larger of their end values (the
/// rounding of the interpolant's construction: a pchip's slope is continuous to it, a
/// linear table's slope jumps by the difference of its chords).
fn jumps_across(table: &Table, knot: f64) -> bool {
    let curve = table.curve();
    let knots = curve.knots();
    let (first, last) = table.domain();
    if knot == first || knot == last {
        return table.jumps_at(knot);
    }
    let right = knots.partition_point(|&k| k < knot);
    if right == 0 || right >= knots.len() - 1 {
        return false;
    }
    let ends = |piece: usize| {
        let (a, b) = (knots[piece], knots[piece + 1]);
        [curve.value_on(piece, a), curve.value_on(piece, b)]
    };
    let [below_start, below] = ends(right - 1);
    let [above, above_end] = ends(right);
    let scale = [below_start, below, above, above_end]
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    (below - above).abs() > 1e-10 * scale
}

/// `t`, or the first time after it (up by ulps, then by steps doubling from `scale`: at most
/// ~70 tries) at which `reached` holds; `t` if none is found.
fn moved_until(t: f64, scale: f64, reached: impl Fn(f64) -> bool) -> f64 {
    moved(t, scale, reached, true)
}

/// `t`, or a time before it (down as [`moved_until`] goes up) at which `holds` holds; `t`
/// if none is found.
fn moved_down_until(t: f64, scale: f64, holds: impl Fn(f64) -> bool) -> f64 {
    moved(t, scale, holds, false)
}

/// The last time from `holds` up to `fails` at which `holds` (monotone: true, then false) holds,
/// by bisection to the ulp (`holds` itself if it does not hold there).
fn last_holding(mut holds: f64, mut fails: f64, test: impl Fn(f64) -> bool) -> f64 {
    if !test(holds) {
        return holds;
    }
    for _ in 0..128 {
        let middle = holds + 0.5 * (fails - holds);
        if middle <= holds || middle >= fails {
            break;
        }
        match test(middle) {
            true => holds = middle,
            false => fails = middle,
        }
    }
    holds
}

/// [`moved_until`] upwards or downwards.
fn moved(t: f64, scale: f64, reached: impl Fn(f64) -> bool, up: bool) -> f64 {
    if reached(t) {
        return t;
    }
    let next = |t: f64| if up { t.next_up() } else { t.next_down() };
    let mut moved = t;
    for _ in 0..8 {
        moved = next(moved);
        if reached(moved) {
            return moved;
        }
    }
    let sign = if up { 1.0 } else { -1.0 };
    let mut step = (moved - t).abs().max(scale);
    for _ in 0..60 {
        if reached(t + sign * step) {
            return t + sign * step;
        }
        step *= 2.0;
    }
    t
}

/// The knot bracket of `x` in the table `orders[0]`, as the anchor of a switch at the
/// table's knots
/// ([`VariableMassSystem::switch_anchors`](crate::VariableMassSystem::switch_anchors)):
/// j when kⱼ ≤ x < kⱼ₊₁ for the knots k₀ < … < kₙ₋₁, −1 below the first knot, n − 1 from
/// the last on (NaN for a NaN `x`). One binary search; exact as an `f64` below 2⁵³ knots.
///
/// Where the table jumps at an end ([`Table::jumps_at`]) the bracket's edge there is the
/// edge of the lookups' rounding band instead ([`Table::data_edges`]): the data's value
/// holds from the first edge to the last, so that the bracket says which side of the jump
/// a lookup reads (before the review of 2026-11-26, a crossing that left the argument an
/// ulp past the last knot read the value before the jump for the rest of the run).
///
/// `orders` are the derivative orders of the table that the equations read, `orders[0]`
/// (the table), `orders[1]`, … up to the highest (one table: `&[table]`): at each end the
/// bracket's edge is that of the first order read that jumps there (a slope held to 0 under
/// `outside hold` is one), so that a crossing leaves the argument where that order reads
/// its value after the jump, as [`next_knot_time_read`] does for a table of t. Before, the
/// edge was the order-0 table's, the knot itself under `hold`, and a crossing left the
/// argument an ulp past the last knot, where the slope table still read its end piece: a
/// mass law M(x) flew on with the last slope for a whole step (Taylor 6 % off, RK4 1e-3).
pub fn knot_bracket_read<T: Borrow<Table>>(orders: &[T], x: f64) -> f64 {
    let Some(table) = orders.first().map(Borrow::borrow) else {
        return f64::NAN;
    };
    if x.is_nan() {
        return f64::NAN;
    }
    let knots = table.knots();
    let above = match knots.partition_point(|&k| k <= x) {
        // Only at the ends is the band looked at: interior brackets cost one search.
        0 if x >= Edge::FromFirst.of(orders) => 1,
        n if n == knots.len() && x < Edge::PastLast.of(orders) => n - 1,
        above => above,
    };
    above as f64 - 1.0
}

/// The switching function of the knots of a table of the state, anchored at bracket
/// `bracket` ([`knot_bracket_read`] at the run's last accepted point): the distance from `x`
/// to the nearer end of the bracket, min(x − kⱼ, kⱼ₊₁ − x), with kⱼ = −∞ below the first
/// knot and kⱼ₊₁ = +∞ from the last on. Positive inside the bracket, zero at its knots,
/// negative anywhere outside: however many knots a step passes, the sign changes, and the
/// first zero along the step is the first knot crossed. Two knots read, no search, so a
/// table of 1 000 knots costs what one of 2 does.
///
/// At an end where the table jumps, the distance is to the edge of the rounding band the
/// bracket's side reads ([`knot_bracket_read`] on the same `orders`): zero at the last
/// argument that still reads the side the bracket holds, so that g = 0 is the side before
/// the switch, as the run's crossings take it.
pub fn knot_gap_read<T: Borrow<Table>>(orders: &[T], x: f64, bracket: f64) -> f64 {
    let Some(table) = orders.first().map(Borrow::borrow) else {
        return f64::NAN;
    };
    // A NaN argument or anchor must not read as "far inside" (+∞), which would silence the
    // switch: NaN reaches the run's non-finite checks instead.
    if x.is_nan() || bracket.is_nan() {
        return f64::NAN;
    }
    let knots = table.knots();
    let last = knots.len() as f64 - 1.0;
    let knot = |at: f64| (at >= 0.0 && at <= last).then(|| knots[at as usize]);
    // The bracket's lower edge (the first argument reading it) and upper edge (the last);
    // the ends' bands are looked at only in the brackets next to them.
    let lower = match bracket {
        _ if bracket == 0.0 => Some(Edge::FromFirst.of(orders)),
        _ if bracket == last => Some(Edge::PastLast.of(orders)),
        _ => knot(bracket),
    };
    let upper = match bracket {
        _ if bracket == -1.0 => Some(Edge::BelowFirst.of(orders)),
        _ if bracket + 1.0 == last => Some(Edge::ToLast.of(orders)),
        _ => knot(bracket + 1.0),
    };
    let below = lower.map_or(f64::INFINITY, |k| x - k);
    let above = upper.map_or(f64::INFINITY, |k| k - x);
    below.min(above)
}

/// An edge of the brackets at a table's ends: the knot itself, or where the table jumps
/// there, the edge of the band of arguments the lookups snap onto it.
#[derive(Clone, Copy)]
enum Edge {
    /// The last argument reading below the first knot.
    BelowFirst,
    /// The first argument reading the data.
    FromFirst,
    /// The last argument reading the data.
    ToLast,
    /// The first argument reading past the last knot.
    PastLast,
}

impl Edge {
    /// The edge on the first of `orders` (non-empty) that jumps at the end, else the end.
    fn of<T: Borrow<Table>>(self, orders: &[T]) -> f64 {
        let (first, last) = orders[0].borrow().domain();
        let end = match self {
            Edge::BelowFirst | Edge::FromFirst => first,
            Edge::ToLast | Edge::PastLast => last,
        };
        let jumping = orders.iter().map(Borrow::borrow).find(|t| t.jumps_at(end));
        let Some(table) = jumping else {
            return end;
        };
        let edge = table.data_edge(end);
        match self {
            Edge::BelowFirst => edge.next_down(),
            Edge::PastLast => edge.next_up(),
            Edge::FromFirst | Edge::ToLast => edge,
        }
    }
}
