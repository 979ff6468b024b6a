//! Why data could not be read or a table could not be evaluated: typed errors carrying the
//! line (and column) of the offending text, or the argument that fell outside the data.

use alloc::string::String;

/// Malformed table data: what is wrong ([`ReadErrorKind`]) and where, as the 1-based line and
/// column of the offending field in the text that was read.
///
/// Displayed as `line <line>, column <column>: <what is wrong>`; the caller, who knows the
/// file's name, puts it in front.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line}, column {column}: {kind}")]
pub struct ReadError {
    /// 1-based line of the text.
    pub line: usize,
    /// 1-based column (in characters) where the offending field starts; 1 when the whole line
    /// (or the whole file, for [`ReadErrorKind::TooFewPoints`]) is at fault.
    pub column: usize,
    /// What is wrong.
    pub kind: ReadErrorKind,
}

/// What is wrong in a [`ReadError`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ReadErrorKind {
    /// A field that must be a number is not one (`field` is the text found).
    #[error("`{field}` is not a number")]
    NotANumber {
        /// The text of the field.
        field: String,
    },
    /// A number that must be finite is infinite or NaN.
    #[error("`{field}` is not a finite number")]
    NotFinite {
        /// The text of the field.
        field: String,
    },
    /// A line has the wrong number of fields.
    #[error("expected {expected}, found {found} fields")]
    FieldCount {
        /// What the line should hold, e.g. "2 fields (time thrust)".
        expected: &'static str,
        /// How many fields the line has.
        found: usize,
    },
    /// The knots (times, arguments) must increase strictly: this one is not above the previous.
    #[error("the argument {knot} does not increase on the previous one, {previous}")]
    NotIncreasing {
        /// The previous knot.
        previous: f64,
        /// This knot.
        knot: f64,
    },
    /// A RASP time before ignition: the curve starts at t = 0.
    #[error("the time {time} is negative")]
    NegativeTime {
        /// The time found.
        time: f64,
    },
    /// A RASP thrust below zero: a motor only pushes, and a negative thrust would make the
    /// mass law ṁ = −F/u_e a negative flow rate, refused only when a run reaches it.
    #[error("the thrust {thrust} N is negative: a motor's thrust is ≥ 0")]
    NegativeThrust {
        /// The thrust found, N.
        thrust: f64,
    },
    /// The text ends before the header it needs (a RASP header line, a CSV header).
    #[error("missing the header line ({expected})")]
    MissingHeader {
        /// What the header should hold.
        expected: &'static str,
    },
    /// A CSV header whose fields are numbers: the file starts with data, not names.
    #[error("the first line is data; a CSV table starts with a header naming its columns")]
    HeaderIsData,
    /// A second RASP header after data: one file, one motor.
    #[error("a second motor header; a table reads one motor per file")]
    SecondMotor,
    /// The slope between two points overflows (values near ±1.8e308, or arguments a
    /// subnormal apart): the interpolant there would be ±∞ or NaN.
    #[error("the slope from ({:?}, {:?}) to ({:?}, {:?}) is not finite", from.0, from.1, to.0, to.1)]
    SlopeNotFinite {
        /// The previous point (argument, value).
        from: (f64, f64),
        /// This point.
        to: (f64, f64),
    },
    /// The distance between two arguments overflows (knots near ±1.8e308 of opposite
    /// signs): the interpolant would read zero everywhere.
    #[error("the distance from ({:?}, {:?}) to ({:?}, {:?}) is not finite", from.0, from.1, to.0, to.1)]
    SpacingNotFinite {
        /// The earlier point (argument, value): the previous one, or the first.
        from: (f64, f64),
        /// This point.
        to: (f64, f64),
    },
    /// The interpolant between two points overflows though their slope does not (a
    /// `pchip` or `spline` table of values near ±1.8e308: its cubic coefficients reach
    /// 3·δ/h; [`InvalidPoints::InterpolantNotFinite`](crate::InvalidPoints)).
    #[error(
        "the {interpolation} interpolant from ({:?}, {:?}) (line {from_line}) to ({:?}, {:?}) \
         is not finite (its values or slopes overflow between the points)",
        from.0, from.1, to.0, to.1
    )]
    InterpolantNotFinite {
        /// The interpolation's name (`pchip`, `spline`, `linear`).
        interpolation: &'static str,
        /// The line of the previous point.
        from_line: usize,
        /// The previous point (argument, value).
        from: (f64, f64),
        /// This point.
        to: (f64, f64),
    },
    /// Fewer than two points: no interval to interpolate on.
    #[error("{found} point(s); a table needs at least two")]
    TooFewPoints {
        /// How many points were read.
        found: usize,
    },
}

/// Why a table could not be evaluated at an argument.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum LookupError {
    /// The argument lies outside the data and the table's rule is
    /// [`Outside::Error`](crate::Outside::Error).
    #[error("the argument {argument} is outside the data [{first}, {last}]")]
    Outside {
        /// The argument asked for.
        argument: f64,
        /// The first knot.
        first: f64,
        /// The last knot.
        last: f64,
    },
    /// The argument is NaN: no rule gives a value there, and a NaN is never returned silently.
    #[error("the argument is NaN")]
    NotANumber,
}
