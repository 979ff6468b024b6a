//! Tables for varmass: functions of one argument given by measured data — a motor's thrust
//! curve, an atmosphere's density — read from a file, interpolated, and differentiated.
//!
//! * Readers: [`Motor::parse`] for the RASP `.eng` format every rocketry tool shares (the
//!   header's masses included, the curve starting from (0 s, 0 N)) and [`CsvTable::parse`] for
//!   a two-column CSV with a header. Malformed text is a [`ReadError`] with its line and
//!   column; the data are [`Points`]: knots strictly increasing, values finite, two or more.
//!   [`CsvTable::parse_for`] and [`Motor::parse_for`] read for an interpolation, refusing
//!   data whose interpolant overflows at the line that ends the piece
//!   ([`Interpolation::checked`], [`Table::checked`] for points built in code).
//! * Interpolants ([`Interpolation`]): `linear`, `pchip` and `spline` (natural cubic), the
//!   cubics as SciPy computes them. Each is a [`Piecewise`] polynomial whose
//!   [`derivative`](Piecewise::derivative) is again one, so the derivation can differentiate
//!   a table call as often as it needs.
//! * [`Table`]: an interpolant with its [`Outside`] rule (`error`, `zero`, `hold`); lookups
//!   remember their interval (a [`Cursor`] or the table's own hint) and fall back to a binary
//!   search; the [`knots`](Table::knots) are where the table may be non-smooth.
//! * [`Tabulated`]: a table with its derivative tables built once, the field of a generated
//!   system for a `table F(t) = runtime` statement; [`Tabulated::transformed`] scales its
//!   values and stretches its argument (an ensemble dispersing a thrust curve).
//! * Taylor series of a table call ([`series_coefficient`]), and every Taylor recurrence
//!   ([`recurrence`], with its four-chain [`sum`]): here because generated code (through
//!   `varmass-core`) and the run-time tapes (`varmass-symbolic`) both depend on this crate,
//!   and one function each keeps the two bit-identical.
//!
//! The crate is `no_std` (with `alloc`) without its `std` feature, as `varmass-core`.
//! The design, and how the DSL uses tables, is in `docs/tables.md`.
//!
//! ```
//! use varmass_table::{Interpolation, Motor, Outside, Table};
//!
//! let motor = Motor::parse("M1 75 757 0 3.0 5.0 X\n1 100\n2 0\n").unwrap();
//! // The curve starts from ignition: (0, 0), (1, 100), (2, 0); 100 N·s by trapezoids.
//! assert_eq!(motor.thrust.arguments(), [0.0, 1.0, 2.0]);
//! assert_eq!(motor.total_impulse(), 100.0);
//! let thrust = Table::new(&motor.thrust, Interpolation::Linear, Outside::Zero);
//! assert_eq!(thrust.value(0.5), Ok(50.0));
//! assert_eq!(thrust.value(3.0), Ok(0.0)); // burnt out
//! assert_eq!(thrust.derivative().value(1.5), Ok(-100.0));
//! ```

#![cfg_attr(not(feature = "std"), no_std)]
#![warn(missing_docs)]

extern crate alloc;

mod csv;
mod error;
mod interpolant;
mod piecewise;
mod points;
mod rasp;
pub mod recurrence;
mod series;
mod table;
mod tabulated;
mod text;

pub use csv::CsvTable;
pub use error::{LookupError, ReadError, ReadErrorKind};
pub use interpolant::Interpolation;
pub use piecewise::Piecewise;
pub use points::{InvalidPoints, Points};
pub use rasp::Motor;
pub use recurrence::{sum, Scalar};
pub use series::{series_coefficient, Local};
pub use table::{Cursor, Outside, Table, END_SLACK};
pub use tabulated::Tabulated;
